#include "core/io/byte_stream.h"

#include <cmath>

namespace btflut {

Result<Direction> ByteReader::getDirection(const std::string& name, const std::string& what) {
    const double theta = get<double>(), phi = get<double>();
    if (!std::isfinite(theta) || !std::isfinite(phi) || theta < 0 || theta > 90)
        return Error{name + ": invalid " + what + " direction"};
    return Direction::fromDegrees(theta, phi);
}

}  // namespace btflut

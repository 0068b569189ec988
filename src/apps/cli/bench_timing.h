#pragma once
// How the GL benches (bench render, decoder, levels) time their draws: the one loop.
//
//   Result<DrawTimes> t = timeDraws(30, hasTimer, [&] { return renderer.draw(light, mode); });

#include <functional>
#include <limits>

#include "core/result.h"

namespace btflut {

/// Seconds per draw.
struct DrawTimes {
    double wall = 0;  ///< from the first draw to one glFinish after the last, over their count
    double gpu =
        std::numeric_limits<double>::quiet_NaN();  ///< GL_TIME_ELAPSED around each, summed; NaN without a timer
};

/// `count` draws timed (`timer`: the driver has GL_TIME_ELAPSED). The first error a draw
/// returns stops it.
Result<DrawTimes> timeDraws(int count, bool timer, const std::function<Status()>& draw);

}  // namespace btflut

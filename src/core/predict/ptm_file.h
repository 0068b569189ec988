#pragma once
// The .ptm file of RTI tools (HP Labs' PTM format 1.2, PTM_FORMAT_LRGB), so RTIViewer and
// other RTI viewers open btflut's PTM baseline:
//
//   PTM_1.2\n PTM_FORMAT_LRGB\n WIDTH\n HEIGHT\n 6 scales\n 6 integer biases\n
//   then WIDTH x HEIGHT x 6 coefficient bytes (a0..a5 per pixel: u^2, v^2, uv, u, v, 1),
//   then WIDTH x HEIGHT x 3 RGB bytes; both blocks bottom row first.
//
// A coefficient is (byte - bias) * scale, and a pixel's colour is rgb * L / 255 with L the
// luminance polynomial in 0..255 units (btflut's PTM keeps L in 0..1, so the file's scales
// are 255 times its). The file's biases are integers: btflut's are rounded, and each byte
// moved by the rounding's remainder (at most half a code).

#include <string>

#include "core/io/file_io.h"
#include "core/predict/light_model.h"

namespace btflut {

/// A light model of basis ptm with an albedo (the bank's PTM, ptm.h).
Bytes encodePtmFile(const LightModel& ptm);

/// Reads an LRGB .ptm file (header checked field by field, sizes against the payload);
/// errors name the file. A light model of basis ptm.
Result<LightModel> decodePtmFile(const Bytes& bytes, const std::string& name);

}  // namespace btflut

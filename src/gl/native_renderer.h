#pragma once
// The GPU path of `btflut relight`: the bank's reference image at its native size, relit by
// one RelightPass (relight_pass.h) into a float texture and read back. Under a directional
// light the LUT is the same for every texel, so it is blended once on the CPU (Relighter) and
// uploaded; the shader does one linearly filtered fetch per channel. Needs a current context
// (context.h).
//
//   Result<Image> img = renderNative(bank, light, view, /*dither=*/true);

#include "core/bank/lut_bank.h"

namespace btflut {

/// With `interpolate` false, the LUT of the nearest measured node (LutBank::lookup).
Result<Image> renderNative(const LutBank& bank, Direction light, Direction view, bool dither, bool interpolate = true);

}  // namespace btflut

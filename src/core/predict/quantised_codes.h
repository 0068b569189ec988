#pragma once
// A texel's codes as a learned model stores them (learned_model.h; NeuralRTI's baseline too):
// N bytes per texel, code k's value (byte_k - bias_k) scale_k, one scale and bias per code as
// RTI web formats store them. The one definition of that form: its values (learned_training.h,
// codeValues) and its quantisation (below).
//
//   QuantisedCodes q = QuantisedCodes::quantise(codes, inside, 9);  // from float codes
//   float v = q.value(texel, k);

#include <cstddef>
#include <cstdint>
#include <vector>

namespace btflut {

struct QuantisedCodes {
    std::vector<float> scale, bias;   ///< per code: value = (byte - bias) scale
    std::vector<std::uint8_t> bytes;  ///< N per texel, rows top first

    bool empty() const { return bytes.empty(); }
    /// N, the codes per texel.
    std::size_t count() const { return scale.size(); }
    /// Texel `texel`'s code k's value.
    float value(std::size_t texel, std::size_t k) const {
        return (static_cast<float>(bytes[texel * count() + k]) - bias[k]) * scale[k];
    }

    /// 8 bits per code of `codes` (N per texel) over the range the `inside` texels span (others
    /// clamped into it); each byte the nearest, or with `truncate` the one below (as NeuralRTI
    /// stores them).
    static QuantisedCodes quantise(const std::vector<float>& codes, const std::vector<std::uint32_t>& inside,
                                   std::size_t N, bool truncate = false);
};

}  // namespace btflut

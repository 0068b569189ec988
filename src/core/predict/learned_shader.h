#pragma once
// A learned model's decoder as shader source specialised to it (docs/engines.md, "A learned
// material"): its sizes fixed, its weights literal constants, every layer unrolled into vec4
// multiply-adds. A GPU then reads no weight it must index at run time, keeps every activation
// in registers, and folds what it can at compile time: the texture path of the generic include
// (btflut.glsl's btflutLearnedPrediction, weights by texelFetch in loops of run-time bounds)
// ran 25 times slower than such a shader on an H200 and on llvmpipe alike (issue 46).
//
// btflut's own renderer compiles it after the include (shaders/lut_common.glsl, with the frame
// from the CPU, LearnedModel::lightFrame), and `export` writes it beside the include for
// engines, in GLSL (GLSL 3.30, GLSL ES 3.00, Godot 4: one text) and HLSL. It defines
// BTFLUT_NETWORK and, after the include (its structs and btflutBasisTerms):
//
//   vec3 btflutNetworkValue(vec4 codes[8], BtflutLearnedFrame f)     a texel: its codes' bytes (0..255)
//                                                                     to its value per channel in [0, 1]
//   BtflutLearnedFrame btflutNetworkFrame(vec3 light, vec3 view)     the frame at a light (tangent frame):
//                                                                     per fragment where the light varies
//   BtflutPrediction btflutNetworkPrediction(sampler2DArray planes, vec2 uv, BtflutLearnedFrame f)
//
//   std::string glsl = learnedShaderSource(model, ShaderLanguage::Glsl);

#include <cstddef>
#include <string>

#include "core/predict/learned_model.h"

namespace btflut {

enum class ShaderLanguage {
    Glsl,  ///< GLSL 3.30 and later, GLSL ES 3.00, Godot 4's shading language
    Hlsl,  ///< shader model 5 (Unity, Unreal): samplers as a texture and its SamplerState
};

/// What the specialised decoder costs a GPU.
struct LearnedShaderCost {
    std::size_t texelMultiplyAdds = 0;  ///< per texel: the codes' basis and the residual network
    std::size_t frameMultiplyAdds = 0;  ///< per frame: the light network and the residual's light part
    std::size_t constants = 0;          ///< vec4 literals of btflutNetworkValue (constant storage a target holds)
};
LearnedShaderCost learnedShaderCost(const LearnedModel& model);
/// The texel's multiply-adds of a model of these sizes (before it is trained: auto's bound).
std::size_t learnedTexelMultiplyAdds(int codes, int channels, const std::vector<int>& hidden);

/// The most vec4 constants a specialised decoder holds: 64 KB, what every target's constant
/// storage holds (a GL uniform block's and a D3D11 constant buffer's 4096 vectors). The largest
/// network a GPU draws (LearnedModel::fitsGpu: 4 hidden layers of 64, 16 codes) holds 3449.
constexpr std::size_t kMaxShaderConstants = 4096;

/// Whether the model's decoder is written as source (its constants within kMaxShaderConstants).
bool hasLearnedShader(const LearnedModel& model);

/// The source (the model non-empty, hasLearnedShader). `name` goes into its opening comment.
std::string learnedShaderSource(const LearnedModel& model, ShaderLanguage language, const std::string& name = {});

}  // namespace btflut

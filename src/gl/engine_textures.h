#pragma once
// An EngineMaterial (core/relight/engine_material.h) on the GPU, as shaders/btflut.glsl reads
// it: the LUT grid as a 3D texture, and for banks with a predictor its planes (or references
// and albedo), weights over the light disk and region labels, with the `predictor` uniforms.
// The sphere and the cylinder draw with it, as an engine draws an exported folder.
//
//   EngineTextures t = EngineTextures::upload(material, bytes);   // per bank
//   t.bind(program, material, 1);                                 // per draw: units 1 .. 4

#include "core/relight/engine_material.h"
#include "gl/objects.h"
#include "gl/shader.h"

namespace btflut {

struct EngineTextures {
    GlTexture luts, planes, weights, labels;

    static EngineTextures upload(const EngineMaterial& material, std::size_t& bytes);
    /// Binds `luts`, and for a predictor `planes`, `weights` and `labels`, to units first ..
    /// first + 3, and sets the sampler uniforms of those names and `predictor`.
    void bind(const ShaderProgram& program, const EngineMaterial& material, int first) const;
};

}  // namespace btflut

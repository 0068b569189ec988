#include "gl/native_renderer.h"

#include <optional>

#include "core/relight/engine_material.h"
#include "gl/objects.h"
#include "gl/prediction_textures.h"
#include "gl/relight_pass.h"
#include "gl/textures.h"

namespace btflut {

namespace {

GlTexture uploadReference(const Image& image) {
    GlTexture texture = makeTexture();
    gl.BindTexture(GL_TEXTURE_2D, texture.id());
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    // Float texels keep 8- and 16-bit codes exact; the shader reads them with texelFetch.
    const std::vector<float> rgb = rgbSamples(image);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGB32F, image.width, image.height, 0, GL_RGB, GL_FLOAT, rgb.data());
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    return texture;
}

}  // namespace

Result<Image> renderNative(const LutBank& bank, Direction light, Direction view, bool dither, bool interpolate) {
    const Image& ref = bank.reference;
    if (ref.samples.empty()) return Error{"the bank has no reference image inside"};
    if (Status s = drawnOnGpu(bank); !s) return Error{s.error()};
    GLint maxSize = 0;
    gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    if (ref.width > maxSize || ref.height > maxSize)
        return Error{"the reference image (" + std::to_string(ref.width) + "x" + std::to_string(ref.height) +
                     ") is larger than this GL driver's largest texture (" + std::to_string(maxSize) + ")"};
    GlTexture reference = uploadReference(ref);
    std::optional<PredictionTextures> prediction;
    if (bank.makesLuts()) {
        std::size_t bytes = 0;
        prediction = PredictionTextures::upload(bank, bytes);
    }
    RelightPass pass(bank, reference.id(), prediction ? &*prediction : nullptr);
    const std::vector<GlTexture> luts = pass.makeLuts();
    // A float target, so the read-back is the shader's value, not an 8-bit rounding of it.
    GlTexture target = allocateTexture2D(ref.width, ref.height, GL_RGBA32F, GL_RGBA, GL_FLOAT);
    if (Status s = pass.run(Relighter(bank).frame(light, view, interpolate), luts, target.id(), dither); !s)
        return Error{s.error()};

    std::vector<float> rgba(ref.pixelCount() * 4);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.ReadPixels(0, 0, ref.width, ref.height, GL_RGBA, GL_FLOAT, rgba.data());
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    if (GLenum error = gl.GetError(); error != GL_NO_ERROR)
        return Error{"OpenGL error " + std::to_string(error) + " while rendering"};
    Image out(ref.width, ref.height, ref.channels, ref.bitDepth);
    const auto channels = static_cast<std::size_t>(ref.channels);
    for (std::size_t i = 0; i < ref.pixelCount(); ++i)  // GL row r is image row r (RelightPass)
        for (std::size_t c = 0; c < channels; ++c) out.samples[i * channels + c] = rgba[i * 4 + c];
    return out;
}

}  // namespace btflut

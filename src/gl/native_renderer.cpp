#include "gl/native_renderer.h"

#include <optional>

#include "gl/blend_textures.h"
#include "gl/objects.h"
#include "gl/shader.h"
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
    GLint maxSize = 0;
    gl.GetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    if (ref.width > maxSize || ref.height > maxSize)
        return Error{"the reference image (" + std::to_string(ref.width) + "x" + std::to_string(ref.height) +
                     ") is larger than this GL driver's largest texture (" + std::to_string(maxSize) + ")"};
    std::vector<std::string> defines = bank.makesLuts() ? BlendTextures::defines(bank) : std::vector<std::string>{};
    if (!bank.makesLuts() && bank.colour == ColourMode::Rgb) defines.push_back("RGB_MODE");
    if (dither) defines.push_back("DITHER");
    Result<GlProgram> program = buildProgram({"quad.vert"}, {"lut_common.glsl", "native.frag"}, defines);
    if (!program) return Error{program.error()};

    // The LUTs: the bank's for the light, or made from the blend (Relighter).
    const Relighter relighter(bank);
    const RelightFrame frame = relighter.frame(light, view, interpolate);
    GlTexture reference = uploadReference(ref);
    std::vector<GlTexture> luts;
    std::optional<BlendTextures> blend;
    if (bank.makesLuts()) {
        std::size_t bytes = 0;
        blend = BlendTextures::upload(bank, bytes);
        luts = blend->makeLutTables();
        blend->updateLuts(luts, frame);
    } else {
        for (int c = 0; c < bank.channels(); ++c)
            luts.push_back(uploadLut(&frame.luts[static_cast<std::size_t>(c) * bank.entries], bank.entries));
    }

    // A float target, so the read-back is the shader's value, not an 8-bit rounding of it.
    GlTexture target = makeTexture();
    gl.BindTexture(GL_TEXTURE_2D, target.id());
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, ref.width, ref.height, 0, GL_RGBA, GL_FLOAT, nullptr);
    GlFramebuffer framebuffer = makeFramebuffer();
    gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target.id(), 0);
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return Error{"the GL driver cannot render to a float image"};

    const GLuint p = program->id();
    gl.UseProgram(p);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, reference.id());
    gl.Uniform1i(gl.GetUniformLocation(p, "reference"), 0);
    if (blend) {
        blend->bind(p, frame, luts, 4);
    } else {
        for (int c = 0; c < 3; ++c) {
            gl.ActiveTexture(static_cast<GLenum>(GL_TEXTURE1 + c));
            gl.BindTexture(GL_TEXTURE_1D, luts[static_cast<std::size_t>(std::min(c, bank.channels() - 1))].id());
            const std::string name = "lut[" + std::to_string(c) + "]";
            gl.Uniform1i(gl.GetUniformLocation(p, name.c_str()), 1 + c);
        }
    }
    const float inCode = inputCode(ref, bank.colour);
    gl.Uniform1i(gl.GetUniformLocation(p, "entries"), bank.entries);
    gl.Uniform1i(gl.GetUniformLocation(p, "referenceChannels"), ref.channels);
    gl.Uniform1i(gl.GetUniformLocation(p, "height"), ref.height);
    gl.Uniform1f(gl.GetUniformLocation(p, "inCode"), inCode);
    gl.Uniform1f(gl.GetUniformLocation(p, "outCode"), bank.targetCode());

    GlVertexArray vao = makeVertexArray();
    gl.BindVertexArray(vao.id());
    gl.Viewport(0, 0, ref.width, ref.height);
    gl.DrawArrays(GL_TRIANGLES, 0, 3);

    std::vector<float> rgba(ref.pixelCount() * 4);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.ReadPixels(0, 0, ref.width, ref.height, GL_RGBA, GL_FLOAT, rgba.data());
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    if (GLenum error = gl.GetError(); error != GL_NO_ERROR)
        return Error{"OpenGL error " + std::to_string(error) + " while rendering"};

    Image out(ref.width, ref.height, ref.channels, ref.bitDepth);
    for (int row = 0; row < ref.height; ++row)
        for (int x = 0; x < ref.width; ++x) {
            const float* px = &rgba[(static_cast<std::size_t>(ref.height - 1 - row) * ref.width + x) * 4];
            for (int c = 0; c < ref.channels; ++c) out.at(x, row, c) = px[c];
        }
    return out;
}

}  // namespace btflut

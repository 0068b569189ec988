#include "gl/scene_renderer.h"

#include <map>

#include "core/bank_file.h"
#include "gl/objects.h"
#include "gl/shader.h"
#include "gl/textures.h"

namespace btflut {

namespace {

struct Material {
    LutBank bank;
    GlTexture reference;
};

GlTexture uploadMipmapped(const Image& image, std::size_t& bytes) {
    GlTexture texture = makeTexture();
    gl.BindTexture(GL_TEXTURE_2D, texture.id());
    const std::vector<float> rgb = rgbSamples(image);
    const bool sixteen = image.bitDepth == 16;
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl.TexImage2D(GL_TEXTURE_2D, 0, sixteen ? GL_RGB16 : GL_RGB8, image.width, image.height, 0, GL_RGB, GL_FLOAT,
                  rgb.data());
    gl.GenerateMipmap(GL_TEXTURE_2D);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    bytes += image.pixelCount() * (sixteen ? 8 : 4) * 4 / 3;  // the driver pads RGB to RGBA; mipmaps add 1/3
    return texture;
}

}  // namespace

Result<Image> renderScene(const Scene& scene, RenderStats& stats) {
    stats = {};
    const std::vector<std::size_t> visible = visibleQuads(scene);
    stats.quadsCulled = scene.quads.size() - visible.size();

    // Load only the materials some visible quad uses.
    std::map<std::string, Material> materials;
    for (std::size_t i : visible) {
        const std::string& name = scene.quads[i].material;
        if (materials.count(name)) continue;
        Result<LutBank> bank = loadBank(scene.materials.at(name));
        if (!bank) return Error{bank.error()};
        if (bank->reference.samples.empty())
            return Error{scene.materials.at(name) + ": the bank has no reference image inside"};
        Material& m = materials[name];
        m.bank = std::move(*bank);
        m.reference = uploadMipmapped(m.bank.reference, stats.textureBytes);
        stats.loadedMaterials.push_back(name);
    }
    for (const auto& [name, path] : scene.materials)
        if (!materials.count(name)) stats.skippedMaterials.push_back(name);

    GlTexture target = makeTexture(), depth = makeTexture();
    gl.BindTexture(GL_TEXTURE_2D, target.id());
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, scene.width, scene.height, 0, GL_RGBA, GL_FLOAT, nullptr);
    gl.BindTexture(GL_TEXTURE_2D, depth.id());
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, scene.width, scene.height, 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                  nullptr);
    GlFramebuffer framebuffer = makeFramebuffer();
    gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target.id(), 0);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth.id(), 0);
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return Error{"the GL driver cannot render to a float image with depth"};
    gl.Viewport(0, 0, scene.width, scene.height);
    gl.ClearColor(0, 0, 0, 1);
    gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl.Enable(GL_DEPTH_TEST);
    GlVertexArray vao = makeVertexArray();
    gl.BindVertexArray(vao.id());
    const std::array<float, 16> matrix = viewProjection(scene);

    std::map<std::vector<std::string>, GlProgram> programs;  // by defines
    for (std::size_t i : visible) {
        const SceneQuad& quad = scene.quads[i];
        Material& material = materials.at(quad.material);
        const Vec3 local = toQuadFrame(quad, scene.light);
        const bool unlit = quad.mode == RenderMode::Lut && local.z <= 1e-9;  // flat shows the texture as is
        std::vector<std::string> defines;
        if (unlit) defines.push_back("UNLIT");
        if (quad.mode == RenderMode::Lut) defines.push_back("LUT_MODE");
        if (material.bank.colour == ColourMode::Rgb) defines.push_back("RGB_MODE");
        auto found = programs.find(defines);
        if (found == programs.end()) {
            Result<GlProgram> program = buildProgram({"scene.vert"}, {"lut_common.glsl", "scene.frag"}, defines);
            if (!program) return Error{program.error()};
            found = programs.emplace(defines, std::move(*program)).first;
        }
        const GLuint p = found->second.id();
        gl.UseProgram(p);
        std::vector<GlTexture> luts;
        if (quad.mode == RenderMode::Lut && !unlit) {
            // The view direction of the quad's centre picks the view layer(s).
            const Vec3 eyeLocal = toQuadFrame(
                quad, {scene.eye.x - quad.center.x, scene.eye.y - quad.center.y, scene.eye.z - quad.center.z});
            const Direction view = eyeLocal.z > 0 ? fromVector(eyeLocal) : Direction{};
            const BankLookup lookup = material.bank.lookup(fromVector(local), view);
            for (int c = 0; c < material.bank.channels(); ++c) {
                luts.push_back(uploadLut(&lookup.values[static_cast<std::size_t>(c) * material.bank.entries],
                                         material.bank.entries));
                stats.textureBytes += static_cast<std::size_t>(material.bank.entries) * 4;
            }
        }
        gl.ActiveTexture(GL_TEXTURE0);
        gl.BindTexture(GL_TEXTURE_2D, material.reference.id());
        gl.Uniform1i(gl.GetUniformLocation(p, "reference"), 0);
        for (int c = 0; c < 3 && !luts.empty(); ++c) {
            gl.ActiveTexture(static_cast<GLenum>(GL_TEXTURE1 + c));
            gl.BindTexture(GL_TEXTURE_1D, luts[static_cast<std::size_t>(std::min<int>(c, static_cast<int>(luts.size()) - 1))].id());
            const std::string name = "lut[" + std::to_string(c) + "]";
            gl.Uniform1i(gl.GetUniformLocation(p, name.c_str()), 1 + c);
        }
        gl.Uniform1i(gl.GetUniformLocation(p, "entries"), material.bank.entries);
        gl.UniformMatrix4fv(gl.GetUniformLocation(p, "viewProjection"), 1, GL_FALSE, matrix.data());
        const Vec3 t = quad.tangent, n = quad.normal;
        const Vec3 b{n.y * t.z - n.z * t.y, n.z * t.x - n.x * t.z, n.x * t.y - n.y * t.x};
        gl.Uniform3f(gl.GetUniformLocation(p, "center"), static_cast<float>(quad.center.x),
                     static_cast<float>(quad.center.y), static_cast<float>(quad.center.z));
        gl.Uniform3f(gl.GetUniformLocation(p, "halfTangent"), static_cast<float>(t.x * quad.width / 2),
                     static_cast<float>(t.y * quad.width / 2), static_cast<float>(t.z * quad.width / 2));
        gl.Uniform3f(gl.GetUniformLocation(p, "halfBitangent"), static_cast<float>(b.x * quad.height / 2),
                     static_cast<float>(b.y * quad.height / 2), static_cast<float>(b.z * quad.height / 2));
        gl.Uniform1f(gl.GetUniformLocation(p, "uvScale"), static_cast<float>(quad.uvScale));
        gl.DrawArrays(GL_TRIANGLES, 0, 6);
        ++stats.quadsDrawn;
        stats.quadsUnlit += unlit;
    }
    gl.Disable(GL_DEPTH_TEST);
    std::vector<float> rgba(static_cast<std::size_t>(scene.width) * scene.height * 4);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.ReadPixels(0, 0, scene.width, scene.height, GL_RGBA, GL_FLOAT, rgba.data());
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    if (GLenum error = gl.GetError(); error != GL_NO_ERROR)
        return Error{"OpenGL error " + std::to_string(error) + " while rendering " + scene.file};
    Image out(scene.width, scene.height, 3);
    for (int row = 0; row < scene.height; ++row)
        for (int x = 0; x < scene.width; ++x)
            for (int c = 0; c < 3; ++c)
                out.at(x, row, c) = rgba[(static_cast<std::size_t>(scene.height - 1 - row) * scene.width + x) * 4 + c];
    return out;
}

}  // namespace btflut

#include "gl/scene_renderer.h"

#include "core/bank_file.h"
#include "gl/shader.h"
#include "gl/textures.h"

namespace btflut {

namespace {

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
    bytes += image.pixelCount() * (sixteen ? 8 : 4) * 4 / 3;  // drivers pad RGB to RGBA; mipmaps add 1/3
    return texture;
}

const char* modeDefine(RenderMode mode) {
    switch (mode) {
        case RenderMode::Lut: return "LUT_MODE";
        case RenderMode::Brdf: return "BRDF_MODE";
        case RenderMode::Flat: return "FLAT_MODE";
    }
    return "";
}

}  // namespace

Result<std::unique_ptr<SceneRenderer>> SceneRenderer::create(const Scene& scene) {
    std::unique_ptr<SceneRenderer> r(new SceneRenderer());
    r->m_scene = scene;
    const std::vector<std::size_t> visible = visibleQuads(scene);
    r->m_stats.quadsCulled = scene.quads.size() - visible.size();
    for (std::size_t i : visible) {
        const std::string& name = scene.quads[i].material;
        if (!r->m_materials.count(name)) {
            Result<LutBank> bank = loadBank(scene.materials.at(name));
            if (!bank) return Error{bank.error()};
            if (bank->reference.samples.empty())
                return Error{scene.materials.at(name) + ": the bank has no reference image inside"};
            Material& m = r->m_materials[name];
            m.bank = std::move(*bank);
            m.reference = uploadMipmapped(m.bank.reference, r->m_stats.textureBytes);
            m.referenceGrey = countGreyLevels(m.bank.reference, fullMask(m.bank.reference.width, m.bank.reference.height));
            r->m_stats.loadedMaterials.push_back(name);
        }
        QuadState q{i, {}};
        const LutBank& bank = r->m_materials.at(name).bank;
        for (int c = 0; c < bank.channels(); ++c) {
            q.luts.push_back(uploadLut(std::vector<float>(static_cast<std::size_t>(bank.entries)).data(), bank.entries));
            r->m_stats.textureBytes += static_cast<std::size_t>(bank.entries) * 4;
        }
        r->m_quads.push_back(std::move(q));
    }
    for (const auto& [name, path] : scene.materials)
        if (!r->m_materials.count(name)) r->m_stats.skippedMaterials.push_back(name);

    r->m_target = makeTexture();
    gl.BindTexture(GL_TEXTURE_2D, r->m_target.id());
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, scene.width, scene.height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    r->m_depth = makeTexture();
    gl.BindTexture(GL_TEXTURE_2D, r->m_depth.id());
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, scene.width, scene.height, 0, GL_DEPTH_COMPONENT, GL_FLOAT,
                  nullptr);
    r->m_framebuffer = makeFramebuffer();
    gl.BindFramebuffer(GL_FRAMEBUFFER, r->m_framebuffer.id());
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, r->m_target.id(), 0);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, r->m_depth.id(), 0);
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return Error{"the GL driver cannot render to an RGBA8 image with depth"};
    r->m_vertexArray = makeVertexArray();
    return r;
}

Result<GLuint> SceneRenderer::program(RenderMode mode, const LutBank& bank) {
    std::vector<std::string> defines{modeDefine(mode)};
    if (bank.colour == ColourMode::Rgb) defines.push_back("RGB_MODE");
    auto found = m_programs.find(defines);
    if (found == m_programs.end()) {
        Result<GlProgram> p = buildProgram({"scene.vert"}, {"lut_common.glsl", "scene.frag"}, defines);
        if (!p) return Error{p.error()};
        found = m_programs.emplace(defines, std::move(*p)).first;
    }
    return found->second.id();
}

void SceneRenderer::updateLut(QuadState& q, const Vec3& light) {
    if (light.x == q.lightUploaded.x && light.y == q.lightUploaded.y && light.z == q.lightUploaded.z) return;
    q.lightUploaded = light;
    const SceneQuad& quad = m_scene.quads[q.index];
    const Material& material = m_materials.at(quad.material);
    const Vec3 local = toQuadFrame(quad, light);
    q.unlit = local.z <= 1e-9;
    if (q.unlit) return;
    // The view direction of the quad's centre picks the view layer(s).
    const Vec3 eye = toQuadFrame(quad, {m_scene.eye.x - quad.center.x, m_scene.eye.y - quad.center.y,
                                        m_scene.eye.z - quad.center.z});
    const LutBank& bank = material.bank;
    const BankLookup lookup = bank.lookup(fromVector(local), eye.z > 0 ? fromVector(eye) : Direction{});
    for (std::size_t c = 0; c < q.luts.size(); ++c) {
        gl.BindTexture(GL_TEXTURE_1D, q.luts[c].id());
        gl.TexSubImage1D(GL_TEXTURE_1D, 0, 0, bank.entries, GL_RED, GL_FLOAT,
                         &lookup.values[c * static_cast<std::size_t>(bank.entries)]);
    }
    // brdf mode: the mean grey the LUT gives the reference, over the reference's own mean.
    const LevelCounts& grey = material.referenceGrey;
    double target = 0, reference = 0;
    for (std::size_t k = 0; k < grey.counts.size(); ++k) {
        if (!grey.counts[k]) continue;
        const auto v = static_cast<float>(grey.valueOf(k));
        target += static_cast<double>(grey.counts[k]) * Lut::applyLut(lookup.values.data(), bank.entries, v);
        reference += static_cast<double>(grey.counts[k]) * v;
    }
    q.brightness = reference > 0 ? static_cast<float>(target / reference) : 1.f;
}

Status SceneRenderer::draw(const Vec3& light, std::optional<RenderMode> modeOverride) {
    gl.BindFramebuffer(GL_FRAMEBUFFER, m_framebuffer.id());
    gl.Viewport(0, 0, m_scene.width, m_scene.height);
    gl.ClearColor(0, 0, 0, 1);
    gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl.Enable(GL_DEPTH_TEST);
    gl.BindVertexArray(m_vertexArray.id());
    const std::array<float, 16> matrix = viewProjection(m_scene);
    m_stats.quadsDrawn = m_stats.quadsUnlit = 0;
    for (QuadState& q : m_quads) {
        const SceneQuad& quad = m_scene.quads[q.index];
        const Material& material = m_materials.at(quad.material);
        const RenderMode mode = modeOverride.value_or(quad.mode);
        if (mode != RenderMode::Flat) updateLut(q, light);
        Result<GLuint> p = program(mode, material.bank);
        if (!p) return Error{p.error()};
        gl.UseProgram(*p);
        gl.ActiveTexture(GL_TEXTURE0);
        gl.BindTexture(GL_TEXTURE_2D, material.reference.id());
        gl.Uniform1i(gl.GetUniformLocation(*p, "reference"), 0);
        for (int c = 0; c < 3; ++c) {
            gl.ActiveTexture(static_cast<GLenum>(GL_TEXTURE1 + c));
            gl.BindTexture(GL_TEXTURE_1D, q.luts[std::min<std::size_t>(static_cast<std::size_t>(c), q.luts.size() - 1)].id());
            const std::string name = "lut[" + std::to_string(c) + "]";
            gl.Uniform1i(gl.GetUniformLocation(*p, name.c_str()), 1 + c);
        }
        const bool unlit = mode != RenderMode::Flat && q.unlit;
        gl.Uniform1i(gl.GetUniformLocation(*p, "entries"), material.bank.entries);
        gl.Uniform1i(gl.GetUniformLocation(*p, "unlit"), unlit ? 1 : 0);
        gl.Uniform1f(gl.GetUniformLocation(*p, "brightness"), q.brightness);
        gl.UniformMatrix4fv(gl.GetUniformLocation(*p, "viewProjection"), 1, GL_FALSE, matrix.data());
        const Vec3 t = quad.tangent, n = quad.normal;
        const Vec3 b{n.y * t.z - n.z * t.y, n.z * t.x - n.x * t.z, n.x * t.y - n.y * t.x};
        auto f = [](double v) { return static_cast<float>(v); };
        gl.Uniform3f(gl.GetUniformLocation(*p, "center"), f(quad.center.x), f(quad.center.y), f(quad.center.z));
        gl.Uniform3f(gl.GetUniformLocation(*p, "halfTangent"), f(t.x * quad.width / 2), f(t.y * quad.width / 2),
                     f(t.z * quad.width / 2));
        gl.Uniform3f(gl.GetUniformLocation(*p, "halfBitangent"), f(b.x * quad.height / 2), f(b.y * quad.height / 2),
                     f(b.z * quad.height / 2));
        gl.Uniform1f(gl.GetUniformLocation(*p, "uvScale"), f(quad.uvScale));
        gl.DrawArrays(GL_TRIANGLES, 0, 6);
        ++m_stats.quadsDrawn;
        m_stats.quadsUnlit += unlit;
    }
    gl.Disable(GL_DEPTH_TEST);
    if (GLenum error = gl.GetError(); error != GL_NO_ERROR)
        return Error{"OpenGL error " + std::to_string(error) + " while rendering " + m_scene.file};
    return success();
}

void SceneRenderer::finish() const { gl.Finish(); }

Image SceneRenderer::readBack() const {
    std::vector<unsigned char> rgba(static_cast<std::size_t>(m_scene.width) * m_scene.height * 4);
    gl.BindFramebuffer(GL_FRAMEBUFFER, m_framebuffer.id());
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.ReadPixels(0, 0, m_scene.width, m_scene.height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    Image out(m_scene.width, m_scene.height, 3);
    for (int row = 0; row < m_scene.height; ++row)
        for (int x = 0; x < m_scene.width; ++x)
            for (int c = 0; c < 3; ++c)
                out.at(x, row, c) =
                    rgba[(static_cast<std::size_t>(m_scene.height - 1 - row) * m_scene.width + x) * 4 + c] / 255.f;
    return out;
}

Result<Image> renderScene(const Scene& scene, RenderStats& stats) {
    Result<std::unique_ptr<SceneRenderer>> renderer = SceneRenderer::create(scene);
    if (!renderer) return Error{renderer.error()};
    if (Status s = (*renderer)->draw(scene.light); !s) return Error{s.error()};
    stats = (*renderer)->stats();
    return (*renderer)->readBack();
}

}  // namespace btflut

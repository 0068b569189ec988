#include "gl/scene_renderer.h"

#include <algorithm>

#include "core/bank/bank_file.h"
#include "core/check.h"
#include "core/relight/engine_material.h"
#include "gl/shader.h"
#include "gl/textures.h"

namespace btflut {

namespace {

const char* modeDefine(RenderMode mode) {
    switch (mode) {
        case RenderMode::Lut:
            return "LUT_MODE";
        case RenderMode::Brdf:
            return "BRDF_MODE";
        case RenderMode::Ptm:
            return "PTM_MODE";
        case RenderMode::Flat:
            return "FLAT_MODE";
        case RenderMode::Nearest:
            return "NEAREST_MODE";
    }
    return "";
}

}  // namespace

Result<std::unique_ptr<SceneRenderer>> SceneRenderer::create(const Scene& scene, const SceneRendererOptions& options) {
    std::unique_ptr<SceneRenderer> r(new SceneRenderer());
    r->m_scene = scene;
    r->m_interpolate = scene.interpolateLuts;
    r->m_exactMatch = scene.exactMatch;
    r->m_lutPath = options.lutPath;
    r->m_predictionOnly = options.predictionOnly;
    r->m_dither = scene.dither;
    r->m_fixedCamera = options.fixedCamera;
    const std::vector<std::size_t> visible = visibleQuads(scene);
    r->m_stats.quadsCulled = scene.quads.size() - visible.size();
    for (std::size_t i : visible) {
        const std::string& name = scene.quads[i].material;
        if (!r->m_materials.count(name)) {
            const std::string& path = scene.materials.at(name).bank;
            // Not the PTM (read when a ptm quad is drawn), nor the grids of LUTs (the renderer
            // blends nodes; a bank with a predictor keeps its match grids, Relighter::gridFrame),
            // nor, for a fixed camera, view layers that no visible quad looks along.
            BankReadOptions read{.ptm = false, .grids = false};
            if (options.fixedCamera) read.views = r->viewsOf(name, visible);
            Result<LutBank> bank = loadBank(path, read);
            if (!bank) return Error{bank.error()};
            r->m_stats.viewLayers += bank->layers.size();
            for (const ViewLayer& layer : bank->layers) r->m_stats.viewLayersLoaded += layer.lutsLoaded;
            if (bank->reference.samples.empty()) return Error{path + ": the bank has no reference image inside"};
            if (Status s = drawnOnGpu(*bank); !s) return Error{path + ": " + s.error()};
            Material& m = r->m_materials[name];
            m.bank = std::move(*bank);
            m.relighter.emplace(m.bank);
            m.referenceGrey = brdfReferenceGrey(m.bank);
            r->m_stats.loadedMaterials.push_back(name);
        }
        QuadState q{i, {}};
        r->m_quads.push_back(std::move(q));
    }
    for (const auto& [name, paths] : scene.materials)
        if (!r->m_materials.count(name)) r->m_stats.skippedMaterials.push_back(name);

    if (Status size = r->resize(scene.width, scene.height); !size) return Error{size.error()};
    r->m_vertexArray = makeVertexArray();
    return r;
}

Status SceneRenderer::resize(int width, int height) {
    if (width < 1 || height < 1)
        return Error{"image size " + std::to_string(width) + "x" + std::to_string(height) + " is empty"};
    if (m_target.id() && width == m_scene.width && height == m_scene.height) return success();
    m_scene.width = width;
    m_scene.height = height;
    Result<ColourDepthTarget> target = allocateColourDepthTarget(width, height);
    if (!target) return Error{target.error()};
    m_target = std::move(target->colour);
    m_depth = std::move(target->depth);
    m_framebuffer = std::move(target->framebuffer);
    return success();
}

void SceneRenderer::setCamera(const Vec3& eye, const Vec3& target, const Vec3& up, double orthographicHeight) {
    BTFLUT_CHECK(!m_fixedCamera);  // created with SceneRendererOptions::fixedCamera false
    m_scene.eye = eye;
    m_scene.target = target;
    m_scene.up = up;
    m_scene.orthographicHeight = orthographicHeight;
}

void SceneRenderer::setInterpolation(bool interpolate) {
    if (interpolate == m_interpolate) return;
    m_interpolate = interpolate;
    for (QuadState& q : m_quads) q.lightUploaded = kNoLight;  // blend again
    for (auto& [name, m] : m_materials) m.relit.clear();      // relight again
}

const LutBank* SceneRenderer::bank(const std::string& material) const {
    auto it = m_materials.find(material);
    return it == m_materials.end() ? nullptr : &it->second.bank;
}

Result<const ShaderProgram*> SceneRenderer::program(RenderMode mode, const Material& material, bool unlit,
                                                    bool perFragment) {
    const LutBank& bank = material.bank;
    std::vector<std::string> defines{unlit ? "UNLIT" : modeDefine(mode)};
    if (!unlit && mode == RenderMode::Lut && (bank.layers.size() == 1 || bank.makesLuts())) {
        // A bank of one view layer (or a predictor of views): its relit texture, drawn flat; or
        // relit per fragment.
        defines = {perFragment ? "LUT_FRAGMENT" : "FLAT_MODE"};
        if (perFragment) {
            // The pass's defines, made once per material: the predictor is not made per frame.
            BTFLUT_CHECK(material.pass.has_value());  // prepare makes it for every quad drawn this way
            const std::vector<std::string>& pass = material.pass->defines();
            defines.insert(defines.end(), pass.begin(), pass.end());
            if (bank.makesLuts()) defines.push_back("PREDICT_FILTERED");
            if (bank.reference.channels == 1) defines.push_back("GREY_TEXTURE");
            if (m_dither) defines.push_back("DITHER");
            if (m_predictionOnly) defines.push_back("PREDICTION_ONLY");
        }
    } else if (!unlit && mode == RenderMode::Lut) {
        if (bank.colour == ColourMode::Rgb) defines.push_back("RGB_MODE");
        if (bank.reference.channels == 1) defines.push_back("GREY_TEXTURE");
    }
    // A predictor's own source (a learned decoder) goes with its pass's defines, which name it.
    static const std::vector<ShaderFile> none;
    const std::vector<ShaderFile>& sources =
        defines.front() == "LUT_FRAGMENT" && material.pass ? material.pass->sources() : none;
    // Programs by defines and, for sources made per material, by the material's source.
    std::vector<std::string> key = defines;
    for (const ShaderFile& f : sources) key.push_back(std::to_string(reinterpret_cast<std::uintptr_t>(f.text.data())));
    auto found = m_programs.find(key);
    if (found == m_programs.end()) {
        Result<ShaderProgram> p =
            buildProgram({"scene.vert"}, {"btflut.glsl", "lut_common.glsl", "scene.frag"}, defines, sources);
        if (!p) return Error{p.error()};
        found = m_programs.emplace(std::move(key), std::move(*p)).first;
    }
    return &found->second;
}

Status SceneRenderer::draw(const Vec3& light, std::optional<RenderMode> modeOverride) {
    std::vector<RenderMode> modes;
    for (QuadState& q : m_quads) {
        const RenderMode mode = modeOverride.value_or(m_scene.quads[q.index].mode);
        modes.push_back(mode);
        update(q, light, mode);
        if (Status s = prepare(q, mode, light); !s) return s;
    }
    choosePaths(modes);
    if (Status s = relight(modes); !s) return s;
    gl.BindFramebuffer(GL_FRAMEBUFFER, m_framebuffer.id());
    gl.Viewport(0, 0, m_scene.width, m_scene.height);
    gl.ClearColor(0, 0, 0, 1);
    gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl.Enable(GL_DEPTH_TEST);
    gl.BindVertexArray(m_vertexArray.id());
    const std::array<float, 16> matrix = viewProjection(m_scene);
    m_stats.quadsDrawn = m_stats.quadsUnlit = 0;
    for (std::size_t i = 0; i < m_quads.size(); ++i) {
        QuadState& q = m_quads[i];
        const SceneQuad& quad = m_scene.quads[q.index];
        const RenderMode mode = modes[i];
        const Material& material = m_materials.at(quad.material);
        const bool unlit = mode != RenderMode::Flat && q.unlit;
        Result<const ShaderProgram*> program = this->program(mode, material, unlit, q.perFragment);
        if (!program) return Error{program.error()};
        const ShaderProgram& p = **program;
        gl.UseProgram(p.id());
        auto bind = [&](int unit, GLenum target, GLuint texture, const char* name) {
            gl.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + unit));
            gl.BindTexture(target, texture);
            gl.Uniform1i(p[name], unit);
        };
        if (unlit) {
            // black: nothing to bind
        } else if (mode == RenderMode::Ptm) {
            bind(0, GL_TEXTURE_2D, material.ptm[0].id(), "ptmLow");
            bind(1, GL_TEXTURE_2D, material.ptm[1].id(), "ptmHigh");
            bind(2, GL_TEXTURE_2D, material.ptm[2].id(), "ptmAlbedo");
            // The light's PTM weights (ptmWeights: on texels in [0, 1]) as btflut.glsl's
            // BtflutModelFrame on the coefficient bytes, in 1 / kWeightUnit: the PTM is a light
            // model of six planes drawn by the one predictor.
            const std::array<float, 7>& w = q.ptmWeights;
            const float unit = static_cast<float>(kWeightUnit) / 255.f;
            const float weights[8] = {w[0] * unit, w[1] * unit, w[2] * unit, w[3] * unit,
                                      w[4] * unit, w[5] * unit, 0,           0};
            gl.Uniform4fv(p["ptmFrame.weights[0]"], 1, weights);
            gl.Uniform4fv(p["ptmFrame.weights[3]"], 1, weights + 4);
            gl.Uniform3f(p["ptmFrame.offset"], w[6] * static_cast<float>(kWeightUnit), 0, 0);
            gl.Uniform1f(p["ptmFrame.scale"], 1.f);
        } else if (mode == RenderMode::Nearest) {
            bind(0, GL_TEXTURE_2D, material.imageTextures.at(q.nearestImage).id(), "reference");
        } else if (relitInTextureSpace(q, mode)) {
            bind(0, GL_TEXTURE_2D, material.relit[q.relit].texture.id(), "reference");
        } else if (relitLut(q, mode)) {
            bindPerFragment(p, q, material);
        } else {
            bind(0, GL_TEXTURE_2D, material.reference.id(), "reference");
        }
        if (mode == RenderMode::Lut && !unlit && !relitLut(q, mode)) {
            for (int c = 0; c < 3; ++c) {  // every sampler on a unit of its own type, even unused ones
                gl.ActiveTexture(static_cast<GLenum>(GL_TEXTURE0 + 1 + c));
                gl.BindTexture(GL_TEXTURE_3D,
                               q.luts[std::min<std::size_t>(static_cast<std::size_t>(c), q.luts.size() - 1)].id());
            }
            const GLint units[3] = {1, 2, 3};
            gl.Uniform1iv(p["lut"], 3, units);
            const auto n = static_cast<float>(material.bank.entries);
            gl.Uniform2f(p["lutCoordinate"], (n - 1) / n, 0.5f / n);
            gl.Uniform1i(p["viewGrid"], kViewGrid);
            gl.Uniform1i(p["mipLevels"], material.mipLuts->levels());
            gl.Uniform2f(p["referenceSize"], static_cast<float>(material.bank.reference.width),
                         static_cast<float>(material.bank.reference.height));
        }
        gl.Uniform1f(p["brightness"], q.brightness);
        gl.UniformMatrix4fv(p["viewProjection"], 1, GL_FALSE, matrix.data());
        const Vec3 t = quad.tangent, b = bitangentOf(quad);
        auto f = [](double v) { return static_cast<float>(v); };
        gl.Uniform3f(p["center"], f(quad.center.x), f(quad.center.y), f(quad.center.z));
        gl.Uniform3f(p["halfTangent"], f(t.x * quad.width / 2), f(t.y * quad.width / 2), f(t.z * quad.width / 2));
        gl.Uniform3f(p["halfBitangent"], f(b.x * quad.height / 2), f(b.y * quad.height / 2), f(b.z * quad.height / 2));
        gl.Uniform1f(p["uvScale"], f(quad.uvScale));
        gl.DrawArrays(GL_TRIANGLES, 0, 6);
        ++m_stats.quadsDrawn;
        m_stats.quadsUnlit += unlit;
    }
    gl.Disable(GL_DEPTH_TEST);
    if (GLenum error = gl.GetError(); error != GL_NO_ERROR)
        return Error{"OpenGL error " + std::to_string(error) + " while rendering " + m_scene.file};
    return success();
}

// LUT_FRAGMENT's textures and uniforms: the reference (unit 0) or the blend's textures, and
// the quad's frame (its LUTs, and a predictor's weights), from unit 1.
void SceneRenderer::bindPerFragment(const ShaderProgram& p, const QuadState& q, const Material& material) const {
    const LutBank& bank = material.bank;
    if (!bank.makesLuts()) {
        gl.ActiveTexture(GL_TEXTURE0);
        gl.BindTexture(GL_TEXTURE_2D, material.reference.id());
        gl.Uniform1i(p["reference"], 0);
    }
    material.pass->bindLuts(p, q.frame, q.luts, 1);
    gl.Uniform2i(p["texels"], bank.reference.width, bank.reference.height);
}

void SceneRenderer::finish() const { gl.Finish(); }

FrameSamples SceneRenderer::sampleFrame(int stride) {
    FrameSamples s;
    s.stride = stride | 1;
    s.width = std::max(1, m_scene.width / s.stride), s.height = std::max(1, m_scene.height / s.stride);
    s.frameHeight = m_scene.height;
    if (!m_samples.colour.id() || m_samplesWidth != s.width || m_samplesHeight != s.height) {
        Result<ColourDepthTarget> target = allocateColourDepthTarget(s.width, s.height);
        if (!target) return {};
        m_samples = std::move(*target);
        m_samplesWidth = s.width, m_samplesHeight = s.height;
    }
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, m_framebuffer.id());
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, m_samples.framebuffer.id());
    gl.BlitFramebuffer(0, 0, s.width * s.stride, s.height * s.stride, 0, 0, s.width, s.height,
                       GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT, GL_NEAREST);
    const auto n = static_cast<std::size_t>(s.width) * s.height;
    std::vector<std::uint8_t> rgba(n * 4);
    std::vector<float> depth(n);
    gl.BindFramebuffer(GL_FRAMEBUFFER, m_samples.framebuffer.id());
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.ReadPixels(0, 0, s.width, s.height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    gl.ReadPixels(0, 0, s.width, s.height, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
    s.rgb.resize(n * 3);
    s.covered.resize(n);
    for (int j = 0; j < s.height; ++j)  // GL's rows run bottom up
        for (int i = 0; i < s.width; ++i) {
            const std::size_t from = static_cast<std::size_t>(s.height - 1 - j) * s.width + i;
            const std::size_t to = static_cast<std::size_t>(j) * s.width + i;
            std::copy_n(&rgba[from * 4], 3, &s.rgb[to * 3]);
            s.covered[to] = depth[from] < 1.f;
        }
    return s;
}

Image SceneRenderer::readBack() const { return readFramebufferRgb(m_framebuffer.id(), m_scene.width, m_scene.height); }

Result<Image> renderScene(const Scene& scene, RenderStats& stats) {
    Result<std::unique_ptr<SceneRenderer>> renderer = SceneRenderer::create(scene);
    if (!renderer) return Error{renderer.error()};
    if (Status s = (*renderer)->draw(scene.light); !s) return Error{s.error()};
    stats = (*renderer)->stats();
    return (*renderer)->readBack();
}

}  // namespace btflut

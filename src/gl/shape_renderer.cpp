#include "gl/shape_renderer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/bank/bank_file.h"
#include "gl/gl_api.h"
#include "gl/shader.h"
#include "gl/textures.h"

namespace btflut {

namespace {

constexpr int kAround = 128, kAlong = 64;  // cells: smooth silhouettes at viewer sizes
constexpr int kMaxLayers = 16;             // shape.frag's layerViews[]

std::string gridNoteOf(const LutBank& bank) {
    std::size_t clamped = 0, modelled = 0;
    for (Provenance p : bank.layers[0].gridProvenance) {
        clamped += p == Provenance::Clamped;
        modelled += p == Provenance::Modelled;
    }
    double measured = 0;
    for (const LightNode& n : bank.layers[0].nodes)
        if (!n.modelled) measured = std::max(measured, n.light.thetaDegrees());
    char line[200];
    if (clamped > 0)
        std::snprintf(line, sizeof line,
                      "lights beyond theta %.0f were not measured: there the LUTs are clamped to the nearest "
                      "measured ones (the rim of a curved object; bake --fill model to model them)",
                      measured);
    else if (modelled > 0)
        std::snprintf(line, sizeof line, "lights beyond theta %.0f come from the fitted model (bake --fill model)",
                      measured);
    else
        return {};
    return line;
}

}  // namespace

Result<std::unique_ptr<ShapeRenderer>> ShapeRenderer::create(const std::string& bankPath) {
    Result<LutBank> loaded = loadBank(bankPath, {.ptm = false});
    if (!loaded) return Error{loaded.error()};
    LutBank& bank = *loaded;
    if (bank.layers.size() > kMaxLayers)
        return Error{"the sphere and the cylinder draw banks of up to " + std::to_string(kMaxLayers) + " view layers"};
    Result<EngineMaterial> material = engineMaterial(bank, bankPath);
    if (!material) return Error{material.error()};
    std::vector<std::string> defines;
    if (bank.makesLuts()) defines.push_back("PREDICTOR");
    // A learned model's decoder specialised to it (it defines BTFLUT_NETWORK), as an export's.
    const std::string decoder = material->networkGlsl;
    std::vector<ShaderFile> generated;
    if (!decoder.empty()) generated.push_back({"btflut_network.glsl (generated)", decoder});
    Result<ShaderProgram> program = buildProgram({"shape.vert"}, {"btflut.glsl", "shape.frag"}, defines, generated);
    if (!program) return Error{program.error()};
    std::unique_ptr<ShapeRenderer> r(new ShapeRenderer);
    r->m_program = std::move(*program);
    r->m_vertexArray = makeVertexArray();
    std::size_t bytes = 0;
    r->m_reference = uploadMipmapped(bank.reference, bytes);  // repeats
    r->m_textures = EngineTextures::upload(*material, bytes);
    r->m_gridNote = gridNoteOf(bank);
    r->m_window = sampleWindow(bank);
    r->m_bank = std::move(*loaded);
    // The textures are on the GPU now: keep what bind() reads (the scalars, and whether there is
    // an albedo), not a second copy of the images.
    material->lutTexels = {};
    material->reference = Image();
    material->images = {};
    material->weightGrid = {};
    material->labels = Image();
    r->m_material = std::move(*material);
    return r;
}

Status ShapeRenderer::draw(const ShapeFrame& frame, int width, int height) {
    if (width != m_width || height != m_height) {
        Result<ColourDepthTarget> target = allocateColourDepthTarget(width, height);
        if (!target) return Error{target.error()};
        m_target = std::move(*target);
        m_width = width, m_height = height;
    }
    Scene camera;
    camera.width = width, camera.height = height;
    camera.eye = frame.eye, camera.target = frame.target, camera.up = frame.up;
    camera.fovDegrees = frame.fovDegrees;
    const std::array<float, 16> m = viewProjection(camera);

    gl.BindFramebuffer(GL_FRAMEBUFFER, m_target.framebuffer.id());
    gl.Viewport(0, 0, width, height);
    gl.ClearColor(0, 0, 0, 1);
    gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    gl.Enable(GL_DEPTH_TEST);
    const ShaderProgram& p = m_program;
    gl.UseProgram(p.id());
    auto location = [&](const char* name) { return p[name]; };
    gl.UniformMatrix4fv(location("viewProjection"), 1, GL_FALSE, m.data());
    gl.Uniform1i(location("shape"), frame.shape == Shape::Sphere ? 0 : 1);
    gl.Uniform1i(location("around"), kAround);
    gl.Uniform1i(location("along"), kAlong);
    // Texels about square: the sphere's equator is 2 pi round and pi from pole to pole; the
    // cylinder 2 pi round and 2 high.
    // A window (the mask's largest rectangle) is tiled mirrored: an even count around.
    const Image& reference = m_bank.reference;
    const std::optional<PixelRect>& window = m_window;
    const double aspect = window ? static_cast<double>(window->width) / window->height
                                 : static_cast<double>(reference.width) / reference.height;
    const double turn = (frame.shape == Shape::Sphere ? 2.0 : M_PI) / aspect;
    const double around = window ? 2 * std::max(1.0, std::round(turn / 2)) : std::max(1.0, std::round(turn));
    gl.Uniform2f(location("uvRepeats"), static_cast<float>(around), 1.f);
    gl.Uniform1i(location("windowed"), window ? 1 : 0);
    if (window) {
        // From its first texels' centres to its last's: bilinear filtering never reaches outside.
        const float w = static_cast<float>(reference.width), h = static_cast<float>(reference.height);
        const std::array<float, 4> rect{
            (static_cast<float>(window->x) + 0.5f) / w, (static_cast<float>(window->y) + 0.5f) / h,
            static_cast<float>(window->width - 1) / w, static_cast<float>(window->height - 1) / h};
        gl.Uniform4fv(location("window"), 1, rect.data());
    }
    gl.Uniform1i(location("pointLight"), frame.light.point ? 1 : 0);
    gl.Uniform3f(location("lightDirection"), static_cast<float>(frame.light.direction.x),
                 static_cast<float>(frame.light.direction.y), static_cast<float>(frame.light.direction.z));
    gl.Uniform3f(location("lightPosition"), static_cast<float>(frame.light.position.x),
                 static_cast<float>(frame.light.position.y), static_cast<float>(frame.light.position.z));
    gl.Uniform3f(location("eye"), static_cast<float>(frame.eye.x), static_cast<float>(frame.eye.y),
                 static_cast<float>(frame.eye.z));
    gl.Uniform1i(location("layers"), static_cast<int>(m_bank.layers.size()));
    std::vector<float> views;
    for (const ViewLayer& l : m_bank.layers) {
        const Vec3 v = toVector(l.view);
        views.insert(views.end(), {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)});
    }
    gl.Uniform3fv(location("layerViews"), static_cast<GLsizei>(m_bank.layers.size()), views.data());
    gl.Uniform1i(location("rgbLuts"), m_bank.colour == ColourMode::Rgb ? 1 : 0);
    gl.Uniform1i(location("greyReference"), m_bank.reference.channels == 1 ? 1 : 0);
    gl.Uniform1f(location("inputCode"), inputCode(m_bank.reference, m_bank.colour));
    gl.Uniform1f(location("outputCode"), m_bank.targetCode());
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, m_reference.id());
    gl.Uniform1i(location("reference"), 0);
    m_textures.bind(p, m_material, 1);
    gl.BindVertexArray(m_vertexArray.id());
    gl.DrawArrays(GL_TRIANGLES, 0, 6 * kAround * kAlong);
    gl.BindVertexArray(0);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.Disable(GL_DEPTH_TEST);
    return success();
}

}  // namespace btflut

#include "gl/shape_renderer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/bank/bank_file.h"
#include "core/predict/light_model.h"
#include "core/predict/relighter.h"
#include "gl/gl_api.h"
#include "gl/shader.h"
#include "gl/textures.h"

namespace btflut {

namespace {

constexpr int kAround = 128, kAlong = 64;  // cells: smooth silhouettes at viewer sizes
constexpr int kMaxLayers = 16;             // shape.frag's layerViews[]

// unorm16 LUTs as a 3D texture (x the LUT entry), a texture channel per LUT channel, linear,
// clamped: btflut.glsl's LUT grid.
GlTexture uploadLuts16(std::size_t entries, std::size_t height, std::size_t depth, std::size_t channels,
                       const std::uint16_t* texels) {
    GlTexture texture = makeTexture();
    gl.BindTexture(GL_TEXTURE_3D, texture.id());
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 2);
    gl.TexImage3D(GL_TEXTURE_3D, 0, channels == 3 ? GL_RGB16 : GL_R16, static_cast<GLsizei>(entries),
                  static_cast<GLsizei>(height), static_cast<GLsizei>(depth), 0, channels == 3 ? GL_RGB : GL_RED,
                  GL_UNSIGNED_SHORT, texels);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        gl.TexParameteri(GL_TEXTURE_3D, wrap, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    return texture;
}

// The grid of every view layer as one 3D texture: x the LUT entry, y grid column i, z layer *
// G + grid row j (docs/engines.md).
GlTexture uploadGrid(const LutBank& bank) {
    const auto g = static_cast<std::size_t>(bank.gridSize);
    return uploadLuts16(static_cast<std::size_t>(bank.entries), g, g * bank.layers.size(),
                        static_cast<std::size_t>(bank.channels()), bank.gridTexels().data());
}

// A bank with a light model: its match grid as one 3D texture, x the LUT entry, y grid column
// i, z region * G + grid row j, 16-bit, a texture channel per LUT channel.
GlTexture uploadMatchGrid(const LutBank& bank) {
    const std::vector<std::uint16_t>& grid = bank.layers[0].matchGridLuts;
    const auto g = static_cast<std::size_t>(bank.gridSize), entries = static_cast<std::size_t>(bank.entries),
               channels = static_cast<std::size_t>(bank.channels()), regions = static_cast<std::size_t>(bank.blend.regions);
    BTFLUT_CHECK(grid.size() == g * g * regions * channels * entries);
    std::vector<std::uint16_t> texels(grid.size());  // per node [region][channel][entry] -> [region][j][i][entry][channel]
    std::size_t at = 0;
    for (std::size_t r = 0; r < regions; ++r)
        for (std::size_t cell = 0; cell < g * g; ++cell)
            for (std::size_t k = 0; k < entries; ++k)
                for (std::size_t c = 0; c < channels; ++c) texels[at++] = grid[((cell * regions + r) * channels + c) * entries + k];
    return uploadLuts16(entries, g, g * regions, channels, texels.data());
}

// A predictor's weights over the light disk (lightModelWeightGrid, referenceWeightGrid:
// kWeightGrid nodes a side, `stride` per node) as a 2D array of RGBA32F layers, four weights
// to a layer, read bilinearly.
constexpr int kWeightGrid = 65;
std::size_t weightStride(const LutBank& bank) {
    const LightModel& m = bank.blend.model;
    return bank.predictsWithModel() ? static_cast<std::size_t>(m.planes * m.channels + m.channels) : bank.blend.references.size();
}
GlTexture uploadWeights(const LutBank& bank) {
    const std::vector<float> grid = bank.predictsWithModel() ? lightModelWeightGrid(bank.blend.model, kWeightGrid)
                                                             : referenceWeightGrid(bank, kWeightGrid);
    const std::size_t stride = weightStride(bank), layers = (stride + 3) / 4,
                      nodes = static_cast<std::size_t>(kWeightGrid) * kWeightGrid;
    std::vector<float> data(layers * nodes * 4, 0.f);
    for (std::size_t n = 0; n < nodes; ++n)
        for (std::size_t k = 0; k < stride; ++k) data[((k / 4) * nodes + n) * 4 + k % 4] = grid[n * stride + k];
    GlTexture texture = makeTexture();
    gl.BindTexture(GL_TEXTURE_2D_ARRAY, texture.id());
    gl.TexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA32F, kWeightGrid, kWeightGrid, static_cast<GLsizei>(layers), 0, GL_RGBA,
                  GL_FLOAT, data.data());
    gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return texture;
}

std::string gridNoteOf(const LutBank& bank) {
    std::size_t clamped = 0, modelled = 0;
    for (Provenance p : bank.layers[0].gridProvenance) {
        clamped += p == Provenance::Extrapolated;
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
        std::snprintf(line, sizeof line, "lights beyond theta %.0f come from the fitted model (bake --fill model)", measured);
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
    std::vector<std::string> defines;
    if (bank.makesLuts()) {
        defines = {"PREDICTOR", "WEIGHT_LAYERS " + std::to_string((weightStride(bank) + 3) / 4)};
        const LightModel& m = bank.blend.model;
        if (bank.predictsWithModel()) {
            defines.insert(defines.end(), {"MODEL", "MODEL_PLANES " + std::to_string(m.planes), "MODEL_WIDE " + std::to_string(m.wide),
                                           "MODEL_CHANNELS " + std::to_string(m.channels),
                                           "BLEND_MODEL_LAYERS " + std::to_string((m.wide + 2) / 3),
                                           "BLEND_MODEL_NIBBLE_LAYERS " + std::to_string((m.planes - m.wide + 5) / 6)});
            if (!m.albedo.empty()) defines.push_back("MODEL_ALBEDO");
        } else {
            defines.push_back("REFERENCE_COUNT " + std::to_string(bank.blend.references.size()));
            if (bank.colour == ColourMode::Lrgb) defines.push_back("LRGB");
            if (bank.blend.references.front().channels == 1) defines.push_back("GREY_REFERENCES");
        }
        if (bank.colour == ColourMode::Rgb) defines.push_back("RGB_MODE");
        if (bank.blend.regions > 1) defines.push_back("REGIONS");
    }
    Result<GlProgram> program = buildProgram({"shape.vert"}, {"btflut.glsl", "shape.frag"}, defines);
    if (!program) return Error{program.error()};
    std::unique_ptr<ShapeRenderer> r(new ShapeRenderer);
    r->m_program = std::move(*program);
    r->m_vertexArray = makeVertexArray();
    std::size_t bytes = 0;
    r->m_reference = uploadMipmapped(bank.reference, bytes);  // repeats
    if (bank.makesLuts()) {
        if (bank.layers[0].matchGridLuts.empty()) bakeMatchGrid(bank);  // a file older than the match grid
        r->m_luts = uploadMatchGrid(bank);
        r->m_weights = uploadWeights(bank);
    } else {
        r->m_luts = uploadGrid(bank);
    }
    r->m_gridNote = gridNoteOf(bank);
    r->m_bank = std::move(*loaded);
    if (r->m_bank.makesLuts()) r->m_planes = BlendTextures::upload(r->m_bank, bytes);  // refers to the bank: after the move
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
    const GLuint p = m_program.id();
    gl.UseProgram(p);
    auto location = [&](const char* name) { return gl.GetUniformLocation(p, name); };
    gl.UniformMatrix4fv(location("viewProjection"), 1, GL_FALSE, m.data());
    gl.Uniform1i(location("shape"), frame.shape == Shape::Sphere ? 0 : 1);
    gl.Uniform1i(location("around"), kAround);
    gl.Uniform1i(location("along"), kAlong);
    // Texels about square: the sphere's equator is 2 pi round and pi from pole to pole; the
    // cylinder 2 pi round and 2 high.
    const double aspect = static_cast<double>(m_bank.reference.width) / m_bank.reference.height;
    const float around = static_cast<float>(std::max(1.0, std::round((frame.shape == Shape::Sphere ? 2.0 : M_PI) / aspect)));
    gl.Uniform2f(location("uvRepeats"), around, 1.f);
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
    gl.ActiveTexture(GL_TEXTURE1);
    gl.BindTexture(GL_TEXTURE_3D, m_luts.id());
    gl.Uniform1i(location("luts"), 1);
    if (m_planes) {  // a predictor: its planes (or references), weights and labels; the codes its LUTs read
        gl.ActiveTexture(GL_TEXTURE2);
        gl.BindTexture(GL_TEXTURE_2D_ARRAY, m_planes->planes());
        gl.Uniform1i(location("planes"), 2);
        gl.ActiveTexture(GL_TEXTURE3);
        gl.BindTexture(GL_TEXTURE_2D_ARRAY, m_weights.id());
        gl.Uniform1i(location("modelWeights"), 3);
        if (m_planes->albedo()) {  // lrgb
            gl.ActiveTexture(GL_TEXTURE5);
            gl.BindTexture(GL_TEXTURE_2D, m_planes->albedo());
            gl.Uniform1i(location("albedo"), 5);
        }
        if (m_planes->labels()) {
            gl.ActiveTexture(GL_TEXTURE4);
            gl.BindTexture(GL_TEXTURE_2D, m_planes->labels());
            gl.Uniform1i(location("labels"), 4);
        }
        gl.Uniform2i(location("texels"), m_bank.reference.width, m_bank.reference.height);
        gl.Uniform1f(location("codes"), static_cast<float>(predictionCodes(m_bank)));
    }
    gl.BindVertexArray(m_vertexArray.id());
    gl.DrawArrays(GL_TRIANGLES, 0, 6 * kAround * kAlong);
    gl.BindVertexArray(0);
    gl.ActiveTexture(GL_TEXTURE0);
    gl.Disable(GL_DEPTH_TEST);
    return success();
}

}  // namespace btflut

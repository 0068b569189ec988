// What each quad of a scene needs per frame (SceneRenderer, scene_renderer.h): its light and
// view directions in its own frame, the LUTs or weights its mode applies, what is loaded the
// first time a mode needs it, and the texture-space relit textures of mode lut.
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "core/bank/bank_file.h"
#include "core/check.h"
#include "core/predict/ptm.h"
#include "gl/scene_renderer.h"
#include "gl/textures.h"

namespace btflut {

namespace {

bool sameVector(const Vec3& a, const Vec3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

}  // namespace

// Every view direction the renderer may look a material up at: the view grid of each
// visible quad that uses it (the centre is one of its points).
std::vector<Direction> SceneRenderer::viewsOf(const std::string& material,
                                              const std::vector<std::size_t>& visible) const {
    std::vector<Direction> views;
    for (std::size_t i : visible)
        if (m_scene.quads[i].material == material) {
            const std::vector<Direction> grid = viewGridDirections(m_scene.quads[i]);
            views.insert(views.end(), grid.begin(), grid.end());
        }
    return views;
}

// The view directions at kViewGrid x kViewGrid points spread over the quad, row by row from
// its (-1, -1) corner: the nodes of the LUT volume of a bank with view layers.
std::vector<Direction> SceneRenderer::viewGridDirections(const SceneQuad& quad) const {
    std::vector<Direction> views;
    for (int j = 0; j < kViewGrid; ++j)
        for (int i = 0; i < kViewGrid; ++i)
            views.push_back(fromVector(viewAt(quad, -1 + 2.0 * i / (kViewGrid - 1), -1 + 2.0 * j / (kViewGrid - 1))));
    return views;
}

// The direction from the quad point at corner coordinates (x, y) in [-1, 1]^2 to the eye,
// in the quad's frame; behind the quad it is clamped to just above the horizon.
Vec3 SceneRenderer::viewAt(const SceneQuad& quad, double x, double y) const {
    const Vec3 b = bitangentOf(quad);
    const double u = x * quad.width / 2, v = y * quad.height / 2;
    const Vec3 point{quad.center.x + u * quad.tangent.x + v * b.x, quad.center.y + u * quad.tangent.y + v * b.y,
                     quad.center.z + u * quad.tangent.z + v * b.z};
    // An orthographic camera looks the same way from everywhere: towards it from the target.
    const Vec3 from = m_scene.orthographicHeight > 0 ? m_scene.target : point;
    Vec3 view = toQuadFrame(quad, {m_scene.eye.x - from.x, m_scene.eye.y - from.y, m_scene.eye.z - from.z});
    view.z = std::max(view.z, 1e-6 * std::hypot(view.x, view.y, view.z));
    return view;
}

RelightFrame SceneRenderer::centreFrame(std::size_t quad, const Vec3& light) const {
    const SceneQuad& q = m_scene.quads[quad];
    const Material& material = m_materials.at(q.material);
    const Vec3 local = toQuadFrame(q, light);
    const Direction l = fromVector({local.x, local.y, std::max(local.z, 1e-9)}), v = fromVector(viewAt(q, 0, 0));
    return frameFor(material, l, v);
}

RelightFrame SceneRenderer::frameFor(const Material& material, Direction light, Direction view) const {
    const LutBank& bank = material.bank;
    if (bank.makesLuts() && m_interpolate && !m_exactMatch)
        return material.relighter->gridFrame(light, view);  // no counting of the prediction per light change
    return material.relighter->frame(light, view, m_interpolate);
}

// Per quad and frame, only what the mode needs and only when the light, the camera (for
// banks with view layers) or the mode changed: the LUT volume (lut, banks with view layers),
// the brightness (brdf), the PTM weights (ptm), the nearest image's name (nearest). Mode lut
// on a bank of one view layer needs only the light in the quad's frame (relight()).
void SceneRenderer::update(QuadState& q, const Vec3& light, RenderMode mode) {
    const SceneQuad& quad = m_scene.quads[q.index];
    const Material& material = m_materials.at(quad.material);
    const LutBank& bank = material.bank;
    const bool viewGrid = bank.layers.size() > 1;
    if (mode == q.modeUploaded && sameVector(light, q.lightUploaded) &&
        (!viewGrid || sameVector(m_scene.eye, q.eyeUploaded)))
        return;
    q.modeUploaded = mode;
    q.lightUploaded = light;
    q.eyeUploaded = m_scene.eye;
    q.light = toQuadFrame(quad, light);
    q.unlit = q.light.z <= 1e-9;
    q.view = bank.makesLuts() && bank.predictor().viewDependent() ? viewAt(quad, 0, 0) : toVector(bank.layers[0].view);
    if (q.unlit || mode == RenderMode::Flat) return;
    if (relitLut(q, mode)) return;  // the rest is relight()'s, or choosePaths()'s
    const Direction lightDirection = fromVector(q.light);
    const Direction centreView = fromVector(viewAt(quad, 0, 0));
    if (mode == RenderMode::Ptm) {
        // As RTI viewers draw: the light's terms folded with each coefficient's scale and bias
        // into six weights and an offset, once per quad, so a fragment does two dot products.
        if (!material.ptmLoaded) return;
        const PtmWeights w = ptmWeights(material.ptmScale, material.ptmBias, lightDirection);
        std::copy(w.weights.begin(), w.weights.end(), q.ptmWeights.begin());
        q.ptmWeights[6] = w.offset;
        return;
    }
    if (mode == RenderMode::Nearest) {
        const LutBank::NodeRef nearest = bank.nearestNode(lightDirection, centreView);
        q.nearestImage = bank.layers[nearest.layer].nodes[nearest.node].name;
        return;
    }
    const std::size_t entries = static_cast<std::size_t>(bank.entries);
    if (mode == RenderMode::Lut) {
        // Volumes per channel: [mip level][grid row][grid column][entry], each grid point's
        // LUT and the per-level LUTs made from it.
        if (!material.mipLuts || q.luts.empty()) return;  // prepare() makes them, then updates again
        constexpr int k = kViewGrid;
        const MipLuts& mips = *material.mipLuts;
        const auto levels = static_cast<std::size_t>(mips.levels());
        const std::vector<Direction> views = viewGridDirections(quad);
        std::vector<std::vector<float>> volume(q.luts.size(), std::vector<float>(levels * views.size() * entries));
        std::vector<float> perLevel(levels * entries);
        for (std::size_t v = 0; v < views.size(); ++v) {
            const BankLookup lut = bank.lookup(lightDirection, views[v], m_interpolate);
            for (std::size_t c = 0; c < q.luts.size(); ++c) {
                mips.apply(static_cast<int>(c), &lut.values[c * entries], perLevel.data());
                for (std::size_t m = 0; m < levels; ++m)
                    std::copy_n(&perLevel[m * entries], entries, &volume[c][(m * views.size() + v) * entries]);
            }
        }
        for (std::size_t c = 0; c < q.luts.size(); ++c) {
            gl.BindTexture(GL_TEXTURE_3D, q.luts[c].id());
            gl.TexSubImage3D(GL_TEXTURE_3D, 0, 0, 0, 0, bank.entries, k, k * static_cast<int>(levels), GL_RED, GL_FLOAT,
                             volume[c].data());
        }
        return;
    }
    // brdf: the target's mean grey over the reference's own mean
    q.brightness = brdfScale(bank, material.referenceGrey, bank.lookup(lightDirection, centreView, m_interpolate));
}

bool SceneRenderer::relitLut(const QuadState& q, RenderMode mode) const {
    const LutBank& bank = m_materials.at(m_scene.quads[q.index].material).bank;
    return mode == RenderMode::Lut && (bank.layers.size() == 1 || bank.makesLuts());
}

bool SceneRenderer::relitInTextureSpace(const QuadState& q, RenderMode mode) const {
    return relitLut(q, mode) && !q.perFragment;
}

namespace {

// What the paths cost on llvmpipe, in units of one pixel shaded flat (bench render --lut-path
// texture and fragment, issue 22; bench/RESULTS.md): a texel relit in texture space, its
// mipmaps and the pass's render targets included, and a pixel shaded per fragment beyond its
// flat cost: one reference (a filtered fetch, the LUT from uniforms, the dither), or a
// predictor (its planes sampled bilinearly, the LUT from uniforms, the dither), and what its
// decoding adds (Predictor::decodeCost: a learned model's network).
double decoderCost(const LutBank& bank, bool perFragment) {
    return bank.makesLuts() ? bank.predictor().decodeCost(perFragment) : 0.0;
}
double relitTexelCost(const LutBank& bank) { return (bank.makesLuts() ? 4.8 : 4.6) + decoderCost(bank, false); }
double perFragmentExtraCost(const LutBank& bank) { return (bank.makesLuts() ? 0.55 : 0.33) + decoderCost(bank, true); }

}  // namespace

// Per material and light direction (in the quads' own frames), the lit mode lut quads of a
// bank of one view layer are drawn per fragment when the light moved since the last frame, no
// relit texture holds the direction, and covering their pixels per fragment costs less than
// relighting the reference; else in texture space (relight()). A renderer's first frame, and
// the frame after the light stops, relight: the relit texture is mipmapped from relit texels
// (a far quad shows the mean of LUT values), and later frames draw it flat.
void SceneRenderer::choosePaths(const std::vector<RenderMode>& modes) {
    m_stats.quadsTextureSpace = m_stats.quadsPerFragment = 0;
    std::map<std::pair<std::string, std::array<double, 6>>, std::vector<QuadState*>> groups;
    for (std::size_t i = 0; i < m_quads.size(); ++i) {
        QuadState& q = m_quads[i];
        q.perFragment = false;
        if (!relitLut(q, modes[i]) || q.unlit) continue;
        groups[{m_scene.quads[q.index].material, {q.light.x, q.light.y, q.light.z, q.view.x, q.view.y, q.view.z}}]
            .push_back(&q);
    }
    for (auto& [key, quads] : groups) {
        Material& material = m_materials.at(key.first);
        const LutBank& bank = material.bank;
        const Vec3 light = quads.front()->light, view = quads.front()->view;
        bool perFragment = m_lutPath == LutPath::PerFragment;
        if (m_lutPath == LutPath::Auto) {
            const bool moved = std::all_of(quads.begin(), quads.end(), [&](const QuadState* q) {
                return q->lastFrameLight.z > 0 && !sameVector(q->lastFrameLight, light);
            });
            const bool relit = std::any_of(material.relit.begin(), material.relit.end(), [&](const Relit& r) {
                return sameVector(r.light, light) && sameVector(r.view, view);
            });
            if (moved && !relit) {
                double pixels = 0;
                int level = std::numeric_limits<int>::max();  // the finest its quads read, where they show it:
                TexelRegion region;                           // what a relight makes
                for (const QuadState* q : quads) {
                    const SceneQuad& quad = m_scene.quads[q->index];
                    pixels += coveredPixels(quad);
                    level = std::min(level, relitLevel(material, quad));
                    region = region.merged(seenRegion(quad, bank.reference.width, bank.reference.height));
                }
                const auto texels = static_cast<double>(
                    region.texelsAt(levelSize(bank.reference.width, level), levelSize(bank.reference.height, level)));
                perFragment = pixels * perFragmentExtraCost(bank) < texels * relitTexelCost(bank);
            }
        }
        for (QuadState* q : quads) {
            q->perFragment = perFragment;
            if (!perFragment) continue;
            if (q->luts.empty()) {
                q->luts = material.pass->makeLuts();
                m_stats.textureBytes.luts += material.pass->lutBytes();
            }
            if (!sameVector(q->frameLight, light) || !sameVector(q->frameView, view)) {
                q->frame = frameFor(material, fromVector(light), fromVector(view));
                material.pass->uploadLuts(q->frame, q->luts);
                q->frameLight = light;
                q->frameView = view;
            }
        }
        (perFragment ? m_stats.quadsPerFragment : m_stats.quadsTextureSpace) += quads.size();
    }
    for (QuadState& q : m_quads) q.lastFrameLight = q.unlit ? kNoLight : q.light;
}

std::vector<SceneRenderer::ClipPoint> SceneRenderer::clippedQuad(const SceneQuad& quad) const {
    // The quad in clip space, clipped to the view volume's sides and to w > 0 (the polygon
    // clipping of Sutherland and Hodgman, in homogeneous coordinates). Clip coordinates are
    // linear in the quad's (s, t), so the cut points carry theirs by the same weights.
    const std::array<float, 16> m = viewProjection(m_scene);  // column-major
    const Vec3 b = bitangentOf(quad);
    std::vector<ClipPoint> polygon;
    for (const auto& [su, sv] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
        const double u = su * quad.width / 2, v = sv * quad.height / 2;
        const double p[3] = {quad.center.x + u * quad.tangent.x + v * b.x, quad.center.y + u * quad.tangent.y + v * b.y,
                             quad.center.z + u * quad.tangent.z + v * b.z};
        ClipPoint c{0, 0, 0, 0, static_cast<double>(su), static_cast<double>(sv)};
        for (std::size_t r = 0; r < 4; ++r) c[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
        polygon.push_back(c);
    }
    const std::array<std::function<double(const ClipPoint&)>, 5> inside{
        [](const ClipPoint& c) { return c[3] - 1e-6; }, [](const ClipPoint& c) { return c[3] + c[0]; },
        [](const ClipPoint& c) { return c[3] - c[0]; }, [](const ClipPoint& c) { return c[3] + c[1]; },
        [](const ClipPoint& c) { return c[3] - c[1]; }};
    for (const auto& distance : inside) {
        std::vector<ClipPoint> kept;
        for (std::size_t k = 0; k < polygon.size(); ++k) {
            const ClipPoint &a = polygon[k], &c = polygon[(k + 1) % polygon.size()];
            const double da = distance(a), dc = distance(c);
            if (da >= 0) kept.push_back(a);
            if ((da >= 0) != (dc >= 0)) {  // the edge crosses the plane
                const double t = da / (da - dc);
                ClipPoint x{};
                for (std::size_t r = 0; r < x.size(); ++r) x[r] = a[r] + t * (c[r] - a[r]);
                kept.push_back(x);
            }
        }
        polygon = std::move(kept);
    }
    return polygon;
}

double SceneRenderer::coveredPixels(const SceneQuad& quad) const {
    const std::vector<ClipPoint> polygon = clippedQuad(quad);
    double area = 0;  // the shoelace formula over the screen points
    for (std::size_t k = 0; k < polygon.size(); ++k) {
        const ClipPoint &a = polygon[k], &c = polygon[(k + 1) % polygon.size()];
        area += a[0] / a[3] * c[1] / c[3] - c[0] / c[3] * a[1] / a[3];
    }
    return std::abs(area) / 2 * m_scene.width / 2 * m_scene.height / 2;
}

int SceneRenderer::relitLevel(const Material& material, const SceneQuad& quad) const {
    const LutBank& bank = material.bank;
    if (!m_interpolate || m_exactMatch || !LevelMatch::supports(bank)) return 0;
    const int width = bank.reference.width, height = bank.reference.height;
    return std::min(levelCount(width, height) - 1, finestLevel(quad, width, height));
}

// GL's level of detail is log2 of the longer of the texel coordinates' derivatives along the
// screen's x and y. The quad's point (s, t) in [-1, 1]^2 has texel coordinates (1 + s, 1 - t)
// / 2 * uvScale * (texelsWide, texelsHigh) (scene.vert); its pixel coordinates come from the
// projection, differentiated numerically. None behind the eye, or seen edge on.
std::optional<double> SceneRenderer::levelOfDetail(const SceneQuad& quad, double s, double t, int texelsWide,
                                                   int texelsHigh) const {
    const std::array<float, 16> m = viewProjection(m_scene);  // column-major
    const Vec3 b = bitangentOf(quad);
    auto pixel = [&](double ps, double pt, std::array<double, 2>& out) {
        const double u = ps * quad.width / 2, v = pt * quad.height / 2;
        const double p[3] = {quad.center.x + u * quad.tangent.x + v * b.x, quad.center.y + u * quad.tangent.y + v * b.y,
                             quad.center.z + u * quad.tangent.z + v * b.z};
        double c[4]{};
        for (std::size_t r = 0; r < 4; ++r) c[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
        if (c[3] < 1e-6) return false;
        out = {(c[0] / c[3] + 1) / 2 * m_scene.width, (c[1] / c[3] + 1) / 2 * m_scene.height};
        return true;
    };
    const double du = quad.uvScale * texelsWide / 2, dv = quad.uvScale * texelsHigh / 2;  // texels per unit s, t
    constexpr double h = 1e-4;
    std::array<double, 2> p{}, ps{}, pt{};
    if (!pixel(s, t, p) || !pixel(s + h, t, ps) || !pixel(s, t + h, pt)) return std::nullopt;
    // J: pixels per (s, t); its inverse: (s, t) per pixel; times the texels per (s, t).
    const double j00 = (ps[0] - p[0]) / h, j10 = (ps[1] - p[1]) / h, j01 = (pt[0] - p[0]) / h, j11 = (pt[1] - p[1]) / h;
    const double det = j00 * j11 - j01 * j10;
    if (std::abs(det) < 1e-12) return std::nullopt;
    const double dsdx = j11 / det, dsdy = -j01 / det, dtdx = -j10 / det, dtdy = j00 / det;
    return std::log2(std::max(std::hypot(du * dsdx, dv * dtdx), std::hypot(du * dsdy, dv * dtdy)));
}

int SceneRenderer::finestLevel(const SceneQuad& quad, int texelsWide, int texelsHigh) const {
    // Over a 5 x 5 grid of points the least is taken: under perspective it lies at the
    // nearest corner.
    double finest = std::numeric_limits<double>::infinity();
    for (int a = 0; a <= 4; ++a)
        for (int c = 0; c <= 4; ++c) {
            const std::optional<double> lod = levelOfDetail(quad, -1 + a / 2.0, -1 + c / 2.0, texelsWide, texelsHigh);
            if (!lod) return 0;
            finest = std::min(finest, *lod);
        }
    return std::max(0, static_cast<int>(std::floor(finest + 1e-3)));
}

// The texels a quad shows: its part inside the view volume, mapped to texel coordinates, then
// widened so that every mip level trilinear filtering reads there is whole. Each level below
// the one relit is made by GenerateMipmap from the whole level, so its texels are fresh only
// where every texel under them is: the region is aligned to the coarsest level's texels (2^k
// of level 0's), and padded by two of them for bilinear filtering and mip levels of odd sizes.
TexelRegion SceneRenderer::seenRegion(const SceneQuad& quad, int texelsWide, int texelsHigh) const {
    const std::vector<ClipPoint> polygon = clippedQuad(quad);
    if (polygon.empty()) return TexelRegion::span(0, 0, 0, 0, texelsWide, texelsHigh);
    double s0 = 1, s1 = -1, t0 = 1, t1 = -1;
    for (const ClipPoint& c : polygon) {
        s0 = std::min(s0, c[4]), s1 = std::max(s1, c[4]);
        t0 = std::min(t0, c[5]), t1 = std::max(t1, c[5]);
    }
    const int levels = levelCount(texelsWide, texelsHigh);
    double coarsest = -std::numeric_limits<double>::infinity();  // GL's largest level of detail over the part seen
    auto reads = [&](double s, double t) {
        const std::optional<double> lod = levelOfDetail(quad, s, t, texelsWide, texelsHigh);
        coarsest = lod ? std::max(coarsest, *lod) : static_cast<double>(levels);
    };
    for (const ClipPoint& c : polygon) reads(c[4], c[5]);
    for (int a = 0; a <= 4; ++a)
        for (int c = 0; c <= 4; ++c) reads(s0 + (s1 - s0) * a / 4, t0 + (t1 - t0) * c / 4);
    // Trilinear filtering reads floor(lod) and the level after it.
    const int top = std::clamp(static_cast<int>(std::floor(coarsest)) + 1, 0, levels - 1);
    const long long block = 1LL << top, pad = 2 * block;
    auto axis = [&](double from, double to, int texels) {  // texture coordinates [from, to] in level-0 texels
        const double scale = quad.uvScale * texels;
        const long long first = static_cast<long long>(std::floor(from * scale)) - pad,
                        last = static_cast<long long>(std::ceil(to * scale)) + pad;
        const auto floorTo = [&](long long v) { return (v >= 0 ? v : v - block + 1) / block * block; };
        return std::array<long long, 2>{floorTo(first), floorTo(last + block - 1)};
    };
    if (quad.uvScale * std::max(texelsWide, texelsHigh) > 1e9) return TexelRegion::whole(texelsWide, texelsHigh);
    const auto [x0, x1] = axis((1 + s0) / 2, (1 + s1) / 2, texelsWide);
    const auto [y0, y1] = axis((1 - t1) / 2, (1 - t0) / 2, texelsHigh);
    return TexelRegion::span(x0, x1, y0, y1, texelsWide, texelsHigh);
}

// Loads what a mode needs beyond the reference, the first time it is needed.
Status SceneRenderer::prepare(QuadState& q, RenderMode mode, const Vec3& light) {
    const SceneQuad& quad = m_scene.quads[q.index];
    Material& material = m_materials.at(quad.material);
    const SceneMaterial& paths = m_scene.materials.at(quad.material);
    TextureBytes& bytes = m_stats.textureBytes;
    const bool blends = material.bank.makesLuts() && mode == RenderMode::Lut;
    if (blends && !material.prediction)
        material.prediction = PredictionTextures::upload(material.bank, bytes.prediction);
    if (!blends && mode != RenderMode::Ptm && mode != RenderMode::Nearest && !material.reference.id())
        material.reference = uploadMipmapped(material.bank.reference, bytes.reference);
    if (relitLut(q, mode) && !material.pass)
        material.pass.emplace(material.bank, material.reference.id(),
                              material.prediction ? &*material.prediction : nullptr);
    if (mode == RenderMode::Lut && !relitLut(q, mode) && q.luts.empty()) {
        if (!material.mipLuts)
            material.mipLuts.emplace(material.bank.reference, material.bank.colour, material.bank.entries);
        const int levels = material.mipLuts->levels();
        for (int c = 0; c < material.mipLuts->channels(); ++c) {
            q.luts.push_back(uploadLutVolume(nullptr, material.bank.entries, kViewGrid, kViewGrid * levels));
            bytes.luts += static_cast<std::size_t>(material.bank.entries) * kViewGrid * kViewGrid *
                          static_cast<std::size_t>(levels) * 4;
        }
        q.lightUploaded = kNoLight;
        update(q, light, mode);
    }
    if (mode == RenderMode::Ptm && !material.ptmLoaded) {
        Result<LightModel> ptm = loadBankPtm(paths.bank);
        if (!ptm) return Error{ptm.error()};
        const std::vector<Image> planes = lightModelImages(*ptm);  // coefficients 0-2, 3-5, the albedo
        for (std::size_t p = 0; p < material.ptm.size(); ++p) material.ptm[p] = uploadMipmapped(planes[p], bytes.ptm);
        std::copy(ptm->scale.begin(), ptm->scale.end(), material.ptmScale.begin());
        std::copy(ptm->bias.begin(), ptm->bias.end(), material.ptmBias.begin());
        material.ptmLoaded = true;
        m_stats.loadedPtms.push_back(quad.material);
        for (QuadState& other : m_quads)  // their PTM weights are due
            if (m_scene.quads[other.index].material == quad.material) other.lightUploaded = kNoLight;
        update(q, light, mode);
    }
    if (mode == RenderMode::Nearest && !q.unlit && !material.imageTextures.count(q.nearestImage)) {
        if (!material.images) {
            if (paths.images.empty())
                return Error{m_scene.file + ": material '" + quad.material +
                             "' names no \"images\" (mode nearest draws the measured images)"};
            Result<Dataset> dataset = openDataset(paths.images);
            if (!dataset) return Error{dataset.error()};
            material.images = std::move(*dataset);
        }
        const auto& all = material.images->images;
        auto found =
            std::find_if(all.begin(), all.end(), [&](const DatasetImage& im) { return im.name == q.nearestImage; });
        if (found == all.end())
            return Error{paths.images + ": no image named '" + q.nearestImage +
                         "' (the bank's node); is it the dataset "
                         "the bank was baked from?"};
        Result<Image> image = loadImage(found->path);
        if (!image) return Error{image.error()};
        material.imageTextures.emplace(q.nearestImage, uploadMipmapped(*image, bytes.images));
        ++m_stats.imagesLoaded;
    }
    return success();
}

// The relit textures of this frame: one per material and distinct light direction among the
// lit quads drawn in mode lut. A texture already relit for a wanted direction, at the finest
// mip level its quads read or finer, is used as it is; else the texture of that direction
// (relit finer), or the one unused for longest, or a new one, is relit, its mipmaps made from
// the level relit. Banks with a predictor (LevelMatch::supports) are relit from the level
// their quads read: a quad minified 8 times decodes 1/64 of the texels. Textures are kept when
// no quad wants them (a viewer pane in another mode, a light that comes back), so a material
// holds as many as it ever needed at once.
Status SceneRenderer::relight(const std::vector<RenderMode>& modes) {
    ++m_frame;
    m_stats.relitTextures = 0;
    m_stats.textureBytes.relit = 0;
    for (auto& [name, material] : m_materials) {
        std::vector<Relit>& relit = material.relit;
        std::vector<QuadState*> quads;  // this material's, relit in texture space
        for (std::size_t i = 0; i < m_quads.size(); ++i) {
            QuadState& q = m_quads[i];
            if (m_scene.quads[q.index].material == name && !q.unlit && relitInTextureSpace(q, modes[i]))
                quads.push_back(&q);
        }
        if (quads.empty()) continue;
        const LutBank& bank = material.bank;
        for (QuadState* q : quads) {
            q->level = relitLevel(material, m_scene.quads[q->index]);
            q->region = seenRegion(m_scene.quads[q->index], bank.reference.width, bank.reference.height);
        }
        auto same = [](const QuadState& q, const Relit& r) {
            return sameVector(r.light, q.light) && sameVector(r.view, q.view);
        };
        for (QuadState* q : quads) {
            int level = q->level;  // the finest any quad of its direction reads, over the texels they show
            TexelRegion region = q->region;
            for (const QuadState* other : quads)
                if (sameVector(other->light, q->light) && sameVector(other->view, q->view)) {
                    level = std::min(level, other->level);
                    region = region.merged(other->region);
                }
            auto found = std::find_if(relit.begin(), relit.end(), [&](const Relit& r) {
                return same(*q, r) && r.level <= level && r.region.covers(region);
            });
            if (found == relit.end()) {
                found = std::find_if(relit.begin(), relit.end(), [&](const Relit& r) { return same(*q, r); });
                // A camera that pans under a still light grows the texture's region, so that
                // panning back relights nothing.
                if (found != relit.end() && found->level == level) region = found->region.merged(region);
                if (found == relit.end())
                    found = std::min_element(relit.begin(), relit.end(),
                                             [](const Relit& a, const Relit& b) { return a.lastUsed < b.lastUsed; });
                if (found == relit.end() || (found->lastUsed == m_frame && !same(*q, *found))) {
                    relit.push_back(
                        {{}, {}, allocateRelitTexture(bank.reference), 0, {}, material.pass->makeLuts(), 0});
                    found = relit.end() - 1;
                }
                found->light = q->light;
                found->view = q->view;
                found->level = level;
                found->region = region;
                const Direction light = fromVector(q->light), view = fromVector(q->view);
                RelightFrame frame = frameFor(material, light, view);
                if (level > 0) {
                    if (!material.levelMatch) material.levelMatch.emplace(bank);
                    frame.luts = material.levelMatch->luts(light, level);
                }
                if (Status s = material.pass->run(frame, found->luts, found->texture.id(), m_dither, level, region); !s)
                    return s;
                gl.BindTexture(GL_TEXTURE_2D, found->texture.id());
                gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, level);  // the finer levels are stale
                gl.GenerateMipmap(GL_TEXTURE_2D);  // from the relit texels: far quads average LUT values
                ++m_stats.relightPasses;
                m_stats.relitTexels +=
                    region.texelsAt(levelSize(bank.reference.width, level), levelSize(bank.reference.height, level));
            }
            found->lastUsed = m_frame;
            q->relit = static_cast<std::size_t>(found - relit.begin());
        }
    }
    for (const auto& [name, material] : m_materials) {
        m_stats.relitTextures += material.relit.size();
        if (!material.relit.empty())
            m_stats.textureBytes.relit +=
                material.relit.size() * (relitTextureBytes(material.bank.reference) + material.pass->lutBytes());
    }
    return success();
}

}  // namespace btflut

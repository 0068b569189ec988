// A bank's lookups (lut_bank.h): the grid's bilinear reads, and a light and view's LUT as a
// weighted sum of the nodes around them (their layers' triangulations, the isotropic domain's
// pairs, the fitted model's nodes beyond the measured hull).
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "core/bank/lut_bank.h"

namespace btflut {

namespace {

int rank(Provenance p) {
    switch (p) {
        case Provenance::Measured:
            return 0;
        case Provenance::Interpolated:
            return 1;
        case Provenance::Modelled:
            return 2;
        case Provenance::Clamped:
            return 3;
    }
    return 3;
}

Provenance combine(Provenance a, Provenance b) { return rank(a) >= rank(b) ? a : b; }

Provenance provenanceOf(const Weights& w) {
    if (!w.inside) return Provenance::Clamped;
    double top = *std::max_element(w.weight.begin(), w.weight.begin() + w.count);
    return top > 1 - 1e-9 ? Provenance::Measured : Provenance::Interpolated;
}

}  // namespace

namespace {

// The bilinear read of a grid of unorm16 values (`length` per node) at a light's disk point,
// as one filtered fetch of the exported 3D texture does.
std::vector<float> bilinearOnGrid(const std::vector<std::uint16_t>& grid, int gridSize, std::size_t length,
                                  Direction light) {
    const GridCell cell = gridCellAt(toDisk(light), gridSize);
    std::vector<float> out(length);
    for (std::size_t k = 0; k < length; ++k) {
        double sum = 0;
        for (std::size_t n = 0; n < 4; ++n) sum += cell.weight[n] * grid[cell.node[n] * length + k];
        out[k] = static_cast<float>(sum / 65535.0);
    }
    return out;
}

}  // namespace

std::vector<float> LutBank::gridLookup(Direction light, std::size_t layer) const {
    const ViewLayer& l = layers.at(layer);
    BTFLUT_CHECK(!l.gridLuts.empty());
    return bilinearOnGrid(l.gridLuts, gridSize, nodeLength(), light);
}

std::vector<float> LutBank::matchGridLookup(Direction light, std::size_t layer) const {
    const ViewLayer& l = layers.at(layer);
    BTFLUT_CHECK(!l.matchGridLuts.empty());
    return bilinearOnGrid(l.matchGridLuts, gridSize, matchLength(), light);
}

std::vector<float> LutBank::matchGridLookup(Direction light, Direction view) const {
    if (layers.size() == 1) return matchGridLookup(light, std::size_t{0});
    BTFLUT_CHECK(domain == BankDomain::Layers);
    std::vector<float> out(matchLength(), 0.f);
    const Weights vw = views.weightsAt(toDisk(view));  // as lookup blends the layers' nodes
    for (int v = 0; v < vw.count; ++v) {
        if (vw.weight[v] == 0) continue;
        const std::vector<float> grid = matchGridLookup(light, static_cast<std::size_t>(vw.index[v]));
        for (std::size_t k = 0; k < out.size(); ++k) out[k] += static_cast<float>(vw.weight[v]) * grid[k];
    }
    return out;
}

std::optional<std::size_t> LutBank::nearestLayerMeasuring(DiskPoint light, std::size_t except) const {
    std::optional<std::size_t> best;
    double bestAngle = 0;
    for (std::size_t k = 0; k < layers.size(); ++k) {
        if (k == except || layers[k].measuredNodes < 3) continue;
        const double angle = angleBetween(layers[k].view, layers[except].view);
        if (best && angle >= bestAngle) continue;
        if (!layers[k].lights.weightsAt(light).inside) continue;
        best = k, bestAngle = angle;
    }
    return best;
}

namespace {

// A lookup's values as a weighted sum of nodes' values (in double, rounded once at the end),
// and where they come from.
class NodeBlend {
public:
    explicit NodeBlend(const LutBank& bank) : m_bank(bank), m_sum(bank.nodeLength(), 0.0) {}

    void add(LutBank::NodeRef n, double weight) {
        const ViewLayer& layer = m_bank.layers[n.layer];
        BTFLUT_CHECK(layer.lutsLoaded);
        const float* lut = &layer.nodeLuts[n.node * m_sum.size()];
        for (std::size_t k = 0; k < m_sum.size(); ++k) m_sum[k] += weight * lut[k];
        if (weight > 0) m_blended.push_back(lut);
    }

    // A layer's fit at the light, for its measured nodes' share `weight` (target_fit.h).
    void addFit(const ViewLayer& layer, Direction light, const Weights& w, double weight) {
        if (layer.fit.empty() || weight == 0) return;
        std::vector<Direction> lights;
        std::vector<double> weights;
        for (int l = 0; l < w.count; ++l) {
            lights.push_back(layer.nodes[static_cast<std::size_t>(w.index[l])].light);
            weights.push_back(w.weight[l]);
        }
        addFitCorrection(layer.fit, light, lights, weights, weight, m_sum);
        m_fitted = true;
    }

    // The isotropic domain's fit at q, for the points blended (`points`, their weights).
    void addPairFit(Point3 q, const std::vector<Point3>& points, const std::vector<double>& weights) {
        if (m_bank.pairFit.empty()) return;
        addPairFitCorrection(m_bank.pairFit, q, points, weights, 1, m_sum);
        m_fitted = true;
    }

    BankLookup finish() {
        look.values.assign(m_sum.size(), 0.f);
        for (std::size_t k = 0; k < m_sum.size(); ++k) look.values[k] = static_cast<float>(m_sum[k]);
        if (m_fitted) {  // within the levels of the nodes blended
            SegmentRanges ranges;
            for (const float* lut : m_blended) ranges.include(lut, m_sum.size(), m_bank.segmentLength());
            makeQuantileFunctions(look.values, m_bank.segmentLength(), ranges, m_bank.targetCode());
        }
        look.provenance = combine(look.lightProvenance, look.viewProvenance);
        return look;
    }

    BankLookup look;  ///< its provenances, set as nodes are added

private:
    const LutBank& m_bank;
    std::vector<double> m_sum;
    std::vector<const float*> m_blended;  // the values of the nodes of a nonzero weight
    bool m_fitted = false;
};

// Isotropic banks: the light and view pair's point in the pairs' domain.
void addIsotropic(const LutBank& bank, Direction light, Direction view, NodeBlend& blend) {
    const Point3 q = isotropicPoint(light, view);
    const Weights w = bank.pairs.weightsAt(q);
    const bool fitted = !bank.pairFit.empty();
    std::vector<Point3> points;  // those blended, and their weights: the fit's correction
    std::vector<double> weights;
    auto addPoint = [&](std::size_t point, double weight) {
        const std::vector<LutBank::NodeRef>& nodes = bank.pairNodes[point];
        for (LutBank::NodeRef n : nodes) blend.add(n, weight / static_cast<double>(nodes.size()));
        if (!fitted) return;
        points.push_back(bank.pairs.points()[point]);
        weights.push_back(weight);
    };
    // Beyond the hull, the clamp to its boundary gives way to the nearest measured pair
    // over one grid step. Measurements along a path (CUReT's light and view moving
    // together) make a hull whose faces bridge far-apart pairs; the point on such a face
    // blends the two, while the nearest pair is what was measured closest.
    double clamped = 1;
    if (!w.inside) {
        Point3 onHull{0, 0, 0};
        for (int p = 0; p < w.count; ++p) {
            const Point3& v = bank.pairs.points()[static_cast<std::size_t>(w.index[p])];
            onHull = {onHull.x + w.weight[p] * v.x, onHull.y + w.weight[p] * v.y, onHull.z + w.weight[p] * v.z};
        }
        clamped = bank.hullRamp(std::hypot(q.x - onHull.x, q.y - onHull.y, q.z - onHull.z));
        addPoint(bank.nearestPair(q), 1 - clamped);
    }
    for (int p = 0; p < w.count; ++p) addPoint(static_cast<std::size_t>(w.index[p]), w.weight[p] * clamped);
    // The fit read at q pulled into the box of the measured points: it extrapolates beyond
    // their hull as far as they reach along each axis, never beyond.
    if (fitted) {
        const Point3 &lo = bank.pairsLow, &hi = bank.pairsHigh;
        blend.addPairFit({std::clamp(q.x, lo.x, hi.x), std::clamp(q.y, lo.y, hi.y), std::clamp(q.z, lo.z, hi.z)},
                         points, weights);
    }
    // One domain point carries both: measured only where light and view are.
    blend.look.lightProvenance = blend.look.viewProvenance = provenanceOf(w);
}

// View layer `layer`'s share `viewWeight` of a light: its measured nodes around the light,
// and beyond their hull another view's measurements or the fitted model's nodes.
void addLayer(const LutBank& bank, std::size_t layer, double viewWeight, Direction light, NodeBlend& blend) {
    const ViewLayer& lights = bank.layers[layer];
    const DiskPoint lightPoint = toDisk(light);
    const Weights lw = lights.lights.weightsAt(lightPoint);
    // Beyond the measured hull the measurements clamped to it give way to other data over
    // one grid step, so a LUT never jumps at the hull: their share of the blend.
    auto clampedShare = [&] {
        DiskPoint onHull{0, 0};
        for (int l = 0; l < lw.count; ++l) {
            const DiskPoint q = lights.lights.points()[static_cast<std::size_t>(lw.index[l])];
            onHull = {onHull.x + lw.weight[l] * q.x, onHull.y + lw.weight[l] * q.y};
        }
        return bank.hullRamp(std::hypot(lightPoint.x - onHull.x, lightPoint.y - onHull.y));
    };
    Provenance& provenance = blend.look.lightProvenance;
    double measured = 1;  // the share of this layer's measured nodes
    std::optional<std::size_t> borrowed;
    // Another view's measurements at the light come before the model's.
    if (!lw.inside) borrowed = bank.nearestLayerMeasuring(lightPoint, layer);
    if (borrowed) {
        // Beyond this view's lights, within another view's: the nearest such view's
        // measurements at this light (shadows and highlights follow the light more than
        // the view), rather than this view's clamped to its hull.
        measured = clampedShare();
        const Weights ow = bank.layers[*borrowed].lights.weightsAt(lightPoint);
        for (int o = 0; o < ow.count; ++o)
            blend.add({*borrowed, static_cast<std::size_t>(ow.index[o])}, viewWeight * ow.weight[o] * (1 - measured));
        provenance = combine(provenance, Provenance::Interpolated);
    } else if (!lw.inside && lights.measuredNodes < lights.nodes.size()) {
        // Beyond every view's measured lights: towards the fitted model (model_fill.h).
        measured = clampedShare();
        const Weights mw = lights.modelLights.weightsAt(lightPoint);
        for (int m = 0; m < mw.count; ++m)
            blend.add({layer, lights.measuredNodes + static_cast<std::size_t>(mw.index[m])},
                      viewWeight * mw.weight[m] * (1 - measured));
        provenance = combine(provenance, Provenance::Modelled);
    } else {
        provenance = combine(provenance, provenanceOf(lw));
    }
    for (int l = 0; l < lw.count; ++l)
        blend.add({layer, static_cast<std::size_t>(lw.index[l])}, viewWeight * lw.weight[l] * measured);
    // The fit's correction, read at the light pulled in to the farthest measured light's
    // radius on the disk: around the hull of a ring of lights it extrapolates as far as the
    // ring reaches (validation tests that: the ring's lights are left out in turn), never
    // beyond the lights' reach (the target is then constant outwards, as the clamp is).
    const double radius = std::hypot(lightPoint.x, lightPoint.y);
    const double reach = lights.measuredReach;
    const Direction fitLight =
        radius > reach ? fromDisk({lightPoint.x * reach / radius, lightPoint.y * reach / radius}) : light;
    blend.addFit(lights, fitLight, lw, viewWeight * measured);
}

}  // namespace

BankLookup LutBank::lookup(Direction light, Direction view, bool interpolate) const {
    if (!interpolate) {
        const NodeRef n = nearestNode(light, view);
        const ViewLayer& layer = layers[n.layer];
        BTFLUT_CHECK(layer.lutsLoaded);
        const float* lut = &layer.nodeLuts[n.node * nodeLength()];
        BankLookup out;
        out.values.assign(lut, lut + nodeLength());
        const bool exact = angleBetween(layer.view, view) < kSameDirection &&
                           angleBetween(layer.nodes[n.node].light, light) < kSameDirection;
        out.provenance = exact ? Provenance::Measured : Provenance::Interpolated;
        out.lightProvenance = out.viewProvenance = out.provenance;
        return out;
    }
    NodeBlend sum(*this);
    if (domain == BankDomain::Isotropic) {
        addIsotropic(*this, light, view, sum);
        return sum.finish();
    }
    const Weights vw = views.weightsAt(toDisk(view));
    sum.look.viewProvenance = provenanceOf(vw);
    for (int v = 0; v < vw.count; ++v)
        if (vw.weight[v] != 0) addLayer(*this, static_cast<std::size_t>(vw.index[v]), vw.weight[v], light, sum);
    return sum.finish();
}

}  // namespace btflut

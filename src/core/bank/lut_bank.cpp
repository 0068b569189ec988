#include "core/bank/lut_bank.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

namespace btflut {

const char* colourName(ColourMode c) {
    switch (c) {
        case ColourMode::Grey:
            return "grey";
        case ColourMode::Rgb:
            return "rgb";
        case ColourMode::Lrgb:
            return "lrgb";
    }
    return "?";
}

const char* domainName(BankDomain d) { return d == BankDomain::Isotropic ? "isotropic" : "layers"; }

Result<BankDomain> parseDomain(const std::string& name) {
    if (name == "layers") return BankDomain::Layers;
    if (name == "isotropic") return BankDomain::Isotropic;
    return Error{"domain '" + name + "' is not layers or isotropic"};
}

Point3 isotropicPoint(Direction light, Direction view) {
    const double turn = view.theta > 0 ? view.phi : 0.0;
    const DiskPoint l = toDisk({light.theta, light.phi - turn});
    return {l.x, std::abs(l.y), std::numbers::sqrt2 * std::sin(0.5 * view.theta)};
}

const char* provenanceName(Provenance p) {
    switch (p) {
        case Provenance::Measured:
            return "measured";
        case Provenance::Interpolated:
            return "interpolated";
        case Provenance::Clamped:
            return "clamped";
        case Provenance::Modelled:
            return "modelled";
    }
    return "?";
}

DiskPoint LutBank::gridPoint(int i, int j) const { return diskGridPoint(i, j, gridSize); }

LutBank LutBank::sameDirections() const {
    LutBank out;
    out.entries = entries;
    out.colour = colour;
    out.gridSize = gridSize;
    out.domain = domain;
    out.views = views;
    out.pairs = pairs;
    out.pairNodes = pairNodes;
    out.pairsLow = pairsLow;
    out.pairsHigh = pairsHigh;
    for (const ViewLayer& layer : layers) {
        ViewLayer& copy = out.layers.emplace_back();
        copy.view = layer.view;
        copy.nodes = layer.nodes;
        copy.lights = layer.lights;
        copy.modelLights = layer.modelLights;
        copy.measuredNodes = layer.measuredNodes;
        copy.measuredReach = layer.measuredReach;
    }
    return out;
}

void LutBank::buildTriangulations() {
    std::vector<DiskPoint> viewPoints;
    for (ViewLayer& layer : layers) {
        std::vector<DiskPoint> points, modelled;
        for (const LightNode& node : layer.nodes) {
            BTFLUT_CHECK(node.modelled || modelled.empty());  // the measured nodes come first
            (node.modelled ? modelled : points).push_back(toDisk(node.light));
        }
        layer.measuredNodes = points.size();
        layer.measuredReach = 0;
        for (const DiskPoint& p : points) layer.measuredReach = std::max(layer.measuredReach, std::hypot(p.x, p.y));
        layer.lights = Triangulation(std::move(points));
        layer.modelLights = modelled.empty() ? Triangulation() : Triangulation(std::move(modelled));
        viewPoints.push_back(toDisk(layer.view));
    }
    views = Triangulation(std::move(viewPoints));
    pairs = {};
    pairNodes.clear();
    pairsLow = pairsHigh = {};
    if (domain != BankDomain::Isotropic) return;
    // Points that the symmetry maps onto one another become one point of the domain.
    std::vector<Point3> points;
    std::map<std::array<long long, 3>, std::size_t> seen;
    for (std::size_t l = 0; l < layers.size(); ++l)
        for (std::size_t n = 0; n < layers[l].nodes.size(); ++n) {
            const Point3 p = isotropicPoint(layers[l].nodes[n].light, layers[l].view);
            const auto key = std::array{std::llround(p.x * 1e9), std::llround(p.y * 1e9), std::llround(p.z * 1e9)};
            auto [it, added] = seen.emplace(key, points.size());
            if (added) {
                points.push_back(p);
                pairNodes.emplace_back();
            }
            pairNodes[it->second].push_back({l, n});
        }
    if (!points.empty()) pairsLow = pairsHigh = points.front();
    for (const Point3& p : points) {
        pairsLow = {std::min(pairsLow.x, p.x), std::min(pairsLow.y, p.y), std::min(pairsLow.z, p.z)};
        pairsHigh = {std::max(pairsHigh.x, p.x), std::max(pairsHigh.y, p.y), std::max(pairsHigh.z, p.z)};
    }
    pairs = Triangulation3(std::move(points));
}

void LutBank::fillGrids() {
    const std::size_t length = nodeLength();
    for (ViewLayer& layer : layers) {
        const auto cells = static_cast<std::size_t>(gridSize) * gridSize;
        layer.gridLuts.assign(cells * length, 0);
        layer.gridProvenance.assign(cells, Provenance::Clamped);
        for (int j = 0; j < gridSize; ++j)
            for (int i = 0; i < gridSize; ++i) {
                // Beyond the horizon: the horizon's LUT (fromDisk pulls the point onto it).
                const BankLookup lut = lookup(fromDisk(gridPoint(i, j)), layer.view);
                const auto cell = static_cast<std::size_t>(j) * gridSize + i;
                layer.gridProvenance[cell] = lut.lightProvenance;
                for (std::size_t k = 0; k < length; ++k)
                    layer.gridLuts[cell * length + k] =
                        static_cast<std::uint16_t>(std::lround(lut.values[k] * 65535.0));
            }
    }
}

double LutBank::lightCoverage(std::size_t layer) const {
    // Equal-area disk: the share of sample points of the unit disk inside the hull is the
    // share of solid angle.
    constexpr int n = 128;
    int inside = 0, total = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const DiskPoint p{-1 + (i + 0.5) * 2.0 / n, -1 + (j + 0.5) * 2.0 / n};
            if (p.x * p.x + p.y * p.y > 1) continue;
            ++total;
            inside += domain == BankDomain::Isotropic
                          ? pairs.weightsAt(isotropicPoint(fromDisk(p), layers[layer].view)).inside
                          : layers[layer].lights.weightsAt(p).inside;
        }
    return static_cast<double>(inside) / total;
}

std::vector<std::size_t> LutBank::layersFor(Direction view) const {
    std::vector<std::size_t> used;
    if (domain == BankDomain::Isotropic) {
        for (std::size_t l = 0; l < layers.size(); ++l) used.push_back(l);
        return used;
    }
    const Weights w = views.weightsAt(toDisk(view));
    for (int v = 0; v < w.count; ++v)
        if (w.weight[v] != 0) used.push_back(static_cast<std::size_t>(w.index[v]));
    std::size_t nearest = 0;
    for (std::size_t l = 1; l < layers.size(); ++l)
        if (angleBetween(layers[l].view, view) < angleBetween(layers[nearest].view, view)) nearest = l;
    used.push_back(nearest);
    return used;
}

bool LutBank::followsLight() const {
    if (domain == BankDomain::Isotropic) {
        for (const Point3& p : pairs.points())
            if (std::hypot(p.x - pairs.points()[0].x, p.y - pairs.points()[0].y) > 1e-9) return true;
        return false;
    }
    return std::any_of(layers.begin(), layers.end(), [](const ViewLayer& l) { return l.nodes.size() > 1; });
}

std::size_t LutBank::nearestPair(Point3 q) const {
    std::size_t best = 0;
    double bestDistance = std::numeric_limits<double>::infinity();
    const std::vector<Point3>& points = pairs.points();
    for (std::size_t i = 0; i < points.size(); ++i)
        if (const double d = std::hypot(points[i].x - q.x, points[i].y - q.y, points[i].z - q.z); d < bestDistance)
            best = i, bestDistance = d;
    return best;
}

double LutBank::hullRamp(double distance) const { return std::max(0.0, 1 - distance * (gridSize - 1) / 2.0); }

LutBank::NodeRef LutBank::nearestNode(Direction light, Direction view) const {
    auto nearest = [](const auto& items, auto angleTo) {
        std::size_t best = 0;
        for (std::size_t i = 1; i < items.size(); ++i)
            if (angleTo(items[i]) < angleTo(items[best])) best = i;
        return best;
    };
    if (domain == BankDomain::Isotropic) return pairNodes[nearestPair(isotropicPoint(light, view))].front();
    NodeRef ref;
    ref.layer = nearest(layers, [&](const ViewLayer& l) { return angleBetween(l.view, view); });
    ref.node = nearest(layers[ref.layer].nodes, [&](const LightNode& n) { return angleBetween(n.light, light); });
    return ref;
}

std::vector<std::uint16_t> LutBank::gridTexels() const {
    const auto cells = static_cast<std::size_t>(gridSize) * gridSize, width = segmentLength();
    const auto regions = static_cast<std::size_t>(makesLuts() ? prediction.regions : 1),
               ch = static_cast<std::size_t>(channels());
    std::vector<std::uint16_t> texels(layers.size() * cells * regions * width * ch);
    std::size_t at = 0;
    for (const ViewLayer& layer : layers)
        for (std::size_t cell = 0; cell < cells; ++cell)
            for (std::size_t r = 0; r < regions; ++r)
                for (std::size_t k = 0; k < width; ++k)
                    for (std::size_t c = 0; c < ch; ++c)
                        texels[at++] = layer.gridLuts[((cell * regions + r) * ch + c) * width + k];
    return texels;
}

Status setNodes(LutBank& bank, const std::vector<DirectionalLut>& luts, std::optional<BankDomain> domain,
                const std::string& source) {
    const std::size_t length = bank.nodeLength();
    bank.layers.clear();
    // Group by view into layers, and merge repeated light directions within a layer by
    // averaging their LUTs (the barycentre of the repeated measurements).
    std::vector<std::vector<int>> mergedCount;
    for (const DirectionalLut& lut : luts) {
        BTFLUT_CHECK(lut.values.size() == length);
        auto layer = std::find_if(bank.layers.begin(), bank.layers.end(),
                                  [&](const ViewLayer& l) { return angleBetween(l.view, lut.view) < kSameDirection; });
        if (layer == bank.layers.end()) {
            bank.layers.push_back(ViewLayer{lut.view, {}, {}, {}, {}, {}});
            mergedCount.emplace_back();
            layer = std::prev(bank.layers.end());
        }
        auto& counts = mergedCount[static_cast<std::size_t>(layer - bank.layers.begin())];
        auto node = std::find_if(layer->nodes.begin(), layer->nodes.end(),
                                 [&](const LightNode& n) { return angleBetween(n.light, lut.light) < kSameDirection; });
        if (node == layer->nodes.end()) {
            layer->nodes.push_back({lut.name, lut.light});
            layer->nodeLuts.insert(layer->nodeLuts.end(), lut.values.begin(), lut.values.end());
            counts.push_back(1);
        } else {
            auto n = static_cast<std::size_t>(node - layer->nodes.begin());
            float* sum = &layer->nodeLuts[n * length];
            for (std::size_t k = 0; k < length; ++k) sum[k] += lut.values[k];
            ++counts[n];
        }
    }
    for (std::size_t l = 0; l < bank.layers.size(); ++l)
        for (std::size_t n = 0; n < mergedCount[l].size(); ++n)
            if (mergedCount[l][n] > 1)
                for (std::size_t k = 0; k < length; ++k)
                    bank.layers[l].nodeLuts[n * length + k] /= static_cast<float>(mergedCount[l][n]);
    bank.buildTriangulations();  // the layers' own, for the choice below
    const bool layersSpanTheDisk = std::all_of(bank.layers.begin(), bank.layers.end(),
                                               [](const ViewLayer& l) { return !l.lights.triangles().empty(); });
    bank.domain =
        domain ? *domain : (bank.layers.size() == 1 || layersSpanTheDisk ? BankDomain::Layers : BankDomain::Isotropic);
    bank.buildTriangulations();
    if (!bank.followsLight()) {
        if (bank.domain == BankDomain::Layers && bank.layers.size() > 1)
            return Error{source +
                         ": each view direction has one light direction, so a bank over view layers cannot "
                         "follow the light; bake it with --domain isotropic (for isotropic materials)"};
        return Error{source + ": the light directions do not vary" +
                     (bank.domain == BankDomain::Isotropic ? std::string(" relative to the view") : std::string()) +
                     ", so no bank baked from them can follow the light"};
    }
    bank.fillGrids();
    return success();
}

std::optional<PixelRect> sampleWindow(const LutBank& bank) {
    const Mask& mask = bank.prediction.mask;
    if (!bank.makesLuts() || mask.inside.empty() || mask.count() == mask.inside.size()) return std::nullopt;
    const PixelRect r = largestRectInside(mask);
    if (r.width <= 0 || r.height <= 0) return std::nullopt;
    return r;
}

float inputCode(const Image& image, ColourMode colour) {
    const int codes = colour == ColourMode::Rgb ? image.maxCode() : image.channels * image.maxCode();
    return 1.f / static_cast<float>(codes);
}

Image applyLuts(const Image& image, ColourMode colour, const std::vector<float>& values, int entries,
                float targetCode) {
    Image out = image;
    const auto width = static_cast<std::uint32_t>(image.width);
    const std::size_t n = image.pixelCount();
    const bool dither = targetCode > 0;
    const float code = inputCode(image, colour);
    auto map = [&](const float* lut, float v, std::size_t i, std::uint32_t c) {
        if (!dither) return Lut::applyLut(lut, entries, v);
        const auto index = static_cast<std::uint32_t>(i);
        const float in = lutInput(v, index % width, index / width, code, c);
        return lutOutput(Lut::applyLut(lut, entries, in), targetCode);
    };
    if (colour == ColourMode::Rgb) {
        BTFLUT_CHECK(image.channels == 3);
        for (std::size_t i = 0; i < n; ++i)
            for (std::uint32_t c = 0; c < 3; ++c)
                out.samples[i * 3 + c] =
                    map(&values[c * static_cast<std::size_t>(entries)], image.samples[i * 3 + c], i, c);
        return out;
    }
    if (image.channels == 1) {
        for (std::size_t i = 0; i < n; ++i) out.samples[i] = map(values.data(), image.samples[i], i, 0);
        return out;
    }
    for (std::size_t i = 0; i < n; ++i) {
        const float grey = image.grey(i);
        setGrey(&out.samples[i * 3], grey, map(values.data(), grey, i, 0));
    }
    return out;
}

const Predictor& LutBank::predictor() const {
    BTFLUT_CHECK(makesLuts() && prediction.predictor);
    return *prediction.predictor;
}

std::string LutBank::predictorName() const { return makesLuts() ? predictor().name() : ""; }

double LutBank::predictorBytesPerTexel() const {
    if (!makesLuts()) return reference.channels * (reference.bitDepth / 8.0);
    return predictor().bytesPerTexel() + (prediction.regions > 1 ? 1 : 0);
}

LevelCounts brdfReferenceGrey(const LutBank& bank) {
    const Image& reference = bank.reference;
    // The target's mean is the sample's (brdfScale): the reference's must be too, or a
    // capture whose sample covers 42% of the image is drawn 2.4x too bright.
    if (bank.makesLuts() && !bank.prediction.mask.inside.empty())
        return countGreyLevels(reference, bank.prediction.mask);
    return countGreyLevels(reference, fullMask(reference.width, reference.height));
}

float brdfScale(const LutBank& bank, const LevelCounts& referenceGrey, const BankLookup& lookup) {
    double reference = 0, total = 0, target = 0;
    for (std::size_t k = 0; k < referenceGrey.counts.size(); ++k) {
        if (!referenceGrey.counts[k]) continue;
        const double v = referenceGrey.valueOf(k), n = static_cast<double>(referenceGrey.counts[k]);
        reference += n * v;
        total += n;
        if (!bank.makesLuts()) target += n * Lut::applyLut(lookup.values.data(), bank.entries, static_cast<float>(v));
    }
    if (bank.makesLuts()) {
        // The target's mean grey: each region's quantile function's mean (trapezoids over
        // [0, 1]), weighted by its sample texels; rgb banks: the mean over their channels.
        const LutBank::Prediction& prediction = bank.prediction;
        const auto samples = static_cast<std::size_t>(prediction.quantiles),
                   channels = static_cast<std::size_t>(bank.channels());
        std::vector<double> texels(static_cast<std::size_t>(prediction.regions), 0);
        for (std::size_t i = 0; i < prediction.mask.inside.size(); ++i)
            texels[prediction.labels.empty() ? 0 : prediction.labels[i]] += prediction.mask.inside[i];
        double mean = 0;
        for (std::size_t r = 0; r < texels.size(); ++r)
            for (std::size_t c = 0; c < channels; ++c) {
                const float* q = &lookup.values[(r * channels + c) * samples];
                double integral = 0;
                for (std::size_t m = 0; m + 1 < samples; ++m) integral += 0.5 * (q[m] + q[m + 1]);
                mean += texels[r] / static_cast<double>(prediction.mask.count()) * integral /
                        static_cast<double>(samples - 1) / static_cast<double>(channels);
            }
        target = mean * total;
    }
    return reference > 0 ? static_cast<float>(target / reference) : 1.f;
}

void setGrey(float* rgb, float grey, float target) {
    if (grey <= 0.f) {
        rgb[0] = rgb[1] = rgb[2] = target;
        return;
    }
    const float scale = target / grey;
    float top = 0.f;
    for (int c = 0; c < 3; ++c) top = std::max(top, rgb[c] *= scale);
    if (top > 1.f) {
        // Pull the colour towards its grey until the brightest channel is 1: the mean (the
        // grey value) stays at target.
        const float k = (1.f - target) / (top - target);
        for (int c = 0; c < 3; ++c) rgb[c] = target + (rgb[c] - target) * k;
    }
}

}  // namespace btflut

#pragma once
// A LUT bank: everything a renderer needs to give one reference image the histogram of the
// material under any light (and view) direction.
//
//   Result<LutBank> bank = bakeBank(dataset, BakeOptions{});    // bake.h
//   BankLookup lut = bank->lookup(light, view);    // blended LUT + how it was obtained
//   Image relit = relight(*bank, light, view);     // the CPU reference (relight/relighter.h)
//
// Layout. Images are grouped by view direction into layers (one layer for a fixed camera).
// Each layer holds
//   - nodes: one LUT per measured light direction (float, exact), and
//   - grid: the LUTs resampled on a gridSize x gridSize regular grid over the equal-area
//     disk (direction.h) — what an engine uploads as a texture array and reads with
//     hardware bilinear filtering; nodes outside the unit disk hold the horizon's LUT.
// Queries use the nodes: Delaunay interpolation over the measured directions, so a measured
// direction reproduces its measurement exactly, and directions outside the measured hull
// are clamped to its boundary, or, in banks filled from the model (model_fill.h), move from
// the clamped LUT to the model's within one grid step; in the layers domain, a light beyond
// one view's measured lights but within another's moves likewise to the nearest such view's
// LUT at that light (measurements come before the clamp and the model); in the isotropic
// domain, a pair beyond the hull moves likewise to the nearest measured pair. Blending LUTs
// blends quantile functions (lut.h). Two domains:
//   - layers: within a layer over the light disk, then across the layers' view directions.
//     Any material, when each layer's lights span the disk (a fixed camera, Bonn BTFs).
//   - isotropic: over (theta_i, theta_r, phi_i - phi_r) in 3-D (isotropicPoint), for
//     isotropic materials measured with light and view moving together (CUReT: 205
//     light/view pairs; synth's curet-c2), where a layer holds one light or a few.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/bank/target_fit.h"
#include "core/data/dataset.h"
#include "core/direction/triangulation.h"
#include "core/histogram/lut.h"
#include "core/image/image.h"
#include "core/predict/light_model.h"
#include "core/predict/predictor.h"

namespace btflut {

enum class ColourMode : std::uint32_t {
    Grey = 1,  ///< one LUT on the grey value; pixel colour ratios kept
    Rgb = 3,   ///< one LUT per channel
    Lrgb = 4,  ///< grey references and one RGB albedo: a LUT on the grey value, the albedo's chroma
};

const char* colourName(ColourMode c);

/// How a LUT was obtained: from a measurement at that direction, by interpolating
/// measurements around it, by clamping to the nearest measured boundary, or (wholly or in
/// part) from the fitted rough-surface model that fills directions without measurements
/// (model_fill.h). From best to worst: measured, interpolated, modelled, clamped. One word per
/// state in every output (`relight`, `info`, the viewer, the page, material.json).
enum class Provenance : std::uint8_t { Measured = 0, Interpolated = 1, Clamped = 2, Modelled = 3 };

const char* provenanceName(Provenance p);

/// How lookups interpolate between the measured directions (see the top of this file).
enum class BankDomain : std::uint32_t { Layers = 0, Isotropic = 1 };

const char* domainName(BankDomain d);
Result<BankDomain> parseDomain(const std::string& name);

/// A light/view pair as a point of the isotropic domain: the light's equal-area disk point
/// in the frame turned so that the view's azimuth is 0, mirrored to y >= 0 (isotropic
/// surfaces look the same mirrored), and the view's equal-area radius as z. A frontal view
/// keeps the sample frame.
Point3 isotropicPoint(Direction light, Direction view);

/// Directions closer than this (radians) are one node: repeated measurements are merged.
constexpr double kSameDirection = 1e-6;

struct LightNode {
    std::string name;  ///< image it came from (merged duplicates: the first)
    Direction light;
    bool modelled = false;  ///< filled from the fitted model (model_fill.h), not measured
};

struct ViewLayer {
    Direction view;
    std::vector<LightNode> nodes;
    /// nodes x nodeLength(): each node's LUTs (channels x entries), or, in banks that make
    /// their LUTs at run time, its targets' quantile functions (regions x channels x quantiles)
    std::vector<float> nodeLuts;
    std::vector<std::uint16_t> gridLuts;  ///< gridSize^2 x nodeLength(), unorm16
    /// Banks with a predictor: at each grid node, the LUT that takes the prediction at the
    /// node's light to the target there (regions x channels x entries, unorm16; Relighter::
    /// bakeMatchGrid). Read bilinearly (matchGridLookup), it spares the renderer counting the
    /// prediction when the light moves. Empty for banks of LUTs.
    std::vector<std::uint16_t> matchGridLuts;
    std::vector<Provenance> gridProvenance;  ///< gridSize^2; node (i, j) at j * gridSize + i
    Triangulation lights;                    ///< over the measured nodes' disk points (they come first)
    Triangulation modelLights;               ///< over the modelled nodes' (index + measuredNodes); empty without
    std::size_t measuredNodes = 0;
    double measuredReach = 0;  ///< the disk radius of the farthest measured light
    bool lutsLoaded = true;    ///< false: read without its LUTs (BankReadOptions::views)
    /// Banks that make their LUTs: the smooth fit their lookups add to the blend of the
    /// measured targets between measured lights (target_fit.h); empty: the blend alone.
    TargetFit fit;
};

struct BankLookup {
    std::vector<float> values;                     ///< nodeLength(): LUTs, or quantile functions (LutBank::prediction)
    Provenance provenance = Provenance::Measured;  ///< the worse of the two below
    Provenance lightProvenance = Provenance::Measured, viewProvenance = Provenance::Measured;
};

struct LutBank {
    /// A measured node: layer and node index.
    struct NodeRef {
        std::size_t layer = 0, node = 0;
    };

    int entries = 256;
    ColourMode colour = ColourMode::Grey;
    int gridSize = 17;
    BankDomain domain = BankDomain::Layers;
    std::vector<ViewLayer> layers;
    Triangulation views;   ///< layers domain: over the layers' view directions
    Triangulation3 pairs;  ///< isotropic domain: over the nodes' isotropicPoint
    /// isotropic domain: the nodes at each point of `pairs` (several where the symmetry
    /// maps measurements onto one point; they are averaged).
    std::vector<std::vector<NodeRef>> pairNodes;
    /// isotropic domain: the corners of the box the points of `pairs` span (lowest x, y, z;
    /// highest), where pairFit is read.
    Point3 pairsLow, pairsHigh;
    /// isotropic domain: the estimate of the targets between the measured pairs chosen by
    /// validation (bake/target_choice.h), over the pairs' points; empty: their blend alone.
    TargetFit pairFit;

    std::string referenceName;
    Direction referenceLight, referenceView;
    Image reference;  ///< without samples when the bank was written without it
    /// The baseline PTM of the reference view (a light model of basis ptm, ptm.h); empty unless
    /// baked with one.
    LightModel ptm;
    /// The model's parameters (JSON, docs/model-params.md) where nodes were filled from the
    /// fitted model (LightNode::modelled); empty otherwise.
    std::string modelFill;
    bool ptmInFile = false;  ///< read from a file holding a PTM (decoded or skipped)

    /// Banks that make their LUTs at run time (bake --references K > 1, --regions, --colour
    /// lrgb, a light model or a learned model; relighter.h): a predictor relit per light, and
    /// regions of the sample, each matched to its own target. Their nodes hold the targets'
    /// quantile functions.
    struct Prediction {
        /// What predicts each texel before each light's LUT matches it (predictor.h): the
        /// references blended (reference_blend.h), a light model (model_predictor.h; a bank's
        /// PTM as one) or a learned model (learned_predictor.h). Shared by the bank's copies:
        /// a predictor never changes.
        std::shared_ptr<const Predictor> predictor;
        /// How far each light's LUT moves the prediction's distribution towards the target's:
        /// 1 fully (the target's histogram), 0 not at all (the prediction as it is); between,
        /// the quantile functions blended (the Wasserstein geodesic between the two).
        float match = 1;
        /// How a light's LUT is made. Measured: the measured distributions' quantile
        /// functions are blended at the light, and the prediction there is matched to that
        /// target (its distribution counted per light change). Corrections: at each node the
        /// LUT that takes the prediction at the node's light to the node's measured
        /// distribution (made once per bank), blended at the light as a classic bank blends
        /// its LUTs and applied to the prediction there: the predictor supplies how the
        /// distribution moves between the measured lights, the measurements correct its
        /// level and spread. Both reproduce a measured node exactly; only Measured counts
        /// per light change.
        enum class Target : std::uint32_t { Measured = 0, Corrections = 1 } target = Target::Measured;
        std::vector<std::uint8_t> labels;  ///< per texel its region (all texels); empty: one region
        Mask mask;                         ///< the sample texels: the blend's statistics are theirs
        int regions = 1;
        int quantiles = 0;  ///< samples per quantile function; 0: a bank of LUTs
    } prediction;

    /// How `bake --predictor auto` chose the predictor: the candidates and their validation
    /// figures, JSON (docs/predictors.md); empty for banks baked otherwise.
    std::string selection;
    /// How bake chose each layer's and region's estimate of the target between measured
    /// lights (ViewLayer::fit): the candidates and their validation figures, JSON
    /// (docs/predictors.md); empty for banks without the choice.
    std::string targetChoice;

    /// True for banks that make their LUTs at run time (see Blend).
    bool makesLuts() const { return prediction.quantiles > 0; }
    /// The predictor of a bank that makes its LUTs.
    const Predictor& predictor() const;
    /// Its kind, for what only that kind has (its file chunk, its sidecar, its description):
    /// the predictor as `Kind`, or null when it is another (or the bank makes no LUTs).
    template <class Kind>
    const Kind* predictorAs() const {
        return dynamic_cast<const Kind*>(prediction.predictor.get());
    }
    /// The predictor's name as the command line gives it (`--predictor`): the light model's
    /// (ptm, hsh2, rbf9, bln9c, ...), the learned model's (neural9) or "references"; "" for a
    /// bank of LUTs.
    std::string predictorName() const;
    /// The predictor's kind; Luts for a bank of LUTs.
    PredictorKind predictorKind() const { return makesLuts() ? predictor().kind() : PredictorKind::Luts; }
    /// Bytes per texel the predictor stores (Predictor::bytesPerTexel), with regions one more
    /// for the labels; a bank of LUTs: its reference's.
    double predictorBytesPerTexel() const;
    int channels() const { return colour == ColourMode::Rgb ? 3 : 1; }
    /// One code of the values the LUTs map to (those of the reference's format: 1/765 for
    /// the grey of 8-bit RGB), the unit of the dithered output shift.
    float targetCode() const {
        int perValue = colour == ColourMode::Rgb ? 1 : reference.channels;
        return 1.f / static_cast<float>(perValue * (reference.bitDepth == 16 ? 65535 : 255));
    }
    std::size_t lutLength() const { return static_cast<std::size_t>(channels()) * entries; }
    /// Values per node: lutLength(), or regions x channels x quantiles (makesLuts).
    std::size_t nodeLength() const {
        return makesLuts() ? static_cast<std::size_t>(prediction.regions) * channels() * prediction.quantiles
                           : lutLength();
    }
    /// The length of one monotonic segment of a node's values: entries or quantiles.
    std::size_t segmentLength() const { return static_cast<std::size_t>(makesLuts() ? prediction.quantiles : entries); }

    /// The LUT for a light and view direction (any direction in the upper hemisphere);
    /// with `interpolate` false, the LUT of the nearest measured node (for comparisons).
    BankLookup lookup(Direction light, Direction view = {}, bool interpolate = true) const;
    /// The layer nearest `except` by view whose measured lights' hull holds `light` (layers
    /// domain: where a view's own lights do not reach, lookup() takes that view's).
    std::optional<std::size_t> nearestLayerMeasuring(DiskPoint light, std::size_t except) const;

    /// The LUT an engine reads from the resampled grid (layer `layer`): bilinear between the
    /// four grid nodes around the light's disk point, from their unorm16 values, as one
    /// filtered fetch of the exported 3D texture does (shaders/btflut.glsl). It equals
    /// lookup() at grid nodes; between them it differs most near the measured triangles' edges.
    std::vector<float> gridLookup(Direction light, std::size_t layer = 0) const;
    /// The same over a layer's matchGridLuts: per region and channel, the LUT on the
    /// prediction's codes (Relighter::gridFrame).
    std::vector<float> matchGridLookup(Direction light, std::size_t layer = 0) const;
    /// At a view: the layers' grids blended with the view's weights, as lookup() blends the
    /// layers' nodes (a bank of views; one layer: that layer's).
    std::vector<float> matchGridLookup(Direction light, Direction view) const;
    /// Values per node of matchGridLuts: regions x channels x entries.
    std::size_t matchLength() const {
        return static_cast<std::size_t>(prediction.regions) * static_cast<std::size_t>(channels()) *
               static_cast<std::size_t>(entries);
    }

    /// Every view layer's grid as one block of unorm16 texels, channels interleaved, ordered
    /// [layer][grid node j * gridSize + i][region][segment entry][channel]: for a bank of LUTs
    /// (one region), the memory of the 3D texture that `export -o DIR/` writes and
    /// shaders/btflut.glsl samples (x the LUT entry, y grid column i, z layer * G + row j).
    std::vector<std::uint16_t> gridTexels() const;

    /// The measured node nearest to a light direction in the layer nearest to a view
    /// direction (nearest by angle); in the isotropic domain, the node nearest in it.
    NodeRef nearestNode(Direction light, Direction view = {}) const;
    /// Isotropic domain: the point of `pairs` nearest q.
    std::size_t nearestPair(Point3 q) const;
    /// The share a LUT clamped to a measured hull keeps at `distance` (disk units) beyond it:
    /// 1 on the hull, 0 one grid step out; other data take the rest.
    double hullRamp(double distance) const;

    /// Disk point of grid node (i, j): x = -1 + 2 i / (gridSize - 1), likewise y.
    DiskPoint gridPoint(int i, int j) const;

    /// The share of the hemisphere of light directions (by solid angle) where lookups at a
    /// layer's view interpolate between measurements, rather than clamp or use the model.
    double lightCoverage(std::size_t layer) const;

    /// The layers that lookups at a view direction use: those the view triangulation blends
    /// there, and the nearest by angle (every layer in the isotropic domain).
    std::vector<std::size_t> layersFor(Direction view) const;

    /// True when lookups at some view give different LUTs for different lights (there are
    /// two measured light directions to blend between, in a layer or in the isotropic domain).
    bool followsLight() const;

    /// Rebuilds the triangulations from the node and layer directions (after loading).
    void buildTriangulations();
    /// A bank of the same directions, to hold other values at them: the LUT format (entries,
    /// colour, grid size), the domain, every layer's view and nodes and the triangulations
    /// over them; no node values, grids, fits, reference or predictor (the relighter's banks
    /// of each node's correction, and of its match grid).
    LutBank sameDirections() const;
    /// Fills every layer's grid from its nodes.
    void fillGrids();
};

/// A LUT at one light and view direction (measured or modelled); values are
/// channels x entries.
struct DirectionalLut {
    std::string name;
    Direction light;
    Direction view;
    std::vector<float> values;
};

/// Builds `bank`'s layers from LUTs: one layer per view direction, repeated light directions
/// merged by averaging (the barycentre), then the domain, triangulations and grids.
/// bank.entries, colour, gridSize (and blend) must be set; each holds bank.nodeLength() values.
/// Without a domain: layers when there is one layer or every layer's lights span the light
/// disk, isotropic otherwise. Refuses (naming `source`) a bank that could not follow the light.
Status setNodes(LutBank& bank, const std::vector<DirectionalLut>& luts, std::optional<BankDomain> domain,
                const std::string& source);

/// What a closed surface (a sphere) wraps of the reference: where the bank's sample mask
/// leaves part of the image out, the largest rectangle inside it, so that no background is
/// tiled over the surface; none where the whole image is the material.
std::optional<PixelRect> sampleWindow(const LutBank& bank);

/// One code of the value a LUT maps for this image: of a channel in rgb mode or for a grey
/// image, of the grey value (channels x max code) otherwise. The unit of the dithered input.
float inputCode(const Image& image, ColourMode colour);

/// Applies a LUT (channels x entries, as BankLookup::values) to an image. Grey mode sets
/// each pixel's grey to LUT(grey), scaling its colour by LUT(grey) / grey and, where that
/// would clip a channel, desaturating towards grey so the new grey value is kept exactly;
/// rgb mode maps each channel by its own LUT. With `targetCode` > 0 (one code of the
/// targets' values, e.g. 1/765) the LUT is applied dithered (lutInput/lutOutput in lut.h),
/// which reproduces the target histogram closely; with 0, plainly.
Image applyLuts(const Image& image, ColourMode colour, const std::vector<float>& values, int entries, float targetCode);

/// The reference's grey levels over the texels the bank's targets describe: a bank that
/// makes its LUTs at run time, its sample mask (its targets are the sample's distributions);
/// a bank of LUTs, every texel (its LUTs map every texel). brdfScale's input, counted once.
LevelCounts brdfReferenceGrey(const LutBank& bank);

/// The paper's "2D texture mapping" (renderer mode brdf): the factor that brings the mean
/// grey of the reference (`referenceGrey`: brdfReferenceGrey(bank)) to the target's at a
/// lookup's direction, over the same texels; 1 for a black reference.
float brdfScale(const LutBank& bank, const LevelCounts& referenceGrey, const BankLookup& lookup);

/// Grey mode's colour step: an RGB pixel of grey value `grey` (the mean of its channels)
/// gets grey `target`: its colour is scaled by target / grey and, where a channel would
/// exceed 1, desaturated towards grey so the grey stays `target` (black pixels become grey).
void setGrey(float* rgb, float grey, float target);

}  // namespace btflut

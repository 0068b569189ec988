#include "core/bake/bake.h"
#include "core/bake/target_choice.h"

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <optional>

#include "core/parallel.h"
#include "core/predict/model_predictor.h"
#include "core/predict/ptm.h"
#include "core/predict/reference_blend.h"
#include "core/predict/references.h"
#include "core/relight/relighter.h"

namespace btflut {

namespace {

// Runs a step of parallelFor's work items in index order, each index exactly once: float sums
// made there (the PTM's moments, the lrgb albedo) then do not depend on which thread finished
// first, so the same inputs give the same bank bytes. No deadlock: parallelFor hands out
// indices in increasing order, so the lowest one not yet through is never waiting.
class InIndexOrder {
public:
    template <class Step>
    void run(std::size_t index, Step&& step) {
        std::unique_lock lock(m_mutex);
        m_turn.wait(lock, [&] { return m_next == index; });
        step();
        ++m_next;
        m_turn.notify_all();
    }

private:
    std::mutex m_mutex;
    std::condition_variable m_turn;
    std::size_t m_next = 0;
};

// Per-image result of the streaming pass.
struct ImageLuts {
    std::vector<float> values;  // channels x entries
    std::string error;
};

std::vector<LevelCounts> countLevels(const Image& image, const Mask& mask, ColourMode colour) {
    if (colour == ColourMode::Grey) return {countGreyLevels(image, mask)};
    return {countChannelLevels(image, mask, 0), countChannelLevels(image, mask, 1), countChannelLevels(image, mask, 2)};
}

// A reference whose most common grey level holds more of the sample than this is passed
// over by default: a LUT gives all texels of one level one value, so it cannot spread such
// a tie over the target's quantiles (a foil more than half black under a frontal camera).
constexpr double kLargestTie = 0.25;

// The default reference and its image (decoded into `storage`, or the provider's): the image nearest to a frontal
// camera, then nearest to frontal light, whose most common grey level holds at most kLargestTie of the sample; where
// none does, the one whose most common level holds least. Images are decoded in that order until one qualifies, so a
// well-exposed frontal image costs nothing extra.
Result<std::pair<std::size_t, const Image*>> chooseReference(const Dataset& dataset, const ImageProvider& images,
                                                             Image& storage) {
    std::vector<std::size_t> order(dataset.images.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    auto frontal = [&](std::size_t i) {
        const DatasetImage& im = dataset.images[i];
        // Angles equal within 1e-12 rad count as one, so the dataset's order settles them.
        return std::pair{std::llround(im.view.theta * 1e12), std::llround(im.light.theta * 1e12)};
    };
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return frontal(a) < frontal(b); });
    std::optional<std::pair<std::size_t, const Image*>> best;
    double bestTie = 2;
    std::optional<Mask> mask;
    for (std::size_t i : order) {
        Image decoded;
        Result<const Image*> image = images(i, decoded);
        if (!image) return Error{image.error()};
        if (!mask) {
            Result<Mask> loaded = loadDatasetMask(dataset, (*image)->width, (*image)->height);
            if (!loaded) return Error{loaded.error()};
            mask = std::move(*loaded);
        }
        // The mask has the first candidate's size; another size is refused by bake itself.
        if ((*image)->width != mask->width || (*image)->height != mask->height) continue;
        const LevelCounts levels = countGreyLevels(**image, *mask);
        const double tie = static_cast<double>(*std::max_element(levels.counts.begin(), levels.counts.end())) /
                           static_cast<double>(std::max<std::uint64_t>(levels.total(), 1));
        if (tie < bestTie) {
            bestTie = tie;
            if (*image == &decoded) storage = std::move(decoded);
            best = {i, *image == &decoded ? &storage : *image};
        }
        if (tie <= kLargestTie) break;
    }
    BTFLUT_CHECK(best);  // the first candidate always has the mask's size
    return *best;
}

// What a bank that makes its LUTs at run time is baked with besides the classic reference:
// the other references, the regions (as one mask each) and, for lrgb, the albedo.
struct PredictionSetup {
    std::vector<std::size_t> references;  // dataset indices, the classic reference first
    std::vector<Mask> regionMasks;        // the sample mask split by region
    Regions regions;
};

Result<PredictionSetup> setUpPrediction(const Dataset& dataset, const BakeOptions& options, std::size_t refIndex,
                                        const Image& ref, const Mask& mask, const ImageProvider& images) {
    PredictionSetup setup;
    if (!dataset.fixedView()) {
        // Several views: a learned model of the views on rectified images (one frame for every
        // view), its bank a layer per view; every other predictor predicts one camera's images.
        if (!options.fit || !options.fit->takesViews())
            return Error{dataset.source +
                         ": --references, --regions, --colour lrgb and the light models need one view (a fixed "
                         "camera); this dataset has several (a learned model, --predictor neural, takes rectified "
                         "views)"};
        if (!dataset.rectified)
            return Error{dataset.source +
                         ": a learned model of several views needs them rectified (one frame for every view: the "
                         "manifest's \"rectified\": true); without, bake the one-reference bank per view"};
        if (options.regions > 1 || !options.labelsPath.empty())
            return Error{dataset.source + ": --regions and --labels need one view (a fixed camera)"};
        if (options.domain == BankDomain::Isotropic)
            return Error{dataset.source + ": a learned model of views is baked in the layers domain, not isotropic"};
        // A layer per view follows the light only with 3 lights in each (checked before the
        // training, which the layers would otherwise waste).
        if (const auto [view, lights] = dataset.fewestLightsPerView(); lights < 3)
            return Error{dataset.source + ": view (" + std::to_string(view.thetaDegrees()) + ", " +
                         std::to_string(view.phiDegrees()) + ") has " + std::to_string(lights) +
                         " light(s); a learned model of views needs a layer per view with 3 or more"};
    }
    std::vector<Direction> lights;
    for (const DatasetImage& im : dataset.images) lights.push_back(im.light);
    std::vector<DiskPoint> points;
    for (Direction l : lights) points.push_back(toDisk(l));
    std::size_t distinct = 0;  // distinct light directions
    for (std::size_t i = 0; i < lights.size(); ++i) {
        bool seen = false;
        for (std::size_t j = 0; j < i && !seen; ++j) seen = angleBetween(lights[i], lights[j]) < kSameDirection;
        distinct += !seen;
    }
    if (options.references < 1 || static_cast<std::size_t>(options.references) > distinct)
        return Error{"--references " + std::to_string(options.references) + " must be within 1.." +
                     std::to_string(distinct) + " (the distinct light directions of " + dataset.source + ")"};
    if (options.fitsModel()) {
        // no references: the model is fitted to every image
    } else if (options.colour == ColourMode::Lrgb && options.references > 16)
        return Error{"--colour lrgb packs at most 16 references (four per texture layer); --references " +
                     std::to_string(options.references) + " is more"};
    else
        setup.references = pickReferences(lights, refIndex, static_cast<std::size_t>(options.references));

    if (!options.labelsPath.empty()) {
        Result<Image> labels = loadImage(options.labelsPath);
        if (!labels) return Error{labels.error()};
        Result<Regions> r = regionsFromLabels(*labels, mask, ref.width, ref.height, options.labelsPath);
        if (!r) return Error{r.error()};
        setup.regions = std::move(*r);
    } else if (options.regions > 1) {
        // Responses under at most 32 lights spread over the measured ones.
        const std::vector<std::size_t> spread = spreadLights(lights, 32);
        Responses responses{ref.width, ref.height, static_cast<int>(spread.size()),
                            std::vector<std::uint8_t>(ref.pixelCount() * spread.size())};
        for (std::size_t k = 0; k < spread.size(); ++k) {
            Image storage;
            Result<const Image*> image =
                spread[k] == refIndex ? Result<const Image*>(&ref) : images(spread[k], storage);
            if (!image) return Error{image.error()};
            if (Status size = requireSameSize(**image, dataset.images[spread[k]].path, ref.width, ref.height,
                                              dataset.images[refIndex].path + " (the reference)");
                !size)
                return Error{size.error()};
            for (std::size_t i = 0; i < ref.pixelCount(); ++i)
                responses.values[i * spread.size() + k] =
                    static_cast<std::uint8_t>(std::lround((*image)->grey(i) * 255.f));
        }
        Result<Regions> r = segmentRegions(responses, mask, options.regions, dataset.source);
        if (!r) return Error{r.error()};
        setup.regions = std::move(*r);
    } else {
        setup.regions = {1, std::vector<std::uint8_t>(ref.pixelCount(), 0)};
    }
    for (int r = 0; r < setup.regions.count; ++r) {
        Mask m = mask;
        for (std::size_t i = 0; i < m.inside.size(); ++i) m.inside[i] = m.inside[i] && setup.regions.labels[i] == r;
        setup.regionMasks.push_back(std::move(m));
    }
    return setup;
}

// Decodes every image into `decoded` (the reference copied) and fits the model (a light
// model or a learned one) to them, as the bank's predictor.
Result<std::shared_ptr<const Predictor>> fitModel(const Dataset& dataset, const BakeOptions& options,
                                                  std::size_t refIndex, const Image& ref, const Mask& mask,
                                                  const ImageProvider& images, std::vector<Image>& decoded,
                                                  bool perChannel) {
    decoded.assign(dataset.images.size(), Image());
    std::vector<std::string> errors(dataset.images.size());
    parallelFor(dataset.images.size(), options.threads, [&](std::size_t i) {
        if (i == refIndex) {
            decoded[i] = ref;
            return;
        }
        Image storage;
        Result<const Image*> image = images(i, storage);
        if (!image) {
            errors[i] = image.error();
        } else if (Status size = requireSameSize(**image, dataset.images[i].path, ref.width, ref.height,
                                                 dataset.images[refIndex].path + " (the reference)");
                   !size) {
            errors[i] = size.error();
        } else if ((*image)->channels != ref.channels) {
            errors[i] = dataset.images[i].path + ": " + ((*image)->channels == 3 ? "colour" : "grey") + " among " +
                        (ref.channels == 3 ? "colour" : "grey") + " images";
        } else {
            decoded[i] = *image == &storage ? std::move(storage) : **image;
        }
    });
    for (const std::string& e : errors)
        if (!e.empty()) return Error{e};
    if (options.fitted) return options.fitted;
    std::vector<const Image*> view;
    std::vector<Direction> lights, views;
    for (std::size_t i = 0; i < dataset.images.size(); ++i) {
        view.push_back(&decoded[i]);
        lights.push_back(dataset.images[i].light);
        views.push_back(dataset.images[i].view);
    }
    // Rectified views (setUpPrediction refuses others, and kinds that do not take them).
    if (dataset.fixedView()) views.clear();
    return options.fit->fit(FitImages{view, lights, views, mask, perChannel, options.threads, dataset.source});
}

// A reference as the blend stores it: 8-bit (blends are integer sums of 8-bit codes,
// relighter.h), its grey value alone for lrgb.
Image blendForm(const Image& image, ColourMode colour) {
    const bool grey = colour == ColourMode::Lrgb && image.channels == 3;
    Image out(image.width, image.height, grey ? 1 : image.channels, 8);
    for (std::size_t i = 0; i < out.pixelCount(); ++i)
        for (int c = 0; c < out.channels; ++c) {
            const float v =
                grey ? image.grey(i)
                     : image.samples[i * static_cast<std::size_t>(image.channels) + static_cast<std::size_t>(c)];
            out.samples[i * static_cast<std::size_t>(out.channels) + static_cast<std::size_t>(c)] =
                std::round(v * 255.f) / 255.f;
        }
    return out;
}

// Options that no dataset can satisfy, refused before anything is decoded.
Status checkOptions(const Dataset& dataset, const BakeOptions& options) {
    if (dataset.images.empty()) return Error{dataset.source + ": dataset has no images"};
    if (options.gridSize < 2 || options.gridSize > 257)
        return Error{"--grid " + std::to_string(options.gridSize) + " is outside [2, 257]"};
    if (options.entries != 0 && (options.entries < 2 || options.entries > 65536))
        return Error{"--entries " + std::to_string(options.entries) + " is outside [2, 65536]"};
    if (options.regions < 1 || options.regions > 255)
        return Error{"--regions " + std::to_string(options.regions) + " is outside [1, 255]"};
    if (options.quantiles < 2 || options.quantiles > 65536)
        return Error{"--quantiles " + std::to_string(options.quantiles) + " is outside [2, 65536]"};
    return success();
}

// One bake, step by step (bakeBank): the reference and the bank's header, what the
// predictor needs (the blend's references and regions, or the fitted light model), one
// streaming pass over the images, then the predictor and the nodes.
class Baking {
public:
    Baking(const Dataset& dataset, const BakeOptions& options, const ImageProvider& images)
        : m_dataset(dataset), m_options(options), m_images(images), m_makesLuts(options.predicts()) {}

    // The reference (--reference, or the default) decoded, its mask, and the bank's header.
    Status chooseReference() {
        const Image* reference = nullptr;
        if (m_options.referenceName.empty()) {
            Result<std::pair<std::size_t, const Image*>> chosen =
                btflut::chooseReference(m_dataset, m_images, m_referenceStorage);
            if (!chosen) return Error{chosen.error()};
            std::tie(m_refIndex, reference) = *chosen;
        } else {
            auto it = std::find_if(m_dataset.images.begin(), m_dataset.images.end(), [&](const DatasetImage& im) {
                return im.name == m_options.referenceName || im.path == m_options.referenceName;
            });
            if (it == m_dataset.images.end())
                return Error{m_dataset.source + ": no image named '" + m_options.referenceName + "' for --reference"};
            m_refIndex = static_cast<std::size_t>(it - m_dataset.images.begin());
            Result<const Image*> decoded = m_images(m_refIndex, m_referenceStorage);
            if (!decoded) return Error{decoded.error()};
            reference = *decoded;
        }
        m_ref = reference;
        const DatasetImage& refInfo = m_dataset.images[m_refIndex];
        if (m_options.colour != ColourMode::Grey && m_ref->channels != 3)
            return Error{refInfo.path + ": --colour " + colourName(m_options.colour) +
                         " needs colour images, this one is grey"};
        Result<Mask> loadedMask = loadDatasetMask(m_dataset, m_ref->width, m_ref->height);
        if (!loadedMask) return Error{loadedMask.error()};
        m_mask = std::move(*loadedMask);
        m_bank.colour = m_options.colour;
        m_bank.gridSize = m_options.gridSize;
        m_bank.entries = m_options.entries ? m_options.entries : (m_ref->bitDepth == 16 ? 1024 : 256);
        m_bank.referenceName = refInfo.name;
        m_bank.referenceLight = refInfo.light;
        m_bank.referenceView = refInfo.view;
        return success();
    }

    // Banks that make their LUTs at run time keep each image's target per region as a
    // quantile function: their references and regions are chosen, or their light model
    // fitted to every image (decoded first and kept, so the pass reads them from memory).
    // Classic banks keep each image's LUT from the reference: its levels are counted.
    Status preparePredictor() {
        const DatasetImage& refInfo = m_dataset.images[m_refIndex];
        if (m_options.fitsModel() && (m_options.references > 1 || m_options.colour == ColourMode::Lrgb))
            return Error{"--predictor " + m_options.fit->family() +
                         " relights with a model: it takes no --references, and its colour is the model's (grey "
                         "or rgb)"};
        if (!(m_options.match >= 0 && m_options.match <= 1))
            return Error{"--match must be from 0 (not at all) to 1 (fully)"};
        if (m_makesLuts) {
            Result<PredictionSetup> setup = setUpPrediction(m_dataset, m_options, m_refIndex, *m_ref, m_mask, m_images);
            if (!setup) return Error{setup.error()};
            m_prediction = std::move(*setup);
            m_bank.prediction.regions = m_prediction.regions.count;
            m_bank.prediction.quantiles = m_options.quantiles;
        } else {
            m_refLevels = countLevels(*m_ref, m_mask, m_options.colour);
            for (const LevelCounts& levels : m_refLevels)
                if (levels.presentCodes() < 2)
                    return Error{refInfo.path +
                                 ": reference image is constant over the sample, so no "
                                 "LUT can give it another histogram; choose another "
                                 "with --reference"};
        }
        if (m_options.fitsModel()) {
            Result<std::shared_ptr<const Predictor>> model =
                fitModel(m_dataset, m_options, m_refIndex, *m_ref, m_mask, m_images, m_decoded,
                         m_bank.colour == ColourMode::Rgb);
            if (!model) return Error{model.error()};
            m_model = std::move(*model);
        }
        return success();
    }

    // Streams through the images: decode, count, match (or keep the quantiles), forget; the
    // PTM and the lrgb albedo accumulate on the way, the blend's references are kept.
    Result<std::vector<DirectionalLut>> measure() {
        const ImageProvider fromMemory = [&](std::size_t i, Image&) -> Result<const Image*> { return &m_decoded[i]; };
        const ImageProvider& pass = m_options.fitsModel() ? fromMemory : m_images;
        const DatasetImage& refInfo = m_dataset.images[m_refIndex];
        const Image& ref = *m_ref;
        const std::size_t length = m_bank.nodeLength();
        std::vector<ImageLuts> results(m_dataset.images.size());
        std::mutex progressMutex;
        std::size_t done = 0;
        if (m_options.ptm) m_ptm.emplace(ref.width, ref.height);
        if (m_options.colour == ColourMode::Lrgb) m_albedo.emplace(ref.width, ref.height);
        m_blendReferences.resize(m_prediction.references.size());  // as the blend keeps them, in pick order
        InIndexOrder accumulating;
        parallelFor(m_dataset.images.size(), m_options.threads, [&](std::size_t i) {
            const DatasetImage& info = m_dataset.images[i];
            ImageLuts& out = results[i];
            Image storage;
            Result<const Image*> image = i == m_refIndex ? Result<const Image*>(&ref) : pass(i, storage);
            if (!image) {
                out.error = image.error();
            } else if (Status size = requireSameSize(**image, info.path, ref.width, ref.height,
                                                     refInfo.path + " (the reference)");
                       !size) {
                out.error = size.error();
            } else if (m_options.colour != ColourMode::Grey && (*image)->channels != 3) {
                out.error = info.path + ": --colour " + std::string(colourName(m_options.colour)) +
                            " needs colour images, this one is grey";
            } else {
                out.values.reserve(length);
                measureOne(**image, i, out.values);
            }
            accumulating.run(i, [&] {  // every index, failed ones too
                if (!out.error.empty()) return;
                if (m_ptm && angleBetween(info.view, refInfo.view) < 1e-9) m_ptm->add(**image, info.light);
                if (m_albedo) m_albedo->add(**image);
            });
            if (m_options.progress) {
                std::lock_guard lock(progressMutex);
                m_options.progress(++done, m_dataset.images.size());
            }
        });
        for (const ImageLuts& r : results)
            if (!r.error.empty()) return Error{r.error};
        std::vector<DirectionalLut> luts;
        for (std::size_t i = 0; i < m_dataset.images.size(); ++i) {
            const DatasetImage& info = m_dataset.images[i];
            luts.push_back({info.name, info.light, info.view, std::move(results[i].values)});
        }
        return luts;
    }

    // The reference, the predictor's parts, the nodes, the PTM and the match grid.
    Result<LutBank> finish(const std::vector<DirectionalLut>& luts) {
        // The decoded reference is ours to keep; a provider's image is copied.
        if (m_ref == &m_referenceStorage)
            m_bank.reference = std::move(m_referenceStorage);
        else
            m_bank.reference = *m_ref;
        if (Status s = setPredictor(); !s) return Error{s.error()};
        if (Status s = setNodes(m_bank, luts, m_options.domain, m_dataset.source); !s) return Error{s.error()};
        if (m_bank.makesLuts() && m_bank.predictor().viewDependent() && m_bank.domain != BankDomain::Layers)
            return Error{m_dataset.source +
                         ": its views hold too few lights each for a layer per view (the isotropic domain); a "
                         "learned model of views needs layers"};
        if (m_options.fitTargets) {
            chooseTargetFits(m_bank, m_options.threads,
                             m_bank.makesLuts() ? std::vector<std::vector<double>>{} : entryWeights());
            m_bank.fillGrids();  // the grid's targets between the lights are the chosen estimate's
        }
        if (m_ptm) {
            Result<LightModel> fitted = m_ptm->finish(m_dataset.source);
            if (!fitted) return Error{fitted.error()};
            m_bank.ptm = std::move(*fitted);
        }
        if (m_bank.makesLuts() && m_options.matchGrid)
            bakeMatchGrid(m_bank, m_options.threads);  // the LUTs an engine or a moving light reads
        return std::move(m_bank);
    }

private:
    // One image's node values: per region its quantile functions (a bank that makes its
    // LUTs), or the LUT from the reference to it per channel.
    void measureOne(const Image& image, std::size_t index, std::vector<float>& values) {
        if (m_makesLuts) {
            const ColourMode counted = m_options.colour == ColourMode::Rgb ? ColourMode::Rgb : ColourMode::Grey;
            for (const Mask& region : m_prediction.regionMasks)
                for (const LevelCounts& levels : countLevels(image, region, counted)) {
                    const std::vector<float> q = quantileFunction(levels, m_options.quantiles);
                    values.insert(values.end(), q.begin(), q.end());
                }
            for (std::size_t k = 0; k < m_prediction.references.size(); ++k)
                if (m_prediction.references[k] == index) m_blendReferences[k] = blendForm(image, m_options.colour);
            return;
        }
        std::vector<LevelCounts> levels = countLevels(image, m_mask, m_options.colour);
        for (std::size_t c = 0; c < levels.size(); ++c) {
            Lut lut = matchLut(m_refLevels[c], levels[c], m_bank.entries);
            values.insert(values.end(), lut.values.begin(), lut.values.end());
        }
    }

    // A bank of LUTs: per channel, the reference's share of the sample at each LUT entry (the
    // weight of the entry's value in the relit histogram), as the LUTs are read (nearest entry).
    std::vector<std::vector<double>> entryWeights() const {
        std::vector<std::vector<double>> weights;
        const auto last = static_cast<double>(m_bank.entries - 1);
        for (const LevelCounts& levels : m_refLevels) {
            std::vector<double>& w = weights.emplace_back(static_cast<std::size_t>(m_bank.entries), 0.0);
            for (std::size_t code = 0; code < levels.counts.size(); ++code)
                w[static_cast<std::size_t>(std::lround(levels.valueOf(code) * last))] +=
                    static_cast<double>(levels.counts[code]);
        }
        return weights;
    }

    // The predictor's parts in the bank: the model, or the references, their lights and the
    // albedo; the regions' labels and the sample mask.
    Status setPredictor() {
        LutBank::Prediction& prediction = m_bank.prediction;
        prediction.match = m_makesLuts ? m_options.match : 1.f;
        if (!m_makesLuts) return success();
        prediction.target = m_options.target;
        prediction.labels =
            m_prediction.regions.count > 1 ? std::move(m_prediction.regions.labels) : std::vector<std::uint8_t>{};
        prediction.mask = m_mask;
        const bool perChannel = m_bank.colour == ColourMode::Rgb;
        if (m_model) {
            prediction.predictor = std::move(m_model);
            return success();
        }
        for (const Image& r : m_blendReferences) {
            const std::vector<LevelCounts> levels =
                countLevels(r, m_mask, perChannel ? ColourMode::Rgb : ColourMode::Grey);
            for (const LevelCounts& l : levels)
                if (l.presentCodes() < 2)
                    return Error{m_dataset.source + ": a reference image is constant over the sample"};
        }
        std::vector<ReferenceLight> lights;
        for (std::size_t k : m_prediction.references)
            lights.push_back({m_dataset.images[k].name, m_dataset.images[k].light});
        prediction.predictor = std::make_shared<ReferenceBlend>(std::move(m_blendReferences), std::move(lights),
                                                                perChannel, m_albedo ? m_albedo->finish() : Image{});
        return success();
    }

    const Dataset& m_dataset;
    const BakeOptions& m_options;
    const ImageProvider& m_images;
    const bool m_makesLuts;
    LutBank m_bank;
    std::size_t m_refIndex = 0;
    Image m_referenceStorage;  // the reference when decoded here
    const Image* m_ref = nullptr;
    Mask m_mask;
    PredictionSetup m_prediction;
    std::vector<LevelCounts> m_refLevels;  // classic banks: the reference's levels per channel
    std::vector<Image> m_decoded;          // a light model's images, decoded once for the fit and the pass
    std::vector<Image> m_blendReferences;
    std::shared_ptr<const Predictor> m_model;  // a fitted model, before the images are measured
    std::optional<PtmFitter> m_ptm;
    std::optional<AlbedoAccumulator> m_albedo;
};

}  // namespace

std::optional<Status> setModelNamed(BakeOptions& options, const std::string& name) {
    std::optional<Result<FitPointer>> fitted = predictorFitNamed(name);
    if (!fitted) return std::nullopt;
    if (!*fitted) return Status{Error{fitted->error()}};
    options.fit = **fitted;
    return success();
}

void BakeOptions::setTraining(double seconds, std::function<void(double)> done) {
    if (trains()) fit = fit->trainedFor(seconds, std::move(done));
}

Result<LutBank> bakeBank(const Dataset& dataset, const BakeOptions& options, const ImageProvider& provider) {
    const ImageProvider decode = [&](std::size_t i, Image& storage) -> Result<const Image*> {
        Result<Image> image = loadImage(dataset.images[i].path);
        if (!image) return Error{image.error()};
        storage = std::move(*image);
        return &storage;
    };
    if (Status s = checkOptions(dataset, options); !s) return Error{s.error()};
    Baking baking(dataset, options, provider ? provider : decode);
    if (Status s = baking.chooseReference(); !s) return Error{s.error()};
    if (Status s = baking.preparePredictor(); !s) return Error{s.error()};
    Result<std::vector<DirectionalLut>> luts = baking.measure();
    if (!luts) return Error{luts.error()};
    return baking.finish(*luts);
}

}  // namespace btflut

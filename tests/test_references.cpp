// Banks that blend several references and match regions (issue 11): quantile functions,
// reference picking, regions, relighting (blend, then match), the .btflut version 3 file,
// btflut eval, and the bad input of all of them.
#include <doctest/doctest.h>

#include <random>

#include "core/bake/bake.h"
#include "core/bank/bank_file.h"
#include "core/eval/holdout.h"
#include "core/eval/metrics.h"
#include "core/histogram/histogram.h"
#include "core/predict/model_predictor.h"
#include "core/predict/reference_blend.h"
#include "core/predict/references.h"
#include "core/relight/relighter.h"
#include "helpers.h"

using namespace btflut;
using namespace btflut::test;

namespace {

// A small rendered material under 9 lights (synth), and the same tinted to colour.
struct Material {
    std::string grey, colour;
};

Material renderedMaterial(const TempDir& dir) {
    REQUIRE(runCli({"synth", "--preset", "plastic", "--geometry", "rti-9", "--size", "48", "--correlation-length", "6",
                    "--albedo-variation", "0.5", "-q", "-o", dir / "grey"})
                .status == 0);
    fs::copy(dir / "grey", dir / "colour", fs::copy_options::recursive);
    for (const auto& entry : fs::directory_iterator(dir / "colour")) {
        if (entry.path().extension() != ".png" || entry.path().filename() == "mask.png") continue;
        Result<Image> grey = loadImage(entry.path().string());
        REQUIRE(grey.ok());
        Image rgb(grey->width, grey->height, 3);
        for (std::size_t i = 0; i < grey->pixelCount(); ++i) {
            const float g = grey->samples[i];
            const float tint[3] = {1.f, 0.8f, 0.55f};
            for (int c = 0; c < 3; ++c) rgb.samples[i * 3 + c] = std::round(g * tint[c] * 255.f) / 255.f;
        }
        REQUIRE(savePng(rgb, entry.path().string()).ok());
    }
    return {dir / "grey", dir / "colour"};
}

double histogramL1(const Image& a, const Image& b, const Mask& mask) {
    const auto ha = binHistogram(countGreyLevels(a, mask), 64), hb = binHistogram(countGreyLevels(b, mask), 64);
    double l1 = 0;
    for (std::size_t k = 0; k < ha.size(); ++k) l1 += std::abs(ha[k] - hb[k]);
    return l1;
}

double meanAbsolute(const Image& a, const Image& b) {
    double sum = 0;
    for (std::size_t i = 0; i < a.pixelCount(); ++i) sum += std::abs(a.grey(i) - b.grey(i));
    return sum / static_cast<double>(a.pixelCount());
}

}  // namespace

TEST_CASE("quantile functions: matching to a target's quantiles is matching to the target") {
    std::mt19937 rng(5);
    for (int trial = 0; trial < 20; ++trial) {
        LevelCounts reference, target;
        reference.counts.assign(766, 0);
        target.counts.assign(766, 0);
        for (int i = 0; i < 3000; ++i) {
            ++reference.counts[rng() % 500 + 100];
            ++target.counts[trial % 2 ? rng() % 300 : (rng() % 20) * 30];  // dense, or spikes with gaps
        }
        const Lut direct = matchLut(reference, target, 256);
        const std::vector<float> q = quantileFunction(target, 4096);
        CHECK(isValidLut(q.data(), q.size()));
        CHECK(q.front() >= 0.f);
        CHECK(q.back() <= 1.f);
        const Lut viaQuantiles = matchToQuantiles(reference, q, 256);
        // Equal but where u falls on a jump of the target's quantile function (a gap between
        // its codes), which the sampled function crosses in one sample.
        double sum = 0;
        int off = 0;
        for (int e = 0; e < 256; ++e) {
            const double d =
                std::abs(viaQuantiles.values[static_cast<std::size_t>(e)] - direct.values[static_cast<std::size_t>(e)]);
            sum += d;
            off += d > 1.0 / 765;
        }
        CHECK(sum / 256 < 0.5 / 765);
        CHECK(off <= 5);
    }
}

TEST_CASE("references are spread over the lights, the classic reference first") {
    std::vector<Direction> lights{Direction::fromDegrees(5, 0)};
    for (int k = 0; k < 12; ++k) lights.push_back(Direction::fromDegrees(30 + 30 * (k % 2), 30 * k));
    const std::vector<std::size_t> picked = pickReferences(lights, 0, 5);
    REQUIRE(picked.size() == 5);
    CHECK(picked[0] == 0);
    for (std::size_t a = 0; a < picked.size(); ++a)
        for (std::size_t b = a + 1; b < picked.size(); ++b) CHECK(picked[a] != picked[b]);
    // The second is the farthest from the first: one of the theta-60 lights.
    CHECK(lights[picked[1]].thetaDegrees() == doctest::Approx(60));
}

TEST_CASE("regions: k-means finds responses that differ, label images map grey values, bad input refused") {
    // Left half responds with rising light index, right half falling: two clean clusters.
    Responses responses{20, 10, 6, std::vector<std::uint8_t>(200 * 6)};
    std::mt19937 rng(1);
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 20; ++x)
            for (int k = 0; k < 6; ++k) {
                const int v = x < 10 ? 30 + 30 * k : 180 - 30 * k;
                responses.values[(static_cast<std::size_t>(y) * 20 + x) * 6 + k] =
                    static_cast<std::uint8_t>(v + static_cast<int>(rng() % 7));
            }
    const Mask all = fullMask(20, 10);
    Result<Regions> two = segmentRegions(responses, all, 2, "test");
    REQUIRE(two.ok());
    CHECK(two->count == 2);
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 20; ++x)
            CHECK((two->labels[static_cast<std::size_t>(y) * 20 + x] == two->labels[0]) == (x < 10));
    Result<Regions> many = segmentRegions(responses, all, 4, "test");
    REQUIRE_FALSE(many.ok());
    CHECK(many.error().find("too few for 4 regions") != std::string::npos);

    Image labels(20, 10, 1);
    for (std::size_t i = 0; i < labels.pixelCount(); ++i) labels.samples[i] = (i % 20) < 5 ? 200 / 255.f : 7 / 255.f;
    Result<Regions> fromImage = regionsFromLabels(labels, all, 20, 10, "labels.png");
    REQUIRE(fromImage.ok());
    CHECK(fromImage->count == 2);
    CHECK(fromImage->labels[0] == 1);  // 200 is the larger value: region 1
    CHECK(fromImage->labels[5] == 0);
    CHECK(regionsFromLabels(labels, all, 21, 10, "labels.png").error().find("labels.png: label image is 20x10") == 0);
    Mask half = all;
    for (std::size_t i = 0; i < half.inside.size(); ++i) half.inside[i] = (i % 20) >= 5;
    CHECK(regionsFromLabels(labels, half, 20, 10, "labels.png").error().find("has no sample pixels") !=
          std::string::npos);
}

TEST_CASE("several references: blend, then match keeps the measured histogram; the references move the shading") {
    TempDir dir;
    const Material m = renderedMaterial(dir);
    auto dataset = openDataset(m.colour);
    REQUIRE(dataset.ok());
    const Mask mask = *loadDatasetMask(*dataset, 48, 48);
    for (ColourMode colour : {ColourMode::Grey, ColourMode::Rgb, ColourMode::Lrgb}) {
        auto one = bakeBank(*dataset, {.colour = colour == ColourMode::Lrgb ? ColourMode::Grey : colour});
        auto blend = bakeBank(*dataset, {.colour = colour, .references = 4});
        REQUIRE(one.ok());
        REQUIRE(blend.ok());
        REQUIRE(blend->makesLuts());
        CHECK(blend->predictorAs<ReferenceBlend>()->references().size() == 4);
        const Relighter oneRelighter(*one), blendRelighter(*blend);
        double oneError = 0, blendError = 0, oneL1 = 0, blendL1 = 0;
        for (const DatasetImage& im : dataset->images) {
            const Image measured = *loadImage(im.path);
            const Image withOne = oneRelighter.apply(oneRelighter.frame(im.light), true);
            const Image withBlend = blendRelighter.apply(blendRelighter.frame(im.light), true);
            oneL1 += histogramL1(quantised(withOne, 8), measured, mask);
            blendL1 += histogramL1(quantised(withBlend, 8), measured, mask);
            oneError += meanAbsolute(withOne, measured);
            blendError += meanAbsolute(withBlend, measured);
        }
        INFO(colourName(colour) << ": histogram L1 " << blendL1 / 9 << " (one reference " << oneL1 / 9
                                << "), pixel error " << blendError / 9 << " (one reference " << oneError / 9 << ")");
        // At the measured lights the histogram is the measured one as closely as with one
        // reference (on a 48 x 48 material 8-bit rounding alone costs some 0.03) ...
        CHECK(blendL1 / 9 < oneL1 / 9 + 0.01);
        // ... and the pixels are far closer than one reference's.
        CHECK(blendError < 0.5 * oneError);
        // At a reference's own light the blend is that reference: the photograph comes back.
        const ReferenceLight& second = blend->predictorAs<ReferenceBlend>()->lights()[1];
        auto found = std::find_if(dataset->images.begin(), dataset->images.end(),
                                  [&](const DatasetImage& im) { return im.name == second.name; });
        REQUIRE(found != dataset->images.end());
        CHECK(meanAbsolute(blendRelighter.apply(blendRelighter.frame(second.light), true), *loadImage(found->path)) <
              2.0 / 255);
    }
}

TEST_CASE("blending per-reference LUTs instead loses the histogram (the measured alternative)") {
    TempDir dir;
    const Material m = renderedMaterial(dir);
    auto dataset = openDataset(m.grey);
    REQUIRE(dataset.ok());
    auto bank = bakeBank(*dataset, {.references = 3});
    REQUIRE(bank.ok());
    const Relighter relighter(*bank);
    const Mask all = fullMask(48, 48);
    // Between references: the target is the bank's interpolated quantile functions.
    double blendThenMatch = 0, matchThenBlend = 0;
    for (double phi : {20.0, 100.0, 200.0, 290.0}) {
        const Direction light = Direction::fromDegrees(40, phi);
        const RelightFrame frame = relighter.frame(light);
        REQUIRE(frame.count > 1);
        // The target's 64-bin histogram, from its quantile function.
        std::vector<double> target(64, 0.0);
        const std::vector<float>& q = frame.target.values;
        for (float v : q)
            target[static_cast<std::size_t>(std::min(63, static_cast<int>(v * 64)))] +=
                1.0 / static_cast<double>(q.size());
        auto l1 = [&](const Image& image) {
            const auto h = binHistogram(countGreyLevels(quantised(image, 8), *loadDatasetMask(*dataset, 48, 48)), 64);
            double sum = 0;
            for (std::size_t k = 0; k < 64; ++k) sum += std::abs(h[k] - target[k]);
            return sum;
        };
        blendThenMatch += l1(relighter.apply(frame, true));
        matchThenBlend += l1(relighter.applyBlendingLuts(light, {}, true));
    }
    (void)all;
    MESSAGE("64-bin L1 to the target over 4 lights: blend then match " << blendThenMatch / 4 << ", blended LUTs "
                                                                       << matchThenBlend / 4);
    CHECK(blendThenMatch / 4 < 0.1);
    CHECK(matchThenBlend > 3 * blendThenMatch);
}

TEST_CASE("regions and the PTM predictor relight to the measured histograms; a one-reference bank is the classic one") {
    TempDir dir;
    const Material m = renderedMaterial(dir);
    auto dataset = openDataset(m.colour);
    REQUIRE(dataset.ok());
    const Mask mask = *loadDatasetMask(*dataset, 48, 48);
    auto l1Over = [&](const LutBank& bank) {
        const Relighter relighter(bank);
        double l1 = 0;
        for (const DatasetImage& im : dataset->images)
            l1 +=
                histogramL1(quantised(relighter.apply(relighter.frame(im.light), true), 8), *loadImage(im.path), mask);
        return l1 / static_cast<double>(dataset->images.size());
    };
    const double classicL1 = l1Over(*bakeBank(*dataset, {}));
    for (BakeOptions options :
         {BakeOptions{.regions = 3}, BakeOptions{.references = 3, .regions = 2},
          BakeOptions{.fit = lightModelFit(LightModelOptions{.basis = LightBasis::Ptm})},
          BakeOptions{.fit = lightModelFit(LightModelOptions{.basis = LightBasis::Ptm}), .regions = 2}}) {
        auto bank = bakeBank(*dataset, options);
        REQUIRE(bank.ok());
        INFO("references " << options.references << " regions " << options.regions << " model "
                           << (options.fit != nullptr));
        CHECK(l1Over(*bank) < classicL1 + 0.01);  // the measured histograms, as closely as the classic bank
    }
    auto classic = bakeBank(*dataset, {});
    auto one = bakeBank(*dataset, {.references = 1});
    REQUIRE(classic.ok());
    REQUIRE(one.ok());
    CHECK_FALSE(one->makesLuts());
    CHECK(encodeBank(*classic) == encodeBank(*one));
    CHECK(bankFormatVersion(*one) == expectedVersion(*one, 1));
}

TEST_CASE("a bank matched in part reproduces each measured light's histogram; between, its strength, ramped") {
    TempDir dir;
    const Material m = renderedMaterial(dir);
    auto dataset = openDataset(m.colour);
    REQUIRE(dataset.ok());
    const Mask mask = *loadDatasetMask(*dataset, 48, 48);
    for (BakeOptions options :
         {BakeOptions{.fit = lightModelFit(LightModelOptions{.basis = LightBasis::Hsh, .order = 2}), .match = 0},
          BakeOptions{.references = 3, .match = 0.5f}}) {
        auto bank = bakeBank(*dataset, options);
        auto full = bakeBank(*dataset, [&] {
            BakeOptions o = options;
            o.match = 1;
            return o;
        }());
        REQUIRE(bank.ok());
        REQUIRE(full.ok());
        const Relighter relighter(*bank), fullRelighter(*full);
        INFO("match " << options.match);
        for (const DatasetImage& im : dataset->images) {
            CHECK(relighter.matchAt(im.light) == 1.f);
            // At a measured light the LUTs are those of the fully matched bank: the photograph's histogram.
            CHECK(relighter.frame(im.light).luts == fullRelighter.frame(im.light).luts);
            const double l1 =
                histogramL1(quantised(relighter.apply(relighter.frame(im.light), true), 8), *loadImage(im.path), mask);
            CHECK(l1 == histogramL1(quantised(fullRelighter.apply(fullRelighter.frame(im.light), true), 8),
                                    *loadImage(im.path), mask));
        }
        // Between, it moves smoothly (smoothstep: at most 1.5 (1 - match) per radius), and
        // from `radius` away from every measured light on it is the bank's own.
        const float radius = relighter.matchRampRadius();
        REQUIRE(radius > 0);
        float last = relighter.matchAt(dataset->images.front().light);
        int away = 0;
        for (int step = 1; step <= 120; ++step) {
            const DiskPoint p = toDisk(dataset->images.front().light);
            const DiskPoint q{p.x + step * radius / 8, p.y - step * radius / 16};
            if (q.x * q.x + q.y * q.y > 1) break;
            const float strength = relighter.matchAt(fromDisk(q));
            CHECK(std::abs(strength - last) <= 1.5f * (1 - options.match) / 8 * 1.2f);
            CHECK(strength >= options.match);
            double nearest = 1e9;
            for (const DatasetImage& im : dataset->images) {
                const DiskPoint l = toDisk(im.light);
                nearest = std::min(nearest, std::hypot(l.x - q.x, l.y - q.y));
            }
            if (nearest > radius * 1.001) {
                CHECK(strength == doctest::Approx(options.match));
                ++away;
            }
            last = strength;
        }
        CHECK(away > 0);
    }
}

TEST_CASE("the same inputs give the same bank bytes, whatever the threads (the PTM and lrgb albedo sums in order)") {
    TempDir dir;
    const Material m = renderedMaterial(dir);
    auto dataset = openDataset(m.colour);
    REQUIRE(dataset.ok());
    std::optional<Bytes> first;
    for (int threads : {1, 8, 3, 8, 8}) {  // more threads than cores: items finish out of order
        auto bank = bakeBank(*dataset, {.colour = ColourMode::Lrgb, .threads = threads, .ptm = true, .references = 4});
        REQUIRE(bank.ok());
        const Bytes bytes = encodeBank(*bank);
        if (!first) first = bytes;
        INFO("threads " << threads);
        CHECK(bytes == *first);
    }
}

TEST_CASE("version 3 and 6 files round-trip, and every cut and flipped bit is refused") {
    TempDir dir;
    const Material m = renderedMaterial(dir);
    auto dataset = openDataset(m.colour);
    REQUIRE(dataset.ok());
    for (BakeOptions options :
         {BakeOptions{.colour = ColourMode::Lrgb, .references = 4, .regions = 2},
          BakeOptions{.colour = ColourMode::Rgb, .references = 3},
          BakeOptions{.fit = lightModelFit(LightModelOptions{.basis = LightBasis::Ptm}), .regions = 2}}) {
        auto bank = bakeBank(*dataset, options);
        REQUIRE(bank.ok());
        CHECK(bankFormatVersion(*bank) == expectedVersion(*bank, 5));
        if (!options.fit) {
            // Without it (the blend alone), the LUTs baked over the grid (MGRD) are version 5, and
            // without those the references' banks are what version 3 readers read.
            BakeOptions blendOnly = options;
            blendOnly.fitTargets = false;
            Result<LutBank> blended = bakeBank(*dataset, blendOnly);
            REQUIRE(blended.ok());
            CHECK(bankFormatVersion(*blended) == 5);
            LutBank plain = *blended;
            for (ViewLayer& layer : plain.layers) layer.matchGridLuts.clear();
            CHECK(bankFormatVersion(plain) == 3);
            Result<LutBank> back3 = decodeBank(encodeBank(plain), "v3.btflut");
            REQUIRE(back3.ok());
            const Relighter a(*blended), b(*back3);  // the grid made again on reading
            const Direction light = Direction::fromDegrees(35, 70);
            CHECK(a.apply(a.gridFrame(light), true).samples == b.apply(b.gridFrame(light), true).samples);
        }
        const Bytes bytes = encodeBank(*bank);
        auto back = decodeBank(bytes, "b.btflut");
        REQUIRE(back.ok());
        CHECK(encodeBank(*back) == bytes);
        // The same relit image from the decoded bank.
        const Direction light = Direction::fromDegrees(35, 70);
        const Relighter a(*bank), b(*back);
        CHECK(a.apply(a.frame(light), true).samples == b.apply(b.frame(light), true).samples);
        for (std::size_t cut = 8; cut < bytes.size(); cut += bytes.size() / 37)
            CHECK_FALSE(decodeBank(Bytes(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(cut)), "cut").ok());
        for (std::size_t at = 12; at < bytes.size(); at += bytes.size() / 53) {
            Bytes flipped = bytes;
            flipped[at] ^= 0x10;
            CHECK_FALSE(decodeBank(flipped, "flip").ok());
        }
    }
}

TEST_CASE("bake refuses bad settings of references, regions and labels with one line") {
    TempDir dir;
    const Material m = renderedMaterial(dir);
    const std::string out = dir / "m.btflut";
    requireOneLineError(runCli({"bake", m.grey, "-o", out, "--references", "10"}),
                        "--references 10 must be within 1..9");
    requireOneLineError(runCli({"bake", m.grey, "-o", out, "--references", "0"}), "--references");
    requireOneLineError(runCli({"bake", m.grey, "-o", out, "--regions", "60"}), "too few for 60 regions");
    requireOneLineError(runCli({"bake", m.grey, "-o", out, "--colour", "lrgb"}), "--colour lrgb needs colour images");
    requireOneLineError(
        runCli({"bake", m.colour, "-o", out, "--colour", "lrgb", "--references", "17", "--regions", "1"}),
        "--references 17 must be within 1..9");
    Image labels(20, 20, 1);
    REQUIRE(savePng(labels, dir / "labels.png").ok());
    requireOneLineError(runCli({"bake", m.grey, "-o", out, "--labels", dir / "labels.png"}),
                        "labels.png: label image is 20x20 but the images are 48x48");
    requireOneLineError(runCli({"bake", m.grey, "-o", out, "--predictor", "ptm", "--references", "3"}),
                        "--predictor ptm");
    CHECK_FALSE(fs::exists(out));

    // Fine settings bake, and info describes them.
    REQUIRE(
        runCli({"bake", m.colour, "-o", out, "--colour", "lrgb", "--references", "4", "--regions", "2", "-q"}).status ==
        0);
    CliRun info = runCli({"info", out});
    REQUIRE(info.status == 0);
    CHECK((info.out.find("format version 5") != std::string::npos ||  // 6 with a fit between the lights
           info.out.find("format version 6") != std::string::npos));
    CHECK(info.out.find("4 reference(s) blended per light") != std::string::npos);
    CHECK(info.out.find("  between:   ") != std::string::npos);
    CHECK(info.out.find("2 region(s)") != std::string::npos);
    REQUIRE(runCli({"relight", out, "--light", "30,40", "-o", dir / "r.png", "-q"}).status == 0);
    CHECK(loadImage(dir / "r.png")->channels == 3);

    // export: the atlas (a row per grid node and region, a column per quantile sample) and
    // the textures the bank relights from.
    REQUIRE(runCli({"export", out, "-o", dir / "x.png"}).status == 0);
    const Image atlas = *loadImage(dir / "x.png");
    CHECK(atlas.width == 1024);
    CHECK(atlas.height == 17 * 17 * 2);
    const auto side = nlohmann::json::parse(readText(dir / "x.json"));
    CHECK(side["blend"]["references"].size() == 4);
    CHECK(side["blend"]["regions"] == 2);
    for (const char* file : {"x-reference-3.png", "x-albedo.png", "x-labels.png", "x-mask.png"})
        CHECK(fs::exists(dir / file));
}

TEST_CASE("hold-out folds, and eval end to end on a small material") {
    TempDir dir;
    const Material m = renderedMaterial(dir);
    auto dataset = openDataset(m.grey);
    REQUIRE(dataset.ok());
    auto every = holdoutFolds(*dataset, "every:3", 2);
    REQUIRE(every.ok());
    REQUIRE(every->size() == 1);
    CHECK(every->front().test == std::vector<std::size_t>{0, 3, 6});
    auto loo = holdoutFolds(*dataset, "loo", 6);
    REQUIRE(loo.ok());
    CHECK(loo->size() == 9);
    CHECK(loo->at(4).train.size() == 8);
    CHECK(holdoutFolds(*dataset, "every:1", 2).error().find("expected every:K with K >= 2") != std::string::npos);
    std::ofstream(dir / "held.txt") << dataset->images[2].name << "\nnobody\n";
    CHECK(holdoutFolds(*dataset, dir / "held.txt", 2).error().find("held.txt:2: no image named 'nobody'") !=
          std::string::npos);
    std::ofstream(dir / "most.txt") << "l1\nl2\nl3\nl4\n";
    CHECK(holdoutFolds(*dataset, dir / "most.txt", 6).error().find("leaves 5 training images") != std::string::npos);

    CliRun r = runCli({"eval", m.colour, "--holdout", "every:3", "--references", "1,3", "--regions", "1,2", "--colour",
                       "grey,lrgb", "--predictor", "references,ptm", "--blended-luts", "--no-gl", "--json", "-o",
                       dir / "eval"});
    INFO(r.err);
    REQUIRE(r.status == 0);
    const auto json = nlohmann::json::parse(r.out);
    CHECK(json["options"]["holdout"] == "every:3");  // what made the figures, to repeat them
    CHECK(json["options"]["colour"] == "grey,lrgb");
    CHECK_FALSE(json["btflut_version"].get<std::string>().empty());
    std::map<std::string, nlohmann::json> byName;
    for (const auto& mode : json["modes"]) byName[mode["name"]] = mode;
    for (const char* name : {"lut K1 R1 grey", "lut K3 R2 lrgb", "lut K3 R1 grey (LUTs blended)", "lut ptm R2 grey",
                             "brdf", "ptm", "nearest"}) {
        INFO(name);
        REQUIRE(byName.count(name));
        CHECK(byName[name]["psnr"].get<double>() > 10);
        // Each mean's spread over the three held-out images: an interval around it.
        const nlohmann::json& l1 = byName[name]["spread"]["l1"];
        CHECK(l1["sd"].get<double>() >= 0);
        CHECK(l1["ci95"][0].get<double>() <= byName[name]["l1"].get<double>());
        CHECK(l1["ci95"][1].get<double>() >= byName[name]["l1"].get<double>());
    }
    CHECK(json["rows"].size() == json["modes"].size() * 3);
    // Sweeps: a predictor's bank at each match strength, bake's choice at each budget.
    const CliRun swept = runCli({"eval", m.grey, "--holdout", "every:3", "--modes", "lut", "--predictor", "auto,hsh2",
                                 "--match", "0,1", "--budget", "1,4", "--no-gl", "--json"});
    INFO(swept.err);
    REQUIRE(swept.status == 0);
    std::vector<std::string> sweptNames;
    const nlohmann::json sweptJson = nlohmann::json::parse(swept.out);
    for (const auto& mode : sweptJson["modes"]) sweptNames.push_back(mode["name"]);
    CHECK(sweptNames == std::vector<std::string>{"lut auto match 0 budget 1", "lut auto match 0 budget 4",
                                                 "lut auto match 1 budget 1", "lut auto match 1 budget 4",
                                                 "lut hsh2 R1 grey match 0", "lut hsh2 R1 grey match 1"});
    // A predictor's bank reports its target's own L1 beside the relit image's: matched fully,
    // the two agree (the relit histogram is the target's, up to its codes); the paper's bank
    // (a bank of LUTs) has none.
    for (const auto& mode : sweptJson["modes"])
        if (mode["name"] == "lut hsh2 R1 grey match 1") {
            REQUIRE(mode["target_l1"].is_number());
            CHECK(mode["target_l1"].get<double>() == doctest::Approx(mode["l1"].get<double>()).epsilon(0.1));
        }
    CHECK(byName["lut K1 R1 grey"]["target_l1"].is_null());
    CHECK(byName["lut ptm R2 grey"]["target_l1"].get<double>() > 0);
    // lut auto says what bake chose in each fold (one fold here), and only lut auto does.
    for (const auto& mode : sweptJson["modes"]) {
        INFO(mode["name"]);
        const bool automatic = mode["name"].get<std::string>().rfind("lut auto", 0) == 0;
        REQUIRE(mode.contains("chosen") == automatic);
        if (automatic) {
            REQUIRE(mode["chosen"].size() == 1);
            CHECK(mode["chosen"][0].get<std::string>().find(" match ") != std::string::npos);
        }
    }
    CHECK(runCli({"eval", m.grey, "--match", "2", "--no-gl"}).err.find("--match '2': expected") != std::string::npos);
    CHECK(json["rows"][0]["theta"].get<double>() > 0);  // each row says its light
    // --no-gl: the GL figures are "-" in the table, not nan.
    const CliRun table = runCli({"eval", m.grey, "--holdout", "every:2", "--modes", "lut", "--no-gl"});
    REQUIRE(table.status == 0);
    CHECK(table.out.find("nan") == std::string::npos);
    CHECK(table.out.find(" - ") != std::string::npos);
    CHECK(table.out.find("lut K<k> R<r> <colour>: a bank of k references") != std::string::npos);  // names explained
    // Several references put the shading where it is: better pixels than one reference.
    CHECK(byName["lut K3 R1 grey"]["psnr"].get<double>() > byName["lut K1 R1 grey"]["psnr"].get<double>() + 1);
    CHECK(byName["lut K3 R1 lrgb"]["bytes_per_texel"] == 6);
    CHECK(byName["ptm"]["bytes_per_texel"] == 9);
    for (const char* file : {"eval.txt", "eval.json", "rows.csv", "contact.png", "tradeoff.png", "error_theta.png"})
        CHECK(fs::exists(dir / ("eval/" + std::string(file))));
    const Image contact = *loadImage(dir / "eval/contact.png");
    CHECK(contact.width > 192 * 8);
    // Under each held-out light's row, a row of error maps: six rows of cells for three lights.
    const Image photo = *loadImage(dataset->images[0].path);
    CHECK(contact.height > 6 * 192 * photo.height / photo.width);
    CHECK(contact.height < 9 * 192 * photo.height / photo.width + 6 * 60);
    // The contact sheet: --contact lights (default 4) spread over the held-out images; here 3 are held out.
    CHECK(json["contact_sheet"].size() == 3);
    // Run time against error: the Pareto fronts of each figure and cost, cheapest first. On
    // PSNR against bytes per texel the front rises; nothing off it is cheaper and better.
    const nlohmann::json& front = json["pareto_fronts"]["psnr_bytes_per_texel"];
    REQUIRE(front.size() >= 1);
    for (std::size_t i = 1; i < front.size(); ++i) {
        CHECK(byName[front[i]]["psnr"].get<double>() > byName[front[i - 1]]["psnr"].get<double>());
        CHECK(byName[front[i]]["bytes_per_texel"].get<double>() >=
              byName[front[i - 1]]["bytes_per_texel"].get<double>());
    }
    for (const auto& [name, mode] : byName)
        for (const auto& on : front) {
            INFO(name << " against " << on);
            const bool dominates =
                mode["bytes_per_texel"].get<double>() <= byName[on]["bytes_per_texel"].get<double>() &&
                mode["psnr"].get<double>() > byName[on]["psnr"].get<double>();
            CHECK_FALSE(dominates);
        }
    CHECK(json["pareto_fronts"]["psnr_frame_ms"].empty());  // --no-gl: no frame times
    // Where each mode fails: mean figures in bands of the light's theta, over every row.
    std::size_t counted = 0;
    for (const auto& mode : json["by_theta"]["modes"])
        for (const auto& n : mode["count"]) counted += n.get<std::size_t>();
    CHECK(counted == json["rows"].size());
    // Bands centred on multiples of 10: each row's theta within 5 degrees of a band its mode has.
    for (const auto& row : json["rows"]) {
        const double theta = row["theta"].get<double>();
        bool inBand = false;
        for (const auto& mode : json["by_theta"]["modes"])
            if (mode["name"] == row["mode"])
                for (const auto& centre : mode["theta"])
                    inBand = inBand || (std::abs(centre.get<double>() - theta) <= 5 &&
                                        std::fmod(centre.get<double>(), 10.0) == 0);
        CHECK(inBand);
    }
    CHECK(loadImage(dir / "eval/tradeoff.png")->width > 3 * 400);
    CliRun two =
        runCli({"eval", m.grey, "--holdout", "every:2", "--modes", "lut", "--no-gl", "--json", "--contact", "2"});
    REQUIRE(two.status == 0);
    CHECK(nlohmann::json::parse(two.out)["contact_sheet"].size() == 2);

    requireOneLineError(runCli({"eval", m.grey, "--holdout", "every:2", "--modes", "ptm", "--no-gl"}),
                        "the PTM fits six terms");
    requireOneLineError(runCli({"eval", m.grey, "--modes", "lut,shiny", "--no-gl"}),
                        "'shiny' is not a mode eval measures: lut, brdf, nearest, flat, a light model (ptm, hsh");
    requireOneLineError(runCli({"eval", m.grey, "--references", "1,x", "--no-gl"}), "--references '1,x'");
}

TEST_CASE("an .lp capture takes the mask.png beside it") {
    TempDir dir;
    std::string manifest = writeSyntheticDataset(dir, {{0, 0, 0, 0, 0, 1}, {30, 0, 0, 0, 40, 1}});
    std::ofstream(dir / "c.lp") << "2\nshot0.png 0 0 1\nshot1.png 0.5 0 0.8660254\n";
    CHECK(openDataset(dir / "c.lp")->maskPath.empty());
    Image mask(40, 30, 1);
    mask.samples[3] = 1;
    REQUIRE(savePng(mask, dir / "mask.png").ok());
    CHECK(openDataset(dir / "c.lp")->maskPath == dir / "mask.png");
}

// Linear light models (core/predict/light_model.h) and `bake --predictor auto`
// (core/bake/auto_bake.h): fits, the fixed-point evaluator, numerical traps, degenerate
// captures, version 5 files, and the validated choice on the shared data.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

#include "core/bake/auto_bake.h"
#include "core/bake/bake.h"
#include "core/bank/bank_file.h"
#include "core/data/dataset.h"
#include "core/eval/metrics.h"
#include "core/predict/kind_chunk.h"
#include "core/predict/learned_predictor.h"
#include "core/predict/learned_shader.h"
#include "core/predict/light_model.h"
#include "core/predict/model_predictor.h"
#include "core/predict/rti_file.h"
#include "core/relight/relighter.h"
#include "helpers.h"

using namespace btflut;
using namespace btflut::test;

namespace {

std::vector<LightModelOptions> everyBasis() {
    return {{.basis = LightBasis::Ptm},
            {.basis = LightBasis::Hsh, .order = 2},
            {.basis = LightBasis::Hsh, .order = 3},
            {.basis = LightBasis::Rbf, .planes = 6},
            {.basis = LightBasis::Bilinear, .planes = 6},
            {.basis = LightBasis::Rbf, .planes = 5, .packed = true},
            {.basis = LightBasis::Bilinear, .planes = 4, .packed = true}};
}

Result<LightModel> fit(const std::vector<Image>& images, const std::vector<Direction>& lights, const Mask& mask,
                       const LightModelOptions& o) {
    std::vector<const Image*> pointers;
    for (const Image& image : images) pointers.push_back(&image);
    return fitLightModel(pointers, lights, mask, o, "relief");
}

}  // namespace

TEST_CASE("light models: a Lambertian relief between the measured lights, every basis closer than the nearest image") {
    const Relief relief;
    const std::vector<Direction> lights = dome(30, 70);
    std::vector<Image> images;
    for (Direction l : lights) images.push_back(reliefImage(relief, l));
    const Mask mask = fullMask(relief.size, relief.size);
    for (const LightModelOptions& o : everyBasis()) {
        Result<LightModel> model = fit(images, lights, mask, o);
        REQUIRE_MESSAGE(model.ok(), model.error());
        CHECK(model->bytesPerTexel() == (o.basis == LightBasis::Ptm   ? 9
                                         : o.basis == LightBasis::Hsh ? o.order * o.order + 3
                                                                      : o.planes));
        double psnr = 0, nearest = 0;
        for (Direction l :
             {Direction::fromDegrees(25, 10), Direction::fromDegrees(45, 200), Direction::fromDegrees(60, 300)}) {
            const Image truth = reliefImage(relief, l);
            psnr += compareImages(model->render(l), truth, mask).psnr / 3;
            std::size_t n = 0;
            for (std::size_t i = 1; i < lights.size(); ++i)
                if (angleBetween(lights[i], l) < angleBetween(lights[n], l)) n = i;
            nearest += compareImages(images[n], truth, mask).psnr / 3;
        }
        INFO(lightModelName(*model) << ": " << psnr << " dB, the nearest image " << nearest << " dB");
        CHECK(psnr > nearest + 3);
        // hsh3 holds a Lambertian relief without shadows almost exactly.
        if (o.basis == LightBasis::Hsh && o.order == 3) CHECK(psnr > 38);
    }
}

TEST_CASE("light models: the fixed-point prediction (the shader's arithmetic) is the float one within a code") {
    const Relief relief{.size = 24};
    const std::vector<Direction> lights = dome(20, 65);
    std::vector<Image> images;
    for (Direction l : lights) images.push_back(reliefImage(relief, l));
    for (const LightModelOptions& o : everyBasis()) {
        Result<LightModel> model = fit(images, lights, fullMask(relief.size, relief.size), o);
        REQUIRE(model.ok());
        for (Direction l :
             {Direction::fromDegrees(0, 0), Direction::fromDegrees(35, 80), Direction::fromDegrees(80, 250)}) {
            const Image ideal = model->render(l);
            const LightModelFixed fixed = lightModelFixed(*model, l);
            double w = 0;
            for (std::size_t i = 0; i < model->texels(); ++i) {
                const std::array<std::int64_t, 3> c = predictFixed(*model, fixed, i);
                for (int k = 0; k < ideal.channels; ++k)
                    w = std::max(
                        w,
                        std::abs(
                            static_cast<double>(c[static_cast<std::size_t>(k)]) / (255.0 * kWeightUnit) -
                            ideal.samples[i * static_cast<std::size_t>(ideal.channels) + static_cast<std::size_t>(k)]));
            }
            INFO(lightModelName(*model) << " at " << l.thetaDegrees() << ": " << w * 255 << "/255");
            CHECK(w <= 1.0 / 255);
        }
    }
}

TEST_CASE("light models: lights within 5 degrees and black pixels give finite models, banks and relightings") {
    TempDir dir;
    const Relief relief{.size = 32, .border = 4};
    std::vector<Direction> clustered;
    for (int i = 0; i < 9; ++i) clustered.push_back(Direction::fromDegrees(30 + 2.0 * (i % 3), 40 + 2.5 * (i / 3)));
    const std::string manifest = writeRelief(dir, relief, clustered);
    Result<Dataset> dataset = openDataset(manifest);
    REQUIRE(dataset.ok());
    for (const LightModelOptions& o : everyBasis()) {
        Result<LutBank> bank = bakeBank(*dataset, {.fit = lightModelFit(o)});
        REQUIRE_MESSAGE(bank.ok(), bank.error());
        const LightModel& m = bank->predictorAs<ModelPredictor>()->model();
        for (std::size_t p = 0; p < static_cast<std::size_t>(m.planes); ++p) {
            CHECK(std::isfinite(m.scale[p]));
            CHECK(std::isfinite(m.bias[p]));
        }
        for (float v : m.table) CHECK(std::isfinite(v));
        const Relighter relighter(*bank);
        for (Direction l : {Direction::fromDegrees(31, 42), Direction::fromDegrees(75, 200)}) {  // inside, far outside
            const Image image = relighter.apply(relighter.frame(l), true);
            bool finite = true, blackBorder = true;
            for (float v : image.samples) finite = finite && std::isfinite(v) && v >= 0 && v <= 1;
            for (int c = 0; c < image.channels; ++c) blackBorder = blackBorder && image.at(0, 0, c) >= 0;
            CHECK(finite);
            CHECK(blackBorder);
        }
        const Bytes bytes = encodeBank(*bank);
        CHECK(decodeBank(bytes, "clustered.btflut").ok());
    }
    // The default bakes them and says what it chose.
    CliRun run = runCli({"bake", manifest, "-o", dir / "auto.btflut"});
    REQUIRE_MESSAGE(run.status == 0, run.err);
    CHECK(run.out.find("chosen by validation") != std::string::npos);
    CliRun info = runCli({"info", dir / "auto.btflut"});
    CHECK(info.out.find("chosen:") != std::string::npos);
}

TEST_CASE("auto: the choice is the best validation PSNR within 0.002 L1 of the paper's bank, and info prints it") {
    TempDir dir;
    const std::string manifest = writeRelief(dir, Relief{.size = 40, .border = 3}, dome(16, 70));
    Result<Dataset> dataset = openDataset(manifest);
    REQUIRE(dataset.ok());
    Result<LutBank> bank = bakeAuto(*dataset, {});
    REQUIRE_MESSAGE(bank.ok(), bank.error());
    const nlohmann::json s = nlohmann::json::parse(bank->selection);
    REQUIRE(s["candidates"].size() >= 8);
    const nlohmann::json& classic = s["candidates"][0];
    REQUIRE(classic["name"] == "K1");
    const double bound = classic["validation"][0]["l1"].get<double>() + 0.002;
    double best = -1;
    std::string bestName;
    double bestMatch = -1;
    for (const nlohmann::json& c : s["candidates"]) {
        if (c.contains("skipped")) continue;
        for (const nlohmann::json& v : c["validation"])
            if (v["l1"].get<double>() <= bound && v["psnr"].get<double>() > best)
                best = v["psnr"], bestName = c["name"], bestMatch = v["match"];
    }
    CHECK(s["chosen"]["name"] == bestName);
    CHECK(s["chosen"]["match"].get<double>() == doctest::Approx(bestMatch));
    CHECK(s["candidates"][0]["bytes"] == 3);
    // Over the budget: listed, not validated.
    bool overBudget = false;
    for (const nlohmann::json& c : s["candidates"]) overBudget |= c.contains("skipped") && c["bytes"].get<int>() > 9;
    CHECK(overBudget);
    REQUIRE(saveBank(*bank, dir / "m.btflut").ok());
    CliRun info = runCli({"info", dir / "m.btflut"});
    CHECK(info.out.find("chosen:    " + bestName) != std::string::npos);
    CliRun json = runCli({"info", dir / "m.btflut", "--json"});
    CHECK(nlohmann::json::parse(json.out)["selection"]["chosen"]["name"] == bestName);
    // The same relit image from the file (version 5) as from the bank baked.
    Result<LutBank> back = loadBank(dir / "m.btflut");
    REQUIRE(back.ok());
    const Relighter a(*bank), b(*back);
    const Direction light = Direction::fromDegrees(33, 120);
    CHECK(a.apply(a.frame(light), true).samples == b.apply(b.frame(light), true).samples);
}

TEST_CASE("auto: degenerate captures bake; a budget below every predictor is refused naming the smallest") {
    TempDir dir;
    SUBCASE("all black") {
        // A border as wide as the image: every pixel black, and the whole image the sample.
        const std::string manifest = writeRelief(dir, Relief{.size = 16, .border = 8}, dome(9, 60));
        nlohmann::json m = nlohmann::json::parse(readText(manifest));
        m.erase("mask");
        std::ofstream(manifest) << m.dump();
        CliRun run = runCli({"bake", manifest, "-o", dir / "black.btflut", "-q"});
        CHECK_MESSAGE(run.status == 0, run.err);
        CHECK(runCli({"relight", dir / "black.btflut", "--light", "20,0", "-o", dir / "r.png", "-q"}).status == 0);
    }
    SUBCASE("1 x 1 images") {
        const std::string manifest = writeRelief(dir, Relief{.size = 1}, dome(8, 60));
        CliRun run = runCli({"bake", manifest, "-o", dir / "one.btflut", "-q"});
        CHECK_MESSAGE(run.status == 0, run.err);
        CHECK(runCli({"relight", dir / "one.btflut", "--light", "20,0", "-o", dir / "r.png", "-q"}).status == 0);
    }
    SUBCASE("budget") {
        const std::string manifest = writeRelief(dir, Relief{.size = 16}, dome(8, 60));
        requireOneLineError(runCli({"bake", manifest, "--budget", "2", "-o", dir / "x.btflut"}),
                            "the smallest budget that works is 3 bytes per texel");
        requireOneLineError(runCli({"bake", manifest, "--budget", "4", "--predictor", "rbf", "-o", dir / "x.btflut"}),
                            "--budget in bytes goes with --predictor auto");
        requireOneLineError(runCli({"bake", manifest, "--budget", "90s", "--predictor", "rbf", "-o", dir / "x.btflut"}),
                            "--budget in time bounds a learned model's training");
        for (const char* bad :
             {"0", "9,abc", "9,9", "65", "2.5", "-3s", "30s,2m", "nans", "0mac", "1.5mac", "9mac,9mac", "mac"})
            requireOneLineError(runCli({"bake", manifest, "--budget", bad, "-o", dir / "x.btflut"}),
                                "expected bytes per texel (1 to 64), a training time (90s, 2m), multiply-adds per "
                                "texel (1500mac), or several of them (9,90s,1500mac)");
        for (const char* long_ : {"1e30s", "86401s", "1441m", "9,2000m"})
            requireOneLineError(runCli({"bake", manifest, "--budget", long_, "-o", dir / "x.btflut"}),
                                "a training time of at most 86400 s (a day)");
        requireOneLineError(
            runCli({"eval", manifest, "--modes", "neural9", "--budget", "1e6m", "--no-gl", "-o", dir / "ev"}),
            "a training time of at most 86400 s (a day)");
        requireOneLineError(
            runCli({"bake", manifest, "--budget", "500mac", "--predictor", "hsh2", "-o", dir / "x.btflut"}),
            "--budget in multiply-adds bounds the candidates of --predictor auto");
        requireOneLineError(runCli({"bake", manifest, "--predictor", "rbf99", "-o", dir / "x.btflut"}), "rbf99");
        CHECK_FALSE(fs::exists(dir / "x.btflut"));
        // The smallest budget bakes within it: the paper's bank or a PCA basis of 3 planes.
        REQUIRE(runCli({"bake", manifest, "--budget", "3", "-o", dir / "b3.btflut", "-q"}).status == 0);
        Result<LutBank> bank = loadBank(dir / "b3.btflut");
        REQUIRE(bank.ok());
        CHECK(bank->predictorBytesPerTexel() <= 3);
    }
}

TEST_CASE("the fits' registry: a --predictor name's fit, whether it trains, and auto's candidates by kind") {
    const auto hsh = predictorFitNamed("hsh2");
    REQUIRE((hsh && *hsh));
    CHECK((**hsh)->family() == "hsh");
    CHECK_FALSE((**hsh)->trains());
    CHECK_FALSE((**hsh)->takesViews());
    CHECK(dynamic_cast<const LightModelFit&>(***hsh).options().order == 2);
    CHECK((**hsh)->trainedFor(30, {}) == **hsh);  // a fit that does not train is itself
    const auto neural = predictorFitNamed("neural5");
    REQUIRE((neural && *neural));
    CHECK((**neural)->family() == "neural");
    CHECK((**neural)->trains());
    CHECK((**neural)->takesViews());
    bool called = false;
    const FitPointer timed = (**neural)->trainedFor(30, [&](double) { called = true; });
    const LearnedOptions& o = dynamic_cast<const LearnedFit&>(*timed).options();
    CHECK(o.codes == 5);
    CHECK(o.seconds == 30);
    REQUIRE(o.progress);
    o.progress(0.5);
    CHECK(called);
    CHECK(dynamic_cast<const LearnedFit&>(*(**neural)->trainedFor(0, {})).options().seconds == kDefaultTrainingSeconds);
    // Out of range: an error, yet a trained kind's name (bake refuses a time for hsh2, not neural99).
    const auto wide = predictorFitNamed("neural99");
    REQUIRE(wide);
    CHECK_FALSE(*wide);
    CHECK(predictorTrains("neural99"));
    CHECK_FALSE(predictorTrains("hsh2"));
    for (const char* other : {"auto", "references", "K3", "bogus"}) {
        CHECK_FALSE(predictorFitNamed(other));
        CHECK_FALSE(predictorTrains(other));
    }
    // BakeOptions: a time and progress reach a trained fit alone.
    BakeOptions options;
    REQUIRE(setModelNamed(options, "rbf5"));
    const FitPointer rbf = options.fit;
    options.setTraining(30, {});
    CHECK(options.fit == rbf);
    CHECK_FALSE(options.trains());
    REQUIRE(setModelNamed(options, "neural"));
    CHECK(options.trains());
    options.setTraining(40, {});
    CHECK(dynamic_cast<const LearnedFit&>(*options.fit).options().seconds == 40);

    // Auto's candidates, the kinds in the registry's order: a colour light model's albedo in
    // its bytes, rbf and bln of the bytes, then the learned model of as many codes.
    std::vector<std::string> names;
    for (const FitCandidate& c : fitCandidates({.bytes = 9, .channels = 3, .seconds = 7})) {
        names.push_back(c.name);
        CHECK(c.fit->trains() == (c.name == "neural9"));
        if (c.name == "ptm") CHECK(c.bytes == 9);
        if (c.name == "hsh3") CHECK(c.bytes == 12);
        if (c.name == "neural9") {
            CHECK(c.bytes == 9);
            CHECK(dynamic_cast<const LearnedFit&>(*c.fit).options().seconds == 7);
            CHECK(c.multiplyAdds == learnedTexelMultiplyAdds(9, 3, LearnedOptions{}.hidden));
        }
    }
    CHECK(names == std::vector<std::string>{"ptm", "hsh2", "hsh3", "rbf9", "bln9", "rbf9c", "bln9c", "neural9"});
    // No byte left: no learned model (a light model keeps one plane).
    names.clear();
    for (const FitCandidate& c : fitCandidates({.bytes = 0, .channels = 1, .seconds = 7})) names.push_back(c.name);
    CHECK(names == std::vector<std::string>{"ptm", "hsh2", "hsh3", "rbf1", "bln1", "rbf1c", "bln1c"});
}

TEST_CASE("the kinds' registry: a kind's own chunk found by kind, number and tag; missing or twice, refused") {
    std::set<std::uint32_t> numbers, tags;
    for (PredictorKind kind :
         {PredictorKind::Luts, PredictorKind::Model, PredictorKind::References, PredictorKind::Learned}) {
        const KindChunk* own = kindChunkOf(kind);
        if (!own) continue;
        CHECK(own->kind == kind);
        CHECK(kindChunkNumbered(own->number) == own);
        CHECK(kindChunkTagged(tagOf(own->tag)) == own);
        CHECK(own->number > 1);  // 0 and 1: HEAD's references and PTM
        CHECK(own->since <= kBankFormatVersion);
        CHECK(numbers.insert(own->number).second);
        CHECK(tags.insert(tagOf(own->tag)).second);
    }
    CHECK(numbers.size() == 2);   // the light model's and the learned model's
    std::set<std::string> names;  // material.json's, one a kind
    for (const auto& [kind, name] : kPredictorKindNames) {
        CHECK(names.insert(name).second);
        CHECK(std::string(predictorKindName(kind)) == name);
    }
    CHECK(names.size() == 4);
    CHECK(kindChunkOf(PredictorKind::References) == nullptr);
    CHECK(kindChunkNumbered(4) == nullptr);
    CHECK(kindChunkTagged(tagOf("REFS")) == nullptr);

    // A light model's bank without its LMDL chunk, or with it twice: one line each.
    TempDir dir;
    Result<Dataset> dataset = openDataset(writeRelief(dir, Relief{.size = 12}, dome(12, 65)));
    REQUIRE(dataset.ok());
    Result<LutBank> bank =
        bakeBank(*dataset, {.fit = lightModelFit(LightModelOptions{.basis = LightBasis::Hsh, .order = 2})});
    REQUIRE(bank.ok());
    const Bytes bytes = encodeBank(*bank);
    std::size_t at = 12, lmdl = 0, length = 0;  // after the signature and version: tag, length, payload, CRC
    while (at + 8 <= bytes.size()) {
        std::uint32_t tag = 0, size = 0;
        std::memcpy(&tag, &bytes[at], 4);
        std::memcpy(&size, &bytes[at + 4], 4);
        if (tag == tagOf("LMDL")) lmdl = at, length = 12 + size;
        at += 12 + size;
    }
    REQUIRE(length > 0);
    Bytes without = bytes, twice = bytes;
    without.erase(without.begin() + static_cast<std::ptrdiff_t>(lmdl),
                  without.begin() + static_cast<std::ptrdiff_t>(lmdl + length));
    twice.insert(twice.begin() + static_cast<std::ptrdiff_t>(lmdl), bytes.begin() + static_cast<std::ptrdiff_t>(lmdl),
                 bytes.begin() + static_cast<std::ptrdiff_t>(lmdl + length));
    CHECK(decodeBank(without, "w.btflut").error() ==
          "w.btflut: a bank predicted by a light model without its model (LMDL chunk)");
    CHECK(decodeBank(twice, "t.btflut").error() == "t.btflut: unexpected LMDL chunk");
    REQUIRE(decodeBank(bytes, "b.btflut").ok());
}

TEST_CASE("version 6 banks of every basis round-trip; every cut and flipped bit is refused") {
    TempDir dir;
    Result<Dataset> dataset = openDataset(writeRelief(dir, Relief{.size = 20}, dome(12, 65)));
    REQUIRE(dataset.ok());
    for (const LightModelOptions& o : everyBasis()) {
        Result<LutBank> bank = bakeBank(*dataset, {.fit = lightModelFit(o), .match = 0.5f, .regions = 2});
        REQUIRE(bank.ok());
        CHECK(bankFormatVersion(*bank) == expectedVersion(*bank, 5));
        const Bytes bytes = encodeBank(*bank);
        Result<LutBank> back = decodeBank(bytes, "b.btflut");
        REQUIRE_MESSAGE(back.ok(), back.error());
        CHECK(encodeBank(*back) == bytes);
        CHECK(back->predictorAs<ModelPredictor>()->model().coefficients ==
              bank->predictorAs<ModelPredictor>()->model().coefficients);
        CHECK(back->prediction.match == 0.5f);
        for (std::size_t cut = 8; cut < bytes.size(); cut += bytes.size() / 29)
            CHECK_FALSE(decodeBank(Bytes(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(cut)), "cut").ok());
        for (std::size_t at = 12; at < bytes.size(); at += bytes.size() / 41) {
            Bytes flipped = bytes;
            flipped[at] ^= 0x10;
            CHECK_FALSE(decodeBank(flipped, "flip").ok());
        }
    }
    // A newer format is refused with a line naming its version.
    Result<LutBank> bank = bakeBank(*dataset, {.fit = lightModelFit(LightModelOptions{.basis = LightBasis::Rbf})});
    REQUIRE(bank.ok());
    Bytes bytes = encodeBank(*bank);
    bytes[8] = static_cast<std::uint8_t>(kBankFormatVersion + 1);
    Result<LutBank> newer = decodeBank(bytes, "new.btflut");
    REQUIRE_FALSE(newer.ok());
    CHECK(newer.error().find("unsupported .btflut version " + std::to_string(kBankFormatVersion + 1)) !=
          std::string::npos);
}

TEST_CASE("shared data: lut auto beats relight-cli's best 9-plane basis, with the histograms of the paper's bank") {
    // relight-cli's figures on the same protocol (issue 21): dome-synth every:4 rbf9 19.73 dB;
    // psm-rock's best 9-plane basis (bln9, leave-one-out) 32.49 dB, checked here on every:4 (fewer training
    // lights than leave-one-out; the leave-one-out figures are in bench/RESULTS.md).
    for (const auto& [name, path, relight] :
         {std::tuple{"dome-synth", "/dome-synth/dirs.lp", 19.73}, {"psm-rock", "/psm-rock", 32.49}}) {
        if (!haveSharedData(name)) continue;
        CliRun run = runCli({"eval", sharedDataDir() + path, "--modes", "lut,rbf,bln", "--no-gl", "--json"});
        REQUIRE_MESSAGE(run.status == 0, run.err);
        const nlohmann::json report = nlohmann::json::parse(run.out);
        std::map<std::string, nlohmann::json> modes;
        for (const nlohmann::json& m : report["modes"]) modes[m["name"]] = m;
        const nlohmann::json& automatic = modes.at("lut auto");
        const nlohmann::json& paper = modes.at("lut K1 R1 grey");
        MESSAGE(std::string(name) << ": lut auto " << automatic["psnr"] << " dB, L1 " << automatic["l1"]
                                  << "; the paper's bank " << paper["psnr"] << " dB, L1 " << paper["l1"] << "; rbf "
                                  << modes.at("rbf")["psnr"] << ", bln " << modes.at("bln")["psnr"]);
        CHECK(automatic["bytes_per_texel"].get<double>() <= 9);
        CHECK(automatic["psnr"].get<double>() >= relight);
        CHECK(automatic["psnr"].get<double>() >= modes.at("rbf")["psnr"].get<double>());
        CHECK(automatic["psnr"].get<double>() >= modes.at("bln")["psnr"].get<double>());
        CHECK(automatic["l1"].get<double>() <= paper["l1"].get<double>() + 0.002);
    }
}

TEST_CASE("the match LUTs baked over the grid: close to the exact run-time LUT, finer grids closer, kept in the file") {
    TempDir dir;
    Result<Dataset> dataset = openDataset(writeRelief(dir, Relief{.size = 40}, dome(20, 70)));
    REQUIRE(dataset.ok());
    const Mask mask = fullMask(40, 40);
    double previous = 0;
    for (int grid : {9, 33}) {
        Result<LutBank> bank = bakeBank(
            *dataset,
            {.gridSize = grid, .fit = lightModelFit(LightModelOptions{.basis = LightBasis::Rbf, .planes = 6})});
        REQUIRE(bank.ok());
        REQUIRE(bank->layers[0].matchGridLuts.size() == static_cast<std::size_t>(grid * grid) * bank->matchLength());
        const Relighter relighter(*bank);
        double psnr = 0;
        for (Direction l :
             {Direction::fromDegrees(27, 15), Direction::fromDegrees(52, 170), Direction::fromDegrees(66, 290)})
            psnr += compareImages(relighter.apply(relighter.gridFrame(l), true),
                                  relighter.apply(relighter.frame(l), true), mask)
                        .psnr /
                    3;
        INFO("grid " << grid << ": the grid's relighting against the exact one, " << psnr << " dB");
        CHECK(psnr > 35);
        CHECK(psnr > previous);
        previous = psnr;
        // In the file: read back, the same grid and the same relighting.
        Result<LutBank> back = decodeBank(encodeBank(*bank), "g.btflut");
        REQUIRE(back.ok());
        CHECK(back->layers[0].matchGridLuts == bank->layers[0].matchGridLuts);
    }
    // A corrupted grid is refused.
    Result<LutBank> bank =
        bakeBank(*dataset, {.gridSize = 5, .fit = lightModelFit(LightModelOptions{.basis = LightBasis::Ptm})});
    REQUIRE(bank.ok());
    LutBank broken = *bank;
    broken.layers[0].matchGridLuts[0] = 65535;  // the first LUT falls from its first entry to its second
    broken.layers[0].matchGridLuts[1] = 0;
    Result<LutBank> refused = decodeBank(encodeBank(broken), "broken.btflut");
    REQUIRE_FALSE(refused.ok());
    CHECK(refused.error().find("match grid is not monotonic") != std::string::npos);
}

TEST_CASE("export --rti: an HSH model as RTIViewer's file, read back as CHI's viewers read it") {
    // Decodes the file as CHI's RTI viewers do (comments, type 3, sizes, terms; scales and
    // biases; bytes per pixel, band and term, rows top first) and evaluates it at `light`.
    auto evaluate = [](const Bytes& file, Direction light, int& width, int& height) {
        std::string text(file.begin(), file.end());
        std::size_t at = 0;
        while (text[at] == '#') at = text.find('\n', at) + 1;
        std::istringstream header(text.substr(at, 64));
        int type = 0, bands = 0, terms = 0, basisType = 0, elementSize = 0;
        header >> type >> width >> height >> bands >> terms >> basisType >> elementSize;
        REQUIRE(type == 3);
        REQUIRE(bands == 3);
        REQUIRE(elementSize == 1);
        for (int line = 0; line < 3; ++line) at = text.find('\n', at) + 1;
        std::vector<float> scale(static_cast<std::size_t>(terms)), bias(static_cast<std::size_t>(terms));
        std::memcpy(scale.data(), file.data() + at, scale.size() * 4);
        std::memcpy(bias.data(), file.data() + at + scale.size() * 4, bias.size() * 4);
        const std::uint8_t* bytes = file.data() + at + 8 * scale.size();
        REQUIRE(file.size() == at + 8 * scale.size() + static_cast<std::size_t>(width) * height * 3 * terms);
        const std::vector<double> t =
            basisTerms(LightBasis::Hsh, static_cast<int>(std::lround(std::sqrt(terms))), light);
        Image out(width, height, 3);
        for (std::size_t i = 0; i < out.samples.size(); ++i) {
            double v = 0;
            for (int q = 0; q < terms; ++q)
                v += (*bytes++ / 255.0 * scale[static_cast<std::size_t>(q)] + bias[static_cast<std::size_t>(q)]) *
                     t[static_cast<std::size_t>(q)];
            out.samples[i] = static_cast<float>(std::clamp(v, 0.0, 1.0));
        }
        return out;
    };
    const Relief relief;  // colour: the model has an LRGB albedo
    const std::vector<Direction> lights = dome(30, 70);
    std::vector<Image> images;
    for (Direction l : lights) images.push_back(reliefImage(relief, l));
    const Mask mask = fullMask(relief.size, relief.size);
    for (int order : {2, 3}) {
        Result<LightModel> model = fit(images, lights, mask, {.basis = LightBasis::Hsh, .order = order});
        REQUIRE(model.ok());
        const Bytes file = encodeHshRtiFile(*model);
        CHECK(std::string(file.begin(), file.begin() + 8) == "#HSH1.2\n");
        for (Direction l : {Direction::fromDegrees(20, 30), Direction::fromDegrees(55, 250)}) {
            int width = 0, height = 0;
            const Image read = evaluate(file, l, width, height);
            CHECK(width == relief.size);
            CHECK(height == relief.size);
            const ImageErrors e = compareImages(read, model->render(l), mask);
            INFO("hsh" << order << " at " << l.thetaDegrees() << ": max " << e.maxDifference * 255 << "/255");
            CHECK(e.maxDifference * 255 < 3);
            CHECK(e.meanDifference * 255 < 0.5);
        }
    }
}

TEST_CASE("export --rti: written for HSH banks, refused for others naming what to bake") {
    TempDir dir;
    const std::string material = BTFLUT_DEFAULT_MATERIAL;
    REQUIRE(runCli({"bake", material, "--predictor", "hsh2", "-o", dir / "h.btflut", "-q"}).status == 0);
    REQUIRE(runCli({"bake", material, "--references", "1", "-o", dir / "k.btflut", "-q"}).status == 0);
    const CliRun written = runCli({"export", dir / "h.btflut", "--rti", dir / "h.rti", "--json"});
    INFO(written.err);
    REQUIRE(written.status == 0);
    CHECK(nlohmann::json::parse(written.out)["rti"] == dir / "h.rti");
    CHECK(readFile(dir / "h.rti")->size() > 256 * 256 * 3 * 4);
    const CliRun refused = runCli({"export", dir / "k.btflut", "--rti", dir / "k.rti"});
    CHECK(refused.status != 0);
    CHECK(refused.err.find("--predictor hsh2 or hsh3") != std::string::npos);
    CHECK_FALSE(fs::exists(dir / "k.rti"));
    CHECK(runCli({"export", dir / "h.btflut", "--rti", dir / "h.ptm"}).err.find("--rti") != std::string::npos);
}

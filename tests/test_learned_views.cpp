// A learned model of views as a bank (issue 35, item 5): baked from rectified multi-view sets
// (synth --geometry btf-N), a view layer per measured view and one decoder taking the view,
// written as bank version 9, relit per view on the CPU, on the GPU and by an engine.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "core/bake/auto_bake.h"
#include "core/bake/bake.h"
#include "core/bank/bank_file.h"
#include "core/data/dataset.h"
#include "core/eval/metrics.h"
#include "core/predict/learned_predictor.h"
#include "core/relight/relighter.h"
#include "helpers.h"

using namespace btflut;
using namespace btflut::test;

namespace {

// A rectified btf-N set of a rough surface and its learned bank (a short training).
struct ViewBank {
    TempDir dir;
    Dataset dataset;
    LutBank bank;
    std::string path;

    explicit ViewBank(int views, const char* preset = "concrete") {
        REQUIRE(runCli({"synth", "--preset", preset, "--geometry", "btf-" + std::to_string(views), "--size", "32",
                        "--correlation-length", "4", "--samples", "1", "-q", "-o", dir / "btf"})
                    .status == 0);
        Result<Dataset> ds = openDataset(dir / "btf");
        REQUIRE(ds.ok());
        dataset = std::move(*ds);
        BakeOptions options{.fit = learnedFit(LearnedOptions{.steps = 300})};
        options.threads = 1;
        Result<LutBank> baked = bakeBank(dataset, options);
        REQUIRE_MESSAGE(baked.ok(), baked.error());
        bank = std::move(*baked);
        path = dir / "views.btflut";
        REQUIRE(saveBank(bank, path).ok());
    }
};

}  // namespace

TEST_CASE("learned model of views: a layer per view, one decoder, version 9, relit per view") {
    ViewBank v(5);
    const LutBank& bank = v.bank;
    REQUIRE(bank.makesLuts());
    const LearnedPredictor* learned = bank.predictorAs<LearnedPredictor>();
    REQUIRE(learned);
    CHECK(learned->viewDependent());
    CHECK(learned->model().viewFeatures == kLearnedViewFeatures);
    CHECK(bank.layers.size() == 5);
    CHECK(bank.domain == BankDomain::Layers);
    for (const ViewLayer& layer : bank.layers) CHECK_FALSE(layer.matchGridLuts.empty());

    // Version 9, a byte-exact round trip that keeps the view features; the same bytes on one
    // thread or two.
    CHECK(bankFormatVersion(bank) == 9);
    const Bytes bytes = encodeBank(bank);
    Result<LutBank> back = decodeBank(bytes, "views.btflut");
    REQUIRE_MESSAGE(back.ok(), back.error());
    CHECK(back->predictorAs<LearnedPredictor>()->model().viewFeatures == kLearnedViewFeatures);
    CHECK(encodeBank(*back) == bytes);
    BakeOptions twoThreads{.fit = learnedFit(LearnedOptions{.steps = 300})};
    twoThreads.threads = 2;
    Result<LutBank> again = bakeBank(v.dataset, twoThreads);
    REQUIRE(again.ok());
    CHECK(encodeBank(*again) == bytes);

    // Each measured (light, view) relit from the bank is nearer its photograph than the paper's
    // one-reference bank of views relights it, and the view changes the image.
    Result<LutBank> paper = bakeBank(v.dataset, BakeOptions{});
    REQUIRE(paper.ok());
    const Mask mask = fullMask(bank.reference.width, bank.reference.height);
    double learnedPsnr = 0, paperPsnr = 0;
    const std::size_t n = v.dataset.images.size();
    for (const DatasetImage& im : v.dataset.images) {
        Result<Image> photo = loadImage(im.path);
        REQUIRE(photo.ok());
        const Image relit = relight(bank, im.light, im.view);
        for (float s : relit.samples) REQUIRE((std::isfinite(s) && s >= 0 && s <= 1));
        learnedPsnr += compareImages(relit, *photo, mask).psnr / static_cast<double>(n);
        paperPsnr += compareImages(relight(*paper, im.light, im.view), *photo, mask).psnr / static_cast<double>(n);
    }
    INFO("learned bank " << learnedPsnr << " dB, one-reference bank " << paperPsnr << " dB");
    CHECK(learnedPsnr > paperPsnr + 3);
    const Direction light = Direction::fromDegrees(35, 60);
    CHECK(relight(bank, light, bank.layers[0].view).samples != relight(bank, light, bank.layers[4].view).samples);

    // The match grids blend across views as lookup does: at a layer's own view, that layer's.
    const Relighter relighter(bank);
    CHECK(relighter.gridFrame(light, bank.layers[2].view).luts == bank.matchGridLookup(light, std::size_t{2}));

    // Matched below 1, a measured (light, view) pair is still matched fully, and the same light
    // seen from between the measured views is not: the ramp is over pairs, not lights alone.
    LutBank half = bank;
    half.prediction.match = 0.5f;
    const Relighter halfway(half);
    const Direction measured = bank.layers[0].nodes[0].light;
    CHECK(halfway.matchAt(measured, bank.layers[0].view) == 1.f);
    const Vec3 a = toVector(bank.layers[0].view), b = toVector(bank.layers[1].view);
    const Direction between = fromVector({a.x + b.x, a.y + b.y, a.z + b.z});
    CHECK(halfway.matchAt(measured, between) < 0.9f);
    CHECK(halfway.matchAt(measured, between) >= 0.5f);

    // The chunk's view-feature count is checked.
    LutBank bad = bank;
    LearnedModel changed = learned->model();
    changed.viewFeatures = 2;
    bad.prediction.predictor = std::make_shared<LearnedPredictor>(std::move(changed), false);
    Result<LutBank> refused = decodeBank(encodeBank(bad), "bad.btflut");
    REQUIRE_FALSE(refused.ok());
    CHECK_MESSAGE(refused.error().find("bad.btflut: LRND chunk: invalid view feature count") == 0, refused.error());
}

TEST_CASE("learned model of views: bake takes rectified views only, the others say why in one line") {
    TempDir dir;
    REQUIRE(runCli({"synth", "--preset", "concrete", "--geometry", "btf-3", "--size", "16", "--correlation-length", "4",
                    "--samples", "1", "-q", "-o", dir / "btf"})
                .status == 0);
    requireOneLineError(runCli({"bake", dir / "btf", "--predictor", "hsh2", "-o", dir / "x.btflut"}),
                        "the light models need one view (a fixed camera); this dataset has several (a learned model, "
                        "--predictor neural, takes rectified views)");
    requireOneLineError(
        runCli({"bake", dir / "btf", "--predictor", "neural4", "--regions", "2", "-o", dir / "x.btflut"}),
        "--regions and --labels need one view");
    requireOneLineError(
        runCli({"bake", dir / "btf", "--predictor", "neural4", "--domain", "isotropic", "-o", dir / "x.btflut"}),
        "a learned model of views is baked in the layers domain");
    // The paper's geometry (curet-c2: one light per view) has no layer per view to follow the
    // light; auto keeps the paper's bank there without validating.
    REQUIRE(
        runCli({"synth", "--preset", "plastic", "--size", "16", "--correlation-length", "4", "-q", "-o", dir / "c2"})
            .status == 0);
    requireOneLineError(runCli({"bake", dir / "c2", "--predictor", "neural4", "-o", dir / "x.btflut"}),
                        "light(s); a learned model of views needs a layer per view with 3 or more");
    nlohmann::json manifest = readJson(dir / "btf/btflut-dataset.json");
    manifest["rectified"] = false;
    std::ofstream(dir / "btf/btflut-dataset.json") << manifest.dump();
    requireOneLineError(runCli({"bake", dir / "btf", "--predictor", "neural4", "-o", dir / "x.btflut"}),
                        "a learned model of several views needs them rectified");
    CHECK_FALSE(fs::exists(dir / "x.btflut"));
}

TEST_CASE("auto on views: rectified ones validate a learned model of them against the paper's bank") {
    ViewBank v(5);
    AutoBakeOptions options;
    options.base.threads = 1;
    options.seconds = 3;
    Result<LutBank> bank = bakeAuto(v.dataset, options);
    REQUIRE_MESSAGE(bank.ok(), bank.error());
    const nlohmann::json selection = nlohmann::json::parse(bank->selection);
    CHECK(selection["folds"] == 2);
    REQUIRE(selection["candidates"].size() == 2);  // the one-reference bank and neural9: nothing else takes views
    for (const auto& c : selection["candidates"]) {
        INFO(c.dump());
        CHECK_FALSE(c.contains("skipped"));
    }
    CHECK(selection["candidates"][1]["name"] == "neural9");
    if (bank->makesLuts()) {
        CHECK(bank->predictor().viewDependent());
        // The fewest quantiles that cost nothing on the folds (their models reused): fewer than
        // 1024 samples where one of 64 to 512 does; --quantiles given, as given.
        REQUIRE(selection.contains("quantiles"));
        const nlohmann::json& q = selection["quantiles"];
        INFO(q.dump());
        CHECK(q["chosen"] == bank->prediction.quantiles);
        CHECK(q["of"] == 1024);
        for (const auto& row : q["tried"]) CHECK(row["costs_nothing"] == (row["quantiles"] == q["chosen"]));
        CHECK(bank->prediction.quantiles < 1024);
        AutoBakeOptions given = options;
        given.chooseQuantiles = false;
        Result<LutBank> full = bakeAuto(v.dataset, given);
        REQUIRE(full.ok());
        CHECK(full->prediction.quantiles == 1024);
        CHECK_FALSE(nlohmann::json::parse(full->selection).contains("quantiles"));
        CHECK(encodeBank(*bank).size() * 2 < encodeBank(*full).size());
    }
    // Not rectified: the paper's bank, unvalidated.
    Dataset plain = v.dataset;
    plain.rectified = false;
    Result<LutBank> classic = bakeAuto(plain, options);
    REQUIRE(classic.ok());
    CHECK_FALSE(classic->makesLuts());
}

TEST_CASE("eval across views: the learned bank matched beside lut, nearest and the model unmatched") {
    TempDir dir;
    REQUIRE(runCli({"synth", "--preset", "concrete", "--geometry", "btf-5", "--size", "32", "--correlation-length", "4",
                    "--samples", "1", "-q", "-o", dir / "btf"})
                .status == 0);
    CliRun run = runCli({"eval", dir / "btf", "--no-gl", "--json", "--modes", "lut,nearest,neural4", "--predictor",
                         "references,neural4", "--match", "0.5"});
    INFO(run.err);
    REQUIRE(run.status == 0);
    std::map<std::string, double> psnr;
    const nlohmann::json json = nlohmann::json::parse(run.out);
    for (const auto& m : json["modes"]) psnr[m["name"].get<std::string>()] = m["psnr"].get<double>();
    INFO("lut neural4 " << psnr["lut neural4 R1 grey match 0.5"] << " dB, neural4 " << psnr["neural4"] << ", lut "
                        << psnr["lut K1 R1 grey"] << ", nearest " << psnr["nearest"]);
    REQUIRE(psnr.count("lut neural4 R1 grey match 0.5"));
    CHECK(psnr["lut neural4 R1 grey match 0.5"] > psnr["lut K1 R1 grey"] + 3);
    CHECK(psnr["lut neural4 R1 grey match 0.5"] > psnr["nearest"] + 3);
    requireOneLineError(runCli({"eval", dir / "btf", "--predictor", "hsh2"}),
                        "on rectified views a learned model's (--predictor neuralN, or auto)");
}

TEST_SUITE("gl") {
    TEST_CASE("learned model of views on the GPU: render --native and an engine's quad as relight at each view") {
        ViewBank v(3, "plastic");
        const std::string light = "40,30";
        for (const ViewLayer& layer : v.bank.layers)
            for (const std::string& view :
                 {std::to_string(layer.view.thetaDegrees()) + "," + std::to_string(layer.view.phiDegrees()),
                  std::string("25,200")}) {
                INFO("view " << view);
                const std::string gpu = v.dir / "gpu.png", cpu = v.dir / "cpu.png";
                REQUIRE(
                    runCli({"render", v.path, "--native", "--light", light, "--view", view, "-o", gpu, "-q"}).status ==
                    0);
                REQUIRE(runCli({"relight", v.path, "--light", light, "--view", view, "-o", cpu, "-q"}).status == 0);
                CHECK(runCli({"compare", gpu, cpu, "--tolerance", "max=1"}).status == 0);
            }
        // An engine: the prediction at the view, the LUTs of the nearest view layer, as relight --grid.
        const std::string folder = v.dir / "engine";
        REQUIRE(runCli({"export", v.path, "-o", folder, "-q"}).status == 0);
        const nlohmann::json material = readJson(folder + "/material.json");
        CHECK(material["shader_version"] == 5);
        CHECK(material["luts"]["layers"] == 3);
        for (const std::string view : {"25,200", "60,100"}) {
            const std::string example = v.dir / "example.png", grid = v.dir / "grid.png";
            const std::string command = "ASAN_OPTIONS=detect_leaks=0 " + std::string(BTFLUT_EXAMPLE_QUAD) + " " +
                                        folder + " --light " + light + " --view " + view + " -o " + example +
                                        " > /dev/null";
            REQUIRE(std::system(command.c_str()) == 0);
            REQUIRE(runCli({"relight", v.path, "--grid", "--light", light, "--view", view, "-o", grid, "-q"}).status ==
                    0);
            const CliRun same = runCli({"compare", example, grid, "--tolerance", "max=1"});
            INFO("view " << view << ": " << same.out << same.err);
            CHECK(same.status == 0);
        }
    }
}

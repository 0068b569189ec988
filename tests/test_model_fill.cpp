// Directions without measurements filled from the fitted model (core/inverse/model_fill.h,
// bake --fill model, eval --fill) against today's clamping.
#include <doctest/doctest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/bank/bank_file.h"
#include "core/inverse/model_fill.h"
#include "helpers.h"

using namespace btflut;
using namespace btflut::test;
namespace fs = std::filesystem;

namespace {

// A rendered Lambertian rough surface under a 24-light dome; returns its folder.
std::string synthDome(const TempDir& dir) {
    const std::string folder = dir / "dome";
    REQUIRE(runCli({"synth", "--preset", "concrete", "--geometry", "rti-24", "--size", "128", "--samples", "1",
                    "--correlation-length", "8", "-q", "-o", folder})
                .status == 0);
    return folder;
}

// The names of the third of a dataset's lights nearest the horizon.
std::vector<std::string> grazingThird(const std::string& folder) {
    Result<Dataset> dataset = openDataset(folder);
    REQUIRE(dataset.ok());
    std::vector<DatasetImage> images = dataset->images;
    std::sort(images.begin(), images.end(), [](const auto& a, const auto& b) { return a.light.theta > b.light.theta; });
    std::vector<std::string> names;
    for (std::size_t i = 0; i < images.size() / 3; ++i) names.push_back(images[i].name);
    return names;
}

}  // namespace

TEST_CASE("fill model: at lights removed from a synthetic dataset, relit histograms closer to the truth than clamped") {
    TempDir dir;
    const std::string folder = synthDome(dir);
    std::ofstream list(dir / "grazing.txt");
    for (const std::string& name : grazingThird(folder)) list << name << "\n";
    list.close();
    CliRun run = runCli({"eval", folder, "--holdout", dir / "grazing.txt", "--modes", "lut", "--predictor",
                         "references", "--fill", "clamp,model", "--no-gl", "--json"});
    REQUIRE_MESSAGE(run.status == 0, run.err);
    const nlohmann::json report = nlohmann::json::parse(run.out);
    REQUIRE(report["modes"].size() == 2);
    const nlohmann::json& clamped = report["modes"][0];
    const nlohmann::json& filled = report["modes"][1];
    REQUIRE(clamped["fill"] == "clamp");
    REQUIRE(filled["fill"] == "model");
    MESSAGE("64-bin L1 at the removed lights: clamped "
            << clamped["l1"].get<double>() << ", filled " << filled["l1"].get<double>() << "; EMD "
            << clamped["emd"].get<double>() << " -> " << filled["emd"].get<double>());
    CHECK(filled["l1"].get<double>() < clamped["l1"].get<double>());
    CHECK(filled["emd"].get<double>() < clamped["emd"].get<double>());
}

TEST_CASE("bake --fill model: modelled nodes recorded in the bank, the measured ones untouched, no jump at the hull") {
    TempDir dir;
    const std::string folder = synthDome(dir);
    REQUIRE(runCli({"bake", folder, "--references", "1", "-o", dir / "clamp.btflut", "-q"}).status == 0);
    CliRun run = runCli({"bake", folder, "--references", "1", "--fill", "model", "-o", dir / "fill.btflut"});
    REQUIRE_MESSAGE(run.status == 0, run.err);
    CHECK(run.out.find("fitted lambert") != std::string::npos);

    Result<LutBank> clamped = loadBank(dir / "clamp.btflut"), filled = loadBank(dir / "fill.btflut");
    REQUIRE(clamped.ok());
    REQUIRE_MESSAGE(filled.ok(), filled.error());
    CHECK(bankFormatVersion(*filled) == expectedVersion(*filled, 4));
    CHECK(filled->modelFill.find("\"roughness\"") != std::string::npos);
    const ViewLayer& layer = filled->layers[0];
    REQUIRE(layer.measuredNodes == clamped->layers[0].nodes.size());
    REQUIRE(layer.nodes.size() > layer.measuredNodes);
    for (std::size_t n = 0; n < layer.nodes.size(); ++n) CHECK(layer.nodes[n].modelled == (n >= layer.measuredNodes));

    // Inside the measured hull: the clamped bank's LUTs exactly.
    for (Direction light : {Direction::fromDegrees(20, 40), Direction::fromDegrees(50, 200)}) {
        const BankLookup a = clamped->lookup(light), b = filled->lookup(light);
        CHECK(a.lightProvenance == Provenance::Interpolated);
        CHECK(b.lightProvenance == Provenance::Interpolated);
        CHECK(a.values == b.values);
    }
    // Beyond it: modelled (no longer clamped), and darker towards the horizon, as shadows grow.
    const BankLookup grazing = filled->lookup(Direction::fromDegrees(85, 120));
    CHECK(grazing.lightProvenance == Provenance::Modelled);
    CHECK(clamped->lookup(Direction::fromDegrees(85, 120)).lightProvenance == Provenance::Clamped);
    auto mean = [](const std::vector<float>& lut) {
        double sum = 0;
        for (float v : lut) sum += v;
        return sum / static_cast<double>(lut.size());
    };
    CHECK(mean(grazing.values) < mean(filled->lookup(Direction::fromDegrees(80, 120)).values));
    CHECK(mean(filled->lookup(Direction::fromDegrees(80, 120)).values) <
          mean(clamped->lookup(Direction::fromDegrees(80, 120)).values));
    // Continuous at the hull: just outside it the LUT moves from the clamped one gradually.
    double theta = 60;
    while (filled->lookup(Direction::fromDegrees(theta, 120)).lightProvenance != Provenance::Modelled) theta += 0.05;
    const BankLookup inside = filled->lookup(Direction::fromDegrees(theta - 0.05, 120));
    const BankLookup outside = filled->lookup(Direction::fromDegrees(theta, 120));
    double jump = 0;
    for (std::size_t k = 0; k < inside.values.size(); ++k)
        jump = std::max(jump, static_cast<double>(std::abs(inside.values[k] - outside.values[k])));
    INFO("hull at theta " << theta);
    CHECK(jump < 0.01);

    // The grid the GPU reads says so too; the file keeps it all.
    std::size_t modelledCells = 0;
    for (Provenance p : layer.gridProvenance) modelledCells += p == Provenance::Modelled;
    CHECK(modelledCells > 0);
    Result<LutBank> again = decodeBank(encodeBank(*filled), "again");
    REQUIRE(again.ok());
    CHECK(again->layers[0].measuredNodes == layer.measuredNodes);
    CHECK(again->modelFill == filled->modelFill);
    CliRun info = runCli({"info", dir / "fill.btflut"});
    REQUIRE(info.status == 0);
    CHECK(info.out.find(" modelled,") != std::string::npos);
    CHECK(info.out.find("filled from {") != std::string::npos);
    CliRun relit = runCli({"relight", dir / "fill.btflut", "--light", "85,120", "-o", dir / "r.png"});
    REQUIRE(relit.status == 0);
    CHECK(relit.out.find("LUT modelled") != std::string::npos);
    CHECK(relit.err.find("--fill model") == std::string::npos);
    // Without the fill: one word, "clamped", and a note that names what fills such lights.
    CliRun clampedRun = runCli({"relight", dir / "clamp.btflut", "--light", "85,120", "-o", dir / "c.png"});
    REQUIRE(clampedRun.status == 0);
    CHECK(clampedRun.out.find("LUT clamped") != std::string::npos);
    CHECK(clampedRun.err.find("outside the measured lights' hull: its theta is past theirs") != std::string::npos);
    CHECK(clampedRun.err.find("`bake --fill model`") != std::string::npos);
    if (haveSharedData("psm-rock")) {  // a narrow capture: theta 30 is within its lights, phi 40 in a gap of theirs
        REQUIRE(runCli({"bake", sharedDataDir() + "/psm-rock", "--references", "1", "-o", dir / "rock.btflut", "-q"})
                    .status == 0);
        const CliRun gap = runCli({"relight", dir / "rock.btflut", "--light", "30,40", "-o", dir / "g.png"});
        CHECK(gap.status == 0);
        CHECK(gap.err.find("its theta is within theirs (up to 38.9), but no measured light lies between phi") !=
              std::string::npos);
        // info: short by default, the validation tables with --verbose, where fits too big for
        // 12 lights say why they have no figure.
        REQUIRE(runCli({"bake", sharedDataDir() + "/psm-rock", "--predictor", "hsh2", "-o", dir / "hsh2.btflut", "-q"})
                    .status == 0);
        const CliRun brief = runCli({"info", dir / "hsh2.btflut"});
        CHECK(std::count(brief.out.begin(), brief.out.end(), '\n') < 16);
        CHECK(brief.out.find("estimates' validation L1: btflut info --verbose") != std::string::npos);
        const CliRun verbose = runCli({"info", dir / "hsh2.btflut", "--verbose"});
        CHECK(verbose.out.find("poly1 ridge 0.01 ") != std::string::npos);
        CHECK(verbose.out.find("poly3 ridge 0.01            not fitted: more terms than two lights a term allow") !=
              std::string::npos);
    }
    CHECK(runCli({"relight", dir / "clamp.btflut", "--light", "85,120", "-o", dir / "c.png", "-q"}).err.empty());
    // --json: what was written and where the light fell; info -q: nothing, the exit status.
    const CliRun json = runCli({"relight", dir / "clamp.btflut", "--light", "85,120", "-o", dir / "c.png", "--json"});
    REQUIRE(json.status == 0);
    const nlohmann::json j = nlohmann::json::parse(json.out);
    CHECK(j["output"] == dir / "c.png");
    CHECK(j["light_provenance"] == "clamped");
    CHECK(j["light"]["theta"].get<double>() == doctest::Approx(85));
    CHECK(j["width"].get<int>() > 0);
    const CliRun quietInfo = runCli({"info", "-q", dir / "clamp.btflut"});
    CHECK(quietInfo.status == 0);
    CHECK(quietInfo.out.empty());
    std::ofstream(dir / "cut.btflut", std::ios::binary) << readText(dir / "clamp.btflut").substr(0, 900);
    CHECK(runCli({"info", "-q", dir / "cut.btflut"}).status != 0);
    // A narrow capture (psm-rock reaches 39 degrees): info says so, in the same words.
    if (!haveSharedData("psm-rock")) return;
    REQUIRE(
        runCli({"bake", sharedDataDir() + "/psm-rock", "--references", "1", "-o", dir / "rock.btflut", "-q"}).status ==
        0);
    const CliRun rock = runCli({"info", dir / "rock.btflut"});
    CHECK(rock.out.find(" clamped; ") != std::string::npos);
    CHECK(rock.out.find("are clamped to the nearest measured edge's LUT") != std::string::npos);
    CHECK(rock.out.find("`bake --fill model`") != std::string::npos);
    CHECK(rock.out.find("extrapolated") == std::string::npos);

    // A parameters file instead of fitting; bad combinations refused with one line.
    std::ofstream(dir / "p.json") << R"({"brdf": "lambert", "roughness": 0.4, "gain": 1})";
    CHECK(runCli({"bake", folder, "--references", "1", "--fill", "model", "--params", dir / "p.json", "-o",
                  dir / "p.btflut", "-q"})
              .status == 0);
    const std::string out = dir / "x.btflut";
    requireOneLineError(runCli({"bake", folder, "--params", dir / "p.json", "-o", out}),
                        "--params and --fit-brdf go with --fill model");
    requireOneLineError(runCli({"bake", folder, "--fill", "model", "--regions", "2", "-o", out}),
                        "not each of --regions");
    requireOneLineError(runCli({"bake", folder, "--fill", "model", "--fit-brdf", "glossy", "-o", out}),
                        "is not lambert, ts or mix");
    std::ofstream(dir / "bad.json") << R"({"roughness": -1})";
    requireOneLineError(runCli({"bake", folder, "--fill", "model", "--params", dir / "bad.json", "-o", out}),
                        "bad.json");
    CHECK_FALSE(fs::exists(out));
    LutBank rgb = *clamped;
    rgb.colour = ColourMode::Rgb;
    Result<ModelFillReport> refused = fillFromModel(rgb, {}, "{}");
    REQUIRE_FALSE(refused.ok());
    CHECK(refused.error().find("--colour grey or lrgb") != std::string::npos);
    Result<ModelFillReport> twice = fillFromModel(*filled, {}, "{}");
    REQUIRE_FALSE(twice.ok());
    CHECK(twice.error().find("already holds modelled nodes") != std::string::npos);
}

TEST_CASE("fill model: a bank that blends references is filled with the model's quantile functions") {
    TempDir dir;
    const std::string folder = synthDome(dir);
    CliRun run = runCli({"bake", folder, "--references", "4", "--fill", "model", "-o", dir / "k4.btflut", "-q"});
    REQUIRE_MESSAGE(run.status == 0, run.err);
    Result<LutBank> bank = loadBank(dir / "k4.btflut");
    REQUIRE_MESSAGE(bank.ok(), bank.error());
    CHECK(bank->makesLuts());
    CHECK(bank->layers[0].nodes.size() > bank->layers[0].measuredNodes);
    CliRun relit = runCli({"relight", dir / "k4.btflut", "--light", "88,10", "-o", dir / "r.png"});
    REQUIRE_MESSAGE(relit.status == 0, relit.err);
    CHECK(relit.out.find("modelled") != std::string::npos);
}

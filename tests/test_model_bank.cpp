#include <doctest/doctest.h>

#include "core/bank/bank_file.h"
#include "core/physics/model_bank.h"
#include "core/relight/relighter.h"
#include "helpers.h"

using namespace btflut;
using namespace btflut::test;

TEST_CASE("a model bank gives the reference the model's histogram at its lights") {
    auto params = parseModelParams(R"({"roughness": 0.5, "brdf": "lambert", "gain": 0.6,
        "lights": [{"theta": 0, "phi": 0}, {"theta": 40, "phi": 0}, {"theta": 70, "phi": 0}, {"theta": 70, "phi": 120}]})",
                                   "m.json");
    REQUIRE(params.ok());
    Image reference(160, 120, 1, 16);  // 16-bit, so reference codes are fine enough to split
    for (int y = 0; y < 120; ++y)
        for (int x = 0; x < 160; ++x)
            reference.at(x, y, 0) =
                static_cast<float>(0.5 + 0.3 * std::sin(0.13 * x) * std::cos(0.07 * y + 0.01 * x * x));
    auto bank = bakeModelBank(*params, reference, fullMask(160, 120), {.name = "ref"});
    REQUIRE(bank.ok());
    CHECK(bank->layers.front().nodes.size() == 4);
    for (double theta : {0.0, 40.0, 70.0}) {
        const Direction light = Direction::fromDegrees(theta, 0);
        Image relit = relight(*bank, light);
        auto got = binHistogram(countGreyLevels(relit, fullMask(160, 120)), 64);
        auto want = simulateHistogram(params->model, light, {}, {.bins = 64, .nodes = 48});
        double l1 = 0;
        for (std::size_t b = 0; b < 64; ++b) l1 += std::abs(got[b] - want[b]);
        INFO("theta " << theta << ": L1 " << l1);
        CHECK(l1 < 0.03);
    }
    // Shadows grow at grazing light: the bin-0 mass of the relit image follows the model.
    auto grazing = binHistogram(countGreyLevels(relight(*bank, Direction::fromDegrees(70, 0)), fullMask(160, 120)), 64);
    CHECK(grazing[0] > 0.05);
}

TEST_CASE("model parameter files: defaults, and errors naming the file and field") {
    auto defaults = parseModelParams(R"({"roughness": 0.4})", "d.json");
    REQUIRE(defaults.ok());
    CHECK(defaults->lights.size() == 97);
    CHECK(defaults->simulation.method == SimulationMethod::Quadrature);
    CHECK(defaults->model.brdf.kd == 1.0);
    struct Case {
        const char* text;
        const char* needle;
    } cases[] = {
        {"{", "p.json: not valid JSON"},
        {"[]", "p.json: expected a JSON object"},
        {"{}", "p.json: no \"roughness\""},
        {R"({"roughness": "rough"})", "\"roughness\" must be a number"},
        {R"({"roughness": 0})", "roughness 0 must be > 0"},
        {R"({"roughness": 0.4, "brdf": "phong"})", "brdf 'phong'"},
        {R"({"roughness": 0.4, "brdf": "mix", "kd": 0.5})", "brdf mix needs kd and ks"},
        {R"({"roughness": 0.4, "brdf": "ts", "sigma": -1})", "sigma -1 must be > 0"},
        {R"({"roughness": 0.4, "ior": 0.5})", "ior 0.5 must be >= 1"},
        {R"({"roughness": 0.4, "method": "guess"})", "--method 'guess'"},
        {R"({"roughness": 0.4, "bins": 1})", "\"bins\""},
        {R"({"roughness": 0.4, "lights": []})", "\"lights\" must be a non-empty array"},
        {R"({"roughness": 0.4, "lights": [{"theta": 95, "phi": 0}]})", "lights[0]: theta 95"},
        {R"({"roughness": 0.4, "view": {"theta": "x"}})", "view: expected"},
    };
    for (const Case& c : cases) {
        INFO(c.text);
        auto r = parseModelParams(c.text, "p.json");
        REQUIRE_FALSE(r.ok());
        CHECK(r.error().rfind("p.json", 0) == 0);
        CHECK(r.error().find(c.needle) != std::string::npos);
    }
}

TEST_CASE("btflut bake --model from files; bad combinations refused") {
    TempDir dir;
    std::ofstream(dir / "m.json")
        << R"({"roughness": 0.4, "gain": 0.6, "lights": [{"theta": 0, "phi": 0}, {"theta": 60, "phi": 90}]})";
    REQUIRE(savePng(randomGreyImage(40, 30, 3), dir / "ref.png").ok());
    CliRun ok = runCli({"bake", "--model", dir / "m.json", "--reference", dir / "ref.png", "-o", dir / "m.btflut"});
    REQUIRE(ok.status == 0);
    auto bank = loadBank(dir / "m.btflut");
    REQUIRE(bank.ok());
    CHECK(bank->referenceName == "ref");
    CHECK(bank->layers.front().nodes.size() == 2);
    requireOneLineError(runCli({"bake", "--model", dir / "m.json", "-o", dir / "x.btflut"}), "needs --reference IMAGE");
    requireOneLineError(runCli({"bake", dir.path().string(), "--model", dir / "m.json", "--reference", dir / "ref.png",
                                "-o", dir / "x.btflut"}),
                        "not both");
    requireOneLineError(runCli({"bake", "--model", dir / "m.json", "--reference", dir / "ref.png", "--colour", "rgb",
                                "-o", dir / "x.btflut"}),
                        "grey LUTs");
    requireOneLineError(
        runCli({"bake", "--model", dir / "missing.json", "--reference", dir / "ref.png", "-o", dir / "x.btflut"}),
        "missing.json: cannot open");
    CHECK_FALSE(fs::exists(dir / "x.btflut"));
}

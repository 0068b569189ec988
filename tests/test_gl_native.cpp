// GL tests (doctest suite "gl", CTest label gl): headless contexts, and the GPU path of relight.
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "core/bake/bake.h"
#include "core/bank/bank_file.h"
#include "core/relight/relighter.h"
#include "gl/context.h"
#include "gl/native_renderer.h"
#include "gl/shader.h"
#include "helpers.h"

using namespace btflut;
using namespace btflut::test;

namespace {

double maxDifference(const Image& a, const Image& b) {
    REQUIRE(a.samples.size() == b.samples.size());
    double worst = 0;
    for (std::size_t i = 0; i < a.samples.size(); ++i)
        worst = std::max(worst, static_cast<double>(std::abs(a.samples[i] - b.samples[i])));
    return worst;
}

// Renders on the backend and checks against the CPU reference at each light, dithered and not.
void checkAgainstRelight(GlBackend backend, const LutBank& bank, const std::vector<Direction>& lights) {
    auto context = createHeadlessContext(backend);
    if (!context.ok()) FAIL(context.error());
    for (const Direction& light : lights)
        for (bool dither : {false, true}) {
            auto gpu = renderNative(bank, light, {}, dither);
            if (!gpu.ok()) FAIL(gpu.error());
            const double d = maxDifference(*gpu, relight(bank, light, {}, dither));
            INFO((*context)->description() << " light " << light.thetaDegrees() << "," << light.phiDegrees()
                                           << " dither " << dither << ": " << d * 255 << " / 255");
            CHECK(d <= 1.0 / 255);
        }
}

}  // namespace

TEST_SUITE("gl") {
    TEST_CASE("headless contexts: OSMesa and EGL give OpenGL 3.3+ core") {
        for (auto [backend, name] : {std::pair{GlBackend::OsMesa, "osmesa"}, std::pair{GlBackend::Egl, "egl"}}) {
            auto context = createHeadlessContext(backend);
            if (!context.ok()) FAIL(context.error());
            CHECK((*context)->description().rfind(name, 0) == 0);
        }
        CHECK(parseGlBackend("vulkan").error().find("--backend 'vulkan'") != std::string::npos);
    }

    TEST_CASE("render --native equals relight at measured and in-between directions (grey and rgb banks)") {
        TempDir dir;
        nlohmann::json manifest{{"images", nlohmann::json::array()}};
        const double lights[4][2] = {{0, 0}, {30, 0}, {30, 120}, {50, 240}};
        for (int s = 0; s < 4; ++s) {
            Image im(48, 32, 3);
            for (int y = 0; y < 32; ++y)
                for (int x = 0; x < 48; ++x)
                    for (int c = 0; c < 3; ++c)
                        im.at(x, y, c) =
                            static_cast<float>(((x * (3 + s) + y * 7 + c * 29 + s * s * 13) % 200 + 20) / 255.0);
            std::string name = "s" + std::to_string(s) + ".png";
            REQUIRE(savePng(im, dir / name).ok());
            manifest["images"].push_back({{"file", name}, {"light", {{"theta", lights[s][0]}, {"phi", lights[s][1]}}}});
        }
        std::ofstream(dir / "set.json") << manifest.dump();
        auto ds = openDataset(dir / "set.json");
        REQUIRE(ds.ok());
        const std::vector<Direction> at{Direction::fromDegrees(30, 0), Direction::fromDegrees(20, 60),
                                        Direction::fromDegrees(45, 200), Direction::fromDegrees(80, 10)};
        for (ColourMode colour : {ColourMode::Grey, ColourMode::Rgb}) {
            auto bank = bakeBank(*ds, {.colour = colour});
            REQUIRE(bank.ok());
            checkAgainstRelight(GlBackend::OsMesa, *bank, at);
            checkAgainstRelight(GlBackend::Egl, *bank, at);
        }
    }

    TEST_CASE("between two nodes the shader's value is the CPU interpolation") {
        TempDir dir;
        auto ds = openDataset(writeSyntheticDataset(dir, {{20, 0, 0, 0, 0, 1}, {40, 0, 0, 0, 100, 2}}));
        REQUIRE(ds.ok());
        auto bank = bakeBank(*ds, {});
        REQUIRE(bank.ok());
        const DiskPoint a = toDisk(Direction::fromDegrees(20, 0)), b = toDisk(Direction::fromDegrees(40, 0));
        std::vector<Direction> between;
        for (double t : {0.25, 0.5, 0.8}) between.push_back(fromDisk({a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)}));
        checkAgainstRelight(GlBackend::Auto, *bank, between);
    }

    TEST_CASE("psm-rock: render --native equals relight on OSMesa and EGL") {
        if (!haveSharedData("psm-rock")) return;
        auto ds = openDataset(sharedDataDir() + "/psm-rock");
        REQUIRE(ds.ok());
        auto bank = bakeBank(*ds, {});
        REQUIRE(bank.ok());
        std::vector<Direction> at{ds->images[0].light, ds->images[5].light, Direction::fromDegrees(25, 80)};
        checkAgainstRelight(GlBackend::OsMesa, *bank, at);
        checkAgainstRelight(GlBackend::Egl, *bank, at);
    }

    TEST_CASE("the include holds the constants the C++ uses (gpu_constants.h, written in by the build)") {
        const std::string_view include = embeddedShader("btflut.glsl");
        auto defines = [&](const std::string& name, long value) {
            return include.find("\n#define " + name + " " + std::to_string(value) + "\n") != std::string_view::npos;
        };
        CHECK(defines("BTFLUT_WEIGHT_UNIT", kWeightUnit));
        CHECK(defines("BTFLUT_MAX_PLANES", LightModel::kMaxPlanes));
        CHECK(defines("BTFLUT_BASIS_BLN", static_cast<long>(LightBasis::Bilinear)));
        CHECK(defines("BTFLUT_KIND_MODEL", BTFLUT_KIND_MODEL));
        CHECK(include.find("btflut: constants (") == std::string_view::npos);  // the marker replaced
    }

    TEST_CASE("a shader that does not compile names the file and line") {
        auto context = createHeadlessContext(GlBackend::Auto);
        REQUIRE(context.ok());
        const std::string broken = "out vec4 colour;\nvoid main() {\n    colour = vec4(undefinedThing);\n}\n";
        auto program = buildProgramFromSources({{"quad.vert", embeddedShader("quad.vert")}},
                                               {{"btflut.glsl", embeddedShader("btflut.glsl")},
                                                {"lut_common.glsl", embeddedShader("lut_common.glsl")},
                                                {"broken.frag", broken}},
                                               {});
        REQUIRE_FALSE(program.ok());
        INFO(program.error());
        CHECK(program.error().find("shaders/broken.frag:3(") != std::string::npos);
        CHECK(program.error().find("undefinedThing") != std::string::npos);
    }

    TEST_CASE("btflut render: the PNG equals relight's; bad input refused") {
        TempDir dir;
        auto ds = openDataset(writeSyntheticDataset(dir, {{0, 0, 0, 0, 0, 1}, {30, 0, 0, 0, 40, 1}}));
        REQUIRE(runCli({"bake", dir / "btflut-dataset.json", "-o", dir / "m.btflut", "-q"}).status == 0);
        REQUIRE(runCli({"render", dir / "m.btflut", "--light", "15,0", "--native", "-o", dir / "gpu.png"}).status == 0);
        REQUIRE(runCli({"relight", dir / "m.btflut", "--light", "15,0", "-o", dir / "cpu.png", "-q"}).status == 0);
        CHECK(readText(dir / "gpu.png") == readText(dir / "cpu.png"));
        // --json: where the light fell, as relight --json says it.
        const CliRun json =
            runCli({"render", dir / "m.btflut", "--light", "15,0", "--native", "-o", dir / "gpu.png", "--json"});
        REQUIRE(json.status == 0);
        const nlohmann::json j = nlohmann::json::parse(json.out);
        CHECK(j["light"]["theta"].get<double>() == doctest::Approx(15));
        CHECK(j["lut"] == "interpolated");
        CHECK(j["light_provenance"] == "interpolated");
        CHECK(
            j["lut"] ==
            nlohmann::json::parse(
                runCli({"relight", dir / "m.btflut", "--light", "15,0", "-o", dir / "cpu.png", "--json"}).out)["lut"]);
        requireOneLineError(runCli({"render", dir / "none.btflut", "--light", "15,0", "--native", "-o", dir / "x.png"}),
                            "none.btflut: cannot open");
        requireOneLineError(runCli({"render", dir / "m.btflut", "--light", "nan,0", "--native", "-o", dir / "x.png"}),
                            "--light");
        requireOneLineError(runCli({"render", dir / "m.btflut", "--light", "10,0", "-o", dir / "x.png"}), "--native");
        CHECK_FALSE(fs::exists(dir / "x.png"));
    }
}

#include "gl/scene_renderer.h"
#include "gl/shape_renderer.h"
#include "gl/textures.h"

TEST_SUITE("gl") {
    TEST_CASE("scenes: golden image, culling, and materials no visible quad uses are never loaded") {
        TempDir dir;
        auto ds = openDataset(
            writeSyntheticDataset(dir, {{0, 0, 0, 0, 0, 1}, {45, 0, 0, 0, 100, 2}, {60, 200, 0, 0, 20, 1}}));
        REQUIRE(ds.ok());
        auto bank = bakeBank(*ds, {});
        REQUIRE(bank.ok());
        REQUIRE(saveBank(*bank, dir / "m.btflut").ok());
        std::ofstream(dir / "scene.json") << R"({
          "image": {"width": 160, "height": 120},
          "camera": {"position": [0, -3, 2.2], "target": [0, 0, 0], "up": [0, 0, 1], "fov_degrees": 45},
          "light": {"direction": [0.6, 0.2, 0.5]},
          "materials": {"m": "m.btflut", "unused": "does-not-exist.btflut", "behind": "also-missing.btflut"},
          "quads": [
            {"material": "m", "center": [0, 0, 0], "normal": [0, 0, 1], "tangent": [1, 0, 0], "size": [3, 3], "uv_scale": 2},
            {"material": "m", "center": [0.9, 0.6, 0.6], "normal": [-1, 0, 0], "tangent": [0, 1, 0], "size": [1, 1], "mode": "flat"},
            {"material": "behind", "center": [0, -30, 0], "normal": [0, 1, 0], "tangent": [1, 0, 0]}
          ]})";
        auto scene = loadScene(dir / "scene.json");
        REQUIRE(scene.ok());
        auto context = createHeadlessContext(GlBackend::Auto);
        REQUIRE(context.ok());
        RenderStats stats;
        auto image = renderScene(*scene, stats);
        if (!image.ok()) FAIL(image.error());
        CHECK(stats.loadedMaterials == std::vector<std::string>{"m"});
        CHECK(stats.skippedMaterials.size() == 2);  // neither missing file was opened
        CHECK(stats.quadsCulled == 1);
        CHECK(stats.quadsDrawn == 2);
        CHECK(stats.textureBytes.reference > 0);
        CHECK(stats.textureBytes.ptm == 0);

        // Golden image: tests/reference/scene-basic.png. BTFLUT_UPDATE_REFERENCE=1 rewrites it
        // (then look at it, and commit it with the change that explains why it moved).
        const std::string golden = std::string(BTFLUT_SOURCE_DIR) + "/tests/reference/scene-basic.png";
        if (const char* update = std::getenv("BTFLUT_UPDATE_REFERENCE"); update && std::string(update) == "1")
            REQUIRE(savePng(*image, golden).ok());
        auto reference = loadImage(golden);
        REQUIRE_MESSAGE(reference.ok(), "missing golden image; run with BTFLUT_UPDATE_REFERENCE=1");
        REQUIRE(reference->width == image->width);
        double sum = 0, worst = 0;
        for (std::size_t i = 0; i < image->samples.size(); ++i) {
            const double d = std::abs(std::round(image->samples[i] * 255) / 255 - reference->samples[i]);
            sum += d;
            worst = std::max(worst, d);
        }
        const double mean = sum / static_cast<double>(image->samples.size());
        INFO("mean " << mean * 255 << " / 255, worst " << worst * 255 << " / 255");
        CHECK(mean <= 0.5 / 255);
        CHECK(worst <= 16.0 / 255);  // edges may rasterise a pixel differently on another driver
    }

    TEST_CASE("the sphere and the cylinder of a bank of LUTs: golden images") {
        // The one-reference path of the shapes (ShapeRenderer) pinned: tests/reference/shape-*.png,
        // made when banks with a predictor joined it (issue 22) and equal to the viewer's before.
        TempDir dir;
        auto ds = openDataset(writeSyntheticDataset(
            dir, {{0, 0, 0, 0, 0, 1}, {45, 0, 0, 0, 100, 2}, {60, 200, 0, 0, 20, 1}, {50, 100, 0, 0, 40, 2}}));
        REQUIRE(ds.ok());
        auto bank = bakeBank(*ds, {});
        REQUIRE(bank.ok());
        REQUIRE_FALSE(bank->makesLuts());
        REQUIRE(saveBank(*bank, dir / "m.btflut").ok());
        auto context = createHeadlessContext(GlBackend::Auto);
        REQUIRE(context.ok());
        auto shape = ShapeRenderer::create(dir / "m.btflut");
        if (!shape.ok()) FAIL(shape.error());
        ShapeFrame sphere{Shape::Sphere, {0, -4, 1.5}, {0, 0, 0}, {0, 0, 1}, 40, {}};
        sphere.light.direction = {0.6, -0.3, 0.74};
        ShapeFrame cylinder{Shape::Cylinder, {2, -3.5, 1}, {0, 0, 0}, {0, 0, 1}, 45, {}};
        cylinder.light = {true, {}, {-2, -2, 1.5}};
        for (const auto& [name, frame] : {std::pair{"shape-sphere.png", sphere}, {"shape-cylinder.png", cylinder}}) {
            REQUIRE((*shape)->draw(frame, 160, 120).ok());
            const Image image = readFramebufferRgb((*shape)->framebuffer(), 160, 120);
            const std::string golden = std::string(BTFLUT_SOURCE_DIR) + "/tests/reference/" + name;
            if (const char* update = std::getenv("BTFLUT_UPDATE_REFERENCE"); update && std::string(update) == "1")
                REQUIRE(savePng(image, golden).ok());
            auto reference = loadImage(golden);
            REQUIRE_MESSAGE(reference.ok(), "missing golden image; run with BTFLUT_UPDATE_REFERENCE=1");
            REQUIRE(reference->samples.size() == image.samples.size());
            double sum = 0, worst = 0;
            for (std::size_t i = 0; i < image.samples.size(); ++i) {
                const double d = std::abs(image.samples[i] - reference->samples[i]);
                sum += d;
                worst = std::max(worst, d);
            }
            const double mean = sum / static_cast<double>(image.samples.size());
            INFO(name << ": mean " << mean * 255 << " / 255, worst " << worst * 255 << " / 255");
            CHECK(mean <= 0.5 / 255);
            CHECK(worst <= 16.0 / 255);  // edges may rasterise a pixel differently on another driver
        }
    }

    TEST_CASE("btflut render SCENE.json: stats, overrides, and bad scenes refused") {
        TempDir dir;
        auto ds = openDataset(writeSyntheticDataset(dir, {{0, 0, 0, 0, 0, 1}, {45, 0, 0, 0, 100, 2}}));
        REQUIRE(runCli({"bake", dir / "btflut-dataset.json", "-o", dir / "m.btflut", "-q"}).status == 0);
        std::ofstream(dir / "s.json")
            << R"({"light": {"direction": [0, 0, 1]}, "materials": {"m": "m.btflut", "x": "nope.btflut"},
            "quads": [{"material": "m", "center": [0,0,0], "normal": [0,0,1], "tangent": [1,0,0], "size": [2,2]}]})";
        CliRun ok = runCli({"render", dir / "s.json", "--size", "96x64", "--light", "30,0", "--mode", "flat", "--stats",
                            "-o", dir / "s.png"});
        REQUIRE(ok.status == 0);
        CHECK(ok.out.find("materials skipped (no visible quad uses them): x") != std::string::npos);
        CHECK(loadImage(dir / "s.png")->width == 96);
        // --json: what was written and the same statistics; -q: nothing.
        CliRun json =
            runCli({"render", dir / "s.json", "--size", "96x64", "--mode", "flat", "--json", "-o", dir / "j.png"});
        REQUIRE(json.status == 0);
        const nlohmann::json stats = nlohmann::json::parse(json.out);
        CHECK(stats["width"] == 96);
        CHECK(stats["stats"]["materials_skipped"] == nlohmann::json::array({"x"}));
        CHECK(stats["stats"]["quads_drawn"] == 1);
        CHECK(runCli({"render", dir / "s.json", "--size", "96x64", "-q", "-o", dir / "q.png"}).out.empty());
        REQUIRE(runCli({"render", dir / "s.json", "--size", "96x64", "--mode", "brdf", "-o", dir / "b.png"}).status ==
                0);
        requireOneLineError(runCli({"render", dir / "s.json", "--mode", "shiny", "-o", dir / "x.png"}),
                            "--mode 'shiny'");
        requireOneLineError(runCli({"render", dir / "s.json", "--mode", "ptm", "-o", dir / "x.png"}),
                            "m.btflut: the bank holds no PTM (bake it with --ptm)");
        requireOneLineError(runCli({"render", dir / "s.json", "--mode", "nearest", "-o", dir / "x.png"}),
                            "material 'm' names no \"images\" (mode nearest draws the measured images)");
        CHECK_FALSE(fs::exists(dir / "x.png"));

        // One renderer, many frames: a new light re-blends the LUT and changes the picture;
        // a light from behind leaves the quad unlit (black), which is not an error.
        auto scene = loadScene(dir / "s.json");
        REQUIRE(scene.ok());
        scene->width = 64;
        scene->height = 48;
        auto context = createHeadlessContext(GlBackend::Auto);
        REQUIRE(context.ok());
        auto renderer = SceneRenderer::create(*scene);
        REQUIRE(renderer.ok());
        REQUIRE((*renderer)->draw(toVector(Direction::fromDegrees(0, 0))).ok());
        Image frontal = (*renderer)->readBack();
        REQUIRE((*renderer)->draw(toVector(Direction::fromDegrees(45, 0))).ok());
        Image oblique = (*renderer)->readBack();
        CHECK(frontal.samples != oblique.samples);
        REQUIRE((*renderer)->draw({0, 0, -1}).ok());
        CHECK((*renderer)->stats().quadsUnlit == 1);
        Image behind = (*renderer)->readBack();
        CHECK(*std::max_element(behind.samples.begin(), behind.samples.end()) == 0.f);
        std::ofstream(dir / "missing.json") << R"({"light": {"direction": [0, 0, 1]}, "materials": {"m": "gone.btflut"},
            "quads": [{"material": "m", "center": [0,0,0], "normal": [0,0,1], "tangent": [1,0,0]}]})";
        requireOneLineError(runCli({"render", dir / "missing.json", "-o", dir / "x.png"}), "gone.btflut: cannot open");
        std::ofstream(dir / "broken.json") << "{ not json";
        requireOneLineError(runCli({"render", dir / "broken.json", "-o", dir / "x.png"}),
                            "broken.json: not valid JSON");
        requireOneLineError(runCli({"render", dir / "s.json", "--size", "0x10", "-o", dir / "x.png"}), "--size '0x10'");
        requireOneLineError(runCli({"render", dir / "s.json", "--light", "nan,0", "-o", dir / "x.png"}), "--light");
        CHECK_FALSE(fs::exists(dir / "x.png"));
    }
}

// The scene renderer's texture-space relighting (issue 12): a relit texture per material and
// light direction, made only when that direction is new; mipmaps made after the LUT, so a far
// quad shows the mean of relit texels; the dither per texel; per-mip LUTs where the LUT varies
// over a quad (view layers); bench render's static and moving figures.
#include <doctest/doctest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "core/bake/bake.h"
#include "core/bank/bank_file.h"
#include "core/histogram/histogram.h"
#include "core/predict/learned_predictor.h"
#include "core/relight/level_match.h"
#include "core/relight/relighter.h"
#include "gl/context.h"
#include "gl/scene_renderer.h"
#include "helpers.h"

using namespace btflut;
using namespace btflut::test;

namespace {

Image drawRelit(SceneRenderer& renderer, Direction light, RenderMode mode = RenderMode::Lut) {
    Status s = renderer.draw(toVector(light), mode);
    if (!s) FAIL(s.error());
    return renderer.readBack();
}

// The grey of each block x block square, averaged (a box-filtered mip level).
std::vector<double> boxMeans(const Image& image, int block) {
    std::vector<double> out;
    for (int by = 0; by + block <= image.height; by += block)
        for (int bx = 0; bx + block <= image.width; bx += block) {
            double sum = 0;
            for (int y = by; y < by + block; ++y)
                for (int x = bx; x < bx + block; ++x) sum += image.at(x, y, 0);
            out.push_back(sum / (block * block));
        }
    return out;
}

std::vector<double> greys(const Image& image) {
    std::vector<double> out;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) out.push_back(image.at(x, y, 0));
    return out;
}

double meanDifference(const std::vector<double>& a, const std::vector<double>& b) {
    REQUIRE(a.size() == b.size());
    double sum = 0;
    for (std::size_t i = 0; i < a.size(); ++i) sum += std::abs(a[i] - b[i]);
    return sum / static_cast<double>(a.size());
}

// Shots whose LUTs are steep: the brighter ones clip half the reference's levels.
std::vector<SyntheticShot> steepShots(double viewTheta = 0, double viewPhi = 0) {
    return {{0, 0, viewTheta, viewPhi, 0, 1},     {45, 0, viewTheta, viewPhi, 100, 2},
            {45, 180, viewTheta, viewPhi, 0, 3},  {60, 90, viewTheta, viewPhi, 20, 1},
            {60, 270, viewTheta, viewPhi, 60, 2}, {30, 45, viewTheta, viewPhi, 10, 1}};
}

// The bank of a synthetic dataset, saved as dir/m.btflut.
LutBank savedBank(const TempDir& dir, const std::vector<SyntheticShot>& shots, int w = 40, int h = 30) {
    auto ds = openDataset(writeSyntheticDataset(dir, shots, w, h));
    REQUIRE(ds.ok());
    auto bank = bakeBank(*ds, {});
    REQUIRE(bank.ok());
    REQUIRE(saveBank(*bank, dir / "m.btflut").ok());
    return std::move(*bank);
}

// A grey concrete synth of `size` texels a side under rti-25 (dir/set), its neural5 bank
// trained briefly, saved as dir/n.btflut.
LutBank learnedSynthBank(const TempDir& dir, int size) {
    REQUIRE(runCli({"synth", "--preset", "concrete", "--geometry", "rti-25", "--size", std::to_string(size),
                    "--correlation-length", "5", "-q", "-o", dir / "set"})
                .status == 0);
    auto dataset = openDataset(dir / "set");
    REQUIRE(dataset.ok());
    auto bank = bakeBank(*dataset, {.fit = learnedFit(LearnedOptions{.codes = 5, .steps = 200})});
    REQUIRE_MESSAGE(bank.ok(), bank.error());
    REQUIRE(saveBank(*bank, dir / "n.btflut").ok());
    return std::move(*bank);
}

}  // namespace

TEST_SUITE("gl") {
    TEST_CASE("mode lut relights once per material and light direction, and only when the light moved") {
        TempDir dir;
        const LutBank bank = savedBank(dir, steepShots());
        auto context = createHeadlessContext(GlBackend::Auto);
        REQUIRE(context.ok());
        Scene scene = frontalScene(dir / "m.btflut", "", 80, 30);
        // Two quads side by side in the same orientation share a relit texture; a third,
        // tilted, has a light direction of its own.
        scene.quads[0].width = 1.2;
        scene.quads[0].center = {-0.6, 0, 0};
        SceneQuad twin = scene.quads[0], tilted = scene.quads[0];
        twin.center = {0.6, 0, 0};
        tilted.center = {0.6, 0.5, 0.1};
        tilted.normal = {0, -0.2, 0.98};
        const double length = std::hypot(tilted.normal.y, tilted.normal.z);
        tilted.normal = {0, tilted.normal.y / length, tilted.normal.z / length};
        scene.quads.push_back(twin);
        scene.quads.push_back(tilted);
        auto renderer = SceneRenderer::create(scene, {.lutPath = LutPath::TextureSpace});
        REQUIRE(renderer.ok());
        SceneRenderer& r = **renderer;
        const Direction a = Direction::fromDegrees(30, 20), b = Direction::fromDegrees(40, 200);
        drawRelit(r, a);
        CHECK(r.stats().relightPasses == 2);
        CHECK(r.stats().relitTextures == 2);
        drawRelit(r, a);  // the light did not move: nothing relit
        CHECK(r.stats().relightPasses == 2);
        drawRelit(r, b);  // the same two textures, relit
        CHECK(r.stats().relightPasses == 4);
        CHECK(r.stats().relitTextures == 2);
        drawRelit(r, b, RenderMode::Flat);  // kept while no quad is in mode lut
        drawRelit(r, b);
        CHECK(r.stats().relightPasses == 4);
        CHECK(r.stats().textureBytes.relit >= 2 * bank.reference.pixelCount());
    }

    TEST_CASE(
        "a moving light is drawn per fragment where that costs less than relighting; the frame after it stops "
        "relights") {
        TempDir dir;
        const LutBank bank = savedBank(dir, steepShots());
        auto context = createHeadlessContext(GlBackend::Auto);
        REQUIRE(context.ok());
        const Direction a = Direction::fromDegrees(30, 20), b = Direction::fromDegrees(40, 200),
                        c = Direction::fromDegrees(50, 80);
        auto renderer = SceneRenderer::create(frontalScene(dir / "m.btflut", "", 40, 30));
        REQUIRE(renderer.ok());
        SceneRenderer& r = **renderer;
        drawRelit(r, a);  // a first frame relights: its texture is mipmapped from relit texels
        CHECK(r.stats().quadsTextureSpace == 1);
        CHECK(r.stats().relightPasses == 1);
        const Image moving = drawRelit(r, b);  // moved: 1,200 pixels per fragment cost less than the pass
        CHECK(r.stats().quadsPerFragment == 1);
        CHECK(r.stats().relightPasses == 1);
        // Per fragment at 1:1 is relight: the same LUT, dithered per texel.
        const Image cpu =
            applyLuts(bank.reference, bank.colour, bank.lookup(b).values, bank.entries, bank.targetCode());
        double worst = 0;
        for (int y = 0; y < 30; ++y)
            for (int x = 0; x < 40; ++x)
                worst = std::max(worst, std::abs(static_cast<double>(moving.at(x, y, 0)) - cpu.at(x, y, 0)));
        INFO("per fragment against relight: worst " << worst * 255 << "/255");
        CHECK(worst <= 1.0 / 255 + 1e-6);
        drawRelit(r, b);  // stopped: relit once
        CHECK(r.stats().quadsTextureSpace == 1);
        CHECK(r.stats().relightPasses == 2);
        drawRelit(r, b);
        CHECK(r.stats().relightPasses == 2);
        drawRelit(r, c);
        CHECK(r.stats().quadsPerFragment == 1);
        CHECK(r.stats().textureBytes.luts > 0);  // the quad's LUTs, made once

        // A quad covering many more pixels than the reference has texels relights even while
        // the light moves.
        auto big = SceneRenderer::create(frontalScene(dir / "m.btflut", "", 400, 300));
        REQUIRE(big.ok());
        drawRelit(**big, a);
        drawRelit(**big, b);
        CHECK((*big)->stats().quadsTextureSpace == 1);
        CHECK((*big)->stats().relightPasses == 2);
    }

    TEST_CASE(
        "a quad seen in part is relit in part: the texels it shows, the same pixels as a whole relight, grown as "
        "the camera pans") {
        TempDir dir;
        const LutBank bank = savedBank(dir, steepShots(), 160, 120);
        auto context = createHeadlessContext(GlBackend::Auto);
        REQUIRE(context.ok());
        const Direction light = Direction::fromDegrees(40, 30);
        const Scene scene = frontalScene(dir / "m.btflut", "", 64, 48);  // the quad fills the frame
        const double distance = scene.eye.z;
        const SceneRendererOptions options{.fixedCamera = false, .lutPath = LutPath::TextureSpace};
        // Zoomed in 4 times on the quad's top left corner (texel 0, 0): the view reaches past it,
        // so filtering there reads the texture's far edges (it repeats).
        auto zoom = [&](SceneRenderer& r, double x, double y) {
            r.setCamera({x, y, distance / 4}, {x, y, 0}, {0, 1, 0});
        };
        const double cornerX = -4.0 / 3 + 0.2, cornerY = 0.85;
        auto whole = SceneRenderer::create(scene, options);
        REQUIRE(whole.ok());
        drawRelit(**whole, light);
        CHECK((*whole)->stats().relitTexels == 160 * 120);
        zoom(**whole, cornerX, cornerY);
        const Image fromWhole = drawRelit(**whole, light);
        CHECK((*whole)->stats().relightPasses == 1);  // what it shows was relit

        auto part = SceneRenderer::create(scene, options);
        REQUIRE(part.ok());
        SceneRenderer& r = **part;
        zoom(r, cornerX, cornerY);
        const Image fromPart = drawRelit(r, light);
        CHECK(r.stats().relightPasses == 1);
        INFO("texels relit for the corner: " << r.stats().relitTexels);
        CHECK(r.stats().relitTexels < 160 * 120 / 10);
        CHECK(r.stats().relitTexels > 40 * 30 / 4);
        double worst = 0;
        for (std::size_t i = 0; i < fromPart.samples.size(); ++i)
            worst = std::max(worst, static_cast<double>(std::abs(fromPart.samples[i] - fromWhole.samples[i])));
        CHECK(worst == 0);  // filtering read only texels it relit

        // Panning under a still light relights the texels it had not; coming back, none.
        zoom(r, 0, 0);
        const Image centre = drawRelit(r, light);
        CHECK(r.stats().relightPasses == 2);
        zoom(r, cornerX, cornerY);
        drawRelit(r, light);
        CHECK(r.stats().relightPasses == 2);
        zoom(**whole, 0, 0);
        const Image centreFromWhole = drawRelit(**whole, light);
        worst = 0;
        for (std::size_t i = 0; i < centre.samples.size(); ++i)
            worst = std::max(worst, static_cast<double>(std::abs(centre.samples[i] - centreFromWhole.samples[i])));
        CHECK(worst == 0);
        // A light change relights what is seen now.
        const std::size_t before = r.stats().relitTexels;
        drawRelit(r, Direction::fromDegrees(50, 200));
        CHECK(r.stats().relitTexels - before < 160 * 120 / 10);

        // Seen in part at a grazing angle, its far texels minified (coarser levels read, made by
        // GenerateMipmap from the level relit): the same pixels.
        auto far = SceneRenderer::create(scene, options);
        REQUIRE(far.ok());
        for (SceneRenderer* each : {&**far, &**whole})
            each->setCamera({cornerX + 0.3, cornerY - 0.9, 0.45}, {cornerX + 0.3, cornerY - 0.2, 0}, {0, 0, 1});
        const Image farPart = drawRelit(**far, light), farWhole = drawRelit(**whole, light);
        CHECK((*far)->stats().relitTexels < 160 * 120 / 2);
        worst = 0;
        for (std::size_t i = 0; i < farPart.samples.size(); ++i)
            worst = std::max(worst, static_cast<double>(std::abs(farPart.samples[i] - farWhole.samples[i])));
        CHECK(worst == 0);
    }

    TEST_CASE("scene quads are dithered per texel, as relight is; --no-dither applies the plain LUT") {
        TempDir dir;
        const LutBank bank = savedBank(dir, steepShots());
        auto context = createHeadlessContext(GlBackend::Auto);
        REQUIRE(context.ok());
        const Direction light = Direction::fromDegrees(50, 40);
        const BankLookup lut = bank.lookup(light);
        for (bool dither : {true, false}) {
            Scene scene = frontalScene(dir / "m.btflut", "", 40, 30);
            scene.dither = dither;
            auto renderer = SceneRenderer::create(scene);
            REQUIRE(renderer.ok());
            const Image gpu = drawRelit(**renderer, light);
            const Image cpu =
                applyLuts(bank.reference, bank.colour, lut.values, bank.entries, dither ? bank.targetCode() : 0);
            double worst = 0;
            for (int y = 0; y < 30; ++y)
                for (int x = 0; x < 40; ++x)
                    worst = std::max(worst, std::abs(static_cast<double>(gpu.at(x, y, 0)) - cpu.at(x, y, 0)));
            INFO("dither " << dither << ": worst " << worst * 255 << "/255");
            CHECK(worst <= 0.5 / 255 + 1e-6);  // the relit texture's and the framebuffer's 8-bit rounding
        }
        // The command: dithered by default, the plain LUT with --no-dither.
        std::ofstream(dir / "s.json")
            << R"({"image": {"width": 40, "height": 30}, "camera": {"position": [0, 0, 2.4142135623730949],
            "target": [0, 0, 0], "up": [0, 1, 0], "fov_degrees": 45}, "light": {"direction": [0.5, 0.4, 0.77]},
            "materials": {"m": "m.btflut"},
            "quads": [{"material": "m", "center": [0,0,0], "normal": [0,0,1], "tangent": [1,0,0], "size": [2.6666666666666665, 2]}]})";
        REQUIRE(runCli({"render", dir / "s.json", "-o", dir / "d.png"}).status == 0);
        REQUIRE(runCli({"render", dir / "s.json", "--no-dither", "-o", dir / "p.png"}).status == 0);
        CHECK(meanDifference(greys(*loadImage(dir / "d.png")), greys(*loadImage(dir / "p.png"))) > 0.2 / 255);
    }

    TEST_CASE("a far quad shows the mean of the relit texels, not the LUT of averaged ones") {
        TempDir dir;
        const LutBank bank = savedBank(dir, steepShots(), 64, 48);
        auto context = createHeadlessContext(GlBackend::Auto);
        REQUIRE(context.ok());
        const Direction light = Direction::fromDegrees(45, 0);  // a node that clips half the levels
        const Relighter relighter(bank);
        const Image relit = relighter.apply(relighter.frame(light), true);
        for (int block : {2, 4}) {
            // The quad fills a (64 / block) x (48 / block) image: each pixel covers block x block texels.
            auto renderer = SceneRenderer::create(frontalScene(dir / "m.btflut", "", 64 / block, 48 / block));
            REQUIRE(renderer.ok());
            const std::vector<double> gpu = greys(drawRelit(**renderer, light));
            const std::vector<double> truth = boxMeans(relit, block);
            // What applying the LUT to the mipmapped reference gives (the per-fragment LUT).
            std::vector<double> lutOfMean = boxMeans(bank.reference, block);
            for (double& v : lutOfMean)
                v = Lut::applyLut(&bank.lookup(light).values[0], bank.entries, static_cast<float>(v));
            const double error = meanDifference(gpu, truth), plain = meanDifference(lutOfMean, truth);
            INFO("blocks of " << block << ": " << error * 255
                              << "/255 from the mean of relit texels; the LUT of the mean " << plain * 255 << "/255");
            CHECK(error <= 1.5 / 255);  // each mip level rounds to 8 bits
            CHECK(plain > 3 * error);
        }
    }

    TEST_CASE("banks with view layers: each mip level has its own LUT, so a far quad keeps its brightness") {
        TempDir dir;
        std::vector<SyntheticShot> shots;
        for (auto [theta, phi] : {std::pair{0.0, 0.0}, {40.0, 0.0}, {40.0, 90.0}, {40.0, 180.0}, {40.0, 270.0}})
            for (SyntheticShot s : steepShots(theta, phi)) shots.push_back(s);
        const LutBank bank = savedBank(dir, shots, 64, 48);
        REQUIRE(bank.layers.size() == 5);
        auto context = createHeadlessContext(GlBackend::Auto);
        REQUIRE(context.ok());
        const Direction light = Direction::fromDegrees(45, 0);
        // Full size: the LUT per fragment (level 0); a quarter: each pixel covers 4 x 4 texels.
        auto full = SceneRenderer::create(frontalScene(dir / "m.btflut", "", 64, 48));
        auto quarter = SceneRenderer::create(frontalScene(dir / "m.btflut", "", 16, 12));
        REQUIRE(full.ok());
        REQUIRE(quarter.ok());
        const Image near = drawRelit(**full, light);
        const std::vector<double> truth = boxMeans(near, 4), far = greys(drawRelit(**quarter, light));
        std::vector<double> lutOfMean = boxMeans(bank.reference, 4);
        const BankLookup centre = bank.lookup(light, Direction{});
        for (double& v : lutOfMean) v = Lut::applyLut(centre.values.data(), bank.entries, static_cast<float>(v));
        // Per-mip LUTs keep the statistics of the blocks (a level's LUT is the expected mean of
        // LUT values over the blocks with that mean), not each block's value: brightness and
        // contrast, measured as the mean and the standard deviation over the quad.
        auto moments = [](const std::vector<double>& v) {
            double mean = 0, square = 0;
            for (double x : v) mean += x / static_cast<double>(v.size());
            for (double x : v) square += (x - mean) * (x - mean) / static_cast<double>(v.size());
            return std::pair{mean, std::sqrt(square)};
        };
        const auto [farMean, farSd] = moments(far);
        const auto [truthMean, truthSd] = moments(truth);
        const auto [plainMean, plainSd] = moments(lutOfMean);
        const double perPixel = meanDifference(far, truth), plainPerPixel = meanDifference(lutOfMean, truth);
        INFO("mean " << truthMean * 255 << "/255, sd " << truthSd * 255 << "/255; per-mip LUTs: " << farMean * 255
                     << ", " << farSd * 255 << "; the LUT of the mean: " << plainMean * 255 << ", " << plainSd * 255
                     << "; per pixel " << perPixel * 255 << " against " << plainPerPixel * 255);
        CHECK(std::abs(farMean - truthMean) < std::abs(plainMean - truthMean) / 2);
        CHECK(std::abs(farMean - truthMean) <= 2.0 / 255);
        CHECK(std::abs(farSd - truthSd) < std::abs(plainSd - truthSd));
    }
}

TEST_CASE("bench render reports static and moving frames, GPU time and overdraw") {
    TempDir dir;
    auto ds = openDataset(writeSyntheticDataset(dir, steepShots()));
    REQUIRE(ds.ok());
    REQUIRE(runCli({"bake", dir / "btflut-dataset.json", "--ptm", "-o", dir / "m.btflut", "-q"}).status == 0);
    CliRun run = runCli({"bench", "render", dir / "m.btflut", "--size", "64x48", "--frames", "2", "--repeat", "1",
                         "--overdraw", "2", "--json"});
    REQUIRE(run.status == 0);
    const nlohmann::json out = nlohmann::json::parse(run.out);
    CHECK(out["quads"] == 8);
    for (const char* key : {"lut_over_flat", "lut_over_ptm", "lut_over_flat_static", "lut_over_ptm_static"})
        CHECK(out[key].get<double>() > 0);
    REQUIRE(out["sizes"].size() == 1);
    CHECK(out["sizes"][0]["width"] == 64);
    CHECK(out["sizes"][0]["lut_static_ms"].get<double>() > 0);
    if (out["gpu_timer"].get<bool>()) CHECK(out["sizes"][0].contains("lut_gpu_ms"));
    requireOneLineError(runCli({"bench", "render", dir / "m.btflut", "--size", "64by48"}), "--size '64by48'");
    // A bank with a predictor: the lut over the predictor drawn per fragment without its LUT.
    REQUIRE(runCli({"bake", dir / "btflut-dataset.json", "--predictor", "ptm", "--ptm", "-o", dir / "p.btflut", "-q"})
                .status == 0);
    run = runCli({"bench", "render", dir / "p.btflut", "--size", "64x48", "--frames", "2", "--repeat", "1", "--json"});
    REQUIRE(run.status == 0);
    const nlohmann::json predictor = nlohmann::json::parse(run.out);
    CHECK(predictor["lut_over_predictor_moving"].get<double>() > 0);
    CHECK(predictor["bytes_per_texel_per_fragment"].get<double>() > 0);
    CHECK(predictor["bytes_per_texel_ptm"].get<double>() > 0);
    CHECK(predictor["sizes"][0]["predictor_ms"].get<double>() > 0);
    CHECK(predictor["sizes"][0]["lut_moving_quads_per_fragment"].get<int>() == 4);  // 64 x 48 pixels: per fragment
    requireOneLineError(runCli({"bench", "render", dir / "p.btflut", "--lut-path", "screen"}), "--lut-path");
}

TEST_CASE(
    "a far quad of a predictor bank is relit at the mip level it reads: 1/64 of the texels at 1/8, the level's "
    "histogram that of the whole relight box-filtered") {
    TempDir dir;
    const LutBank bank = learnedSynthBank(dir, 128);
    REQUIRE(LevelMatch::supports(bank));
    auto context = createHeadlessContext(GlBackend::Auto);
    REQUIRE(context.ok());
    const Direction light = Direction::fromDegrees(50, 130);  // between the grid's nodes
    auto histogram = [](const std::vector<double>& greys) {
        std::vector<double> bins(256, 0.0);
        for (double v : greys)
            bins[static_cast<std::size_t>(std::clamp(v, 0.0, 1.0) * 255 + 0.5)] += 1.0 / greys.size();
        return bins;
    };
    // The whole relight, box-filtered to 16 x 16: what level 3 of a mipmapped relit texture holds.
    const Relighter relighter(bank);
    const std::vector<double> truth = boxMeans(relighter.apply(relighter.gridFrame(light), true), 8);
    const LevelMatch levels(bank);
    {  // The CPU twin: level 3's own LUTs keep the histogram; the bank's would not.
        auto twin = [&](const std::vector<float>& luts) {
            const std::vector<float> v = levels.relitLevel(light, 3, luts);
            return earthMoversDistance(histogram(std::vector<double>(v.begin(), v.end())), histogram(truth));
        };
        const double own = twin(levels.luts(light, 3)), banks = twin(relighter.gridFrame(light).luts);
        INFO("level 3's EMD from the whole relight's: its own LUTs " << own << ", the bank's " << banks);
        CHECK(own <= 0.005);
        CHECK(own < banks / 2);
    }
    // The quad fills a 16 x 16 frame: each pixel is one texel of level 3.
    auto far = SceneRenderer::create(frontalScene(dir / "n.btflut", "", 16, 16));
    REQUIRE(far.ok());
    const std::vector<double> drawn = greys(drawRelit(**far, light));
    CHECK((*far)->stats().relightPasses == 1);
    CHECK((*far)->stats().relitTexels == 16 * 16);
    const double emd = earthMoversDistance(histogram(drawn), histogram(truth));
    INFO("the far quad's EMD from the whole relight's level 3: " << emd);
    CHECK(emd <= 0.005);
    // It is the CPU twin's level 3, pixel for pixel (within a code, the decoder's float sums).
    const std::vector<float> twin = levels.relitLevel(light, 3, levels.luts(light, 3));
    REQUIRE(twin.size() == drawn.size());
    double worst = 0;
    for (std::size_t i = 0; i < drawn.size(); ++i) worst = std::max(worst, std::abs(drawn[i] - twin[i]) * 255);
    CHECK(worst <= 1.01);
    // Near (one pixel a texel), the whole texture is relit.
    auto near = SceneRenderer::create(frontalScene(dir / "n.btflut", "", 128, 128));
    REQUIRE(near.ok());
    drawRelit(**near, light);
    CHECK((*near)->stats().relitTexels == 128 * 128);

    // bench levels: the same measure, side by side with the bank's LUTs, and the time of each.
    CliRun run =
        runCli({"bench", "levels", dir / "n.btflut", "--level", "3", "--frames", "1", "--repeat", "1", "--json"});
    REQUIRE_MESSAGE(run.status == 0, run.err);
    const nlohmann::json out = nlohmann::json::parse(run.out);
    CHECK(out["texels_whole"] == 128 * 128);
    CHECK(out["texels_level"] == 16 * 16);
    CHECK(out["emd_level_luts_max"].get<double>() <= 0.005);
    CHECK(out["emd_level_luts_mean"].get<double>() < out["emd_bank_luts_mean"].get<double>());
    CHECK(out["ms_level"].get<double>() > 0);
    CHECK(out["texels_region"] == 32 * 32);
    CHECK(out["ms_region"].get<double>() > 0);
    requireOneLineError(runCli({"bench", "levels", dir / "n.btflut", "--level", "8"}), "levels 0 to 7");
    REQUIRE(runCli({"bake", dir / "set", "--references", "1", "-o", dir / "r.btflut", "-q"}).status == 0);
    requireOneLineError(runCli({"bench", "levels", dir / "r.btflut"}), "not relit by level");
}

TEST_CASE(
    "bench decoder: the plain shader of the network draws btflut's frame; ratios per fragment and in texture space") {
    TempDir dir;
    learnedSynthBank(dir, 40);
    CliRun run =
        runCli({"bench", "decoder", dir / "n.btflut", "--size", "96x64", "--frames", "1", "--repeat", "1", "--json"});
    REQUIRE_MESSAGE(run.status == 0, run.err);
    const nlohmann::json out = nlohmann::json::parse(run.out);
    CHECK(out["decoder"] == "neural5");
    CHECK(out["multiply_adds_per_texel"] == 5 * 1 + 5 * 24 + 24 * 24 + 24 * 1);
    // The reference computes what btflut's decoder computes: their frames within a code.
    CHECK(out["plain_against_btflut_max_codes"].get<double>() <= 1);
    CHECK(out["btflut_over_plain_throughput_per_fragment"].get<double>() > 0);
    CHECK(out["btflut_over_plain_throughput_texture_space"].get<double>() > 0);
    // Half floats: within the 1/255 contract, and computed (not float's exact figures).
    CHECK(out["half_precision"]["max_codes"].get<double>() > 0);
    CHECK(out["half_precision"]["p99_codes"].get<double>() <= 1);
    CHECK(out["half_precision"]["share_over_one_code"].get<double>() < 0.001);
    for (const char* row : {"plain, per fragment", "btflut, per fragment", "btflut matched, scene per fragment",
                            "plain, texture space", "btflut, texture space", "btflut matched, texture space"})
        CHECK(out["ms_per_mpx"][row].get<double>() > 0);
    // Banks without a learned decoder, and bad sizes, in one line.
    REQUIRE(runCli({"bake", dir / "set", "--references", "1", "-o", dir / "r.btflut", "-q"}).status == 0);
    requireOneLineError(runCli({"bench", "decoder", dir / "r.btflut"}), "not a learned bank");
    requireOneLineError(runCli({"bench", "decoder", dir / "n.btflut", "--size", "0x5"}), "--size '0x5'");
}

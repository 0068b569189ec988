// GL tests (suite "gl") of banks that blend references and match regions: the native
// renderer and the scene renderer against the Relighter, their CPU twin.
#include <doctest/doctest.h>

#include <cmath>

#include "core/bank_file.h"
#include "core/relighter.h"
#include "gl/context.h"
#include "gl/native_renderer.h"
#include "gl/scene_renderer.h"
#include "helpers.h"

using namespace btflut;
using namespace btflut::test;

namespace {

// A small rendered material under 9 lights, tinted to colour.
std::string colourMaterial(const TempDir& dir) {
    REQUIRE(runCli({"synth", "--preset", "plastic", "--geometry", "rti-9", "--size", "40", "--correlation-length", "5",
                    "--albedo-variation", "0.5", "-q", "-o", dir / "m"})
                .status == 0);
    for (const auto& entry : fs::directory_iterator(dir / "m")) {
        if (entry.path().extension() != ".png" || entry.path().filename() == "mask.png") continue;
        Result<Image> grey = loadImage(entry.path().string());
        REQUIRE(grey.ok());
        Image rgb(grey->width, grey->height, 3);
        for (std::size_t i = 0; i < grey->pixelCount(); ++i)
            for (int c = 0; c < 3; ++c) rgb.samples[i * 3 + c] = std::round(grey->samples[i] * (1.f - 0.2f * c) * 255.f) / 255.f;
        REQUIRE(savePng(rgb, entry.path().string()).ok());
    }
    return dir / "m";
}

double worstDifference(const Image& a, const Image& b) {
    REQUIRE(a.samples.size() == b.samples.size());
    double worst = 0;
    for (std::size_t i = 0; i < a.samples.size(); ++i) worst = std::max(worst, static_cast<double>(std::abs(a.samples[i] - b.samples[i])));
    return worst;
}

const std::vector<BakeOptions> kSettings{
    {.references = 3},
    {.colour = ColourMode::Rgb, .references = 3, .regions = 2},
    {.colour = ColourMode::Lrgb, .references = 5, .regions = 2},
    {.ptmPredictor = true, .regions = 2},
};

}  // namespace

TEST_SUITE("gl") {
    TEST_CASE("render --native of banks that blend references equals their relighting (within 1/255)") {
        TempDir dir;
        auto dataset = openDataset(colourMaterial(dir));
        REQUIRE(dataset.ok());
        auto context = createHeadlessContext(GlBackend::Auto);
        if (!context.ok()) FAIL(context.error());
        for (const BakeOptions& options : kSettings) {
            auto bank = bakeBank(*dataset, options);
            REQUIRE(bank.ok());
            const Relighter relighter(*bank);
            for (Direction light : {Direction::fromDegrees(20, 30), Direction::fromDegrees(50, 200), dataset->images[3].light})
                for (bool dither : {false, true}) {
                    auto gpu = renderNative(*bank, light, {}, dither);
                    if (!gpu.ok()) FAIL(gpu.error());
                    const double d = worstDifference(*gpu, relighter.apply(relighter.frame(light), dither));
                    INFO(colourName(options.colour) << " K" << options.references << " R" << options.regions << " ptm "
                                                    << options.ptmPredictor << " dither " << dither << ": " << d * 255 << "/255");
                    CHECK(d <= 1.0 / 255 + 1e-6);
                }
        }
    }

    TEST_CASE("the scene renderer draws banks that blend references as the Relighter does, uploading them only for lut") {
        TempDir dir;
        auto dataset = openDataset(colourMaterial(dir));
        REQUIRE(dataset.ok());
        auto context = createHeadlessContext(GlBackend::Auto);
        if (!context.ok()) FAIL(context.error());
        for (const BakeOptions& options : kSettings) {
            auto bank = bakeBank(*dataset, options);
            REQUIRE(bank.ok());
            REQUIRE(saveBank(*bank, dir / "b.btflut").ok());
            // A frontal quad filling the image texel for texel.
            Scene s;
            s.file = "frontal";
            s.width = s.height = 40;
            s.fovDegrees = 45;
            s.eye = {0, 0, 1 / std::tan(45.0 / 2 * M_PI / 180)};
            s.up = {0, 1, 0};
            s.materials["m"] = {dir / "b.btflut", ""};
            s.quads = {{"m", {0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 2, 2, 1, RenderMode::Lut}};
            auto renderer = SceneRenderer::create(s);
            REQUIRE(renderer.ok());
            const Direction light = Direction::fromDegrees(35, 100);
            REQUIRE((*renderer)->draw(toVector(light), RenderMode::Flat).ok());
            CHECK((*renderer)->stats().textureBytes.blend == 0);  // flat needs the reference only
            REQUIRE((*renderer)->draw(toVector(light)).ok());
            CHECK((*renderer)->stats().textureBytes.blend > 0);
            const Image gpu = (*renderer)->readBack();
            const Relighter relighter(*bank);
            const Image cpu = relighter.apply(relighter.frame(light), false);  // scenes apply the plain LUT
            const Image cpuRgb = cpu.channels == 3 ? cpu : [&] {
                Image rgb(cpu.width, cpu.height, 3);
                for (std::size_t i = 0; i < cpu.pixelCount(); ++i) rgb.samples[i * 3] = rgb.samples[i * 3 + 1] = rgb.samples[i * 3 + 2] = cpu.samples[i];
                return rgb;
            }();
            double mean = 0;
            for (std::size_t i = 0; i < gpu.samples.size(); ++i) mean += std::abs(gpu.samples[i] - cpuRgb.samples[i]);
            mean /= static_cast<double>(gpu.samples.size());
            INFO(colourName(options.colour) << " K" << options.references << " R" << options.regions << " ptm " << options.ptmPredictor
                                            << ": worst " << worstDifference(gpu, cpuRgb) * 255 << "/255, mean " << mean * 255);
            // 8-bit framebuffer rounding, and filtered fetches at texel centres.
            CHECK(worstDifference(gpu, cpuRgb) <= 1.5 / 255);
            CHECK(mean <= 0.6 / 255);
        }
    }
}

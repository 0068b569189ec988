// GL tests (suite "gl") of banks that blend references and match regions: the native
// renderer and the scene renderer against the Relighter, their CPU twin.
#include <doctest/doctest.h>

#include <cmath>
#include <tuple>

#include "core/bake/bake.h"
#include "core/bank/bank_file.h"
#include "core/predict/learned_predictor.h"
#include "core/predict/model_predictor.h"
#include "core/relight/relighter.h"
#include "gl/context.h"
#include "gl/native_renderer.h"
#include "gl/scene_renderer.h"
#include "gl/shape_renderer.h"
#include "gl/textures.h"
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
            for (int c = 0; c < 3; ++c)
                rgb.samples[i * 3 + c] = std::round(grey->samples[i] * (1.f - 0.2f * c) * 255.f) / 255.f;
        REQUIRE(savePng(rgb, entry.path().string()).ok());
    }
    return dir / "m";
}

// A grey image as RGB (its value in the three channels), as the framebuffer reads it back.
Image asRgb(const Image& image) {
    if (image.channels == 3) return image;
    Image rgb(image.width, image.height, 3);
    for (std::size_t i = 0; i < image.pixelCount(); ++i)
        rgb.samples[i * 3] = rgb.samples[i * 3 + 1] = rgb.samples[i * 3 + 2] = image.samples[i];
    return rgb;
}

double worstDifference(const Image& a, const Image& b) {
    REQUIRE(a.samples.size() == b.samples.size());
    double worst = 0;
    for (std::size_t i = 0; i < a.samples.size(); ++i)
        worst = std::max(worst, static_cast<double>(std::abs(a.samples[i] - b.samples[i])));
    return worst;
}

// The banks of each kind, baked from one material (and from a grey one: references of one
// channel; light models of one output channel, no albedo).
std::vector<std::pair<std::string, LutBank>> blendingBanks(const TempDir& dir) {
    auto dataset = openDataset(colourMaterial(dir));
    REQUIRE(dataset.ok());
    REQUIRE(runCli({"synth", "--preset", "concrete", "--geometry", "rti-9", "--size", "40", "--correlation-length", "5",
                    "-q", "-o", dir / "grey"})
                .status == 0);
    auto grey = openDataset(dir / "grey");
    REQUIRE(grey.ok());
    using Basis = LightBasis;
    using Target = LutBank::Prediction::Target;
    std::vector<std::pair<std::string, LutBank>> banks;
    for (const auto& [name, options, greyImages] :
         {std::tuple{"grey K3", BakeOptions{.references = 3}, false},
          {"rgb K3 R2", BakeOptions{.colour = ColourMode::Rgb, .references = 3, .regions = 2}, false},
          {"grey images K4 R2", BakeOptions{.references = 4, .regions = 2}, true},  // one channel per reference
          {"lrgb K5 R2", BakeOptions{.colour = ColourMode::Lrgb, .references = 5, .regions = 2}, false},
          {"ptm R2", BakeOptions{.fit = lightModelFit(LightModelOptions{.basis = Basis::Ptm}), .regions = 2}, false},
          {"hsh3 rgb",
           BakeOptions{.colour = ColourMode::Rgb,
           .fit = lightModelFit(LightModelOptions{.basis = Basis::Hsh, .order = 3})},
           false},
          {"rbf5 match 0.5",
           BakeOptions{.fit = lightModelFit(LightModelOptions{.basis = Basis::Rbf, .planes = 5}), .match = 0.5f},
           false},
          {"bln4 corrections R2",
           BakeOptions{.fit = lightModelFit(LightModelOptions{.basis = Basis::Bilinear, .planes = 4}),
           .target = Target::Corrections,
           .regions = 2},
           false},
          {"grey images hsh2", BakeOptions{.fit = lightModelFit(LightModelOptions{.basis = Basis::Hsh, .order = 2})},
           true},
          {"grey images rbf7", BakeOptions{.fit = lightModelFit(LightModelOptions{.basis = Basis::Rbf, .planes = 7})},
           true},
          {"bln5c (4-bit planes)",
           BakeOptions{.fit = lightModelFit(LightModelOptions{.basis = Basis::Bilinear, .planes = 5, .packed = true})},
           false},
          {"grey images rbf4c",
           BakeOptions{.fit = lightModelFit(LightModelOptions{.basis = Basis::Rbf, .planes = 4, .packed = true})},
           true}}) {
        auto bank = bakeBank(greyImages ? *grey : *dataset, options);
        REQUIRE_MESSAGE(bank.ok(), name << ": " << bank.error());
        banks.emplace_back(name, std::move(*bank));
    }
    // Learned models: trained (a residual network) on 25 lights, and under 16 lights only
    // their linear start (the residual zero).
    REQUIRE(runCli({"synth", "--preset", "concrete", "--geometry", "rti-25", "--size", "40", "--correlation-length",
                    "5", "-q", "-o", dir / "grey25"})
                .status == 0);
    auto grey25 = openDataset(dir / "grey25");
    REQUIRE(grey25.ok());
    const LearnedOptions learned{.codes = 5, .steps = 300};
    for (const auto& [name, options, set] :
         {std::tuple{"neural5 trained", BakeOptions{.fit = learnedFit(learned)}, &*grey25},
          {"neural5 rgb R2", BakeOptions{.colour = ColourMode::Rgb, .fit = learnedFit(learned), .regions = 2},
           &*dataset},
          {"neural5 grey of rgb", BakeOptions{.fit = learnedFit(learned)}, &*dataset}}) {
        auto bank = bakeBank(*set, options);
        REQUIRE_MESSAGE(bank.ok(), name << ": " << bank.error());
        banks.emplace_back(name, std::move(*bank));
    }
    return banks;
}

}  // namespace

TEST_SUITE("gl") {
    TEST_CASE("render --native of banks that blend references equals their relighting (within 1/255)") {
        TempDir dir;
        auto context = createHeadlessContext(GlBackend::Auto);
        if (!context.ok()) FAIL(context.error());
        for (const auto& [name, bank] : blendingBanks(dir)) {
            const Relighter relighter(bank);
            for (Direction light :
                 {Direction::fromDegrees(20, 30), Direction::fromDegrees(50, 200), bank.layers[0].nodes[3].light})
                for (bool dither : {false, true}) {
                    auto gpu = renderNative(bank, light, {}, dither);
                    if (!gpu.ok()) FAIL(gpu.error());
                    const double d = worstDifference(*gpu, relighter.apply(relighter.frame(light), dither));
                    INFO(name << " dither " << dither << ": " << d * 255 << "/255");
                    CHECK(d <= 1.0 / 255 + 1e-6);
                }
        }
    }

    TEST_CASE(
        "the scene renderer draws banks that blend references as the Relighter does, uploading them only for lut") {
        TempDir dir;
        auto context = createHeadlessContext(GlBackend::Auto);
        if (!context.ok()) FAIL(context.error());
        struct Way {
            const char* name;
            bool exact;
            LutPath path;
        };
        // The match LUTs read from the baked grid (the default), in texture space and per
        // fragment, and made at the light ("interpolation": "exact").
        const Way ways[] = {{"grid, texture space", false, LutPath::TextureSpace},
                            {"grid, per fragment", false, LutPath::PerFragment},
                            {"exact", true, LutPath::Auto}};
        for (const auto& [name, bank] : blendingBanks(dir)) {
            REQUIRE(saveBank(bank, dir / "b.btflut").ok());
            const Relighter relighter(bank);
            const Direction light = Direction::fromDegrees(35, 100);
            for (const Way& way : ways) {
                Scene scene = frontalScene(dir / "b.btflut", "", 40, 40);
                scene.exactMatch = way.exact;
                auto renderer = SceneRenderer::create(scene, {.lutPath = way.path});
                REQUIRE(renderer.ok());
                // Read with its match grids, not its grid of quantile functions (no path reads it).
                CHECK_FALSE((*renderer)->bank("m")->layers[0].matchGridLuts.empty());
                CHECK((*renderer)->bank("m")->layers[0].gridLuts.empty());
                REQUIRE((*renderer)->draw(toVector(light), RenderMode::Flat).ok());
                CHECK((*renderer)->stats().textureBytes.prediction == 0);  // flat needs the reference only
                REQUIRE((*renderer)->draw(toVector(light)).ok());
                CHECK((*renderer)->stats().textureBytes.prediction > 0);
                CHECK((*renderer)->stats().quadsPerFragment == (way.path == LutPath::PerFragment ? 1u : 0u));
                const Image gpu = (*renderer)->readBack();
                // Relit in texture space, or per fragment at 1:1, dithered per texel.
                const Image cpuRgb =
                    asRgb(relighter.apply(way.exact ? relighter.frame(light) : relighter.gridFrame(light), true));
                double mean = 0;
                for (std::size_t i = 0; i < gpu.samples.size(); ++i)
                    mean += std::abs(gpu.samples[i] - cpuRgb.samples[i]);
                mean /= static_cast<double>(gpu.samples.size());
                INFO(name << ", " << way.name << ": worst " << worstDifference(gpu, cpuRgb) * 255 << "/255, mean "
                          << mean * 255);
                // 8-bit relit texture and framebuffer, filtered fetches at texel centres.
                CHECK(worstDifference(gpu, cpuRgb) <= 1.0 / 255);
                CHECK(mean <= 0.6 / 255);
            }
        }
    }
}

TEST_SUITE("gl") {
    TEST_CASE("the cylinder draws banks with a predictor: their prediction and match LUTs at each fragment's light") {
        TempDir dir;
        auto context = createHeadlessContext(GlBackend::Auto);
        if (!context.ok()) FAIL(context.error());
        // Every kind of bank with a predictor (the banks of LUTs: the viewer tests). Seen from
        // far along -y (almost orthographic), the cylinder's front line faces the camera:
        // there the tangent frame is x, z, -y, the texture column 0.25 of a turn (3 repeats of a
        // square texture around), its rows along z. A light from (0.3, -0.8, 0.5) is (0.3, 0.5,
        // 0.8) in that frame.
        const int size = 80;
        const double half = 1.05;
        ShapeFrame frame{
            Shape::Cylinder, {0, -200, 0}, {0, 0, 0}, {0, 0, 1}, 2 * std::atan(half / 200) * 180 / M_PI, {}};
        const Vec3 world{0.3, -0.8, 0.5};
        const double n = std::sqrt(0.98);
        frame.light.direction = {world.x / n, world.y / n, world.z / n};
        const Direction local = fromVector({0.3, 0.5, 0.8});
        for (const auto& [name, bank] : blendingBanks(dir)) {
            REQUIRE(saveBank(bank, dir / "s.btflut").ok());
            auto shape = ShapeRenderer::create(dir / "s.btflut");
            if (!shape.ok()) FAIL(name << ": " << shape.error());
            REQUIRE((*shape)->draw(frame, size, size).ok());
            const Image gpu = readFramebufferRgb((*shape)->framebuffer(), size, size);
            const Relighter relighter(bank);
            auto errorAt = [&](Direction light) {
                const Image rgb = asRgb(relighter.apply(relighter.gridFrame(light), false));
                double sum = 0;
                int count = 0;
                for (int y = 0; y < size; ++y) {
                    const double z = half - (y + 0.5) * 2 * half / size;
                    if (std::abs(z) > 0.9) continue;
                    const double px =
                        (size / 2 + 0.5) * 2 * half / size - half;  // the pixel column right of the centre
                    const double tx = (0.75 + std::asin(px) / (2 * M_PI)) * 3 * rgb.width,
                                 ty = (1 - z) / 2 * rgb.height;
                    for (int c = 0; c < 3; ++c) {
                        // The relit image sampled bilinearly where the fragment samples the planes.
                        const double fx = std::fmod(tx - 0.5 + rgb.width, rgb.width),
                                     fy = std::clamp(ty - 0.5, 0.0, rgb.height - 1.0);
                        const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
                        const int x1 = (x0 + 1) % rgb.width, y1 = std::min(y0 + 1, rgb.height - 1);
                        const double ax = fx - x0, ay = fy - y0;
                        const double v = (1 - ay) * ((1 - ax) * rgb.at(x0, y0, c) + ax * rgb.at(x1, y0, c)) +
                                         ay * ((1 - ax) * rgb.at(x0, y1, c) + ax * rgb.at(x1, y1, c));
                        sum += std::abs(v - gpu.at(size / 2, y, c));
                        ++count;
                    }
                }
                return sum / count;
            };
            const double right = errorAt(local), wrong = errorAt(Direction::fromDegrees(60, 200));
            MESSAGE(name << ": mean " << right * 255 << "/255 against the relit column; " << wrong * 255
                         << "/255 under another light");
            // 0.4-2.1: bilinear before the LUT against after, the weights' grid (barycentric
            // weights have kinks it smooths), region labels per texel, the dither per pixel.
            CHECK(right < 3.0 / 255);
            CHECK(wrong > 10 * right);
            // A point light far along the same direction lights it alike (its direction per fragment).
            ShapeFrame point = frame;
            point.light = {
                true,
                {},
                {1e4 * frame.light.direction.x, 1e4 * frame.light.direction.y, 1e4 * frame.light.direction.z}};
            REQUIRE((*shape)->draw(point, size, size).ok());
            const Image far = readFramebufferRgb((*shape)->framebuffer(), size, size);
            double mean = 0;
            for (std::size_t i = 0; i < far.samples.size(); ++i) mean += std::abs(far.samples[i] - gpu.samples[i]);
            CHECK(mean / static_cast<double>(far.samples.size()) < 0.5 / 255);
        }
    }
}

TEST_SUITE("gl") {
    TEST_CASE("the sphere wraps the mask's largest rectangle: no background is tiled over it") {
        TempDir dir;
        auto context = createHeadlessContext(GlBackend::Auto);
        if (!context.ok()) FAIL(context.error());
        // A relief with a black border of 6 texels outside its mask. Seen from far along +x, the
        // sphere's front is the texture's seam (u = 0, its first and last columns): the whole
        // image would show the border there, the mask's rectangle (mirrored) shows the relief.
        const Relief relief{.size = 32, .border = 6};
        Result<Dataset> dataset = openDataset(writeRelief(dir, relief, dome(24, 70)));
        REQUIRE(dataset.ok());
        Result<LutBank> bank = bakeBank(
            *dataset, {.threads = 1, .fit = lightModelFit(LightModelOptions{.basis = LightBasis::Hsh, .order = 2})});
        REQUIRE_MESSAGE(bank.ok(), bank.error());
        const std::optional<PixelRect> window = sampleWindow(*bank);
        REQUIRE(window);
        CHECK(*window == PixelRect{6, 6, 20, 20});
        REQUIRE(saveBank(*bank, dir / "m.btflut").ok());
        auto shape = ShapeRenderer::create(dir / "m.btflut");
        REQUIRE_MESSAGE(shape.ok(), shape.error());
        const int size = 64;
        ShapeFrame frame{Shape::Sphere, {200, 0, 0}, {0, 0, 0}, {0, 0, 1}, 2 * std::atan(1.05 / 200) * 180 / M_PI, {}};
        frame.light.direction = {1, 0, 0};
        REQUIRE((*shape)->draw(frame, size, size).ok());
        const Image gpu = readFramebufferRgb((*shape)->framebuffer(), size, size);
        // The relit border (black texels, matched to the sample's histogram) is darker than any
        // of the relief's texels.
        const Relighter relighter(*bank);
        const Image relit = relighter.apply(relighter.gridFrame(Direction::fromDegrees(0, 0)), false);
        const float border = relit.at(0, 0, 0);
        float darkest = 1;
        for (int y = 6; y < 26; ++y)
            for (int x = 6; x < 26; ++x) darkest = std::min(darkest, relit.at(x, y, 0));
        INFO("the relit border " << border << ", the relief's darkest texel " << darkest);
        REQUIRE(darkest > border + 0.008f);
        // Within 0.3 radii of the centre: none of the border's value (the window's edge texels are
        // sampled at their centres, never blended with the border outside).
        int inside = 0, background = 0;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const double px = (x + 0.5 - size / 2.0) / (size / 2.0) * 1.05,
                             py = (y + 0.5 - size / 2.0) / (size / 2.0) * 1.05;
                if (px * px + py * py > 0.3 * 0.3) continue;
                ++inside;
                background += std::abs(gpu.at(x, y, 0) - border) < 0.006f;
            }
        INFO(background << " of " << inside << " pixels at the sphere's front show the border");
        CHECK(inside > 100);
        CHECK(background == 0);
    }
}

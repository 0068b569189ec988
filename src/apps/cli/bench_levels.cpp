// btflut bench levels: a predictor bank's texture relit whole and mipmapped, against its mip
// level m relit alone (issue 46: a quad minified 2^m times reads level m, which 1/4^m of the
// texels make), side by side in one context: the time of each, and how far level m's histogram
// lies from the whole relight's level m (EMD), with the level's own LUTs (LevelMatch) and with
// the bank's. Also the region a quad zoomed in 4 times shows (the middle 1/16 of level 0, its
// mipmaps made from the whole level as the scene renderer does). Ratios and distances, never
// pass/fail.
#include <chrono>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "cli/bench_timing.h"
#include "cli/cli.h"
#include "cli/command.h"
#include "core/bank/bank_file.h"
#include "core/histogram/histogram.h"
#include "core/io/json_text.h"
#include "core/relight/level_match.h"
#include "gl/context.h"
#include "gl/prediction_textures.h"
#include "gl/relight_pass.h"
#include "gl/textures.h"

namespace btflut::cli {

namespace {

struct BenchLevelsOptions {
    std::string bank;
    int level = 3;
    GlBenchOptions timing;
};

// A texture level's grey values (one channel: its own; RGB: their mean).
std::vector<double> levelGreys(GLuint texture, int level, int width, int height, bool grey) {
    GlFramebuffer framebuffer = makeFramebuffer();
    gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture, level);
    const Image image = readFramebufferRgb(framebuffer.id(), width, height);
    std::vector<double> greys(image.pixelCount());
    for (std::size_t i = 0; i < greys.size(); ++i) {
        const float* p = &image.samples[i * 3];
        greys[i] = grey ? p[0] : (p[0] + p[1] + p[2]) / 3.0;
    }
    return greys;
}

std::vector<double> histogramOf(const std::vector<double>& values) {
    constexpr int kBins = 256;
    std::vector<double> bins(kBins, 0.0);
    for (double v : values)
        bins[static_cast<std::size_t>(std::clamp(v, 0.0, 1.0) * (kBins - 1) + 0.5)] +=
            1.0 / static_cast<double>(values.size());
    return bins;
}

// What level `level` of an image is, exactly: each texel its square's mean (no rounding; a
// driver's GenerateMipmap rounds each level to 8 bits, llvmpipe's down).
std::vector<double> boxFiltered(const std::vector<double>& image, int width, int height, int level) {
    std::vector<double> out(static_cast<std::size_t>(levelSize(width, level)) *
                            static_cast<std::size_t>(levelSize(height, level)));
    for (std::size_t t = 0; t < out.size(); ++t) {
        const std::vector<std::uint32_t> block = levelBlock(level, width, height, static_cast<std::uint32_t>(t));
        for (std::uint32_t b : block) out[t] += image[b] / static_cast<double>(block.size());
    }
    return out;
}

// A relight timed: `draw` relights, `ms` its wall times.
struct TimedRow {
    std::string name;
    std::function<Status()> draw;
    std::vector<double> ms;
};

// Each row's wall ms per relight, `repeat` rounds of `frames`, interleaved so that drift hits
// every row alike.
Status timeRows(std::vector<TimedRow>& rows, const GlBenchOptions& timing) {
    for (int r = 0; r < timing.repeat; ++r)
        for (TimedRow& row : rows) {
            gl.Finish();
            Result<DrawTimes> t = timeDraws(timing.frames, false, row.draw);
            if (!t) return Error{t.error()};
            row.ms.push_back(t->wall * 1e3);
        }
    return success();
}

// The figures of `out` (runBenchLevels' JSON) as text.
void printLevels(const BenchLevelsOptions& o, const nlohmann::json& out, std::size_t lights) {
    const int m = out["level"], width = out["width"], height = out["height"];
    const double wholeMs = out["ms_whole"], levelMs = out["ms_level"], regionMs = out["ms_region"],
                 firstMs = out["ms_first_level_luts"];
    const std::size_t texels = out["texels_whole"], levelTexels = out["texels_level"];
    const unsigned long long regionTexels = out["texels_region"];
    const double matchedSum = out["emd_level_luts_mean"], matchedMax = out["emd_level_luts_max"],
                 plainSum = out["emd_bank_luts_mean"], plainMax = out["emd_bank_luts_max"];
    const std::string predictor = out["predictor"], context = out["context"];
    std::printf("levels of %s (%s, %dx%d), %s; wall ms, median of %d rounds of %d relights\n", o.bank.c_str(),
                predictor.c_str(), width, height, context.c_str(), o.timing.repeat, o.timing.frames);
    std::printf("  relit whole, then mipmapped:      %8.3f ms (%zu texels)\n", wholeMs, texels);
    std::printf("  level %d relit alone, mipmapped:   %8.3f ms (%zu texels): %.1f times faster\n", m, levelMs,
                levelTexels, wholeMs / levelMs);
    std::printf("  its middle 1/16 relit, mipmapped: %8.3f ms (%llu texels): %.1f times faster\n", regionMs,
                regionTexels, wholeMs / regionMs);
    std::printf("  a light's first level-%d LUTs: %.1f ms on the CPU (its grid nodes', made once each)\n", m, firstMs);
    std::printf(
        "  level %d's grey histogram against the whole relight's level %d (EMD, mean / max of %zu lights):\n"
        "    with the level's LUTs %.4f / %.4f; with the bank's LUTs %.4f / %.4f\n",
        m, m, lights, matchedSum, matchedMax, plainSum, plainMax);
}

Status runBenchLevels(const BenchLevelsOptions& o) {
    Result<GlBackend> backend = parseGlBackend(o.timing.backend);
    if (!backend) return Error{backend.error()};
    Result<std::unique_ptr<HeadlessContext>> context = createHeadlessContext(*backend);
    if (!context) return Error{context.error()};
    Result<LutBank> loaded = loadBank(o.bank, {.ptm = false});
    if (!loaded) return Error{loaded.error()};
    const LutBank& bank = *loaded;
    if (!LevelMatch::supports(bank))
        return Error{o.bank +
                     ": not relit by level (a bank with a predictor, one view layer, one region and a match grid)"};
    const LevelMatch levels(bank);
    if (o.level >= levels.levels())
        return Error{"--level " + std::to_string(o.level) + ": " + o.bank + "'s reference has levels 0 to " +
                     std::to_string(levels.levels() - 1)};
    const int m = o.level, width = bank.reference.width, height = bank.reference.height;
    const int levelWidth = levelSize(width, m), levelHeight = levelSize(height, m);
    const bool grey = bank.reference.channels == 1;
    GLint timerBits = 0;
    gl.GetQueryiv(GL_TIME_ELAPSED, GL_QUERY_COUNTER_BITS, &timerBits);

    std::size_t bytes = 0;
    const PredictionTextures planes = PredictionTextures::upload(bank, bytes);
    RelightPass pass(bank, 0, &planes);
    const std::vector<GlTexture> luts = pass.makeLuts();
    const Relighter relighter(bank);
    GlTexture whole = allocateRelitTexture(bank.reference), level = allocateRelitTexture(bank.reference),
              plain = allocateRelitTexture(bank.reference);
    auto relight = [&](GLuint texture, const RelightFrame& frame, int at,
                       const std::optional<TexelRegion>& region = {}) -> Status {
        if (Status s = pass.run(frame, luts, texture, true, at, region); !s) return s;
        gl.BindTexture(GL_TEXTURE_2D, texture);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, at);
        gl.GenerateMipmap(GL_TEXTURE_2D);
        return success();
    };

    // Accuracy at lights between the grid's nodes, and the time a light's first level LUTs take.
    const std::vector<Direction> lights{Direction::fromDegrees(20, 30), Direction::fromDegrees(35, 110),
                                        Direction::fromDegrees(45, 250), Direction::fromDegrees(60, 170),
                                        Direction::fromDegrees(70, 320)};
    double matchedSum = 0, plainSum = 0, matchedMax = 0, plainMax = 0, firstMs = 0;
    nlohmann::json perLight = nlohmann::json::array();
    for (const Direction& light : lights) {
        const RelightFrame frame = relighter.gridFrame(light);
        RelightFrame levelFrame = frame;
        const auto start = std::chrono::steady_clock::now();
        levelFrame.luts = levels.luts(light, m);
        firstMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() /
                   static_cast<double>(lights.size());
        if (Status s = relight(whole.id(), frame, 0); !s) return s;
        if (Status s = relight(level.id(), levelFrame, m); !s) return s;
        if (Status s = relight(plain.id(), frame, m); !s) return s;
        const std::vector<double> truth =
            histogramOf(boxFiltered(levelGreys(whole.id(), 0, width, height, grey), width, height, m));
        const double matched = earthMoversDistance(
                         histogramOf(levelGreys(level.id(), m, levelWidth, levelHeight, grey)), truth),
                     plainEmd = earthMoversDistance(
                         histogramOf(levelGreys(plain.id(), m, levelWidth, levelHeight, grey)), truth);
        matchedSum += matched / static_cast<double>(lights.size());
        plainSum += plainEmd / static_cast<double>(lights.size());
        matchedMax = std::max(matchedMax, matched);
        plainMax = std::max(plainMax, plainEmd);
        perLight.push_back({{"theta", light.thetaDegrees()},
                            {"phi", light.phiDegrees()},
                            {"emd_level_luts", matched},
                            {"emd_bank_luts", plainEmd}});
    }

    // Time: each light change relights (the level's LUTs made before the clock starts).
    const RelightFrame frame = relighter.gridFrame(lights[2]);
    const TexelRegion middle =
        TexelRegion::span(width * 3 / 8, width * 5 / 8, height * 3 / 8, height * 5 / 8, width, height);
    RelightFrame levelFrame = frame;
    levelFrame.luts = levels.luts(lights[2], m);
    std::vector<TimedRow> rows{
        {"whole, mipmapped", [&] { return relight(whole.id(), frame, 0); }, {}},
        {"level " + std::to_string(m) + " alone, mipmapped", [&] { return relight(level.id(), levelFrame, m); }, {}},
        {"the middle 1/16, mipmapped", [&] { return relight(plain.id(), frame, 0, middle); }, {}}};
    if (Status timed = timeRows(rows, o.timing); !timed) return timed;
    if (GLenum error = gl.GetError(); error != GL_NO_ERROR)
        return Error{"OpenGL error " + std::to_string(error) + " in bench levels"};
    const double wholeMs = median(rows[0].ms), levelMs = median(rows[1].ms), regionMs = median(rows[2].ms);
    const std::size_t texels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height),
                      levelTexels = static_cast<std::size_t>(levelWidth) * static_cast<std::size_t>(levelHeight);
    nlohmann::json out{{"context", (*context)->description()},
                       {"bank", o.bank},
                       {"predictor", bank.predictorName()},
                       {"level", m},
                       {"width", width},
                       {"height", height},
                       {"texels_whole", texels},
                       {"texels_level", levelTexels},
                       {"ms_whole", wholeMs},
                       {"ms_level", levelMs},
                       {"whole_over_level_time", wholeMs / levelMs},
                       {"texels_region", middle.texels()},
                       {"ms_region", regionMs},
                       {"whole_over_region_time", wholeMs / regionMs},
                       {"ms_first_level_luts", firstMs},
                       {"emd_level_luts_mean", matchedSum},
                       {"emd_level_luts_max", matchedMax},
                       {"emd_bank_luts_mean", plainSum},
                       {"emd_bank_luts_max", plainMax},
                       {"lights", perLight}};
    if (o.timing.json) {
        std::cout << jsonText(out);
        return success();
    }
    printLevels(o, out, lights.size());
    return success();
}

}  // namespace

void addBenchLevelsCommand(CLI::App& bench, Commands& commands) {
    auto o = std::make_shared<BenchLevelsOptions>();
    CLI::App* levels = bench.add_subcommand(
        "levels",
        "A predictor bank's texture relit whole and mipmapped against one mip level relit alone (what a quad "
        "minified 2^LEVEL times reads): the time of each, and the level's histogram distance (EMD) from the "
        "whole relight's level, with the level's own LUTs and with the bank's");
    levels->add_option("BANK", o->bank, "M.btflut with a predictor (bake's default, or --predictor)")->required();
    levels->add_option("--level", o->level, "the mip level")->check(CLI::Range(1, 15))->capture_default_str();
    addGlBenchOptions(*levels, o->timing, "relights");
    commands.push_back({levels, [o] { return runBenchLevels(*o); }});
}

}  // namespace btflut::cli

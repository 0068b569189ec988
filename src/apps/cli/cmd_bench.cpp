// btflut bench: timings that print ratios measured side by side, never pass/fail.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/command.h"
#include "cli/model_options.h"
#include "core/bake/bake.h"
#include "core/bank/lut_bank.h"
#include "core/check.h"
#include "core/histogram/histogram.h"
#include "core/io/json_text.h"
#include "core/learn/network.h"
#include "core/physics/geometry.h"
#include "core/physics/simulate.h"
#include "core/synth/render.h"
#include "gl/context.h"
#include "gl/objects.h"
#include "gl/scene_renderer.h"

namespace btflut::cli {

namespace {

struct BenchBakeOptions {
    std::string dataset;
    int repeat = 7;
    int threads = 0;
    bool json = false;
};

// The bake without decoding: images are decoded once up front and handed to bakeBank.
Status runBenchBake(const BenchBakeOptions& o) {
    Result<Dataset> dataset = openDatasetWithMask(o.dataset, {});
    if (!dataset) return Error{dataset.error()};
    std::vector<Image> images;
    std::size_t pixels = 0;
    for (const DatasetImage& info : dataset->images) {
        Result<Image> image = loadImage(info.path);
        if (!image) return Error{image.error()};
        pixels += image->pixelCount();
        images.push_back(std::move(*image));
    }
    ImageProvider preloaded = [&](std::size_t i, Image&) -> Result<const Image*> { return &images[i]; };
    auto timeBake = [&](int threads) -> Result<double> {
        BakeOptions options;
        options.threads = threads;
        auto start = std::chrono::steady_clock::now();
        Result<LutBank> bank = bakeBank(*dataset, options, preloaded);
        if (!bank) return Error{bank.error()};
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    std::vector<double> all, one;
    for (int r = 0; r < o.repeat; ++r) {  // interleaved, so drift hits both alike
        Result<double> a = timeBake(o.threads);
        if (!a) return Error{a.error()};
        Result<double> b = timeBake(1);
        if (!b) return Error{b.error()};
        all.push_back(*a);
        one.push_back(*b);
    }
    nlohmann::json out{
        {"dataset", o.dataset}, {"images", images.size()},       {"pixels", pixels},
        {"threads", o.threads}, {"seconds_median", median(all)}, {"seconds_median_1_thread", median(one)},
        {"seconds", all},       {"seconds_1_thread", one}};
    if (o.json) {
        std::cout << jsonText(out);
    } else {
        char text[512];
        std::snprintf(text, sizeof text,
                      "bake (histograms + LUTs + grid, decode excluded) of %zu images, %zu pixels\n"
                      "  all threads: %8.3f ms median of %d\n"
                      "  1 thread:    %8.3f ms median of %d\n"
                      "  throughput:  %.1f Mpixel/s (all threads)\n",
                      images.size(), pixels, median(all) * 1e3, o.repeat, median(one) * 1e3, o.repeat,
                      static_cast<double>(pixels) / median(all) * 1e-6);
        std::cout << text;
    }
    return success();
}

struct BenchSimulateOptions {
    ModelFlags model;
    int repeat = 3;
    bool json = false;
};

// Error (mean EMD over the 11 curet-c2 positions against the quadrature at 512 nodes)
// against time (one whole geometry, median of interleaved repeats).
Status runBenchSimulate(const BenchSimulateOptions& o) {
    Result<SurfaceModel> model = modelFromFlags(o.model);
    if (!model) return Error{model.error()};
    const std::vector<Geometry> geometry = curetC2();
    std::vector<std::vector<double>> reference;
    for (const Geometry& g : geometry)
        reference.push_back(
            simulateHistogram(*model, g.light, g.view, {.method = SimulationMethod::Quadrature, .nodes = 512}));
    struct Config {
        std::string label;
        SimulationOptions options;
        double error = 0;
        std::vector<double> seconds;
    };
    std::vector<Config> configs;
    for (std::uint64_t n : {1000ull, 10000ull, 50000ull, 100000ull, 1000000ull})
        configs.push_back({"mc " + std::to_string(n), {.method = SimulationMethod::Mc, .samples = n, .seed = 5}});
    configs.push_back(
        {"mc 50000 1 thread", {.method = SimulationMethod::Mc, .samples = 50000, .seed = 5, .threads = 1}});
    configs.push_back(
        {"mc 1000000 1 thread", {.method = SimulationMethod::Mc, .samples = 1000000, .seed = 5, .threads = 1}});
    for (int nodes : {4, 6, 8, 12, 16, 24, 32, 48, 64})
        configs.push_back(
            {"quadrature " + std::to_string(nodes), {.method = SimulationMethod::Quadrature, .nodes = nodes}});
    for (int r = 0; r < o.repeat; ++r)
        for (Config& c : configs) {
            auto start = std::chrono::steady_clock::now();
            double error = 0;
            for (std::size_t k = 0; k < geometry.size(); ++k) {
                auto h = simulateHistogram(*model, geometry[k].light, geometry[k].view, c.options);
                error += earthMoversDistance(h, reference[k]);
            }
            c.seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
            c.error = error / static_cast<double>(geometry.size());
        }
    auto find = [&](const std::string& label) -> const Config& {
        return *std::find_if(configs.begin(), configs.end(), [&](const Config& c) { return c.label == label; });
    };
    const Config& mc50k = find("mc 50000");
    double quadSeconds = std::numeric_limits<double>::infinity();
    std::string quadLabel = "none";
    for (const Config& c : configs)
        if (c.options.method == SimulationMethod::Quadrature && c.error <= mc50k.error &&
            median(c.seconds) < quadSeconds) {
            quadSeconds = median(c.seconds);
            quadLabel = c.label;
        }
    const double quadOverMc = quadSeconds / median(mc50k.seconds);
    const double speedup50k = median(find("mc 50000 1 thread").seconds) / median(mc50k.seconds);
    const double speedup1m = median(find("mc 1000000 1 thread").seconds) / median(find("mc 1000000").seconds);
    nlohmann::json out{{"model",
                        {{"roughness", model->roughness},
                         {"kd", model->brdf.kd},
                         {"ks", model->brdf.ks},
                         {"sigma", model->brdf.sigma},
                         {"ior", model->brdf.ior},
                         {"gain", model->gain}}},
                       {"geometry", "curet-c2"},
                       {"reference", "quadrature 512"},
                       {"quad_over_mc50k", quadOverMc},
                       {"quad_matching_mc50k", quadLabel},
                       {"mc_speedup_2_threads", speedup50k},
                       {"mc_speedup_2_threads_1e6", speedup1m},
                       {"configs", nlohmann::json::array()}};
    for (const Config& c : configs)
        out["configs"].push_back({{"label", c.label}, {"mean_emd", c.error}, {"seconds", median(c.seconds)}});
    if (o.json) {
        std::cout << jsonText(out);
        return success();
    }
    char line[200];
    std::cout << "simulate curet-c2 (11 positions), error = mean EMD against quadrature 512, time = median of "
              << o.repeat << "\n";
    std::snprintf(line, sizeof line, "  %-22s %12s %12s\n", "method", "mean EMD", "time ms");
    std::cout << line;
    for (const Config& c : configs) {
        std::snprintf(line, sizeof line, "  %-22s %12.3e %12.3f\n", c.label.c_str(), c.error, median(c.seconds) * 1e3);
        std::cout << line;
    }
    std::snprintf(line, sizeof line,
                  "quad_over_mc50k %.4f (%s reaches mc 50000's error; target <= 0.1)\n"
                  "mc_speedup_2_threads %.2f at 5e4 points, %.2f at 1e6 (target >= 1.8)\n",
                  quadOverMc, quadLabel.c_str(), speedup50k, speedup1m);
    std::cout << line;
    return success();
}

struct BenchSynthOptions {
    int size = 512;
    int samples = 2;
    int repeat = 3;
    bool json = false;
};

// One image of a Lambertian r 0.4 field with cast shadows (light 60 degrees, view 30 degrees
// from the other side), on one thread and on all, interleaved.
Status runBenchSynth(const BenchSynthOptions& o) {
    Result<HeightField> field =
        synthesizeHeightField({.size = o.size, .roughness = 0.4, .correlationLength = std::min(16.0, o.size / 4.0)});
    if (!field) return Error{field.error()};
    const SurfaceModel model{.roughness = 0.4};
    const Direction light = Direction::fromDegrees(60, 0), view = Direction::fromDegrees(30, 180);
    std::vector<double> one, all;
    for (int r = 0; r < o.repeat; ++r)
        for (int threads : {1, 0}) {
            auto start = std::chrono::steady_clock::now();
            Image image =
                renderHeightField(*field, model, light, view, {.samplesPerAxis = o.samples, .threads = threads});
            (threads == 1 ? one : all)
                .push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        }
    const double speedup = median(one) / median(all);
    nlohmann::json out{{"size", o.size},
                       {"rays_per_pixel", o.samples * o.samples},
                       {"seconds_1_thread", median(one)},
                       {"seconds", median(all)},
                       {"speedup_2_threads", speedup}};
    if (o.json) {
        std::cout << jsonText(out);
        return success();
    }
    char text[256];
    std::snprintf(text, sizeof text,
                  "synth render %dx%d, %d rays per pixel, cast shadows: %.3f s on 1 thread, %.3f s on all "
                  "cores (speed-up %.2f), medians of %d\n",
                  o.size, o.size, o.samples * o.samples, median(one), median(all), speedup, o.repeat);
    std::cout << text;
    return success();
}

struct BenchRenderOptions {
    std::string bank;
    int frames = 10;
    int repeat = 3;
    std::vector<std::string> sizes{"1024x1024", "1920x1080"};
    int overdraw = 1;
    std::string backend = "auto";
    std::string lutPath = "auto";
    bool json = false;
};

// The moving light: a new direction every frame (so no relit texture holds it), its elevation
// alternating between the two bench lights' and its azimuth sweeping between theirs.
Vec3 movingLight() {
    static int frame = 0;
    ++frame;
    return toVector(Direction::fromDegrees(frame % 2 ? 55 : 40, 252 + std::fmod(0.37 * frame, 46.0)));
}

// Frame times of one renderer: `frames` frames drawn back to back with no wait between them,
// then one glFinish; wall time per frame is the whole run's over the frames. GPU time per
// frame from GL_TIME_ELAPSED queries around each frame's draw calls, read after the finish
// (NaN where the driver has no timer).
struct FrameTimes {
    double wall = 0, gpu = 0;
};

Result<FrameTimes> timeFrames(SceneRenderer& renderer, RenderMode mode, bool moving, int frames, bool timer) {
    std::vector<GlQuery> queries;
    const auto start = std::chrono::steady_clock::now();
    for (int f = 0; f < frames; ++f) {
        if (timer) {
            queries.push_back(makeQuery());
            gl.BeginQuery(GL_TIME_ELAPSED, queries.back().id());
        }
        if (Status s = renderer.draw(moving ? movingLight() : benchLights()[0], mode); !s) return Error{s.error()};
        if (timer) gl.EndQuery(GL_TIME_ELAPSED);
    }
    renderer.finish();
    FrameTimes t;
    t.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / frames;
    t.gpu = std::numeric_limits<double>::quiet_NaN();
    if (timer) {
        GLuint64 total = 0;
        for (const GlQuery& q : queries) {
            GLuint64 ns = 0;
            gl.GetQueryObjectui64v(q.id(), GL_QUERY_RESULT, &ns);
            total += ns;
        }
        t.gpu = static_cast<double>(total) * 1e-9 / frames;
    }
    BTFLUT_CHECK(renderer.stats().quadsUnlit == 0);
    return t;
}

Status runBenchRender(const BenchRenderOptions& o) {
    Result<GlBackend> backend = parseGlBackend(o.backend);
    if (!backend) return Error{backend.error()};
    Result<std::unique_ptr<HeadlessContext>> context = createHeadlessContext(*backend);
    if (!context) return Error{context.error()};
    GLint timerBits = 0;
    gl.GetQueryiv(GL_TIME_ELAPSED, GL_QUERY_COUNTER_BITS, &timerBits);
    const bool timer = timerBits > 0;
    nlohmann::json out{{"context", (*context)->description()},
                       {"bank", o.bank},
                       {"frames", o.frames},
                       {"rounds", o.repeat},
                       {"overdraw", o.overdraw},
                       {"quads", 4 * o.overdraw},
                       {"gpu_timer", timer},
                       {"sizes", nlohmann::json::array()}};
    // Static: the light stays (lut relights nothing after the first frame). Moving: a new
    // direction every frame, so each frame relights or draws per fragment (lut), recomputes
    // the brightness (brdf) or the PTM weights (ptm).
    Result<LutPath> lutPath = o.lutPath == "auto"      ? Result<LutPath>(LutPath::Auto)
                              : o.lutPath == "texture" ? Result<LutPath>(LutPath::TextureSpace)
                              : o.lutPath == "fragment"
                                  ? Result<LutPath>(LutPath::PerFragment)
                                  : Result<LutPath>(Error{"--lut-path: expected auto, texture or fragment"});
    if (!lutPath) return Error{lutPath.error()};
    std::string text;
    bool first = true;
    for (const std::string& size : o.sizes) {
        Result<FrameSize> parsed = parseFrameSize(size);
        if (!parsed) return Error{parsed.error()};
        const int w = parsed->width, h = parsed->height;
        const Scene scene = benchScene(o.bank, w, h, {}, o.overdraw);
        Result<std::unique_ptr<SceneRenderer>> renderer = SceneRenderer::create(scene, {.lutPath = *lutPath});
        if (!renderer) return Error{renderer.error()};
        // The rows: the four modes, and for a bank with a predictor the predictor drawn per
        // fragment without its LUT (what an RTI viewer draws), by a renderer of its own.
        struct Row {
            std::string name;
            SceneRenderer* renderer;
            RenderMode mode;
        };
        std::vector<Row> rows{{"lut", renderer->get(), RenderMode::Lut},
                              {"flat", renderer->get(), RenderMode::Flat},
                              {"brdf", renderer->get(), RenderMode::Brdf},
                              {"ptm", renderer->get(), RenderMode::Ptm}};
        std::unique_ptr<SceneRenderer> predictor;
        if (const LutBank* bank = (*renderer)->bank("m"); bank && bank->makesLuts() && bank->layers.size() == 1) {
            Result<std::unique_ptr<SceneRenderer>> p =
                SceneRenderer::create(scene, {.lutPath = LutPath::PerFragment, .predictionOnly = true});
            if (!p) return Error{p.error()};
            predictor = std::move(*p);
            rows.push_back({"predictor", predictor.get(), RenderMode::Lut});
        }
        std::map<std::pair<std::string, bool>, std::vector<double>> wall, gpu;
        RenderStats movingLutStats;  // of the last moving lut frame
        for (const Row& row : rows)  // the first frames load and upload
            if (Status s = row.renderer->draw(benchLights()[0], row.mode); !s) return s;
        (*renderer)->finish();
        for (int r = 0; r < o.repeat; ++r)  // interleaved, so drift hits every mode alike
            for (bool moving : {false, true})
                for (const Row& row : rows) {
                    if (!moving) {  // the static run starts from its light, relit before the clock starts
                        if (Status s = row.renderer->draw(benchLights()[0], row.mode); !s) return s;
                        if (Status s = row.renderer->draw(benchLights()[0], row.mode); !s) return s;
                        row.renderer->finish();
                    }
                    Result<FrameTimes> t = timeFrames(*row.renderer, row.mode, moving, o.frames, timer);
                    if (!t) return Error{t.error()};
                    if (moving && row.name == "lut") movingLutStats = row.renderer->stats();
                    wall[{row.name, moving}].push_back(t->wall);
                    gpu[{row.name, moving}].push_back(t->gpu);
                }
        nlohmann::json entry{{"width", w}, {"height", h}};
        char line[320];
        std::snprintf(line, sizeof line, "  %dx%d, %d quads\n    %-9s %13s %13s %13s %13s\n", w, h, 4 * o.overdraw, "",
                      "static ms", "moving ms", "static GPU ms", "moving GPU ms");
        text += line;
        for (const Row& row : rows) {
            const double sw = median(wall[{row.name, false}]), mw = median(wall[{row.name, true}]);
            const double sg = timer ? median(gpu[{row.name, false}]) : NAN,
                         mg = timer ? median(gpu[{row.name, true}]) : NAN;
            entry[row.name + "_ms"] = mw * 1e3;
            entry[row.name + "_static_ms"] = sw * 1e3;
            if (timer) {
                entry[row.name + "_gpu_ms"] = mg * 1e3;
                entry[row.name + "_static_gpu_ms"] = sg * 1e3;
            }
            std::snprintf(line, sizeof line, "    %-9s %13.2f %13.2f %13.2f %13.2f\n", row.name.c_str(), sw * 1e3,
                          mw * 1e3, sg * 1e3, mg * 1e3);
            text += line;
        }
        auto ratio = [&](const char* a, const char* b, bool moving, bool onGpu) {
            auto& t = onGpu ? gpu : wall;
            return median(t[{a, moving}]) / median(t[{b, moving}]);
        };
        // lut_over_flat and lut_over_ptm: the light moving every frame (as before this split).
        entry["lut_over_flat"] = ratio("lut", "flat", true, false);
        entry["lut_over_ptm"] = ratio("lut", "ptm", true, false);
        entry["lut_over_brdf"] = ratio("lut", "brdf", true, false);
        entry["lut_over_flat_static"] = ratio("lut", "flat", false, false);
        entry["lut_over_ptm_static"] = ratio("lut", "ptm", false, false);
        if (predictor) {
            entry["lut_over_predictor_moving"] = ratio("lut", "predictor", true, false);
            entry["lut_over_predictor_static"] = ratio("lut", "predictor", false, false);
        }
        if (timer) {
            entry["gpu_lut_over_flat"] = ratio("lut", "flat", true, true);
            entry["gpu_lut_over_ptm"] = ratio("lut", "ptm", true, true);
            entry["gpu_lut_over_flat_static"] = ratio("lut", "flat", false, true);
            entry["gpu_lut_over_ptm_static"] = ratio("lut", "ptm", false, true);
        }
        std::snprintf(line, sizeof line,
                      "    lut/flat: static %.3f, moving %.3f (GPU %.3f, %.3f);  lut/ptm: static %.3f, moving %.3f "
                      "(GPU %.3f, %.3f)\n",
                      entry["lut_over_flat_static"].get<double>(), entry["lut_over_flat"].get<double>(),
                      timer ? entry["gpu_lut_over_flat_static"].get<double>() : NAN,
                      timer ? entry["gpu_lut_over_flat"].get<double>() : NAN,
                      entry["lut_over_ptm_static"].get<double>(), entry["lut_over_ptm"].get<double>(),
                      timer ? entry["gpu_lut_over_ptm_static"].get<double>() : NAN,
                      timer ? entry["gpu_lut_over_ptm"].get<double>() : NAN);
        text += line;
        if (predictor) {
            std::snprintf(
                line, sizeof line, "    lut/predictor (the predictor per fragment, no LUT): static %.3f, moving %.3f\n",
                entry["lut_over_predictor_static"].get<double>(), entry["lut_over_predictor_moving"].get<double>());
            text += line;
        }
        std::snprintf(
            line, sizeof line, "    lut quads per fragment in the moving frames: %zu of %zu (the last frame)\n",
            movingLutStats.quadsPerFragment, movingLutStats.quadsPerFragment + movingLutStats.quadsTextureSpace);
        entry["lut_moving_quads_per_fragment"] = movingLutStats.quadsPerFragment;
        text += line;
        if (first) {  // the headline figures: the first size
            first = false;
            for (const char* key : {"lut_over_flat", "lut_over_ptm", "lut_over_flat_static", "lut_over_ptm_static",
                                    "lut_over_predictor_moving", "lut_over_predictor_static", "gpu_lut_over_flat",
                                    "gpu_lut_over_ptm", "gpu_lut_over_flat_static", "gpu_lut_over_ptm_static"})
                if (entry.contains(key)) out[key] = entry[key];
            // Per material: lut reads the reference and draws one relit texture per light
            // direction of its quads (here four); ptm needs its three coefficient/albedo textures.
            const TextureBytes& bytes = (*renderer)->stats().textureBytes;
            const std::size_t directions = std::max<std::size_t>((*renderer)->stats().relitTextures, 1);
            const std::size_t lutBytes = bytes.reference + bytes.blend + bytes.relit + bytes.luts;
            out["texture_bytes_lut"] = lutBytes;
            out["texture_bytes_lut_per_direction"] = bytes.relit / directions;
            out["light_directions"] = directions;
            out["texture_bytes_ptm"] = bytes.ptm;
            out["lut_over_ptm_texture_bytes"] = static_cast<double>(lutBytes) / static_cast<double>(bytes.ptm);
            std::snprintf(
                line, sizeof line,
                "  texture memory per material: lut %zu bytes (source %zu + %zu relit textures of %zu), ptm %zu "
                "bytes; lut/ptm %.4f\n",
                lutBytes, bytes.reference + bytes.blend, directions, bytes.relit / directions, bytes.ptm,
                static_cast<double>(lutBytes) / static_cast<double>(bytes.ptm));
            text += line;
            // Drawn per fragment a material needs its source (the reference, or a predictor's
            // planes) and a LUT per channel and region: per texel against the PTM's.
            const double texels = static_cast<double>((*renderer)->bank("m")->reference.pixelCount());
            const double perFragment = static_cast<double>(bytes.reference + bytes.blend + bytes.luts) / texels;
            out["bytes_per_texel_per_fragment"] = perFragment;
            out["bytes_per_texel_ptm"] = static_cast<double>(bytes.ptm) / texels;
            std::snprintf(line, sizeof line,
                          "  drawn per fragment: %.2f bytes per texel (mipmaps and LUTs included), the PTM %.2f\n",
                          perFragment, static_cast<double>(bytes.ptm) / texels);
            text += line;
        }
        out["sizes"].push_back(entry);
    }
    if (o.json) {
        std::cout << jsonText(out);
        return success();
    }
    std::cout << "render " << 4 * o.overdraw << " quads, frame times (median of " << o.repeat << " rounds of "
              << o.frames << " frames, no wait between frames), " << (*context)->description()
              << (timer ? "" : "; no GPU timer in this driver") << "\n"
              << text;
    return success();
}

struct BenchTrainOptions {
    int samples = 200000;
    int epochs = 3;
    int repeat = 3;
    bool json = false;
};

// The trainer the learned kind uses (learn/network.h) on NeuralRTI's decoder, 11-50-50-3 ELU,
// Adam at 1e-3, batches of 1024 samples of a smooth synthetic function: the setting in which
// libtorch's and dlib's C++ trainers were measured (bench/RESULTS.md, issue 35).
Status runBenchTrain(const BenchTrainOptions& o) {
    Random random(1);
    const auto n = static_cast<Eigen::Index>(o.samples);
    Matrix x(11, n), y(3, n);
    for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] = static_cast<float>(random.uniform() * 2 - 1);
    for (Eigen::Index i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) y(c, i) = std::tanh(x(c, i) * x(9, i) + x(3 + c, i) * x(10, i));
    std::vector<double> rates;
    double loss = 0;
    for (int r = 0; r < o.repeat; ++r) {
        Random init(2);
        Network net = Network::random({11, 50, 50, 3}, init);
        Adam adam(net);
        NetworkPass pass;
        const auto start = std::chrono::steady_clock::now();
        for (int e = 0; e < o.epochs; ++e)
            for (Eigen::Index at = 0; at + 1024 <= n; at += 1024) {
                net.forward(x.middleCols(at, 1024), pass);
                Matrix d = pass.output() - y.middleCols(at, 1024);
                loss = d.squaredNorm() / static_cast<double>(d.size());
                d *= 2.f / static_cast<float>(d.size());
                adam.step(net, net.backward(pass, d, false), 1e-3f);
            }
        rates.push_back(static_cast<double>(o.epochs) * static_cast<double>(n) /
                        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / 1e6);
    }
    nlohmann::json out{{"network", "11-50-50-3 ELU, Adam, batch 1024"},
                       {"samples", o.samples},
                       {"epochs", o.epochs},
                       {"million_samples_per_second", median(rates)},
                       {"final_loss", loss}};
    if (o.json) {
        std::cout << jsonText(out);
        return success();
    }
    std::printf(
        "btflut's trainer (learn/network.h), 11-50-50-3 ELU, Adam, batch 1024, %d samples x %d epochs, one "
        "thread: %.2f M samples/s (median of %d), final loss %.5f\n",
        o.samples, o.epochs, median(rates), o.repeat, loss);
    return success();
}

}  // namespace

void addGlBenchOptions(CLI::App& app, GlBenchOptions& o, const std::string& what) {
    app.add_option("--frames", o.frames, what + " per row and round")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    app.add_option("--repeat", o.repeat, "rounds")->check(CLI::Range(1, 100))->capture_default_str();
    app.add_option("--backend", o.backend, "auto, osmesa or egl")->capture_default_str();
    app.add_flag("--json", o.json, "print JSON");
}

void addBenchCommand(CLI::App& root, Commands& commands) {
    CLI::App* bench = root.add_subcommand("bench", "Benchmarks (timings and ratios; never pass/fail)");
    bench->require_subcommand(1);
    auto o = std::make_shared<BenchBakeOptions>();
    CLI::App* bake = bench->add_subcommand("bake", "Time baking a dataset, decoding excluded");
    bake->add_option("DATASET", o->dataset, "dataset folder or file")->required();
    bake->add_option("--repeat", o->repeat, "timed runs")->check(CLI::Range(1, 1000))->capture_default_str();
    bake->add_option("--threads", o->threads, "threads for the main timing (0 = all cores)")
        ->check(CLI::Range(0, 1024));
    bake->add_flag("--json", o->json, "print JSON");
    commands.push_back({bake, [o] { return runBenchBake(*o); }});

    auto so = std::make_shared<BenchSimulateOptions>();
    CLI::App* simulate =
        bench->add_subcommand("simulate", "Error against time: Monte Carlo and quadrature histograms at curet-c2");
    addModelOptions(*simulate, so->model, false);
    simulate->add_option("--repeat", so->repeat, "timed runs")->check(CLI::Range(1, 100))->capture_default_str();
    simulate->add_flag("--json", so->json, "print JSON");
    commands.push_back({simulate, [so] { return runBenchSimulate(*so); }});

    auto yo = std::make_shared<BenchSynthOptions>();
    CLI::App* synth = bench->add_subcommand("synth", "Time rendering one synthetic image, 1 thread against all");
    synth->add_option("--size", yo->size, "image size")->check(CLI::Range(16, 8192))->capture_default_str();
    synth->add_option("--samples", yo->samples, "rays per pixel along each axis")
        ->check(CLI::Range(1, 16))
        ->capture_default_str();
    synth->add_option("--repeat", yo->repeat, "timed runs")->check(CLI::Range(1, 100))->capture_default_str();
    synth->add_flag("--json", yo->json, "print JSON");
    commands.push_back({synth, [yo] { return runBenchSynth(*yo); }});

    auto to = std::make_shared<BenchTrainOptions>();
    CLI::App* train = bench->add_subcommand(
        "train", "Training throughput of the learned kind's trainer on NeuralRTI's decoder (samples per second)");
    train->add_option("--samples", to->samples, "synthetic samples")
        ->check(CLI::Range(1024, 10000000))
        ->capture_default_str();
    train->add_option("--epochs", to->epochs, "passes over them")->check(CLI::Range(1, 100))->capture_default_str();
    train->add_option("--repeat", to->repeat, "timed runs")->check(CLI::Range(1, 100))->capture_default_str();
    train->add_flag("--json", to->json, "print JSON");
    commands.push_back({train, [to] { return runBenchTrain(*to); }});

    auto ro = std::make_shared<BenchRenderOptions>();
    CLI::App* render = bench->add_subcommand(
        "render",
        "Frame times of the scene renderer in modes flat, brdf, ptm and lut (and, for a bank with a "
        "predictor, the predictor per fragment without its LUT), light static and moving (a new direction "
        "every frame), wall and GPU time, interleaved");
    render->add_option("BANK", ro->bank, "M.btflut used for every quad (baked with --ptm)")->required();
    render->add_option("--frames", ro->frames, "frames per mode and round")
        ->check(CLI::Range(1, 1000))
        ->capture_default_str();
    render->add_option("--repeat", ro->repeat, "rounds")->check(CLI::Range(1, 100))->capture_default_str();
    render->add_option("--size", ro->sizes, "image sizes WxH (repeatable)")->capture_default_str();
    render->add_option("--overdraw", ro->overdraw, "layers of the four quads, each drawn over the last")
        ->check(CLI::Range(1, 64))
        ->capture_default_str();
    render->add_option("--backend", ro->backend, "auto, osmesa or egl")->capture_default_str();
    render
        ->add_option("--lut-path", ro->lutPath,
                     "mode lut on banks of one view layer: auto (per quad and frame, whichever costs less), texture "
                     "(relit textures only) or fragment (per fragment only)")
        ->check(CLI::IsMember({"auto", "texture", "fragment"}))
        ->capture_default_str();
    render->add_flag("--json", ro->json, "print JSON");
    commands.push_back({render, [ro] { return runBenchRender(*ro); }});
    addBenchDecoderCommand(*bench, commands);
    addBenchLevelsCommand(*bench, commands);
}

}  // namespace btflut::cli

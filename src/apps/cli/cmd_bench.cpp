// btflut bench: timings that print ratios measured side by side, never pass/fail.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/command.h"
#include "cli/model_options.h"
#include "core/bake/bake.h"
#include "core/bank/lut_bank.h"
#include "core/histogram/histogram.h"
#include "core/io/json_text.h"
#include "core/learn/network.h"
#include "core/physics/geometry.h"
#include "core/physics/simulate.h"
#include "core/synth/render.h"

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

    addBenchRenderCommand(*bench, commands);
    addBenchDecoderCommand(*bench, commands);
    addBenchLevelsCommand(*bench, commands);
}

}  // namespace btflut::cli

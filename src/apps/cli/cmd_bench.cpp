// btflut bench: timings that print ratios measured side by side, never pass/fail.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/cli.h"
#include "core/lut_bank.h"

namespace btflut::cli {

namespace {

struct BenchBakeOptions {
    std::string dataset;
    int repeat = 7;
    int threads = 0;
    bool json = false;
};

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// The bake without decoding: images are decoded once up front and handed to bakeBank.
Status runBenchBake(const BenchBakeOptions& o) {
    Result<Dataset> dataset = openDataset(o.dataset);
    if (!dataset) return Error{dataset.error()};
    std::vector<Image> images;
    std::size_t pixels = 0;
    for (const DatasetImage& info : dataset->images) {
        Result<Image> image = loadImage(info.path);
        if (!image) return Error{image.error()};
        pixels += image->pixelCount();
        images.push_back(std::move(*image));
    }
    ImageProvider preloaded = [&](std::size_t i, Image&) -> Result<const Image*> {
        return &images[i];
    };
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
    nlohmann::json out{{"dataset", o.dataset},
                       {"images", images.size()},
                       {"pixels", pixels},
                       {"threads", o.threads},
                       {"seconds_median", median(all)},
                       {"seconds_median_1_thread", median(one)},
                       {"seconds", all},
                       {"seconds_1_thread", one}};
    if (o.json) {
        std::cout << out.dump(1) << "\n";
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

}  // namespace

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
}

}  // namespace btflut::cli

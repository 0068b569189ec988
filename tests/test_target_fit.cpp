// The target between measured lights (issue 34): the fit over the light that corrects the
// blend of the measured quantile functions, its validated choice, and its chunk.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <tuple>

#include "core/bake/bake.h"
#include "core/bake/target_choice.h"
#include "core/bank/bank_file.h"
#include "core/bank/target_fit.h"
#include "core/data/dataset.h"
#include "core/predict/light_model.h"
#include "core/predict/model_predictor.h"
#include "helpers.h"

using namespace btflut;
using namespace btflut::test;

namespace {

constexpr int kSamples = 32;

// A distribution that moves with the light as a shadowed surface's does: darker and wider
// towards the horizon, a tail of shadow that grows with theta and follows phi.
std::vector<float> shadowed(Direction light) {
    const Vec3 l = toVector(light);
    std::vector<float> q(kSamples);
    for (int k = 0; k < kSamples; ++k) {
        const double u = (k + 0.5) / kSamples;
        const double shadow = std::max(0.0, 0.6 * (1 - l.z) + 0.1 * l.x - u);
        q[static_cast<std::size_t>(k)] = static_cast<float>(std::clamp(0.15 + 0.7 * l.z * u - 0.5 * shadow, 0.0, 1.0));
    }
    std::sort(q.begin(), q.end());
    return q;
}

// A bank that makes its LUTs whose measured targets are `target` at `lights` (no predictor:
// lookups need none).
LutBank quantileBank(const std::vector<Direction>& lights, const std::function<std::vector<float>(Direction)>& target) {
    LutBank bank;
    bank.entries = 16;
    bank.gridSize = 9;
    bank.prediction.quantiles = kSamples;
    bank.reference = Image(4, 4, 1);
    std::vector<DirectionalLut> luts;
    for (std::size_t n = 0; n < lights.size(); ++n)
        luts.push_back({"l" + std::to_string(n), lights[n], {}, target(lights[n])});
    REQUIRE(setNodes(bank, luts, BankDomain::Layers, "test").ok());
    return bank;
}

double meanAbs(const std::vector<float>& a, const std::vector<float>& b) {
    double sum = 0;
    for (std::size_t k = 0; k < a.size(); ++k) sum += std::abs(a[k] - b[k]);
    return sum / static_cast<double>(a.size());
}

// A dataset (its manifest) of `count` lights up to `maxTheta` degrees whose images darken
// towards the horizon: codes shifted by 60 cos(theta).
std::string darkeningDataset(const TempDir& dir, int count, double maxTheta) {
    std::vector<test::SyntheticShot> shots;
    for (const Direction& l : test::dome(count, maxTheta))
        shots.push_back(
            {l.thetaDegrees(), l.phiDegrees(), 0, 0, static_cast<int>(std::lround(60 * std::cos(l.theta))), 1});
    return test::writeSyntheticDataset(dir, shots);
}

// Every lookup over the hemisphere finite, in [0, 1] and non-decreasing.
void requireQuantileFunctions(const LutBank& bank) {
    for (double theta = 0; theta <= 90; theta += 7.5)
        for (double phi = 0; phi < 360; phi += 22.5) {
            const std::vector<float> v = bank.lookup(Direction::fromDegrees(theta, phi)).values;
            for (float x : v) REQUIRE((std::isfinite(x) && x >= 0 && x <= 1));
            for (std::size_t at = 0; at < v.size(); at += bank.segmentLength())
                REQUIRE(std::is_sorted(v.begin() + static_cast<std::ptrdiff_t>(at),
                                       v.begin() + static_cast<std::ptrdiff_t>(at + bank.segmentLength())));
        }
}

// synth's concrete under 9 views x 9 lights, `size` pixels, in dir/btf.
Dataset renderedBtf9(const TempDir& dir, int size, int correlationLength) {
    REQUIRE(runCli({"synth", "--preset", "concrete", "--geometry", "btf-9", "--size", std::to_string(size),
                    "--correlation-length", std::to_string(correlationLength), "-q", "-o", dir / "btf"})
                .status == 0);
    Result<Dataset> dataset = openDataset(dir / "btf");
    REQUIRE(dataset.ok());
    return *dataset;
}

}  // namespace

TEST_CASE("the fit's terms: (degree + 1)^2 - 1 monomials of the light vector, a lower degree's leading") {
    const Direction light = Direction::fromDegrees(40, 75);
    for (int degree = 1; degree <= kMaxFitDegree; ++degree) {
        const std::vector<double> t = fitTerms(light, degree);
        CHECK(static_cast<int>(t.size()) == fitTermCount(degree));
        CHECK(t.size() == static_cast<std::size_t>((degree + 1) * (degree + 1) - 1));
        const std::vector<double> lower = fitTerms(light, degree - 1);
        CHECK(std::equal(lower.begin(), lower.end(), t.begin()));
    }
    const Vec3 v = toVector(light);
    const std::vector<double> one = fitTerms(light, 1);
    CHECK(one[0] == doctest::Approx(v.x));
    CHECK(one[1] == doctest::Approx(v.y));
    CHECK(one[2] == doctest::Approx(v.z));
}

TEST_CASE("a fit corrects the blend between measured lights, and measured lights keep their targets exactly") {
    const std::vector<Direction> lights = test::dome(49, 80);
    LutBank blended = quantileBank(lights, shadowed);
    LutBank fitted = blended;
    chooseTargetFits(fitted, 2);
    REQUIRE_FALSE(fitted.layers[0].fit.empty());
    CHECK(targetChoiceSummary(fitted).rfind("poly", 0) == 0);
    CHECK(targetChoiceSummary(blended) == "blend");
    // Exact at every measured light: the fit's difference vanishes at a node.
    for (std::size_t n = 0; n < lights.size(); ++n) {
        const float* node = &fitted.layers[0].nodeLuts[n * fitted.nodeLength()];
        CHECK(fitted.lookup(lights[n]).values == std::vector<float>(node, node + fitted.nodeLength()));
    }
    // Between them, closer to the truth than the blend, on average over the hemisphere.
    double blendError = 0, fitError = 0;
    int count = 0;
    for (double theta = 5; theta <= 75; theta += 10)
        for (double phi = 10; phi < 360; phi += 40) {
            const Direction at = Direction::fromDegrees(theta, phi);
            blendError += meanAbs(blended.lookup(at).values, shadowed(at));
            fitError += meanAbs(fitted.lookup(at).values, shadowed(at));
            ++count;
        }
    MESSAGE("mean |q - truth| between the lights: blend " << blendError / count << ", fitted " << fitError / count);
    CHECK(fitError < 0.8 * blendError);
    requireQuantileFunctions(fitted);
    // The figures are recorded: every candidate, the blend first, and the choice.
    const nlohmann::json choice = nlohmann::json::parse(fitted.targetChoice);
    CHECK(choice["layers"][0]["candidates"][0]["name"] == "blend");
    CHECK(choice["layers"][0]["lights"] == 49);
    CHECK(choice["layers"][0]["chosen"][0].get<std::string>().rfind("poly", 0) == 0);
}

TEST_CASE("beyond the farthest light's radius the fit does not extrapolate further") {
    const LutBank blended = quantileBank(test::dome(40, 40), shadowed);
    LutBank bank = blended;
    chooseTargetFits(bank, 2);
    REQUIRE_FALSE(bank.layers[0].fit.empty());
    const ViewLayer& layer = bank.layers[0];
    // Beyond the lights' reach (40 degrees) the fit is read at the reach on the light's azimuth.
    for (double theta : {55.0, 70.0, 89.0}) {
        const Direction far = Direction::fromDegrees(theta, 200);
        const DiskPoint p = toDisk(far);
        const double scale = layer.measuredReach / std::hypot(p.x, p.y);
        const Weights w = layer.lights.weightsAt(p);
        std::vector<Direction> lights;
        std::vector<double> weights;
        SegmentRanges ranges;  // the levels of the nodes blended
        for (int k = 0; k < w.count; ++k) {
            const auto n = static_cast<std::size_t>(w.index[k]);
            lights.push_back(layer.nodes[n].light);
            weights.push_back(w.weight[k]);
            if (w.weight[k] > 0)
                ranges.include(&layer.nodeLuts[n * bank.nodeLength()], bank.nodeLength(), bank.segmentLength());
        }
        const std::vector<float> blend = blended.lookup(far).values;
        std::vector<double> sum(blend.begin(), blend.end());
        addFitCorrection(layer.fit, fromDisk({p.x * scale, p.y * scale}), lights, weights, 1, sum);
        std::vector<float> expected(sum.begin(), sum.end());
        makeQuantileFunctions(expected, bank.segmentLength(), ranges, bank.targetCode());
        const std::vector<float> got = bank.lookup(far).values;
        for (std::size_t k = 0; k < got.size(); ++k) CHECK(got[k] == doctest::Approx(expected[k]).epsilon(1e-6));
    }
    requireQuantileFunctions(bank);
}

TEST_CASE(
    "few, ringed, collinear, clustered lights and flat targets: finite monotone targets, the blend where unvalidated") {
    const auto flat = [](float v) { return [v](Direction) { return std::vector<float>(kSamples, v); }; };
    std::vector<std::pair<std::string, std::vector<Direction>>> sets;
    sets.push_back({"2 lights", {Direction::fromDegrees(10, 0), Direction::fromDegrees(40, 90)}});
    sets.push_back({"3 lights", test::dome(3, 50)});
    sets.push_back({"5 lights", test::dome(5, 50)});
    sets.push_back({"12 lights", test::dome(12, 40)});
    std::vector<Direction> ring, line, cluster;
    for (int i = 0; i < 16; ++i) ring.push_back(Direction::fromDegrees(60, 22.5 * i));
    for (int i = 0; i < 16; ++i) line.push_back(Direction::fromDegrees(5 + 5 * i, i % 2 ? 30 : 210));
    for (int i = 0; i < 16; ++i) cluster.push_back(Direction::fromDegrees(30 + 0.01 * i, 45 + 0.01 * i * i));
    sets.push_back({"a ring", ring});
    sets.push_back({"a line", line});
    sets.push_back({"a cluster", cluster});
    for (const auto& [what, lights] : sets)
        for (const auto& target :
             std::vector<std::function<std::vector<float>(Direction)>>{shadowed, flat(0.f), flat(1.f), flat(0.5f)}) {
            CAPTURE(what);
            LutBank bank = quantileBank(lights, target);
            chooseTargetFits(bank, 1);
            if (lights.size() < kMinFitLights) {
                CHECK(bank.layers[0].fit.empty());
                CHECK(nlohmann::json::parse(bank.targetChoice)["layers"][0].contains("skipped"));
            }
            for (float c : bank.layers[0].fit.coefficients) REQUIRE(std::isfinite(c));
            requireQuantileFunctions(bank);
        }
}

TEST_CASE("a fit's correction keeps the measurements' levels: never below the darkest value blended") {
    // Shadows that sit on a black level (0.1, a camera's floor) and grow towards the horizon:
    // a smooth fit's correction overshoots below the floor between and beyond the lights; the
    // lookup keeps each value within the range of the nodes it blends.
    static constexpr float kFloor = 0.1f;
    const auto floored = [](Direction l) {
        std::vector<float> q = shadowed(l);
        for (float& v : q) v = std::max(v, kFloor);
        return q;
    };
    const LutBank blended = quantileBank(test::dome(30, 75), floored);
    LutBank bank = blended;
    chooseTargetFits(bank, 2);
    REQUIRE_FALSE(bank.layers[0].fit.empty());
    const ViewLayer& layer = bank.layers[0];
    int unclamped = 0;  // values the correction alone would put below the floor
    for (double theta = 0; theta <= 90; theta += 5)
        for (double phi = 0; phi < 360; phi += 15) {
            const Direction at = Direction::fromDegrees(theta, phi);
            const std::vector<float> got = bank.lookup(at).values;
            for (float v : got) CHECK(v >= kFloor);
            if (theta > 70) continue;  // within the lights' reach: the fit read at the light itself
            const Weights w = layer.lights.weightsAt(toDisk(at));
            std::vector<Direction> lights;
            std::vector<double> weights;
            for (int k = 0; k < w.count; ++k) {
                lights.push_back(layer.nodes[static_cast<std::size_t>(w.index[k])].light);
                weights.push_back(w.weight[k]);
            }
            const std::vector<float> blend = blended.lookup(at).values;
            std::vector<double> sum(blend.begin(), blend.end());
            addFitCorrection(layer.fit, at, lights, weights, 1, sum);
            unclamped += static_cast<int>(std::ranges::count_if(sum, [](double v) { return v < kFloor - 1e-3; }));
        }
    MESSAGE("values the correction alone puts below the floor: " << unclamped);
    CHECK(unclamped > 0);  // the case the range guards against arises
    requireQuantileFunctions(bank);
}

TEST_CASE("the fit travels in TFIT (version 6): round trip, and corrupt fits refused naming the chunk") {
    // A baked bank whose images darken towards the horizon, and a degree-2 fit of its targets.
    TempDir dir;
    Result<Dataset> dataset = openDataset(darkeningDataset(dir, 36, 75));
    REQUIRE(dataset.ok());
    Result<LutBank> baked =
        bakeBank(*dataset, {.fit = lightModelFit(LightModelOptions{.basis = LightBasis::Hsh, .order = 2})});
    REQUIRE_MESSAGE(baked.ok(), baked.error());
    LutBank& bank = *baked;
    std::vector<Direction> lights;
    for (const LightNode& n : bank.layers[0].nodes) lights.push_back(n.light);
    bank.layers[0].fit = fitTargets(lights, bank.layers[0].nodeLuts.data(), bank.nodeLength(), {{2, 1e-4}});
    bank.fillGrids();
    REQUIRE_FALSE(bank.layers[0].fit.empty());
    CHECK(bankFormatVersion(bank) == 6);
    const Bytes bytes = encodeBank(bank);
    Result<LutBank> back = decodeBank(bytes, "fit.btflut");
    REQUIRE_MESSAGE(back.ok(), back.error());
    CHECK(back->targetChoice == bank.targetChoice);
    CHECK(back->layers[0].fit.degree == bank.layers[0].fit.degree);
    CHECK(back->layers[0].fit.coefficients == bank.layers[0].fit.coefficients);
    const Direction between = Direction::fromDegrees(33, 123);
    CHECK(back->lookup(between).values == bank.lookup(between).values);
    CHECK(encodeBank(*back) == bytes);

    // Without the choice and the fit the bank is what version 5 readers read.
    LutBank plain = bank;
    plain.targetChoice.clear();
    plain.layers[0].fit = {};
    CHECK(bankFormatVersion(plain) == 5);

    auto corrupt = [&](const std::function<void(LutBank&)>& change, const std::string& needle) {
        LutBank b = bank;
        change(b);
        Result<LutBank> read = decodeBank(encodeBank(b), "bad.btflut");
        REQUIRE_FALSE(read.ok());
        CHECK_MESSAGE(read.error().find(needle) != std::string::npos, read.error());
        CHECK(read.error().find("bad.btflut") == 0);
    };
    corrupt([](LutBank& b) { b.layers[0].fit.coefficients[3] = NAN; }, "TFIT chunk: a coefficient is not finite");
    corrupt([](LutBank& b) { b.layers[0].fit.coefficients[0] = INFINITY; }, "TFIT chunk: a coefficient is not finite");
    corrupt([](LutBank& b) { b.targetChoice = "{not json"; }, "TFIT chunk");
    corrupt(
        [](LutBank& b) {
            b.layers[0].fit.degree = kMaxFitDegree + 1;
            b.layers[0].fit.coefficients.resize(static_cast<std::size_t>(fitTermCount(kMaxFitDegree + 1)) *
                                                b.nodeLength());
        },
        "TFIT chunk: truncated, or a fit of an invalid degree");
    corrupt([](LutBank& b) { b.layers[0].fit.coefficients.pop_back(); }, "TFIT chunk");
}

TEST_CASE("shared data: the validated target beats the blend at held-out lights, and never loses beyond noise") {
    // dome-synth (49 lights, every 4th held out): the fit's target 0.117 against the blend's 0.151
    // (issue 34 asks 20% less); psm-rock (12 lights, leave-one-out): 0.172 against 0.174, the
    // fitted model's change mixed with a plane where validation trusts it, else the blend.
    for (const auto& [name, path, holdout, ratio] :
         {std::tuple{"dome-synth", "/dome-synth/dirs.lp", "every:4", 0.8}, {"psm-rock", "/psm-rock", "loo", 1.0}}) {
        if (!haveSharedData(name)) continue;
        CliRun run = runCli({"eval", sharedDataDir() + path, "--holdout", holdout, "--modes", "lut", "--predictor",
                             "hsh2", "--target", "measured,blend", "--no-gl", "--json"});
        REQUIRE_MESSAGE(run.status == 0, run.err);
        const nlohmann::json report = nlohmann::json::parse(run.out);
        std::map<std::string, double> target;
        for (const nlohmann::json& m : report["modes"]) target[m["name"]] = m["target_l1"].get<double>();
        const double fitted = target.at("lut hsh2 R1 grey measured"), blended = target.at("lut hsh2 R1 grey blend");
        MESSAGE(std::string(name) << ": target L1 at the held-out lights " << fitted << ", the blend's " << blended);
        CHECK(fitted <= ratio * blended + 1e-9);
    }
}

TEST_CASE("eval --target: measured, blend and corrections side by side; another word is one line") {
    TempDir dir;
    const std::string dataset = darkeningDataset(dir, 16, 70);
    CliRun run = runCli({"eval", dataset, "--modes", "lut", "--predictor", "hsh2,auto", "--target",
                         "measured,blend,corrections", "--no-gl", "--json"});
    REQUIRE_MESSAGE(run.status == 0, run.err);
    std::vector<std::string> names;
    const nlohmann::json report = nlohmann::json::parse(run.out);
    for (const nlohmann::json& m : report["modes"]) names.push_back(m["name"]);
    for (const char* name : {"lut hsh2 R1 grey measured", "lut hsh2 R1 grey blend", "lut hsh2 R1 grey corrections",
                             "lut auto measured", "lut auto blend"})
        CHECK_MESSAGE(std::ranges::find(names, name) != names.end(), name);
    CHECK(std::ranges::find(names, "lut auto corrections") == names.end());  // auto chooses its own
    // bake's summary names the estimate, for the paper's bank too
    const CliRun bake = runCli({"bake", dataset, "--references", "1", "-o", dir / "k1.btflut"});
    REQUIRE(bake.status == 0);
    CHECK(bake.out.find("targets between the measured lights: ") != std::string::npos);
    requireOneLineError(runCli({"eval", dataset, "--modes", "lut", "--target", "smooth", "--no-gl"}),
                        "--target 'smooth' is not measured, blend or corrections");
}

TEST_CASE("two corrections mixed: the weighted sum of each, whatever their degrees") {
    const std::vector<Direction> lights = test::dome(49, 80);
    LutBank bank = quantileBank(lights, shadowed);
    const std::size_t length = bank.nodeLength();
    const TargetFit two = fitTargets(lights, bank.layers[0].nodeLuts.data(), length, {{2, 1e-4}});
    const TargetFit four = fitTargets(lights, bank.layers[0].nodeLuts.data(), length, {{4, 1e-4}});
    const TargetFit mixed = mixFits(two, 0.25, four, 0.75);
    CHECK(mixed.degree == 4);
    const std::vector<Direction> nodes{lights[0], lights[5], lights[9]};
    const std::vector<double> weights{0.2, 0.5, 0.3};
    for (const Direction at : {Direction::fromDegrees(35, 80), Direction::fromDegrees(70, 300)}) {
        std::vector<double> expected(length, 0.0), got(length, 0.0);
        addFitCorrection(two, at, nodes, weights, 0.25, expected);
        addFitCorrection(four, at, nodes, weights, 0.75, expected);
        addFitCorrection(mixed, at, nodes, weights, 1, got);
        for (std::size_t k = 0; k < length; ++k) CHECK(got[k] == doctest::Approx(expected[k]).epsilon(1e-5));
    }
    // With no fit on one side, the other scaled.
    const TargetFit half = mixFits({}, 0.5, two, 0.5);
    REQUIRE(half.coefficients.size() == two.coefficients.size());
    for (std::size_t k = 0; k < half.coefficients.size(); ++k)
        CHECK(half.coefficients[k] == 0.5f * two.coefficients[k]);
}

TEST_CASE("the fitted rough-surface model: a candidate estimate between the lights, exact at them") {
    // A rendered Gaussian rough surface, as the model describes: the model's change between the
    // lights estimates their targets closer than the blend. Measured lights stay exact.
    TempDir dir;
    REQUIRE(runCli({"synth", "--preset", "concrete", "--geometry", "rti-49", "--size", "64", "--correlation-length",
                    "4", "-q", "-o", dir / "concrete"})
                .status == 0);
    Result<Dataset> dataset = openDataset(dir / "concrete");
    REQUIRE(dataset.ok());
    for (const bool lutBank : {false, true}) {
        CAPTURE(lutBank);
        BakeOptions options;
        if (!lutBank) options.fit = lightModelFit({.basis = LightBasis::Hsh, .order = 2});
        Result<LutBank> bank = bakeBank(*dataset, options);
        REQUIRE_MESSAGE(bank.ok(), bank.error());
        const nlohmann::json choice = nlohmann::json::parse(bank->targetChoice);
        REQUIRE_MESSAGE(choice["model"].contains("roughness"), choice["model"].dump());
        const double roughness = choice["model"]["roughness"].get<double>();
        CHECK((roughness > 0.1 && roughness < 2));
        std::map<std::string, double> l1;
        for (const nlohmann::json& c : choice["layers"][0]["candidates"])
            if (c["l1"][0].is_number()) l1[c["name"]] = c["l1"][0].get<double>();
        MESSAGE("validation L1: blend " << l1.at("blend") << ", model " << l1.at("model") << "; chosen "
                                        << targetChoiceSummary(*bank));
        CHECK(l1.at("model") < 0.8 * l1.at("blend"));
        CHECK(l1.count("model + poly1 ridge 0.01") == 1);
        CHECK(targetChoiceSummary(*bank).find("model") != std::string::npos);
        // info prints the model's fit above the candidates' figures.
        REQUIRE(saveBank(*bank, dir / "bank.btflut").ok());
        const CliRun info = runCli({"info", dir / "bank.btflut"});
        REQUIRE(info.status == 0);
        CHECK(info.out.find("model: lambert rough surface fitted to the measured histograms, r ") != std::string::npos);
        const ViewLayer& layer = bank->layers[0];
        for (std::size_t n = 0; n < layer.measuredNodes; ++n) {
            const float* node = &layer.nodeLuts[n * bank->nodeLength()];
            CHECK(bank->lookup(layer.nodes[n].light).values == std::vector<float>(node, node + bank->nodeLength()));
        }
    }
    // The model describes the whole sample: not a candidate where each region has its target.
    Result<LutBank> regions = bakeBank(*dataset, {.regions = 2});
    REQUIRE_MESSAGE(regions.ok(), regions.error());
    CHECK(nlohmann::json::parse(regions->targetChoice)["model"].is_null());
}

TEST_CASE("the bundled material: the default keeps a predictor, with the paper's bank's held-out histograms") {
    // Its photographs' shadows sit on a black level the fitted model lacks. With the model's
    // correction kept within the measurements' levels, the predictor's target (quantile
    // functions) and the paper's bank's (LUTs) are one estimate (held-out L1 0.179 and 0.178),
    // so the validated default is a predictor matched to it (27.3 dB), not the paper's bank
    // (13.3 dB), which it had become when the predictor's target trailed by 0.04.
    const CliRun run = runCli({"eval", BTFLUT_DEFAULT_MATERIAL, "--holdout", "every:4", "--modes", "lut", "--predictor",
                               "auto,hsh2,references", "--no-gl", "--json"});
    REQUIRE_MESSAGE(run.status == 0, run.err);
    const nlohmann::json report = nlohmann::json::parse(run.out);
    std::map<std::string, nlohmann::json> mode;
    for (const nlohmann::json& m : report["modes"]) mode[m["name"].get<std::string>()] = m;
    const nlohmann::json &automatic = mode.at("lut auto"), &hsh2 = mode.at("lut hsh2 R1 grey"),
                         &paper = mode.at("lut K1 R1 grey");
    MESSAGE("held-out L1: auto " << automatic["l1"] << " (" << automatic["psnr"] << " dB), hsh2's target "
                                 << hsh2["target_l1"] << ", the paper's bank " << paper["l1"] << " (" << paper["psnr"]
                                 << " dB)");
    CHECK(std::abs(hsh2["target_l1"].get<double>() - paper["l1"].get<double>()) < 0.01);
    CHECK(automatic["l1"].get<double>() <= paper["l1"].get<double>() + 0.002);
    CHECK(automatic["psnr"].get<double>() > paper["psnr"].get<double>() + 10);
}

TEST_CASE("the isotropic domain: one estimate over every pair, exact at them, closer than the blend held out") {
    // 9 views x 9 lights of a rendered rough surface, as one isotropic domain of 81 pairs.
    TempDir dir;
    const Dataset dataset = renderedBtf9(dir, 64, 6);
    Result<LutBank> baked = bakeBank(dataset, {.domain = BankDomain::Isotropic});
    REQUIRE_MESSAGE(baked.ok(), baked.error());
    const LutBank& bank = *baked;
    REQUIRE_FALSE(bank.pairFit.empty());
    CHECK(bank.pairFit.domain == FitDomain::Pair);
    const nlohmann::json choice = nlohmann::json::parse(bank.targetChoice);
    CHECK(choice["layers"].size() == 1);
    CHECK(choice["layers"][0]["domain"] == "pairs");
    CHECK(choice["layers"][0]["lights"] == bank.pairNodes.size());
    CHECK(choice["model"].contains("roughness"));
    MESSAGE("chosen over the pairs: " << targetChoiceSummary(bank));
    // At a measured pair the correction vanishes: the lookup is the pair's measured values (to
    // the tetrahedra's weights, which leave 1e-16 on a point's neighbours, fit or not).
    for (std::size_t p = 0; p < bank.pairNodes.size(); ++p) {
        const LutBank::NodeRef n = bank.pairNodes[p].front();
        if (bank.pairNodes[p].size() != 1) continue;  // several nodes at one point are averaged
        const float* node = &bank.layers[n.layer].nodeLuts[n.node * bank.nodeLength()];
        const std::vector<float> got =
            bank.lookup(bank.layers[n.layer].nodes[n.node].light, bank.layers[n.layer].view).values;
        for (std::size_t k = 0; k < got.size(); ++k) CHECK(std::abs(got[k] - node[k]) < 1e-6);
    }
    requireQuantileFunctions(bank);
    // It travels in TFIT (version 7): one fit over the pairs.
    CHECK(bankFormatVersion(bank) == 7);
    const Bytes bytes = encodeBank(bank);
    Result<LutBank> back = decodeBank(bytes, "pairs.btflut");
    REQUIRE_MESSAGE(back.ok(), back.error());
    CHECK(back->pairFit.coefficients == bank.pairFit.coefficients);
    CHECK(back->pairFit.domain == FitDomain::Pair);
    const Direction light = Direction::fromDegrees(40, 100), view = Direction::fromDegrees(30, 20);
    CHECK(back->lookup(light, view).values == bank.lookup(light, view).values);
    CHECK(encodeBank(*back) == bytes);
    LutBank bad = bank;
    bad.pairFit.coefficients[1] = NAN;
    Result<LutBank> read = decodeBank(encodeBank(bad), "bad.btflut");
    REQUIRE_FALSE(read.ok());
    CHECK_MESSAGE(read.error().find("TFIT chunk: a coefficient is not finite") != std::string::npos, read.error());
    Bytes older = bytes;  // a version 6 reader knows no fit over pairs
    older[8] = 6;
    read = decodeBank(older, "old.btflut");
    REQUIRE_FALSE(read.ok());
    CHECK_MESSAGE(read.error().find("unexpected TFIT chunk") != std::string::npos, read.error());
    // Held out (every 4th pair), the validated estimate against the blend alone.
    const CliRun run =
        runCli({"eval", dir / "btf", "--domain", "isotropic", "--target", "measured,blend", "--no-gl", "--json"});
    REQUIRE_MESSAGE(run.status == 0, run.err);
    const nlohmann::json report = nlohmann::json::parse(run.out);
    std::map<std::string, double> l1;
    for (const nlohmann::json& m : report["modes"]) l1[m["name"].get<std::string>()] = m["l1"].get<double>();
    const double measured = l1.at("lut K1 R1 grey measured isotropic"),
                 blended = l1.at("lut K1 R1 grey blend isotropic");
    MESSAGE("held-out L1 over the pairs: validated " << measured << ", the blend " << blended);
    CHECK(measured < 0.85 * blended);
}

TEST_CASE("the isotropic domain's few or planar pairs: finite monotone targets, the blend where unvalidated") {
    // curet-c2: 11 pairs along one plane of the domain; the first 4 of them: too few to choose.
    TempDir dir;
    REQUIRE(runCli({"synth", "--preset", "foil", "--geometry", "curet-c2", "--size", "32", "--correlation-length", "4",
                    "-q", "-o", dir / "c2"})
                .status == 0);
    nlohmann::json manifest = nlohmann::json::parse(readText(dir / "c2/btflut-dataset.json"));
    manifest["images"].erase(manifest["images"].begin() + 4, manifest["images"].end());
    {
        std::ofstream out(dir / "c2/four.json");
        out << manifest.dump();
    }
    for (const auto& [name, skipped] : {std::pair{"c2", false}, {"c2/four.json", true}}) {
        CAPTURE(name);
        Result<Dataset> dataset = openDataset(dir / name);
        REQUIRE_MESSAGE(dataset.ok(), dataset.error());
        Result<LutBank> bank = bakeBank(*dataset, {.domain = BankDomain::Isotropic});
        REQUIRE_MESSAGE(bank.ok(), bank.error());
        const nlohmann::json row = nlohmann::json::parse(bank->targetChoice)["layers"][0];
        CHECK(row["domain"] == "pairs");
        CHECK(row.contains("skipped") == skipped);
        if (skipped) CHECK(bank->pairFit.empty());
        requireQuantileFunctions(*bank);
        for (const Direction& view : {Direction::fromDegrees(0, 0), Direction::fromDegrees(60, 90)})
            for (double theta = 0; theta <= 85; theta += 17)
                for (float v : bank->lookup(Direction::fromDegrees(theta, 30), view).values)
                    REQUIRE((std::isfinite(v) && v >= 0 && v <= 1));
    }
}

TEST_CASE("across views: the model, fitted to every view's lights together, estimates a view's few lights") {
    // btf-9: 9 views of 9 lights, too few per view for a polynomial; the model is one fit of
    // every view's histograms (its view an input).
    TempDir dir;
    const Dataset dataset = renderedBtf9(dir, 48, 4);
    Result<LutBank> bank = bakeBank(dataset, {});
    REQUIRE_MESSAGE(bank.ok(), bank.error());
    REQUIRE(bank->layers.size() == 9);
    const nlohmann::json choice = nlohmann::json::parse(bank->targetChoice);
    REQUIRE(choice["model"].contains("roughness"));
    int modelled = 0;
    double blend = 0, model = 0;
    for (const nlohmann::json& layer : choice["layers"]) {
        for (const nlohmann::json& c : layer["candidates"]) {
            if (c["name"] == "blend") blend += c["l1"][0].get<double>();
            if (c["name"] == "model") model += c["l1"][0].get<double>();
        }
        modelled += layer["chosen"][0].get<std::string>().find("model") != std::string::npos;
    }
    MESSAGE("validation L1 summed over the views: blend " << blend << ", model " << model << "; " << modelled
                                                          << " of 9 views chose it");
    CHECK(model < 0.8 * blend);
    CHECK(modelled >= 5);
    for (const ViewLayer& layer : bank->layers)
        for (std::size_t n = 0; n < layer.measuredNodes; ++n) {
            const float* node = &layer.nodeLuts[n * bank->nodeLength()];
            CHECK(bank->lookup(layer.nodes[n].light, layer.view).values ==
                  std::vector<float>(node, node + bank->nodeLength()));
        }
}

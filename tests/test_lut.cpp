#include <doctest/doctest.h>

#include <random>

#include "core/histogram/lut.h"

using namespace btflut;

namespace {

// Random code counts with empty stretches and spikes, as measured histograms have.
LevelCounts randomLevels(std::mt19937& rng, std::size_t codes) {
    LevelCounts l;
    l.counts.assign(codes, 0);
    int shape = static_cast<int>(rng() % 4);
    for (std::size_t k = 0; k < codes; ++k) {
        switch (shape) {
            case 0:
                l.counts[k] = rng() % 50;
                break;  // dense
            case 1:
                l.counts[k] = (rng() % 4 == 0) ? rng() % 1000 : 0;
                break;  // sparse
            case 2:
                l.counts[k] = (k / 16) % 2 ? rng() % 30 : 0;
                break;  // empty stretches
            default:
                l.counts[k] = rng() % 3 == 0 ? 1 : 0;
                break;  // thin
        }
    }
    if (rng() % 3 == 0) l.counts[rng() % codes] += 100000;  // a spike
    if (l.total() == 0) l.counts[rng() % codes] = 7;
    return l;
}

std::vector<std::size_t> presentCodes(const LevelCounts& l) {
    std::vector<std::size_t> codes;
    for (std::size_t k = 0; k < l.counts.size(); ++k)
        if (l.counts[k]) codes.push_back(k);
    return codes;
}

}  // namespace

TEST_CASE("matchLut agrees with scikit-image's mapping on a hand-worked example") {
    // Values 0, 1/3, 2/3, 1. Reference masses 2,0,1,1; target 0,1,1,2.
    LevelCounts ref{{2, 0, 1, 1}}, target{{0, 1, 1, 2}};
    Lut lut = matchLut(ref, target, 4);
    // np.interp([.5, .75, 1], [.25, .5, 1], [1/3, 2/3, 1]) = [2/3, 5/6, 1]
    CHECK(lut.values[0] == doctest::Approx(2.0 / 3));
    CHECK(lut.values[2] == doctest::Approx(5.0 / 6));
    CHECK(lut.values[3] == doctest::Approx(1.0));
    // 1/3 is absent from the reference: c_ref is flat at .5 there, as at code 0.
    CHECK(lut.values[1] == doctest::Approx(2.0 / 3));
}

TEST_CASE("matchLut keeps empty stretches of the target empty") {
    // Target codes 1 and 7 only (of 0..7): scikit-image would spread code 7's pixels over
    // (1, 7]; here they stay within code 7's cell (6, 7].
    LevelCounts ref{{1, 1, 1, 1, 1, 1, 1, 1}}, target{{0, 4, 0, 0, 0, 0, 0, 4}};
    Lut lut = matchLut(ref, target, 8);
    for (int k = 0; k < 8; ++k) {
        double code = lut.values[static_cast<std::size_t>(k)] * 7;
        CHECK(((code > 0 - 1e-9 && code <= 1 + 1e-6) || (code > 6 - 1e-6 && code <= 7 + 1e-6)));
    }
}

TEST_CASE("matchLut is well defined for spikes and single-valued images") {
    LevelCounts spread{{1, 1, 1, 1, 1}}, spike{{0, 0, 9, 0, 0}};
    Lut toSpike = matchLut(spread, spike, 16);
    for (float v : toSpike.values) CHECK((v > 0.25 - 1e-6 && v <= 0.5 + 1e-6));  // code 2's cell
    Lut fromSpike = matchLut(spike, spread, 16);
    CHECK(isValidLut(fromSpike.values.data(), fromSpike.values.size()));
    CHECK(fromSpike.values[8] == doctest::Approx(1.0));  // all reference mass is the top quantile
    Lut self = matchLut(spike, spike, 5);
    CHECK(self.values[2] == doctest::Approx(0.5));
}

TEST_CASE("matchLut properties over thousands of random histograms") {
    std::mt19937 rng(1234);
    for (int trial = 0; trial < 3000; ++trial) {
        const std::size_t refCodes = trial % 2 ? 256 : 766;
        const std::size_t targetCodes = trial % 3 ? 256 : 766;
        LevelCounts ref = randomLevels(rng, refCodes), target = randomLevels(rng, targetCodes);
        // LUT entries sit on the reference codes, so entry k is the LUT at code k. (Reading
        // it through a float value k / (codes - 1) may land a rounding error into the
        // next entry's interval, which is steep where the target has an empty stretch.)
        const int entries = static_cast<int>(refCodes);
        Lut lut = matchLut(ref, target, entries);
        INFO("trial " << trial);

        // Monotonic, finite, in [0, 1] — also at other LUT sizes.
        REQUIRE(isValidLut(lut.values.data(), lut.values.size()));
        Lut coarse = matchLut(ref, target, 2 + static_cast<int>(rng() % 300));
        REQUIRE(isValidLut(coarse.values.data(), coarse.values.size()));

        // Self-match is the identity at the reference's codes.
        Lut self = matchLut(ref, ref, entries);
        for (std::size_t k : presentCodes(ref))
            REQUIRE(self.values[k] == doctest::Approx(ref.valueOf(k)).epsilon(1e-6));

        // Applying the LUT reproduces the target histogram: every output lies in the cell
        // (y - 1, y] of a present target code y, and the mass at or below each present code
        // matches the target's within the reference's largest single-code mass.
        const auto refTotal = static_cast<double>(ref.total());
        const auto targetTotal = static_cast<double>(target.total());
        const double code = 1.0 / static_cast<double>(targetCodes - 1);
        std::vector<std::size_t> targetPresent = presentCodes(target);
        double maxRefAtom = 0;
        std::vector<std::pair<double, double>> outputs;  // (value, mass)
        for (std::size_t k : presentCodes(ref)) {
            double mass = static_cast<double>(ref.counts[k]) / refTotal;
            maxRefAtom = std::max(maxRefAtom, mass);
            double out = lut.values[k];
            outputs.push_back({out, mass});
            auto above = std::lower_bound(targetPresent.begin(), targetPresent.end(), out - 1e-6,
                                          [&](std::size_t c, double v) { return target.valueOf(c) < v; });
            REQUIRE(above != targetPresent.end());
            REQUIRE(target.valueOf(*above) - out <= code + 1e-6);
        }
        double targetCdf = 0;
        for (std::size_t m : targetPresent) {
            targetCdf += static_cast<double>(target.counts[m]) / targetTotal;
            double outCdf = 0;
            for (auto [value, mass] : outputs)
                if (value <= target.valueOf(m) + 1e-6) outCdf += mass;
            REQUIRE(std::abs(outCdf - targetCdf) <= maxRefAtom + 1e-6);
        }
    }
}

TEST_CASE("dithering splits reference codes, so coarse references reproduce the target") {
    std::mt19937 rng(5);
    for (int trial = 0; trial < 20; ++trial) {
        // A reference with a few big codes (atoms of ~5-20%), a detailed random target.
        LevelCounts ref;
        ref.counts.assign(256, 0);
        for (int i = 0; i < 8; ++i) ref.counts[rng() % 256] += 1 + rng() % 100;
        LevelCounts target = randomLevels(rng, 256);
        Lut lut = matchLut(ref, target, 65536);
        const double last = 255.0;
        // 200k pixels laid out code by code, each dithered by its own pixel position.
        std::vector<double> outputs;
        const double scale = 200000.0 / static_cast<double>(ref.total());
        std::uint32_t pixel = 0;
        for (std::size_t k = 0; k < 256; ++k)
            for (int n = 0; n < static_cast<int>(static_cast<double>(ref.counts[k]) * scale); ++n, ++pixel) {
                float v = lutInput(static_cast<float>(static_cast<double>(k) / last), pixel % 640, pixel / 640,
                                   static_cast<float>(1 / last));
                outputs.push_back(lutOutput(lut.apply(v), static_cast<float>(1 / last)));
            }
        std::sort(outputs.begin(), outputs.end());
        double targetCdf = 0, worst = 0, worstUndithered = 0;
        Lut onCodes = matchLut(ref, target, 256);
        for (std::size_t m : presentCodes(target)) {
            targetCdf += static_cast<double>(target.counts[m]) / static_cast<double>(target.total());
            double top = (static_cast<double>(m) + 0.5) / last + 1e-7;  // float outputs
            double outCdf =
                static_cast<double>(std::upper_bound(outputs.begin(), outputs.end(), top) - outputs.begin()) /
                static_cast<double>(outputs.size());
            worst = std::max(worst, std::abs(outCdf - targetCdf));
            double plain = 0;
            for (std::size_t k : presentCodes(ref))
                if (onCodes.values[k] <= static_cast<double>(m) / last + 1e-7)
                    plain += static_cast<double>(ref.counts[k]) / static_cast<double>(ref.total());
            worstUndithered = std::max(worstUndithered, std::abs(plain - targetCdf));
        }
        INFO("trial " << trial << ": undithered " << worstUndithered);
        CHECK(worst <= 0.006);
        CHECK(worstUndithered >= 5 * worst);
    }
    // The hash itself: uniform in [-1/2, 1/2) and reproducible.
    double mean = 0;
    for (std::uint32_t i = 0; i < 100000; ++i) {
        float d = ditherOffset(i % 317, i / 317);
        REQUIRE(d >= -0.5f);
        REQUIRE(d < 0.5f);
        mean += d;
    }
    CHECK(std::abs(mean / 100000) < 0.005);
    // Pinned: the shaders (btflutDitherOffset) compute the same hash bit for bit, so a changed
    // hash here would part the CPU's dither from the GPU's.
    CHECK(ditherOffset(3, 4) == doctest::Approx(0.39526981115341187 - 0.5).epsilon(1e-7));
    CHECK(ditherOffset(4, 3) == doctest::Approx(0.047659099102020264 - 0.5).epsilon(1e-7));
    CHECK(ditherOffset(3, 4, 1) == doctest::Approx(0.1428270936012268 - 0.5).epsilon(1e-7));
}

TEST_CASE("blending LUTs stays monotonic and equals each LUT at weight one") {
    std::mt19937 rng(99);
    for (int trial = 0; trial < 500; ++trial) {
        LevelCounts ref = randomLevels(rng, 256);
        Lut a = matchLut(ref, randomLevels(rng, 256), 256);
        Lut b = matchLut(ref, randomLevels(rng, 256), 256);
        const float* luts[] = {a.values.data(), b.values.data()};
        std::vector<float> out(256);
        for (double w : {0.0, 0.1, 0.5, 0.77, 1.0}) {
            double weights[] = {1 - w, w};
            blendLuts(luts, weights, 256, out.data());
            REQUIRE(isValidLut(out.data(), out.size()));
            if (w == 0.0) REQUIRE(std::equal(out.begin(), out.end(), a.values.begin()));
            if (w == 1.0) REQUIRE(std::equal(out.begin(), out.end(), b.values.begin()));
        }
    }
}

TEST_CASE("Lut::apply interpolates linearly between entries like a filtered 1D texture") {
    Lut lut{{0.f, 0.5f, 0.6f}};
    CHECK(lut.apply(0.f) == 0.f);
    CHECK(lut.apply(0.25f) == doctest::Approx(0.25));
    CHECK(lut.apply(0.75f) == doctest::Approx(0.55));
    CHECK(lut.apply(1.f) == doctest::Approx(0.6));
    CHECK(lut.apply(2.f) == doctest::Approx(0.6));  // clamped
}

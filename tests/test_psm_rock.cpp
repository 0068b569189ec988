// Acceptance numbers on real measured data (../shared/data/psm-rock).
#include <doctest/doctest.h>

#include "core/bake/bake.h"
#include "core/bank/bank_file.h"
#include "core/relight/relighter.h"
#include "helpers.h"

using namespace btflut;
using namespace btflut::test;

TEST_CASE("psm-rock: relighting at every measured light reproduces its histogram (L1 <= 0.02)") {
    if (!haveSharedData("psm-rock")) return;
    const std::string root = sharedDataDir() + "/psm-rock";
    auto ds = openDataset(root);
    REQUIRE(ds.ok());
    REQUIRE(ds->images.size() == 12);
    auto bank = bakeBank(*ds, {});
    REQUIRE(bank.ok());
    auto mask = loadDatasetMask(*ds, 512, 340);
    REQUIRE(mask.ok());
    auto l1 = [](const std::vector<double>& a, const std::vector<double>& b) {
        double sum = 0;
        for (std::size_t i = 0; i < a.size(); ++i) sum += std::abs(a[i] - b[i]);
        return sum;
    };
    double worst = 0, worst8 = 0, worstPlain = 0;
    for (const DatasetImage& info : ds->images) {
        auto measured = loadImage(info.path);
        REQUIRE(measured.ok());
        auto target = binHistogram(countGreyLevels(*measured, *mask), 64);
        // The relit image at 16 bits per channel (relight --depth 16), as the renderer
        // computes it; 8-bit output adds the rounding of each channel (reported).
        Image relit = relight(*bank, info.light);
        relit.bitDepth = 16;
        double d = l1(binHistogram(countGreyLevels(relit, *mask), 64), target);
        relit.bitDepth = 8;
        double d8 = l1(binHistogram(countGreyLevels(relit, *mask), 64), target);
        Image plain = relight(*bank, info.light, {}, /*dither=*/false);
        plain.bitDepth = 16;
        double dPlain = l1(binHistogram(countGreyLevels(plain, *mask), 64), target);
        MESSAGE(info.name << ": L1 " << d << " (8-bit output " << d8 << ", undithered " << dPlain << ")");
        worst = std::max(worst, d);
        worst8 = std::max(worst8, d8);
        worstPlain = std::max(worstPlain, dPlain);
        CHECK(d <= 0.02);
        CHECK(bank->lookup(info.light).provenance == Provenance::Measured);
    }
    MESSAGE("psm-rock worst L1 " << worst << " (8-bit output " << worst8 << ", undithered " << worstPlain << ")");
}

TEST_CASE("psm-rock: the bank is at most 1.25x the raw size of one image") {
    if (!haveSharedData("psm-rock")) return;
    auto ds = openDataset(sharedDataDir() + "/psm-rock");
    REQUIRE(ds.ok());
    auto bank = bakeBank(*ds, {});
    REQUIRE(bank.ok());
    const double oneImage = 512.0 * 340 * 3;
    const double with = static_cast<double>(encodeBank(*bank).size());
    const double without = static_cast<double>(encodeBank(*bank, {.embedReference = false}).size());
    MESSAGE("bank with reference " << with << " bytes (" << with / oneImage << "x), without " << without << " ("
                                   << without / oneImage << "x)");
    CHECK(with <= 1.25 * oneImage);
    CHECK(without <= 1.25 * oneImage);
}

TEST_CASE("psm-rock: against the PTM baseline, the LUT wins on histograms, the PTM on pixels") {
    if (!haveSharedData("psm-rock")) return;
    auto ds = openDataset(sharedDataDir() + "/psm-rock");
    REQUIRE(ds.ok());
    auto bank = bakeBank(*ds, {.ptm = true});
    REQUIRE(bank.ok());
    auto mask = loadDatasetMask(*ds, 512, 340);
    REQUIRE(mask.ok());
    double worstLut = 0, worstPtm = 0, pixelLut = 0, pixelPtm = 0;
    for (const DatasetImage& info : ds->images) {
        auto measured = loadImage(info.path);
        REQUIRE(measured.ok());
        const auto target = binHistogram(countGreyLevels(*measured, *mask), 64);
        Image lut = relight(*bank, info.light);
        lut.bitDepth = 16;
        Image ptm = bank->ptm.render(info.light);
        ptm.bitDepth = 16;
        auto l1 = [&](const Image& im) {
            const auto h = binHistogram(countGreyLevels(im, *mask), 64);
            double sum = 0;
            for (std::size_t i = 0; i < h.size(); ++i) sum += std::abs(h[i] - target[i]);
            return sum;
        };
        auto pixels = [&](const Image& im) {  // mean |grey difference| over the sample
            double sum = 0;
            for (std::size_t i = 0; i < im.pixelCount(); ++i)
                if (mask->inside[i]) sum += std::abs(im.grey(i) - measured->grey(i));
            return sum / static_cast<double>(mask->count());
        };
        worstLut = std::max(worstLut, l1(lut));
        worstPtm = std::max(worstPtm, l1(ptm));
        pixelLut = std::max(pixelLut, pixels(lut));
        pixelPtm = std::max(pixelPtm, pixels(ptm));
    }
    MESSAGE("worst histogram L1: LUT " << worstLut << ", PTM " << worstPtm << "; worst mean pixel error: LUT "
                                       << pixelLut << ", PTM " << pixelPtm);
    CHECK(worstLut < worstPtm);
    CHECK(pixelPtm < pixelLut);
}

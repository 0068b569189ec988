// Per-mip LUTs (core/bank/mip_luts.h): level m's LUT applied to level m's block means gives, over
// the texture, the blocks' mean of LUT values, where the plain LUT of the mean does not.
#include <doctest/doctest.h>

#include <cmath>

#include "core/bank/mip_luts.h"
#include "core/histogram/lut.h"
#include "core/predict/predictor.h"

using namespace btflut;

namespace {

// A grey 64 x 64 texture of fine, irregular detail (the shape of rough materials), and a
// steep LUT that clips the darker half to black and the top to white.
Image detailed() {
    Image im(64, 64, 1);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) im.at(x, y, 0) = static_cast<float>((x * 7 + y * 13 + (x * y) % 11) % 100) / 99.f;
    return im;
}

std::vector<float> steepLut(int entries) {
    std::vector<float> lut(static_cast<std::size_t>(entries));
    for (int k = 0; k < entries; ++k)
        lut[static_cast<std::size_t>(k)] =
            std::clamp(2.5f * static_cast<float>(k) / static_cast<float>(entries - 1) - 1.f, 0.f, 1.f);
    return lut;
}

}  // namespace

TEST_CASE("per-mip LUTs give a mip level the brightness of its blocks' LUT values") {
    const Image image = detailed();
    constexpr int kEntries = 256;
    const MipLuts mips(image, ColourMode::Grey, kEntries);
    REQUIRE(mips.levels() == 7);  // 64 .. 1
    const std::vector<float> lut = steepLut(kEntries);
    std::vector<float> perLevel(static_cast<std::size_t>(mips.levels()) * kEntries);
    mips.apply(0, lut.data(), perLevel.data());
    CHECK(std::equal(lut.begin(), lut.end(), perLevel.begin()));  // level 0 is the LUT itself
    // A level's LUT is the expected mean of LUT values over the blocks with that mean: the
    // blocks' statistics (their mean over the texture: brightness) come out right, which the
    // plain LUT of the mean misses; each block's own value still varies around it.
    for (int level : {1, 2, 3, 4}) {
        const int block = 1 << level;
        double mip = 0, plain = 0, truth = 0;
        int blocks = 0;
        for (int by = 0; by < 64; by += block)
            for (int bx = 0; bx < 64; bx += block) {
                double mean = 0;
                for (int y = by; y < by + block; ++y)
                    for (int x = bx; x < bx + block; ++x) {
                        mean += image.at(x, y, 0);
                        truth += Lut::applyLut(lut.data(), kEntries, image.at(x, y, 0)) / (block * block);
                    }
                mean /= block * block;
                mip += Lut::applyLut(&perLevel[static_cast<std::size_t>(level) * kEntries], kEntries,
                                     static_cast<float>(mean));
                plain += Lut::applyLut(lut.data(), kEntries, static_cast<float>(mean));
                ++blocks;
            }
        mip /= blocks;
        plain /= blocks;
        truth /= blocks;
        INFO("level " << level << ": mean of the blocks' LUT values " << truth * 255 << "/255; per-mip LUT "
                      << mip * 255 << "/255, the plain LUT of the mean " << plain * 255 << "/255");
        CHECK(std::abs(mip - truth) < 1.0 / 255);
        CHECK(std::abs(plain - truth) > 5 * std::abs(mip - truth));
    }
}

TEST_CASE("per-mip LUTs of the identity stay the identity where blocks have that mean; 16-bit LUTs are resampled") {
    const Image image = detailed();
    for (int entries : {256, 1024}) {
        const MipLuts mips(image, ColourMode::Grey, entries);
        std::vector<float> identity(static_cast<std::size_t>(entries));
        for (int k = 0; k < entries; ++k)
            identity[static_cast<std::size_t>(k)] = static_cast<float>(k) / static_cast<float>(entries - 1);
        std::vector<float> perLevel(static_cast<std::size_t>(mips.levels()) * static_cast<std::size_t>(entries));
        mips.apply(0, identity.data(), perLevel.data());
        // Level 1's block means span the middle of the range: there E[x | mean v] = v.
        for (float v : {0.4f, 0.5f, 0.6f}) {
            const float out = Lut::applyLut(&perLevel[static_cast<std::size_t>(entries)], entries, v);
            INFO(entries << " entries, v " << v);
            CHECK(std::abs(out - v) < 2.0f / 255);
        }
        // Means no block has fall back to the plain LUT.
        CHECK(std::abs(Lut::applyLut(&perLevel[static_cast<std::size_t>(entries) * 4], entries, 0.02f) - 0.02f) <
              1e-3f);
    }
}

TEST_CASE("per-mip LUTs of an rgb bank have a matrix per channel") {
    Image rgb(16, 8, 3);
    for (std::size_t i = 0; i < rgb.samples.size(); ++i) rgb.samples[i] = static_cast<float>((i * 37) % 101) / 100.f;
    CHECK(MipLuts(rgb, ColourMode::Rgb, 64).channels() == 3);
    CHECK(MipLuts(rgb, ColourMode::Grey, 64).channels() == 1);
    CHECK(MipLuts(rgb, ColourMode::Grey, 64).levels() == 5);  // 16x8, 8x4, 4x2, 2x1, 1x1
}

TEST_CASE("a predictor's planes at a mip level: each texel its square's mean, rounded half up, clipped at odd edges") {
    CHECK(levelCount(320, 320) == 9);  // 320 160 80 40 20 10 5 2 1
    CHECK(levelCount(5, 3) == 3);
    CHECK(levelCount(1, 1) == 1);
    CHECK(levelSize(5, 1) == 2);
    CHECK(levelSize(5, 4) == 1);
    // 5 x 3 at level 1 is 2 x 1: the squares at x 0-1 and 2-3 of rows 0-1 (column 4 and row 2 left out).
    CHECK(levelBlock(1, 5, 3, 0) == std::vector<std::uint32_t>{0, 1, 5, 6});
    CHECK(levelBlock(1, 5, 3, 1) == std::vector<std::uint32_t>{2, 3, 7, 8});
    // A square past the image's edge (level 2 of 3 rows is 1 x 1) keeps the texels inside.
    CHECK(levelBlock(2, 5, 3, 0) == std::vector<std::uint32_t>{0, 1, 2, 3, 5, 6, 7, 8, 10, 11, 12, 13});
    const std::vector<std::uint8_t> bytes{0, 1, 2, 3, 10, 20, 30, 40};            // 2 x 2, two channels
    CHECK(levelOfBytes(bytes, 2, 2, 2, 1) == std::vector<std::uint8_t>{11, 16});  // 10.5 -> 11, 16 -> 16
    CHECK(meanByte(3, 2) == 2);                                                   // 1.5 rounds up
    CHECK(meanByte(5, 4) == 1);                                                   // 1.25 rounds down
}

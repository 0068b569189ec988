#include <doctest/doctest.h>

#include "core/image/image.h"
#include "helpers.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

using namespace btflut;
using namespace btflut::test;

namespace {
// Test fixtures in the formats stb_image_write makes (btflut itself only writes PNG).
std::vector<std::uint8_t> rgbBytes(int w, int h) {
    std::vector<std::uint8_t> px(static_cast<std::size_t>(w) * h * 3);
    for (std::size_t i = 0; i < px.size(); ++i) px[i] = static_cast<std::uint8_t>((i * 37) % 251);
    return px;
}
}  // namespace

TEST_CASE("PNG round trip at 8 and 16 bits, grey and RGB") {
    TempDir dir;
    Image rgb(5, 3, 3, 16);
    for (std::size_t i = 0; i < rgb.samples.size(); ++i)
        rgb.samples[i] = static_cast<float>((i * 4099) % 65536) / 65535.f;
    REQUIRE(savePng(rgb, dir / "a16.png", 16).ok());
    auto back = loadImage(dir / "a16.png");
    REQUIRE(back.ok());
    CHECK(back->bitDepth == 16);
    CHECK(back->channels == 3);
    for (std::size_t i = 0; i < rgb.samples.size(); ++i)
        CHECK(std::lround(back->samples[i] * 65535.f) == std::lround(rgb.samples[i] * 65535.f));

    Image grey = randomGreyImage(7, 4, 1);
    REQUIRE(savePng(grey, dir / "g8.png", 8).ok());
    auto g = loadImage(dir / "g8.png");
    REQUIRE(g.ok());
    CHECK(g->channels == 1);
    CHECK(g->bitDepth == 8);
    for (std::size_t i = 0; i < grey.samples.size(); ++i)
        CHECK(std::lround(g->samples[i] * 255) == std::lround(grey.samples[i] * 255));
}

TEST_CASE("TGA, BMP and JPEG load; RGBA drops alpha; truncated files are refused") {
    TempDir dir;
    const int w = 16, h = 12;
    auto px = rgbBytes(w, h);
    REQUIRE(stbi_write_tga((dir / "a.tga").c_str(), w, h, 3, px.data()));
    REQUIRE(stbi_write_bmp((dir / "a.bmp").c_str(), w, h, 3, px.data()));
    REQUIRE(stbi_write_jpg((dir / "a.jpg").c_str(), w, h, 3, px.data(), 95));
    std::vector<std::uint8_t> rgba(static_cast<std::size_t>(w) * h * 4, 200);
    REQUIRE(stbi_write_png((dir / "rgba.png").c_str(), w, h, 4, rgba.data(), w * 4));
    stbi_write_tga_with_rle = 0;
    REQUIRE(stbi_write_tga((dir / "raw.tga").c_str(), w, h, 3, px.data()));

    for (const char* name : {"a.bmp", "raw.tga"}) {
        auto im = loadImage(dir / name);
        REQUIRE(im.ok());
        CHECK(im->width == w);
        CHECK(im->channels == 3);
        CHECK(std::lround(im->samples[5] * 255) == px[5]);
    }
    CHECK(loadImage(dir / "a.jpg")->height == h);
    CHECK(loadImage(dir / "rgba.png")->channels == 3);

    for (std::string name : {"raw.tga", "a.bmp", "a.jpg", "rgba.png"}) {
        std::string bytes = readText(dir / name);
        for (std::size_t keep : {bytes.size() - 1, bytes.size() - 9, bytes.size() / 2, std::size_t{10}}) {
            std::string path = dir / ("cut-" + std::to_string(keep) + "-" + name);
            std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(keep));
            auto r = loadImage(path);
            INFO(name << " cut to " << keep);
            REQUIRE_FALSE(r.ok());
            CHECK(r.error().find(path) == 0);
        }
    }
}

TEST_CASE("missing and non-image files are refused with the file's name") {
    TempDir dir;
    auto missing = loadImage(dir / "nope.png");
    REQUIRE_FALSE(missing.ok());
    CHECK(missing.error().find("nope.png: cannot open") != std::string::npos);
    std::ofstream(dir / "text.png") << "hello, not a png at all, just text here";
    auto text = loadImage(dir / "text.png");
    REQUIRE_FALSE(text.ok());
    CHECK(text.error().find("text.png") != std::string::npos);
}

TEST_CASE("masks must match the image size and hold at least one sample pixel") {
    TempDir dir;
    Image zero(4, 4, 1), some(4, 4, 1);
    some.samples[5] = 1;
    REQUIRE(savePng(zero, dir / "zero.png").ok());
    REQUIRE(savePng(some, dir / "some.png").ok());
    auto ok = loadMask(dir / "some.png", 4, 4);
    REQUIRE(ok.ok());
    CHECK(ok->count() == 1);
    auto empty = loadMask(dir / "zero.png", 4, 4);
    REQUIRE_FALSE(empty.ok());
    CHECK(empty.error().find("no sample pixels") != std::string::npos);
    auto size = loadMask(dir / "some.png", 5, 4);
    REQUIRE_FALSE(size.ok());
    CHECK(size.error().find("4x4 but the images are 5x4") != std::string::npos);
}

TEST_CASE("the largest rectangle inside a mask") {
    Mask mask{8, 6, std::vector<std::uint8_t>(48, 0)};
    CHECK(largestRectInside(mask) == PixelRect{});  // empty
    auto set = [&](int x0, int y0, int x1, int y1) {
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) mask.inside[static_cast<std::size_t>(y) * 8 + x] = 1;
    };
    set(1, 1, 4, 5);  // 3 x 4 = 12
    set(4, 2, 8, 4);  // 4 x 2 beside it: together 7 x 2 = 14 at rows 2-3
    CHECK(largestRectInside(mask) == PixelRect{1, 2, 7, 2});
    set(4, 1, 8, 5);  // now a 7 x 4 block
    CHECK(largestRectInside(mask) == PixelRect{1, 1, 7, 4});
    std::fill(mask.inside.begin(), mask.inside.end(), 1);
    CHECK(largestRectInside(mask) == PixelRect{0, 0, 8, 6});
}

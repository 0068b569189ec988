#pragma once
// Every parser of files btflut reads, as a function of raw bytes that says whether the
// input was accepted: the libFuzzer targets (fuzz_main.cpp, built by tools/fuzz.sh) and the
// regression test over the inputs that fuzzing and audits found (test_fuzz_regressions.cpp)
// call the same functions. For any input a parser must give a value or an error; anything
// else (a crash, a sanitizer report, an exception, a hang) is a finding.

#include <cstdint>
#include <string>
#include <string_view>

#include "core/bank/bank_file.h"
#include "core/data/dataset.h"
#include "core/data/scene.h"
#include "core/histogram/histogram.h"
#include "core/image/image.h"
#include "core/physics/model_bank.h"
#include "core/relight/relighter.h"

namespace btflut::fuzz {

inline std::string text(const std::uint8_t* data, std::size_t size) {
    return {reinterpret_cast<const char*>(data), size};
}

// A decoded bank is also used: lookups and re-encoding must work on anything the reader accepts.
inline bool bank(const std::uint8_t* data, std::size_t size) {
    Result<LutBank> b = decodeBank(Bytes(data, data + size), "fuzz.btflut");
    if (!b) return false;
    for (double theta : {0.0, 40.0, 85.0})
        for (double phi : {0.0, 135.0}) {
            const BankLookup lut =
                b->lookup(Direction::fromDegrees(theta, phi), Direction::fromDegrees(theta / 2, phi));
            // A blend of valid LUTs (or quantile functions) is valid.
            for (std::size_t at = 0; at < lut.values.size(); at += b->segmentLength())
                BTFLUT_CHECK(isValidLut(&lut.values[at], b->segmentLength()));
            b->lookup(Direction::fromDegrees(theta, phi), b->referenceView, false);
        }
    b->lightCoverage(0);
    if (b->makesLuts()) {  // relighting from what the file holds: blend, count, match, apply
        const Relighter relighter(*b);
        BTFLUT_CHECK(relighter.apply(relighter.frame(Direction::fromDegrees(25, 40)), true).pixelCount() ==
                     b->reference.pixelCount());
    }
    // The views option decodes some layers only.
    Result<LutBank> some = decodeBank(Bytes(data, data + size), "fuzz.btflut",
                                      {.ptm = false, .grids = false, .views = {Direction::fromDegrees(30, 10)}});
    BTFLUT_CHECK(some.ok());
    BTFLUT_CHECK(decodeBank(encodeBank(*b), "again.btflut").ok());
    return true;
}

inline bool image(const std::uint8_t* data, std::size_t size) {
    // Keep the fuzzer's own memory small: 4 Mpixel is plenty to reach every decoder path.
    const std::uint64_t limit = maxImagePixels();
    setMaxImagePixels(std::uint64_t{1} << 22);
    Result<Image> im = decodeImage(Bytes(data, data + size), "fuzz");
    setMaxImagePixels(limit);
    if (im) BTFLUT_CHECK(im->samples.size() == im->pixelCount() * static_cast<std::size_t>(im->channels));
    return im.ok();
}

inline bool lp(const std::uint8_t* data, std::size_t size) {
    return parseLpFile(text(data, size), "fuzz.lp", ".").ok();
}

inline bool lights(const std::uint8_t* data, std::size_t size) {
    return parseLightsTxt(text(data, size), "lights.txt").ok();
}

inline bool manifest(const std::uint8_t* data, std::size_t size) {
    return parseManifest(text(data, size), "btflut-dataset.json", ".").ok();
}

inline bool scene(const std::uint8_t* data, std::size_t size) {
    Result<Scene> s = parseScene(text(data, size), "scene.json", ".");
    if (!s) return false;
    visibleQuads(*s);
    BTFLUT_CHECK(parseScene(sceneToJson(*s), "again.json", ".").ok());
    return true;
}

inline bool histograms(const std::uint8_t* data, std::size_t size) {
    return parseHistogramCsv(text(data, size), "h.csv").ok();
}

inline bool params(const std::uint8_t* data, std::size_t size) {
    return parseModelParams(text(data, size), "p.json").ok();
}

// Names as flags and files spell them: Bonn image names and THETA,PHI directions.
inline bool names(const std::uint8_t* data, std::size_t size) {
    const std::string s = text(data, size);
    const bool bonn = parseBonnName(s, ".").ok();
    return parseDirection(s, "--light").ok() || bonn;
}

struct Target {
    std::string_view name;
    bool (*accepts)(const std::uint8_t*, std::size_t);
};

inline constexpr Target kTargets[] = {
    {"bank", bank},   {"image", image},           {"lp", lp},         {"lights", lights}, {"manifest", manifest},
    {"scene", scene}, {"histograms", histograms}, {"params", params}, {"names", names}};

}  // namespace btflut::fuzz

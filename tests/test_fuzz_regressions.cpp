// Every input that fuzzing or the hardening audit found, through the same parser functions
// the fuzz targets call (tests/fuzz/fuzz_targets.h): refused with an error (files named
// valid-* must be accepted), never a crash, and clean under tools/test.sh --sanitize.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "fuzz/fuzz_targets.h"
#include "helpers.h"

using namespace btflut;
using namespace btflut::test;

TEST_CASE("fuzz and audit regressions: every input is refused or accepted as its name says") {
    const fs::path root = fs::path(BTFLUT_SOURCE_DIR) / "tests" / "fuzz" / "regressions";
    std::size_t files = 0;
    for (const fuzz::Target& target : fuzz::kTargets) {
        const fs::path folder = root / std::string(target.name);
        if (!fs::exists(folder)) continue;
        for (const auto& entry : fs::directory_iterator(folder)) {
            const std::string bytes = readText(entry.path().string());
            const bool valid = entry.path().filename().string().rfind("valid-", 0) == 0;
            INFO(target.name << ": " << entry.path().filename().string());
            CHECK(target.accepts(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()) == valid);
            ++files;
        }
    }
    CHECK(files >= 25);
}

TEST_CASE("JSON nested 200000 deep is one error, not a stack overflow") {
    const std::string deep = "{\"images\": " + std::string(200000, '[') + std::string(200000, ']') + "}";
    auto r = parseManifest(deep, "deep.json", ".");
    REQUIRE_FALSE(r.ok());
    CHECK(r.error() == "deep.json: not valid JSON (nested deeper than 64 levels)");
    CHECK_FALSE(parseScene(deep, "deep.json", ".").ok());
}

namespace {
// A bank of one layer with `nodes` light directions on a spiral (entries 2, grid 2).
Bytes spiralBank(std::size_t nodes) {
    LutBank bank;
    bank.entries = 2;
    bank.gridSize = 2;
    bank.reference = Image(4, 4, 1);
    std::vector<DirectionalLut> luts;
    for (std::size_t n = 0; n < nodes; ++n) {
        const double z = 1 - 0.99 * (static_cast<double>(n) + 0.5) / static_cast<double>(nodes);
        luts.push_back(
            {"",
             Direction{std::acos(z), std::fmod(2.39996322972865332 * static_cast<double>(n), 2 * std::numbers::pi)},
             {},
             {0.f, 1.f}});
    }
    REQUIRE(setNodes(bank, luts, {}, "spiral").ok());
    return encodeBank(bank);
}
}  // namespace

TEST_CASE("a bank of 8000 light directions loads (O(n log n) checks); over the node limit is refused") {
    const Bytes many = spiralBank(8000);
    auto bank = decodeBank(many, "many.btflut");
    REQUIRE(bank.ok());
    CHECK(bank->layers[0].nodes.size() == 8000);
    CHECK(bank->lookup(Direction::fromDegrees(30, 40)).provenance == Provenance::Interpolated);
    CHECK(bank->lightCoverage(0) > 0.9);

    LutBank tooMany;
    tooMany.layers.resize(1);
    tooMany.layers[0].nodes.resize(kMaxBankNodes + 1);
    CHECK(checkBankSize(tooMany).error().find("over the format's limit of 65536") != std::string::npos);
}

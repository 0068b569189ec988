#include "core/predict/ptm_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/check.h"
#include "core/predict/ptm.h"

namespace btflut {

namespace {

// Rows of per-pixel records (bytes each), bottom row first.
void putFlipped(Bytes& out, const std::vector<std::uint8_t>& records, int width, int height, std::size_t bytes) {
    for (int row = height - 1; row >= 0; --row) {
        const auto* begin = records.data() + static_cast<std::size_t>(row) * width * bytes;
        out.insert(out.end(), begin, begin + static_cast<std::size_t>(width) * bytes);
    }
}

}  // namespace

Bytes encodePtmFile(const LightModel& ptm) {
    BTFLUT_CHECK(ptm.basis == LightBasis::Ptm && ptm.planes == kPtmTerms && !ptm.albedo.empty());
    std::array<long, kPtmTerms> bias{};
    std::array<double, kPtmTerms> shift{};
    for (int k = 0; k < kPtmTerms; ++k) {
        bias[k] = std::lround(ptm.bias[k]);
        shift[k] = static_cast<double>(bias[k]) - ptm.bias[k];
    }
    std::string header =
        "PTM_1.2\nPTM_FORMAT_LRGB\n" + std::to_string(ptm.width) + "\n" + std::to_string(ptm.height) + "\n";
    char number[32];
    for (int k = 0; k < kPtmTerms; ++k) {
        std::snprintf(number, sizeof number, "%.9g%s", 255.0 * ptm.scale[k], k + 1 < kPtmTerms ? " " : "\n");
        header += number;
    }
    for (int k = 0; k < kPtmTerms; ++k) header += std::to_string(bias[k]) + (k + 1 < kPtmTerms ? " " : "\n");
    std::vector<std::uint8_t> coefficients(ptm.coefficients.size());
    for (std::size_t i = 0; i < coefficients.size(); ++i)
        coefficients[i] = static_cast<std::uint8_t>(
            std::clamp<long>(std::lround(ptm.coefficients[i] + shift[i % kPtmTerms]), 0, 255));
    Bytes out(header.begin(), header.end());
    putFlipped(out, coefficients, ptm.width, ptm.height, kPtmTerms);
    putFlipped(out, ptm.albedo, ptm.width, ptm.height, 3);
    return out;
}

Result<LightModel> decodePtmFile(const Bytes& bytes, const std::string& name) {
    auto fail = [&](const std::string& what) { return Error{name + ": " + what}; };
    // The header: whitespace-separated words after two lines.
    std::size_t pos = 0;
    auto word = [&]() {
        while (pos < bytes.size() && std::isspace(bytes[pos])) ++pos;
        const std::size_t start = pos;
        while (pos < bytes.size() && !std::isspace(bytes[pos]) && pos - start < 64) ++pos;
        return std::string(bytes.begin() + static_cast<std::ptrdiff_t>(start),
                           bytes.begin() + static_cast<std::ptrdiff_t>(pos));
    };
    if (word() != "PTM_1.2") return fail("not a PTM 1.2 file");
    if (const std::string format = word(); format != "PTM_FORMAT_LRGB")
        return fail("format '" + format + "' is not PTM_FORMAT_LRGB (the only one btflut reads)");
    LightModel ptm = ptmShell(0, 0);  // its size from the header below
    auto integer = [&](const std::string& what, long low, long high) -> Result<long> {
        const std::string w = word();
        char* end = nullptr;
        const long v = std::strtol(w.c_str(), &end, 10);
        if (w.empty() || *end != '\0' || v < low || v > high) return fail("invalid " + what + " '" + w + "'");
        return v;
    };
    Result<long> width = integer("width", 1, 1 << 16), height = integer("height", 1, 1 << 16);
    if (!width) return Error{width.error()};
    if (!height) return Error{height.error()};
    ptm.width = static_cast<int>(*width);
    ptm.height = static_cast<int>(*height);
    for (int k = 0; k < kPtmTerms; ++k) {
        const std::string w = word();
        char* end = nullptr;
        const double scale = std::strtod(w.c_str(), &end);
        if (w.empty() || *end != '\0' || !std::isfinite(scale) || scale <= 0) return fail("invalid scale '" + w + "'");
        ptm.scale[k] = static_cast<float>(scale / 255);
    }
    for (int k = 0; k < kPtmTerms; ++k) {
        Result<long> bias = integer("bias", -(1L << 30), 1L << 30);
        if (!bias) return Error{bias.error()};
        ptm.bias[k] = static_cast<float>(*bias);
    }
    if (pos >= bytes.size() || bytes[pos] != '\n') return fail("the header does not end in a newline");
    ++pos;
    const std::size_t texels = ptm.texels();
    if (bytes.size() - pos != texels * 9)
        return fail("holds " + std::to_string(bytes.size() - pos) + " bytes of data, not the " +
                    std::to_string(texels * 9) + " a " + std::to_string(ptm.width) + "x" + std::to_string(ptm.height) +
                    " LRGB PTM needs");
    auto flipped = [&](std::size_t offset, std::size_t record) {
        std::vector<std::uint8_t> out(texels * record);
        const std::size_t rowBytes = static_cast<std::size_t>(ptm.width) * record;
        for (int row = 0; row < ptm.height; ++row)
            std::copy_n(bytes.begin() + static_cast<std::ptrdiff_t>(
                                            offset + static_cast<std::size_t>(ptm.height - 1 - row) * rowBytes),
                        rowBytes, out.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(row) * rowBytes));
        return out;
    };
    ptm.coefficients = flipped(pos, kPtmTerms);
    ptm.albedo = flipped(pos + texels * kPtmTerms, 3);
    return ptm;
}

}  // namespace btflut

#include "core/histogram/histogram.h"
#include "core/io/json_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

namespace btflut {

std::uint64_t LevelCounts::total() const {
    std::uint64_t sum = 0;
    for (std::uint64_t c : counts) sum += c;
    return sum;
}

namespace {
// Integer code of a sample: the float holds code / maxCode exactly enough to round back.
inline std::uint32_t codeOf(float v, float maxCode) { return static_cast<std::uint32_t>(v * maxCode + 0.5f); }
}  // namespace

std::size_t LevelCounts::presentCodes() const {
    return static_cast<std::size_t>(std::count_if(counts.begin(), counts.end(), [](std::uint64_t c) { return c > 0; }));
}

LevelCounts countGreyLevels(const Image& image, const Mask& mask) {
    BTFLUT_CHECK(mask.inside.size() == image.pixelCount());
    const auto maxCode = static_cast<float>(image.maxCode());
    LevelCounts levels;
    levels.counts.assign(static_cast<std::size_t>(image.channels) * image.maxCode() + 1, 0);
    const float* s = image.samples.data();
    const std::uint8_t* in = mask.inside.data();
    const std::size_t n = image.pixelCount();
    if (image.channels == 1) {
        for (std::size_t i = 0; i < n; ++i)
            if (in[i]) ++levels.counts[codeOf(s[i], maxCode)];
    } else {
        for (std::size_t i = 0; i < n; ++i, s += 3)
            if (in[i]) ++levels.counts[codeOf(s[0], maxCode) + codeOf(s[1], maxCode) + codeOf(s[2], maxCode)];
    }
    return levels;
}

LevelCounts countChannelLevels(const Image& image, const Mask& mask, int channel) {
    BTFLUT_CHECK(mask.inside.size() == image.pixelCount());
    BTFLUT_CHECK(channel >= 0 && channel < image.channels);
    const auto maxCode = static_cast<float>(image.maxCode());
    LevelCounts levels;
    levels.counts.assign(static_cast<std::size_t>(image.maxCode()) + 1, 0);
    const std::size_t n = image.pixelCount();
    const auto stride = static_cast<std::size_t>(image.channels);
    for (std::size_t i = 0; i < n; ++i)
        if (mask.inside[i]) ++levels.counts[codeOf(image.samples[i * stride + channel], maxCode)];
    return levels;
}

std::vector<double> binValues(std::span<const float> values, std::span<const double> weights, int bins) {
    BTFLUT_CHECK(bins >= 1 && (weights.empty() || weights.size() == values.size()));
    std::vector<double> h(static_cast<std::size_t>(bins), 0.0);
    double total = 0;
    for (std::size_t k = 0; k < values.size(); ++k) {
        const double w = weights.empty() ? 1.0 : weights[k];
        const int b = std::min(static_cast<int>(std::clamp(values[k], 0.f, 1.f) * static_cast<float>(bins)), bins - 1);
        h[static_cast<std::size_t>(b)] += w;
        total += w;
    }
    if (total > 0)
        for (double& v : h) v /= total;
    return h;
}

std::vector<double> binHistogram(const LevelCounts& levels, int bins) {
    BTFLUT_CHECK(bins >= 1 && levels.counts.size() >= 2);
    std::vector<double> h(static_cast<std::size_t>(bins), 0.0);
    const std::uint64_t last = levels.counts.size() - 1;
    const std::uint64_t total = levels.total();
    if (total == 0) return h;
    for (std::uint64_t k = 0; k <= last; ++k) {
        // Bin of value k / last, computed exactly in integers: floor(k * bins / last).
        std::uint64_t b =
            std::min<std::uint64_t>(k * static_cast<std::uint64_t>(bins) / last, static_cast<std::uint64_t>(bins) - 1);
        h[b] += static_cast<double>(levels.counts[k]);
    }
    for (double& v : h) v /= static_cast<double>(total);
    return h;
}

namespace {
std::string number(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}
}  // namespace

std::vector<HistogramRow> imageHistograms(const Image& image, const Mask& mask, const std::string& name,
                                          Direction light, Direction view, int bins, bool rgb) {
    if (!rgb) return {{name, light, view, binHistogram(countGreyLevels(image, mask), bins)}};
    std::vector<HistogramRow> rows;
    for (int c = 0; c < 3; ++c)
        rows.push_back({name + ":" + "RGB"[c], light, view, binHistogram(countChannelLevels(image, mask, c), bins)});
    return rows;
}

std::string histogramsToCsv(const std::vector<HistogramRow>& rows) {
    std::string out = "name,theta_i,phi_i,theta_r,phi_r";
    std::size_t bins = rows.empty() ? 0 : rows.front().bins.size();
    for (std::size_t b = 0; b < bins; ++b) {
        out += ",b";
        out += std::to_string(b);
    }
    out += '\n';
    for (const HistogramRow& row : rows) {
        BTFLUT_CHECK(row.bins.size() == bins);
        out += row.name;
        for (double a :
             {row.light.thetaDegrees(), row.light.phiDegrees(), row.view.thetaDegrees(), row.view.phiDegrees()})
            (out += ',') += number(a);
        for (double v : row.bins) (out += ',') += number(v);
        out += '\n';
    }
    return out;
}

std::string histogramsToJson(const std::vector<HistogramRow>& rows) {
    nlohmann::json doc;
    doc["bins"] = rows.empty() ? 0 : rows.front().bins.size();
    doc["histograms"] = nlohmann::json::array();
    for (const HistogramRow& row : rows)
        doc["histograms"].push_back({{"name", row.name},
                                     {"theta_i", row.light.thetaDegrees()},
                                     {"phi_i", row.light.phiDegrees()},
                                     {"theta_r", row.view.thetaDegrees()},
                                     {"phi_r", row.view.phiDegrees()},
                                     {"values", row.bins}});
    return jsonText(doc);
}

Status saveHistograms(const std::vector<HistogramRow>& rows, const std::string& path) {
    return writeFileAtomically(path, fileExtension(path) == "csv" ? histogramsToCsv(rows) : histogramsToJson(rows));
}

Result<std::vector<HistogramRow>> parseHistogramCsv(const std::string& text, const std::string& file) {
    std::istringstream in(text);
    std::string line;
    auto split = [](const std::string& s) {
        std::vector<std::string> fields;
        std::string field;
        std::istringstream fs(s);
        while (std::getline(fs, field, ',')) fields.push_back(field);
        if (!s.empty() && s.back() == ',') fields.emplace_back();
        return fields;
    };
    if (!std::getline(in, line)) return Error{file + ": empty file, expected a CSV header"};
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::vector<std::string> header = split(line);
    const char* fixed[] = {"name", "theta_i", "phi_i", "theta_r", "phi_r"};
    bool headerOk = header.size() >= 7;
    for (std::size_t i = 0; headerOk && i < 5; ++i) headerOk = header[i] == fixed[i];
    for (std::size_t i = 5; headerOk && i < header.size(); ++i)
        headerOk = header[i].size() > 1 && header[i][0] == 'b' &&
                   header[i].compare(1, std::string::npos, std::to_string(i - 5)) == 0;
    if (!headerOk) return Error{file + ":1: expected header name,theta_i,phi_i,theta_r,phi_r,b0,b1,..."};
    const std::size_t bins = header.size() - 5;
    std::vector<HistogramRow> rows;
    for (int lineNo = 2; std::getline(in, line); ++lineNo) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty()) continue;
        std::string where = file + ":" + std::to_string(lineNo);
        std::vector<std::string> f = split(line);
        if (f.size() != header.size())
            return Error{where + ": " + std::to_string(f.size()) + " fields, header has " +
                         std::to_string(header.size())};
        std::vector<double> values;
        for (std::size_t i = 1; i < f.size(); ++i) {
            char* end = nullptr;
            double v = std::strtod(f[i].c_str(), &end);
            if (f[i].empty() || *end != '\0' || !std::isfinite(v))
                return Error{where + ": field " + header[i] + " '" + f[i] + "' is not a finite number"};
            if (i >= 5 && v < 0) return Error{where + ": negative bin " + header[i]};
            values.push_back(v);
        }
        HistogramRow row;
        row.name = f[0];
        row.light = Direction::fromDegrees(values[0], values[1]);
        row.view = Direction::fromDegrees(values[2], values[3]);
        row.bins.assign(values.begin() + 4, values.end());
        BTFLUT_CHECK(row.bins.size() == bins);
        rows.push_back(std::move(row));
    }
    return rows;
}

double earthMoversDistance(const std::vector<double>& a, const std::vector<double>& b) {
    BTFLUT_CHECK(a.size() == b.size() && !a.empty());
    double ca = 0, cb = 0, sum = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        ca += a[i];
        cb += b[i];
        sum += std::abs(ca - cb);
    }
    return sum / static_cast<double>(a.size());
}

}  // namespace btflut

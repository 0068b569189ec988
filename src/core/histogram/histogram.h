#pragma once
// Grey-level statistics of images: exact counts per integer code, binned normalised
// histograms, and the histogram table (CSV/JSON) that `btflut hist` and `simulate` share.
//
//   LevelCounts grey = countGreyLevels(image, mask);      // exact, for LUT matching
//   std::vector<double> h = binHistogram(grey, 64);       // normalised, sums to 1
//
// Codes are exact: the grey value of an 8-bit RGB pixel is (R + G + B) / 765, so grey has
// 766 codes; one 8-bit channel has 256; 16-bit sources keep their 65536 (x3) codes.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/direction/direction.h"
#include "core/image/image.h"

namespace btflut {

/// How many pixels (of the mask) fall on each code; the value of code k is
/// k / (counts.size() - 1).
struct LevelCounts {
    std::vector<std::uint64_t> counts;
    std::uint64_t total() const;
    /// Number of codes with at least one pixel (below 2: a constant image).
    std::size_t presentCodes() const;
    double valueOf(std::size_t code) const {
        return static_cast<double>(code) / static_cast<double>(counts.size() - 1);
    }
};

/// Counts of the grey value (mean of R, G, B) over the mask's sample pixels.
LevelCounts countGreyLevels(const Image& image, const Mask& mask);

/// Counts of one channel (0 = R, 1 = G, 2 = B; grey images have only channel 0).
LevelCounts countChannelLevels(const Image& image, const Mask& mask, int channel);

/// Normalised histogram with `bins` equal bins over [0, 1] (value 1 falls in the last).
/// Empty counts give all-zero bins.
std::vector<double> binHistogram(const LevelCounts& levels, int bins);

/// Normalised histogram with `bins` equal bins over [0, 1] of `values` (clamped to it; 1 falls
/// in the last), each weighing its `weights` entry, or alike where `weights` is empty: a
/// quantile function's samples, or a LUT's entries weighed by the reference's share there.
std::vector<double> binValues(std::span<const float> values, std::span<const double> weights, int bins);

/// One histogram with the directions it belongs to.
struct HistogramRow {
    std::string name;
    Direction light;
    Direction view;
    std::vector<double> bins;
};

/// One image's rows over a mask: the grey value's histogram named `name`, or (rgb; a colour
/// image) one per channel named NAME:R, NAME:G, NAME:B; `bins` normalised bins each.
std::vector<HistogramRow> imageHistograms(const Image& image, const Mask& mask, const std::string& name,
                                          Direction light, Direction view, int bins, bool rgb);

/// CSV exactly as documented: header name,theta_i,phi_i,theta_r,phi_r,b0,...,b{N-1}, one
/// row per histogram, angles in degrees, values with 17 significant digits.
std::string histogramsToCsv(const std::vector<HistogramRow>& rows);

/// JSON: {"bins": N, "histograms": [{"name", "theta_i", "phi_i", "theta_r", "phi_r",
/// "values": [...]}]}.
std::string histogramsToJson(const std::vector<HistogramRow>& rows);

/// Writes histograms atomically as CSV or JSON, chosen by the extension of `path`.
Status saveHistograms(const std::vector<HistogramRow>& rows, const std::string& path);

/// Reads the CSV form back; `file` names the source in errors. Rows must all have the
/// header's bin count and finite, non-negative values.
Result<std::vector<HistogramRow>> parseHistogramCsv(const std::string& text, const std::string& file);

/// Earth mover's distance between two normalised histograms on [0, 1] (equal bins): the L1
/// distance of their cumulative sums times the bin width.
double earthMoversDistance(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace btflut

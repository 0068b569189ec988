#include "core/eval/holdout.h"

#include <algorithm>
#include <charconv>
#include <numbers>
#include <sstream>

#include "core/io/file_io.h"

namespace btflut {

namespace {

// Angles as rows.csv prints them (two decimals) name their image.
constexpr double kPairToleranceDegrees = 0.01;

// The image a held-out line names: by name or path, or by its light and view as
// THETA_I,PHI_I,THETA_R,PHI_R in degrees. `where` is FILE:LINE for the error.
Result<std::size_t> heldImage(const Dataset& dataset, const std::string& line, const std::string& where) {
    auto named = std::find_if(dataset.images.begin(), dataset.images.end(),
                              [&](const DatasetImage& im) { return im.name == line || im.path == line; });
    if (named != dataset.images.end()) return static_cast<std::size_t>(named - dataset.images.begin());
    if (std::count(line.begin(), line.end(), ',') != 3)
        return Error{where + ": no image named '" + line + "' in " + dataset.source};
    const std::size_t split = line.find(',', line.find(',') + 1);
    Result<Direction> light = parseDirection(line.substr(0, split), where + ": the light of '" + line + "'");
    if (!light) return Error{light.error()};
    Result<Direction> view = parseDirection(line.substr(split + 1), where + ": the view of '" + line + "'");
    if (!view) return Error{view.error()};
    const double tolerance = kPairToleranceDegrees * std::numbers::pi / 180;
    auto at = std::find_if(dataset.images.begin(), dataset.images.end(), [&](const DatasetImage& im) {
        return angleBetween(im.light, *light) <= tolerance && angleBetween(im.view, *view) <= tolerance;
    });
    if (at == dataset.images.end())
        return Error{where + ": no image at light (" + line.substr(0, split) + ") and view (" + line.substr(split + 1) +
                     ") in " + dataset.source};
    return static_cast<std::size_t>(at - dataset.images.begin());
}

}  // namespace

Result<std::vector<Fold>> holdoutFolds(const Dataset& dataset, const std::string& spec, std::size_t minimumTraining) {
    const std::size_t n = dataset.images.size();
    std::vector<Fold> folds;
    if (spec == "loo") {
        for (std::size_t i = 0; i < n; ++i) {
            Fold f{{}, {i}};
            for (std::size_t j = 0; j < n; ++j)
                if (j != i) f.train.push_back(j);
            folds.push_back(std::move(f));
        }
    } else if (spec.rfind("every:", 0) == 0) {
        std::size_t k = 0;
        const char* first = spec.data() + 6;
        const auto [end, ec] = std::from_chars(first, spec.data() + spec.size(), k);
        if (ec != std::errc{} || end != spec.data() + spec.size() || k < 2)
            return Error{"--holdout '" + spec + "': expected every:K with K >= 2, loo, or a file of image names"};
        Fold f;
        for (std::size_t i = 0; i < n; ++i) (i % k == 0 ? f.test : f.train).push_back(i);
        folds.push_back(std::move(f));
    } else {
        Result<Bytes> text = readFile(spec);
        if (!text) return Error{"--holdout: " + text.error()};
        std::istringstream lines(std::string(text->begin(), text->end()));
        std::vector<bool> held(n, false);
        std::string line;
        for (int number = 1; std::getline(lines, line); ++number) {
            while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
            if (line.empty()) continue;
            Result<std::size_t> image = heldImage(dataset, line, spec + ":" + std::to_string(number));
            if (!image) return Error{image.error()};
            held[*image] = true;
        }
        Fold f;
        for (std::size_t i = 0; i < n; ++i) (held[i] ? f.test : f.train).push_back(i);
        folds.push_back(std::move(f));
    }
    for (const Fold& f : folds) {
        if (f.test.empty()) return Error{"--holdout " + spec + " holds out no image of " + dataset.source};
        if (f.train.size() < minimumTraining)
            return Error{"--holdout " + spec + " leaves " + std::to_string(f.train.size()) + " training images of " +
                         dataset.source + "; the modes asked for need " + std::to_string(minimumTraining) +
                         (minimumTraining >= 6 ? " (the PTM fits six terms)" : "")};
    }
    return folds;
}

Dataset subset(const Dataset& dataset, const std::vector<std::size_t>& images) {
    Dataset out = dataset;
    out.images.clear();
    for (std::size_t i : images) out.images.push_back(dataset.images[i]);
    return out;
}

}  // namespace btflut

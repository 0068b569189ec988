#pragma once
// Recognising a material from one image's histogram under an unknown light (paper 6.3).
//
//   std::vector<MaterialHistograms> library = ...;            // loadMaterial each
//   std::vector<MaterialMatch> ranked = classify(histogram, library, view, Metric::Histogram);
//
// Each material is scored by how close it can come to the image over every light direction
// (the light is unknown): the smallest earth mover's distance between the image's histogram
// and the material's at a light, searched on a grid over the equal-area light disk and then
// refined. The baseline `Metric::MeanBrightness` does the same with the mean grey value
// alone (what a BRDF, or 2D texture mapping, knows of the material).

#include <vector>

#include "core/inverse/material_histograms.h"

namespace btflut {

enum class Metric { Histogram, MeanBrightness };

struct MaterialMatch {
    std::size_t material = 0;  ///< index into the library
    double score = 0;          ///< the metric at the best light (lower is closer)
    Direction light;           ///< that light (sample frame)
};

/// The material's best light for `histogram` (normalised, any bin count) seen from `view`.
MaterialMatch matchMaterial(const std::vector<double>& histogram, const MaterialHistograms& material, Direction view,
                            Metric metric);

/// Every material of the library matched, best first (materials in parallel).
std::vector<MaterialMatch> classify(const std::vector<double>& histogram,
                                    const std::vector<MaterialHistograms>& library, Direction view, Metric metric);

}  // namespace btflut

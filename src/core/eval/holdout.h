#pragma once
// The held-out protocol of `btflut eval`: which images of a dataset are predicted and which
// the banks are baked from.
//
//   Result<std::vector<Fold>> folds = holdoutFolds(dataset, "every:4");
//   Dataset train = subset(dataset, folds->front().train);
//
// Specs: "every:K" holds out every K-th image (indices 0, K, 2K, ...; one fold); "loo" holds
// out each image in turn (one fold per image); any other text names a file listing the images
// to hold out, one per line (one fold): each by its name, or by its light and view as
// THETA_I,PHI_I,THETA_R,PHI_R in degrees (as rows.csv prints them, to 0.01 degrees).

#include <string>
#include <vector>

#include "core/data/dataset.h"

namespace btflut {

struct Fold {
    std::vector<std::size_t> train, test;  ///< indices into the dataset's images
};

/// The folds of a hold-out spec; refuses an unknown spec, a list naming unknown images, and
/// folds without a test image or with fewer than `minimumTraining` training images.
Result<std::vector<Fold>> holdoutFolds(const Dataset& dataset, const std::string& spec, std::size_t minimumTraining);

/// The dataset with only the given images (same mask and source).
Dataset subset(const Dataset& dataset, const std::vector<std::size_t>& images);

}  // namespace btflut

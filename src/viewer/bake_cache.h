#pragma once
// Banks the viewer baked from datasets, kept so that a dataset opens at once the next time
// (validating the predictors takes seconds): $XDG_CACHE_HOME/btflut/view, else
// ~/.cache/btflut/view; the most recently used few are kept.
//
//   std::string file = bakeCachePath(dataset, settings);  // exists: baked before, as asked
//   ... bake, saveBank(bank, file) ...; pruneBakeCache(file);

#include <string>

#include "core/data/dataset.h"

namespace btflut {

/// Where the bank baked from `dataset` with `settings` (the bake options, as text) is kept.
/// The name changes when any of the dataset's files (images, mask, description) or btflut's
/// executable change, so a stale bank is never opened.
std::string bakeCachePath(const Dataset& dataset, const std::string& settings);

/// Marks `kept` as just used and removes the folder's banks beyond the most recent few.
void pruneBakeCache(const std::string& kept);

}  // namespace btflut

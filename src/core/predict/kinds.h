#pragma once
// The registry of the kinds beyond the references: each kind's chunk of the .btflut file
// (kind_chunk.h) and its fit to the images (predictor_fit.h), defined beside its class and
// listed in kinds.cpp, one line a kind. kind_chunk.h and predictor_fit.h look their entries up
// here.

#include <span>

#include "core/predict/kind_chunk.h"
#include "core/predict/predictor_fit.h"

namespace btflut {

struct KindEntry {
    const KindChunk* chunk;  ///< null: the kind has no chunk of its own
    const FitKind* fit;      ///< null: the kind is not fitted to the images
};

/// Every kind's entry, in the order auto bake lists their candidates.
std::span<const KindEntry> kindEntries();

}  // namespace btflut

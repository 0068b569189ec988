#include "core/predict/kinds.h"

#include "core/predict/learned_predictor.h"
#include "core/predict/model_predictor.h"

namespace btflut {

namespace {

// A new kind's entry is one line here.
constexpr KindEntry kKinds[] = {
    {&kLightModelChunk, &kLightModelFit},
    {&kLearnedModelChunk, &kLearnedFit},
};

}  // namespace

std::span<const KindEntry> kindEntries() { return kKinds; }

}  // namespace btflut

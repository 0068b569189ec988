#include "core/predict/kind_chunk.h"

#include "core/predict/learned_predictor.h"
#include "core/predict/model_predictor.h"

namespace btflut {

namespace {

// Every kind with a chunk of its own: a new kind's entry is one line here.
constexpr const KindChunk* kKindChunks[] = {&kLightModelChunk, &kLearnedModelChunk};

template <class Matches>
const KindChunk* findKindChunk(Matches matches) {
    for (const KindChunk* entry : kKindChunks)
        if (matches(*entry)) return entry;
    return nullptr;
}

}  // namespace

const KindChunk* kindChunkOf(PredictorKind kind) {
    return findKindChunk([&](const KindChunk& e) { return e.kind == kind; });
}

const KindChunk* kindChunkNumbered(std::uint32_t number) {
    return findKindChunk([&](const KindChunk& e) { return e.number == number; });
}

const KindChunk* kindChunkTagged(std::uint32_t tag) {
    return findKindChunk([&](const KindChunk& e) { return tagOf(e.tag) == tag; });
}

}  // namespace btflut

#include "core/predict/kind_chunk.h"

#include "core/predict/kinds.h"

namespace btflut {

namespace {

// The kinds with a chunk of their own (kinds.cpp).
template <class Matches>
const KindChunk* findKindChunk(Matches matches) {
    for (const KindEntry& entry : kindEntries())
        if (entry.chunk && matches(*entry.chunk)) return entry.chunk;
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

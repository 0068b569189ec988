#pragma once
// The kinds whose predictor has a chunk of its own in a .btflut file (docs/btflut-format.md): a
// light model's LMDL, a learned model's LRND. Each kind defines its entry beside its class (what
// its chunk holds, how it is written and read back, which banks it can predict); the kinds'
// registry (kinds.cpp) lists the entries, one line a kind. The bank's writer and reader (bank/)
// find a kind's entry here, by its kind, by the number HEAD gives it or by its chunk's tag, and
// name no kind.
//
//   const KindChunk* own = kindChunkOf(bank.predictorKind());  // null: the references, LUTs
//   Bytes chunk = own->encode(bank.predictor(), version);      // written under own->tag

#include <cstdint>
#include <memory>

#include "core/io/byte_stream.h"
#include "core/predict/chunk_planes.h"
#include "core/predict/predictor.h"
#include "core/result.h"

namespace btflut {

struct KindChunk {
    PredictorKind kind;
    std::uint32_t number;  ///< HEAD's predictor field (format version 5 on)
    char tag[5];           ///< its chunk's tag, as errors name it ("LMDL")
    std::uint32_t since;   ///< the format version that added the kind
    /// What the reader says of a bank of the kind without its chunk, or of a colour it cannot predict.
    const char* missing;
    /// The format version a predictor of the kind needs (`since` or later).
    std::uint32_t (*version)(const Predictor& predictor);
    /// The chunk's payload for a predictor of the kind.
    Bytes (*encode)(const Predictor& predictor, std::uint32_t version);
    /// The payload read back as a bank's predictor, every count checked before anything is
    /// allocated by it: `perChannel` an rgb bank's, `greyAndAlbedo` an lrgb bank's. Null (and no
    /// error) where the kind cannot predict a bank of that colour; the reader then says `missing`.
    Result<std::shared_ptr<const Predictor>> (*decode)(ByteReader& in, const ChunkSource& source, std::uint32_t version,
                                                       int referenceChannels, bool perChannel, bool greyAndAlbedo);
};

/// The entry of a kind; null for a kind without a chunk of its own (the references, LUTs).
const KindChunk* kindChunkOf(PredictorKind kind);
/// The entry HEAD numbers `number`; null for none.
const KindChunk* kindChunkNumbered(std::uint32_t number);
/// The entry whose chunk is tagged `tag` (tagOf); null for none.
const KindChunk* kindChunkTagged(std::uint32_t tag);

}  // namespace btflut

#pragma once
// What reading a .btflut file shares between its two files (internal to bank/): bank_read.cpp
// walks the chunks (HEAD, the layers, the match grids, the choice) and checks the whole;
// predictor_chunks.cpp decodes the chunks a bank with a predictor has beside the predictor's own
// (REFS, MASK, LABL, ALBD; a kind's own chunk is decoded beside its class, found in the
// registry of predict/kind_chunk.h, and the baseline PTM's PTMC in ptm.h).

#include <cstdint>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/bank/bank_format.h"
#include "core/bank/lut_bank.h"
#include "core/io/byte_stream.h"
#include "core/predict/predictor.h"
#include "core/predict/reference_blend.h"
#include "core/result.h"

namespace btflut::bank_read {

using namespace bank_format;

// A chunk of a .btflut file, checked against its CRC.
struct Chunk {
    std::uint32_t tag;
    const std::uint8_t* payload;
    std::uint32_t length;
};

// HEAD, read and checked before any other chunk, so every size below is known to be sane.
struct Head {
    std::uint32_t version = 0;
    std::uint32_t layerCount = 0, refWidth = 0, refHeight = 0, refChannels = 0, refDepth = 0;
    std::uint32_t references = 0;  // version 3, banks that make their LUTs at run time
    FilePredictor predictor = FilePredictor::References;
    bool embedded = false;
};

// A predictor's parts as its chunks give them, made into the bank's predictor at the end.
struct PredictorParts {
    std::vector<Image> references;
    std::vector<ReferenceLight> lights;
    Image albedo;
    /// A kind's own chunk (predict/kind_chunk.h) decoded as the predictor; null until then, and
    /// where the kind cannot predict a bank of this colour.
    std::shared_ptr<const Predictor> own;
    bool haveOwnChunk = false;
};

// REFS, MASK, LABL, ALBD: the parts of a bank that makes its LUTs at run time.
Status readPredictionChunk(std::uint32_t tag, ByteReader& in, const std::string& name, const Head& head, LutBank& bank,
                           PredictorParts& parts);

}  // namespace btflut::bank_read

#pragma once
// What the predictors' chunks of a .btflut file share (docs/btflut-format.md): images stored as
// a length, then a PNG, and a light model's planes of codes as lightModelImages lays them out.
// Each kind writes and reads its own chunk beside its class (model_predictor.h,
// learned_predictor.h, ptm.h); bank/ frames the chunks (tag, length, CRC) and checks them
// against the bank.

#include <string>

#include "core/image/image.h"
#include "core/io/byte_stream.h"
#include "core/predict/light_model.h"
#include "core/result.h"

namespace btflut {

/// Where a chunk is read: errors read "<name>: <tag> chunk: what", the decoders' name
/// `name` and what they decode; the reference image's size, which every plane has.
struct ChunkSource {
    std::string name;  ///< the file
    std::string tag;   ///< the chunk's, as errors name it ("LMDL", "PTM")
    int width = 0, height = 0;
    Error fail(const std::string& what) const { return Error{name + ": " + tag + " chunk: " + what}; }
};

/// An image as its length, then its PNG (8 or 16 bits).
void putPng(ByteWriter& w, const Image& image, int bitDepth);
/// The same read back and decoded (the decoder refuses more than the source's size); `what`
/// names it in the chunk's errors, `context` in the decoder's.
Result<Image> readPng(ByteReader& in, const ChunkSource& source, const std::string& what, const std::string& context);
/// The same, refused unless it is an RGB8 image of exactly the source's size: planes of codes.
Result<Image> readRgb8Plane(ByteReader& in, const ChunkSource& source, const std::string& what,
                            const std::string& context);

/// A light model's planes and albedo (m's sizes set, and its albedo sized when it has one), as
/// lightModelImages writes them: 8-bit planes three to an RGB8 PNG, 4-bit planes six (two to a
/// channel), then the albedo; `context` and `word` ("planes ", "coefficients ") name them.
Status readModelPlanes(ByteReader& in, const ChunkSource& source, const std::string& context, const std::string& word,
                       LightModel& m);

}  // namespace btflut

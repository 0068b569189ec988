#pragma once
// What the reader and the writer of .btflut files share (bank_read.cpp, bank_write.cpp): the
// signature, the chunk tags, the limits every field is checked against, and the chunks'
// CRC-32. Internal to src/core/bank; the format is specified in docs/btflut-format.md.

#include <zlib.h>

#include <bit>
#include <cstdint>
#include <string>

#include "core/io/byte_stream.h"

namespace btflut::bank_format {

static_assert(std::endian::native == std::endian::little,
              "the .btflut reader/writer copies little-endian words directly");

constexpr std::uint8_t kSignature[8] = {0x89, 'B', 'T', 'F', 'L', 'U', 'T', 0x0A};
constexpr std::uint32_t kMaxEntries = 65536;
constexpr std::uint32_t kMaxGrid = 257;
constexpr std::uint64_t kMaxChunk = 0xFFFFFFFFu;  // a chunk's length is a u32

constexpr std::uint32_t kHead = tagOf("HEAD"), kLayer = tagOf("LAYR"), kReference = tagOf("REFI"), kPtm = tagOf("PTMC"),
                        kEnd = tagOf("END "), kReferences = tagOf("REFS"), kMask = tagOf("MASK"),
                        kLabels = tagOf("LABL"), kAlbedo = tagOf("ALBD"), kFill = tagOf("FILL"),
                        kSelection = tagOf("CHOS"), kMatchGrid = tagOf("MGRD"), kTargetFit = tagOf("TFIT");

// The HEAD's predictor (version 5): the references blended (REFS), or the bank's PTM (PTMC;
// read from earlier files as the light model it is, written as one). A kind with a chunk of its
// own has its number, its tag and the version that added it in its entry (predict/kind_chunk.h).
enum class FilePredictor : std::uint32_t { References = 0, Ptm = 1 };

inline std::string tagName(std::uint32_t tag) {
    std::string s;
    for (int i = 0; i < 4; ++i) {
        char c = static_cast<char>((tag >> (8 * i)) & 0xFF);
        s += (c >= 32 && c < 127) ? c : '?';
    }
    return s;
}

// CRC-32 of a chunk's tag and payload. (zlib's crc32 treats a null buffer as "return the
// initial value", so an empty payload must not be passed through.)
inline std::uint32_t chunkCrc(std::uint32_t tag, const std::uint8_t* payload, std::size_t length) {
    uLong crc = crc32(0L, reinterpret_cast<const Bytef*>(&tag), 4);
    if (length > 0) crc = crc32_z(crc, payload, length);
    return static_cast<std::uint32_t>(crc);
}

}  // namespace btflut::bank_format

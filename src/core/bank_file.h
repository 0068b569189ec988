#pragma once
// The .btflut file: a LUT bank on disk (format spec: docs/btflut-format.md).
//
//   Status s = saveBank(bank, "rock.btflut");            // atomic
//   Result<LutBank> bank = loadBank("rock.btflut");      // every field validated
//
// Little-endian; an 8-byte signature, then chunks (tag, length, payload, CRC-32), HEAD
// first and END last. The reader refuses a truncated, bit-flipped or inconsistent file with
// one message naming the file and what is wrong.

#include <string>

#include "core/file_io.h"
#include "core/lut_bank.h"

namespace btflut {

constexpr std::uint32_t kBankFormatVersion = 1;

struct BankWriteOptions {
    bool embedReference = true;  ///< store the reference image (PNG) inside the file
};

struct BankReadOptions {
    bool ptm = true;    ///< decode the PTM chunk, if any (its checksum is checked either way)
    bool grids = true;  ///< copy the layers' resampled grids (a renderer blending nodes needs none)
    /// Non-empty: decode the LUTs of only the view layers that lookups at these view
    /// directions use (interpolated or nearest); the others keep their directions and nodes
    /// with ViewLayer::lutsLoaded false. Such a bank cannot be encoded again.
    std::vector<Direction> views;
};

Bytes encodeBank(const LutBank& bank, const BankWriteOptions& options = {});
Result<LutBank> decodeBank(const Bytes& bytes, const std::string& name, const BankReadOptions& options = {});

Status saveBank(const LutBank& bank, const std::string& path, const BankWriteOptions& options = {});
Result<LutBank> loadBank(const std::string& path, const BankReadOptions& options = {});
/// Only the PTM of a bank file (for a renderer that needs it later than the LUTs).
Result<Ptm> loadBankPtm(const std::string& path);

}  // namespace btflut

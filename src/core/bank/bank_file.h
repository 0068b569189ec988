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

#include "core/bank/lut_bank.h"
#include "core/io/file_io.h"

namespace btflut {

/// The newest version this btflut reads (it reads every older one) and writes when a bank
/// needs it; bankFormatVersion says which a bank is written as.
constexpr std::uint32_t kBankFormatVersion = 9;

/// Most measured directions (nodes, over all layers) a bank may hold.
constexpr std::size_t kMaxBankNodes = 65536;

/// The version a bank is written as: the oldest that holds it (1; 2 for the isotropic
/// domain; 3 for banks that make their LUTs at run time; 4 for banks with nodes filled from
/// the model; 5 for banks that predict with a light model, match partly, or record how
/// their predictor was chosen).
std::uint32_t bankFormatVersion(const LutBank& bank);

/// Refuses a bank the format cannot hold (a chunk over 4 GiB, too many nodes).
Status checkBankSize(const LutBank& bank);

struct BankWriteOptions {
    bool embedReference = true;  ///< store the reference image (PNG) inside the file
};

struct BankReadOptions {
    bool ptm = true;    ///< decode the PTM chunk, if any (its checksum is checked either way)
    bool grids = true;  ///< copy the layers' resampled grids (a renderer blending nodes needs none)
    /// copy the layers' match grids (banks with a predictor: the LUTs a renderer reads per
    /// light change, Relighter::gridFrame; without them it makes them on first use)
    bool matchGrids = true;
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
Result<LightModel> loadBankPtm(const std::string& path);

}  // namespace btflut

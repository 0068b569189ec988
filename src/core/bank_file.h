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

Bytes encodeBank(const LutBank& bank, const BankWriteOptions& options = {});
Result<LutBank> decodeBank(const Bytes& bytes, const std::string& name);

Status saveBank(const LutBank& bank, const std::string& path, const BankWriteOptions& options = {});
Result<LutBank> loadBank(const std::string& path);

}  // namespace btflut

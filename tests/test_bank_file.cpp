#include <doctest/doctest.h>

#include "core/bake/bake.h"
#include "core/bank/bank_file.h"
#include "core/io/byte_stream.h"
#include "helpers.h"

using namespace btflut;
using namespace btflut::test;

namespace {
LutBank smallBank(const TempDir& dir) {
    auto ds = openDataset(writeSyntheticDataset(
        dir, {{0, 0, 0, 0, 0, 1}, {30, 0, 0, 0, 40, 1}, {30, 120, 0, 0, 0, 2}, {40, 250, 20, 10, 3, 1}}, 6, 5));
    REQUIRE(ds.ok());
    auto bank = bakeBank(*ds, {.gridSize = 3, .entries = 8});
    REQUIRE(bank.ok());
    return std::move(*bank);
}
}  // namespace

TEST_CASE("a bank file round-trips bit-exactly") {
    TempDir dir;
    LutBank bank = smallBank(dir);
    Bytes bytes = encodeBank(bank);
    auto back = decodeBank(bytes, "m.btflut");
    REQUIRE(back.ok());
    CHECK(encodeBank(*back) == bytes);
    CHECK(back->layers.size() == 2);
    CHECK(back->layers[0].nodeLuts == bank.layers[0].nodeLuts);
    CHECK(back->layers[1].gridLuts == bank.layers[1].gridLuts);
    CHECK(back->reference.samples == bank.reference.samples);
    CHECK(back->referenceName == bank.referenceName);

    Bytes bare = encodeBank(bank, {.embedReference = false});
    auto noRef = decodeBank(bare, "bare.btflut");
    REQUIRE(noRef.ok());
    CHECK(noRef->reference.samples.empty());
    CHECK(noRef->reference.width == 6);
    CHECK(encodeBank(*noRef) == bare);
}

TEST_CASE("every truncation of a bank file is refused") {
    TempDir dir;
    Bytes bytes = encodeBank(smallBank(dir));
    for (std::size_t keep = 0; keep < bytes.size(); ++keep) {
        auto r = decodeBank(Bytes(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(keep)), "cut.btflut");
        INFO("kept " << keep << " of " << bytes.size());
        REQUIRE_FALSE(r.ok());
        REQUIRE(r.error().rfind("cut.btflut: ", 0) == 0);
    }
    Bytes longer = bytes;
    longer.push_back(0);
    CHECK_FALSE(decodeBank(longer, "x").ok());
}

TEST_CASE("every single-bit flip of a bank file is refused") {
    TempDir dir;
    Bytes bytes = encodeBank(smallBank(dir), {.embedReference = false});
    for (std::size_t bit = 0; bit < bytes.size() * 8; ++bit) {
        Bytes flipped = bytes;
        flipped[bit / 8] ^= static_cast<std::uint8_t>(1u << (bit % 8));
        auto r = decodeBank(flipped, "flip.btflut");
        INFO("bit " << bit);
        REQUIRE_FALSE(r.ok());
    }
}

TEST_CASE("the reader names what is wrong") {
    TempDir dir;
    Bytes bytes = encodeBank(smallBank(dir));
    Bytes sig = bytes;
    sig[1] = 'X';
    CHECK(decodeBank(sig, "a.btflut").error() == "a.btflut: not a .btflut file (bad signature)");
    Bytes version = bytes;
    version[8] = 10;
    CHECK(decodeBank(version, "a.btflut").error().find("unsupported .btflut version 10") != std::string::npos);
    Bytes payload = bytes;
    payload[40] ^= 0xFF;
    CHECK(decodeBank(payload, "a.btflut").error().find("checksum mismatch in chunk HEAD") != std::string::npos);
    auto missing = loadBank(dir / "none.btflut");
    CHECK(missing.error().find("none.btflut: cannot open") != std::string::npos);
}

TEST_CASE("saving is atomic: a failed save leaves the old file untouched") {
    TempDir dir;
    LutBank bank = smallBank(dir);
    REQUIRE(saveBank(bank, dir / "m.btflut").ok());
    std::string before = readText(dir / "m.btflut");
    std::ofstream(dir / "a-file") << "x";
    CHECK_FALSE(saveBank(bank, dir / "a-file/m.btflut").ok());  // a folder cannot be made where a file is
    CHECK(readText(dir / "m.btflut") == before);
    for (const auto& entry : fs::directory_iterator(dir.path()))
        CHECK(entry.path().string().find(".tmp.") == std::string::npos);
}

TEST_CASE("a chunk's bytes read back as written; a short read or a bad direction fails and sticks") {
    ByteWriter w;
    w.put(std::uint32_t{7});
    w.put(-1.5f);
    w.putString("reference");
    w.putDirection(Direction::fromDegrees(30, 120));
    const Bytes bytes = w.bytes();
    CHECK(bytes.size() == 4 + 4 + 4 + 9 + 16);

    ByteReader in(bytes.data(), bytes.size());
    CHECK(in.get<std::uint32_t>() == 7);
    CHECK(in.get<float>() == -1.5f);
    CHECK(in.getString() == "reference");
    Result<Direction> d = in.getDirection("m.btflut", "layer view");
    REQUIRE(d.ok());
    CHECK(d->thetaDegrees() == doctest::Approx(30));
    CHECK(d->phiDegrees() == doctest::Approx(120));
    CHECK(in.ok());
    CHECK(in.remaining() == 0);
    CHECK(in.get<std::uint32_t>() == 0);  // past the end: zero, and not ok from now on
    CHECK_FALSE(in.ok());
    CHECK(in.getBytes(0) == nullptr);

    ByteWriter below;
    below.put(95.0);  // theta past the horizon
    below.put(0.0);
    ByteReader bad(below.bytes().data(), below.bytes().size());
    Result<Direction> refused = bad.getDirection("m.btflut", "node light");
    REQUIRE_FALSE(refused.ok());
    CHECK(refused.error() == "m.btflut: invalid node light direction");
}

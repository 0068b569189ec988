#pragma once
// Binary payloads of btflut's files (the .btflut chunks, docs/btflut-format.md): numbers in
// the machine's byte order (little-endian everywhere btflut runs), strings and directions as
// the format writes them. ByteWriter appends; ByteReader reads with bounds checks, and its
// first failure sticks, so a parser reads every field and checks ok() once.
//
//   ByteWriter w;  w.put(std::uint32_t{3});  w.putString(name);  Bytes payload = w.bytes();
//   ByteReader in(payload.data(), payload.size());
//   const auto n = in.get<std::uint32_t>();  std::string s = in.getString();
//   if (!in.ok()) ...                                             // truncated

#include <cstdint>
#include <cstring>
#include <string>

#include "core/direction/direction.h"
#include "core/io/file_io.h"
#include "core/result.h"

namespace btflut {

/// A chunk's four-letter tag as the little-endian word files hold ("HEAD", "LRND").
constexpr std::uint32_t tagOf(const char (&t)[5]) {
    return static_cast<std::uint32_t>(t[0]) | static_cast<std::uint32_t>(t[1]) << 8 |
           static_cast<std::uint32_t>(t[2]) << 16 | static_cast<std::uint32_t>(t[3]) << 24;
}

class ByteWriter {
public:
    template <typename T>
    void put(T v) {
        putBytes(&v, sizeof(T));
    }
    void putBytes(const void* data, std::size_t n) {
        if (n == 0) return;
        const std::size_t at = m_bytes.size();
        m_bytes.resize(at + n);
        std::memcpy(m_bytes.data() + at, data, n);
    }
    void putString(const std::string& s) {
        put(static_cast<std::uint32_t>(s.size()));
        putBytes(s.data(), s.size());
    }
    /// Two doubles: theta and phi in degrees.
    void putDirection(Direction d) {
        put(d.thetaDegrees());
        put(d.phiDegrees());
    }
    Bytes& bytes() { return m_bytes; }

private:
    Bytes m_bytes;
};

class ByteReader {
public:
    ByteReader(const std::uint8_t* data, std::size_t size) : m_data(data), m_size(size) {}
    template <typename T>
    T get() {
        T v{};
        if (need(sizeof(T))) std::memcpy(&v, m_data + m_pos, sizeof(T));
        m_pos += m_ok ? sizeof(T) : 0;
        return v;
    }
    const std::uint8_t* getBytes(std::size_t n) {
        if (!need(n)) return nullptr;
        const std::uint8_t* p = m_data + m_pos;
        m_pos += n;
        return p;
    }
    std::string getString() {
        auto n = get<std::uint32_t>();
        const std::uint8_t* p = getBytes(n);
        return p ? std::string(reinterpret_cast<const char*>(p), n) : std::string();
    }
    /// putDirection's: refused (naming `name` and `what`) unless finite with theta in [0, 90].
    Result<Direction> getDirection(const std::string& name, const std::string& what);
    bool ok() const { return m_ok; }
    std::size_t remaining() const { return m_size - m_pos; }

private:
    bool need(std::size_t n) {
        if (m_ok && n > m_size - m_pos) m_ok = false;
        return m_ok;
    }
    const std::uint8_t* m_data;
    std::size_t m_size;
    std::size_t m_pos = 0;
    bool m_ok = true;
};

}  // namespace btflut

#pragma once
// What reading a .btflut file shares between its two files (internal to bank/): bank_read.cpp
// walks the chunks (HEAD, the layers, the match grids, the choice) and checks the whole;
// predictor_chunks.cpp decodes the chunks of a bank's predictor and baseline (REFS, MASK, LABL,
// ALBD, LMDL, PTMC).

#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "core/bank/bank_format.h"
#include "core/bank/lut_bank.h"
#include "core/predict/learned_model.h"
#include "core/predict/light_model.h"
#include "core/predict/reference_blend.h"
#include "core/result.h"

namespace btflut::bank_read {

using namespace bank_format;

// Bounds-checked reads over one chunk payload; the first failure sticks.
class Reader {
public:
    Reader(const std::uint8_t* data, std::size_t size) : m_data(data), m_size(size) {}
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

Result<Direction> getDirection(Reader& in, const std::string& name, const std::string& what);

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
    std::optional<LightModel> model;
    std::optional<LearnedModel> learned;
};

// LRND: the learned model of a bank predicted by one (encodeLearnedModel in bank_write.cpp).
Result<LearnedModel> decodeLearnedModel(Reader& in, const std::string& name, const Head& head);

// LMDL: the light model of a bank predicted by one (encodeLightModel in bank_write.cpp).
Result<LightModel> decodeLightModel(Reader& in, const std::string& name, const Head& head);

// PTMC: the PTM of a bank whose reference image is width x height.
Result<LightModel> decodePtm(const Chunk& chunk, const std::string& name, std::uint32_t width, std::uint32_t height);

// REFS, MASK, LABL, ALBD: the parts of a bank that makes its LUTs at run time.
Status readPredictionChunk(std::uint32_t tag, Reader& in, const std::string& name, const Head& head, LutBank& bank,
                           PredictorParts& parts);

}  // namespace btflut::bank_read

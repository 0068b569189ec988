#include "core/relight/engine_material.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/check.h"
#include "core/predict/gpu_constants.h"
#include "core/predict/learned_predictor.h"
#include "core/predict/learned_shader.h"
#include "core/predict/light_model.h"
#include "core/predict/model_predictor.h"
#include "core/predict/reference_blend.h"
#include "core/relight/relighter.h"

namespace btflut {

namespace {

// A predictor bank's match grid (LutBank::matchGridLuts, per node [region][channel][entry])
// in the 3D texture's order, [region][j][i][entry][channel].
std::vector<std::uint16_t> matchGridTexels(const LutBank& bank, const std::vector<std::uint16_t>& grid) {
    const auto g = static_cast<std::size_t>(bank.gridSize), entries = static_cast<std::size_t>(bank.entries),
               channels = static_cast<std::size_t>(bank.channels()),
               regions = static_cast<std::size_t>(bank.prediction.regions);
    BTFLUT_CHECK(grid.size() == g * g * regions * channels * entries);
    std::vector<std::uint16_t> texels(grid.size());
    std::size_t at = 0;
    for (std::size_t r = 0; r < regions; ++r)
        for (std::size_t cell = 0; cell < g * g; ++cell)
            for (std::size_t k = 0; k < entries; ++k)
                for (std::size_t c = 0; c < channels; ++c)
                    texels[at++] = grid[((cell * regions + r) * channels + c) * entries + k];
    return texels;
}

// `count` values per node of a size x size grid as layers of four: [layer][node][4].
std::vector<float> inLayers(const std::vector<float>& grid, std::size_t count, int size) {
    const std::size_t nodes = static_cast<std::size_t>(size) * static_cast<std::size_t>(size), layers = (count + 3) / 4;
    BTFLUT_CHECK(grid.size() == nodes * count);
    std::vector<float> out(layers * nodes * 4, 0.f);
    for (std::size_t n = 0; n < nodes; ++n)
        for (std::size_t k = 0; k < count; ++k) out[((k / 4) * nodes + n) * 4 + k % 4] = grid[n * count + k];
    return out;
}

// A light model's rows ((1 + P) x channels: the offsets, then each plane's channel weights)
// over the engine's weight grid: bln's own nodes (its bilinear read is exact), rbf sampled.
std::vector<float> modelWeightGrid(const LightModel& m, int& size) {
    if (m.basis == LightBasis::Bilinear) {
        size = m.grid;
        return m.table;
    }
    size = kEngineWeightGrid;
    const auto P = static_cast<std::size_t>(m.planes), C = static_cast<std::size_t>(m.channels), row = (1 + P) * C;
    std::vector<float> grid(static_cast<std::size_t>(size) * static_cast<std::size_t>(size) * row);
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < size; ++i) {
            const LightModel::Weights w =
                m.weightsAt(fromDisk(diskGridPoint(i, j, size)));  // beyond the rim: the horizon's
            float* node =
                &grid[(static_cast<std::size_t>(j) * static_cast<std::size_t>(size) + static_cast<std::size_t>(i)) *
                      row];
            std::copy_n(w.offset.begin(), C, node);
            std::copy(w.weight.begin(), w.weight.end(), node + C);
        }
    return grid;
}

// A light model's weights: ptm and hsh in closed form (btflut.glsl), rbf and bln on the grid.
void setModel(EngineMaterial& out, const LightModel& m) {
    out.basis = m.basis;
    out.order = m.order;
    out.planes = m.planes;
    out.channels = m.channels;
    out.albedoMultiplies = !m.albedo.empty();
    if (m.basis == LightBasis::Rbf || m.basis == LightBasis::Bilinear) {
        out.weights = (m.planes + 1) * m.channels;
        const std::vector<float> rows = modelWeightGrid(m, out.weightGridSize);
        out.weightGrid = inLayers(rows, static_cast<std::size_t>(out.weights), out.weightGridSize);
    }
}

}  // namespace

Status drawnOnGpu(const LutBank& bank) {
    if (!bank.makesLuts()) return success();
    if (const LearnedPredictor* learned = bank.predictorAs<LearnedPredictor>(); learned && !learned->model().fitsGpu())
        return Error{"its learned model (" + bank.predictorName() +
                     ") has networks larger than the GPU's decoder "
                     "evaluates (at most " +
                     std::to_string(BTFLUT_LEARNED_HIDDEN) + " hidden layers of " +
                     std::to_string(BTFLUT_LEARNED_WIDTH) +
                     " units); it is relit on the CPU only (btflut relight, eval)"};
    return success();
}

Result<EngineMaterial> engineMaterial(const LutBank& bank, const std::string& name) {
    if (Status s = drawnOnGpu(bank); !s) return Error{name + ": " + s.error()};
    if (bank.reference.samples.empty())
        return Error{name + ": the bank holds no reference image (baked with --no-reference)"};
    EngineMaterial out;
    out.kind = bank.predictorKind();
    out.colour = bank.colour;
    out.entries = bank.entries;
    out.gridSize = bank.gridSize;
    out.lutChannels = bank.channels();
    out.outputCode = bank.targetCode();
    if (!bank.makesLuts()) {
        out.blocks = static_cast<int>(bank.layers.size());
        out.lutTexels = bank.gridTexels();
        out.inputCode = inputCode(bank.reference, bank.colour);
        out.reference = bank.reference;
        out.outputChannels = bank.colour == ColourMode::Grey ? bank.reference.channels : 3;
        return out;
    }
    const LutBank::Prediction& blend = bank.prediction;
    // A block per view layer (a predictor of views has several) and region.
    const LutBank* gridded = &bank;
    LutBank copy;
    if (bank.layers[0].matchGridLuts.empty()) {  // a file older than the match grid
        copy = bank;
        bakeMatchGrid(copy);
        gridded = &copy;
    }
    for (const ViewLayer& layer : gridded->layers) {
        const std::vector<std::uint16_t> texels = matchGridTexels(bank, layer.matchGridLuts);
        out.lutTexels.insert(out.lutTexels.end(), texels.begin(), texels.end());
    }
    out.blocks = blend.regions * static_cast<int>(bank.layers.size());
    out.codes = predictionCodes(bank);
    out.inputCode = 1.f / static_cast<float>(out.codes + 1);  // Relighter::inputCode
    out.regions = blend.regions;
    if (!blend.labels.empty()) out.labels = byteImage(blend.labels, bank.reference.width, bank.reference.height, 1);
    out.outputChannels = bank.colour == ColourMode::Grey ? bank.reference.channels : 3;  // as Relighter::apply
    PredictorPlanes planes = bank.predictor().planes();  // the packing btflut's renderer uploads too
    out.images = std::move(planes.layers);
    out.albedo = std::move(planes.albedo);
    out.scale = std::move(planes.scale);
    out.bias = std::move(planes.bias);
    if (const ModelPredictor* model = bank.predictorAs<ModelPredictor>()) {
        setModel(out, model->model());
        return out;
    }
    if (const LearnedPredictor* learned = bank.predictorAs<LearnedPredictor>()) {
        // The decoder in the weight texture: one layer, a square of texels (btflut.glsl).
        out.planes = learned->model().codes;
        out.channels = learned->model().channels;
        out.weights = 4;
        out.weightGridSize = planes.networkSize;
        out.weightGrid = std::move(planes.network);
        const LearnedModel& model = learned->model();
        const LearnedShaderCost cost = learnedShaderCost(model);
        out.texelMultiplyAdds = cost.texelMultiplyAdds;
        out.frameMultiplyAdds = cost.frameMultiplyAdds;
        if (hasLearnedShader(model)) {
            const std::string file = std::filesystem::path(name).filename().string();
            out.networkGlsl = learnedShaderSource(model, ShaderLanguage::Glsl, file);
            out.networkHlsl = learnedShaderSource(model, ShaderLanguage::Hlsl, file);
        }
        return out;
    }
    const ReferenceBlend& references = *bank.predictorAs<ReferenceBlend>();
    out.planes = static_cast<int>(references.references().size());
    out.channels = references.references().front().channels;
    out.weights = out.planes;
    out.weightGridSize = kEngineWeightGrid;
    out.weightGrid = inLayers(referenceWeightGrid(bank, kEngineWeightGrid), static_cast<std::size_t>(out.weights),
                              kEngineWeightGrid);
    return out;
}

}  // namespace btflut

#include "core/relight/engine_material.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "core/check.h"
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

}  // namespace

Status drawnOnGpu(const LutBank& bank) {
    if (!bank.makesLuts()) return success();
    if (std::string why = bank.predictor().beyondGpu(); !why.empty()) return Error{why};
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
    static_cast<EngineParts&>(out) = bank.predictor().engineParts(std::filesystem::path(name).filename().string());
    return out;
}

}  // namespace btflut

#include "core/relight/material_json.h"

#include "core/io/json_text.h"

namespace btflut {

std::string planeImageName(std::size_t k) { return "planes-" + std::to_string(k) + ".png"; }

namespace {

// The sidecar's "predictor" (version 2): what btflut.glsl's BtflutPredictor takes, and the
// files of its textures; what only its kind has, the predictor's own (materialFields).
nlohmann::json predictorJson(const LutBank& b, const EngineMaterial& m) {
    std::vector<std::string> images;
    for (std::size_t k = 0; k < m.images.size(); ++k) images.push_back(planeImageName(k));
    nlohmann::json p{{"kind", predictorKindName(m.kind)},
                     {"kind_index", m.predictorKind()},
                     {"images", images},
                     {"planes", m.planes},
                     {"channels", m.channels},
                     {"codes", m.codes},
                     {"output_channels", m.outputChannels},
                     {"regions", m.regions}};
    if (!m.scale.empty()) {  // a light model's and a learned model's codes
        p["scale"] = m.scale;
        p["bias"] = m.bias;
    }
    if (!m.albedo.samples.empty())
        p["albedo"] = {{"file", "albedo.png"}, {"use", m.albedoMultiplies ? "multiplies" : "chroma"}};
    if (!m.labels.samples.empty())
        p["labels"] = {{"file", "labels.png"}, {"texture", "R8, nearest: each texel's region (value = region)"}};
    if (m.weights > 0)
        p["weights"] = {{"file", "weights.bin"},
                        {"format", "float32, little-endian, [layer][j][i][4]: a 2D array texture of RGBA32F layers"},
                        {"grid_size", m.weightGridSize},
                        {"count", m.weights},
                        {"layers", m.weightLayers()},
                        {"grid_mapping",
                         "node (i, j) at disk point x = -1 + 2 i / (grid_size - 1), y likewise; read "
                         "bilinearly between nodes (btflutWeightLayer)"}};
    else
        p["weights"] = nullptr;  // ptm, hsh: closed form in btflut.glsl
    b.predictor().materialFields(p, m);
    return p;
}

}  // namespace

nlohmann::json materialJson(const LutBank& b, const EngineMaterial& m) {
    const bool predictor = m.kind != PredictorKind::Luts;
    const int g = m.gridSize;
    nlohmann::json side{// Banks of LUTs keep version 1, so that loaders written for it still read them.
                        {"format", "btflut-material"},
                        {"version", predictor ? 2 : 1},
                        {"kind", predictorKindName(m.kind)},
                        {"shader", "btflut.glsl"},
                        {"shader_version", predictor ? m.shaderVersion : 1},
                        {"reference",
                         {{"file", "reference.png"},
                          {"width", b.reference.width},
                          {"height", b.reference.height},
                          {"channels", b.reference.channels},
                          {"bit_depth", b.reference.bitDepth},
                          {"name", b.referenceName},
                          {"light", directionJson(b.referenceLight)},
                          {"view", directionJson(b.referenceView)}}},
                        {"luts",
                         {{"file", "luts.png"},
                          {"texture", "3D, width entries, height grid_size, depth grid_size x " +
                                          std::string(predictor ? "layers x regions" : "layers") + "; 16-bit unorm, " +
                                          (m.lutChannels == 3 ? "RGB (one LUT per colour channel)" : "one channel")},
                          {"entries", m.entries},
                          {"grid_size", g},
                          {"layers", b.layers.size()},
                          {"row_of_node", predictor ? "((layer * regions + region) * grid_size + j) * grid_size + i"
                                                    : "(layer * grid_size + j) * grid_size + i"}}},
                        {"colour", colourName(b.colour)},
                        {"lut_input_code", m.inputCode},
                        {"lut_output_code", m.outputCode},
                        {"grid_mapping",
                         "node (i, j) at disk point x = -1 + 2 i / (grid_size - 1), y likewise with j; a direction "
                         "(theta, phi) maps to sqrt(2) sin(theta / 2) (cos phi, sin phi); z = surface normal, x = "
                         "texture +u (image right), y = texture +v (image up)"},
                        {"views", nlohmann::json::array()}};
    if (predictor) side["luts"]["regions"] = m.regions;
    for (const ViewLayer& layer : b.layers) {
        nlohmann::json provenance = nlohmann::json::array();
        for (Provenance p : layer.gridProvenance) provenance.push_back(provenanceName(p));
        nlohmann::json lights = nlohmann::json::array();  // the measured (or modelled) directions
        for (const LightNode& node : layer.nodes) {
            nlohmann::json light = directionJson(node.light);
            light["modelled"] = node.modelled;
            lights.push_back(light);
        }
        side["views"].push_back(
            {{"view", directionJson(layer.view)}, {"node_provenance", provenance}, {"lights", lights}});
    }
    if (!b.modelFill.empty()) side["model_fill"] = nlohmann::json::parse(b.modelFill, nullptr, false);

    if (predictor) {
        side["predictor"] = predictorJson(b, m);
        side["predictor"]["name"] = b.predictorName();  // as bake's --predictor and info name it: "neural9", "hsh2"
    }
    // The sample's part of the image where the bank's mask leaves some out: what a closed
    // surface (the page's sphere) wraps, so no background is tiled over it.
    if (const std::optional<PixelRect> r = sampleWindow(b); predictor && r)
        side["sample"] = {{"x", r->x},
                          {"y", r->y},
                          {"width", r->width},
                          {"height", r->height},
                          {"what", "the largest rectangle inside the sample mask, pixels, rows top first"}};
    return side;
}

}  // namespace btflut

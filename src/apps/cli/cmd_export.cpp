// btflut export: the bank's grid as a 16-bit PNG atlas and a JSON sidecar, for engines.
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/cli.h"
#include "core/bank_file.h"
#include "core/json_text.h"

namespace btflut::cli {

namespace {

struct ExportOptions {
    std::string bank;
    std::string output;
};

Status runExport(const ExportOptions& o) {
    if (Status s = requireExtension(o.output, {"png"}, "output"); !s) return s;
    Result<LutBank> bank = loadBank(o.bank);
    if (!bank) return Error{bank.error()};
    const LutBank& b = *bank;
    const int cells = b.gridSize * b.gridSize;
    const int channels = b.channels();
    const int width = static_cast<int>(b.segmentLength()), regions = b.makesLuts() ? b.blend.regions : 1;
    const std::uint64_t rows = static_cast<std::uint64_t>(cells) * b.layers.size() * static_cast<std::uint64_t>(regions);
    if (rows > 0x7FFFFFFFu || rows * static_cast<std::uint64_t>(width) > maxImagePixels())
        return Error{o.bank + ": its atlas would be " + std::to_string(width) + "x" + std::to_string(rows) +
                     " pixels, more than a PNG (or --max-pixels) allows; bake it with a smaller --grid"};
    // One row per grid node (layer-major, then j, then i) and region, one column per LUT
    // entry (or quantile sample); RGB banks use the three colour channels of the PNG.
    Image atlas(width, static_cast<int>(rows), channels, 16);
    for (std::size_t l = 0; l < b.layers.size(); ++l)
        for (int cell = 0; cell < cells; ++cell)
            for (int r = 0; r < regions; ++r)
                for (int c = 0; c < channels; ++c)
                    for (int k = 0; k < width; ++k)
                        atlas.at(k, (static_cast<int>(l) * cells + cell) * regions + r, c) =
                            b.layers[l].gridLuts[((static_cast<std::size_t>(cell) * regions + r) * channels + c) * width + k] /
                            65535.f;

    // The textures a bank that blends references relights from, beside the atlas.
    std::vector<std::pair<std::string, Bytes>> textures;
    const std::filesystem::path out(o.output);
    auto texture = [&](const std::string& suffix, const Image& image) {
        const std::string name = out.stem().string() + "-" + suffix + ".png";
        textures.push_back({(out.parent_path() / name).string(), encodePng(image, image.bitDepth)});
        return name;
    };
    nlohmann::json blend;
    if (b.makesLuts()) {
        const LutBank::Blend& bl = b.blend;
        blend["quantiles"] = bl.quantiles;
        blend["regions"] = bl.regions;
        blend["mask"] = texture("mask", byteImage(bl.mask.inside, b.reference.width, b.reference.height, 255));
        if (!bl.labels.empty()) blend["labels"] = texture("labels", byteImage(bl.labels, b.reference.width, b.reference.height, 1));
        if (!bl.albedo.samples.empty()) blend["albedo"] = texture("albedo", bl.albedo);
        if (bl.predictor == LutBank::Blend::Predictor::Ptm) {
            blend["predictor"] = "ptm";
            blend["ptm_scale"] = b.ptm.scale;
            blend["ptm_bias"] = b.ptm.bias;
            for (int p = 0; p < 3; ++p) {
                Image plane(b.ptm.width, b.ptm.height, 3);
                const std::vector<std::uint8_t> bytes = b.ptm.plane(p);
                for (std::size_t i = 0; i < bytes.size(); ++i) plane.samples[i] = bytes[i] / 255.f;
                blend["ptm_planes"].push_back(texture("ptm-" + std::to_string(p), plane));
            }
        } else {
            blend["predictor"] = "references";
            for (std::size_t k = 0; k < bl.references.size(); ++k)
                blend["references"].push_back({{"file", texture("reference-" + std::to_string(k), bl.references[k])},
                                               {"light", {{"theta", bl.lights[k].light.thetaDegrees()},
                                                          {"phi", bl.lights[k].light.phiDegrees()}}}});
        }
        blend["how"] =
            "per light: blend the references of the Delaunay triangle (equal-area disk) around the light with "
            "barycentric weights (or relight the PTM), round the blend to its codes, and per region map its "
            "distribution over the mask's texels onto the quantile function blended from the atlas's nodes "
            "(see src/core/relighter.h)";
    }
    nlohmann::json side;
    side["format"] = "btflut-atlas";
    side["version"] = 1;
    side["atlas"] = std::filesystem::path(o.output).filename().string();
    side["entries"] = b.entries;
    side["colour"] = colourName(b.colour);
    if (b.makesLuts()) side["blend"] = blend;
    side["grid_size"] = b.gridSize;
    side["row_of_node"] = "(layer * grid_size^2 + j * grid_size + i) * regions + region";
    side["entry_value"] = b.makesLuts()
                              ? "column k holds the target's quantile function at k / (quantiles - 1); 16-bit value / 65535"
                              : "column k holds LUT(k / (entries - 1)); 16-bit value / 65535";
    side["grid_mapping"] =
        "node (i, j) sits at disk point x = -1 + 2 i / (grid_size - 1), y likewise with j; a "
        "direction (theta, phi) maps to r = sqrt(2) sin(theta / 2), (x, y) = r (cos phi, sin phi) "
        "(Lambert equal-area; z = surface normal, phi from image right towards image up)";
    side["reference"] = {{"name", b.referenceName},
                         {"light", {{"theta", b.referenceLight.thetaDegrees()}, {"phi", b.referenceLight.phiDegrees()}}},
                         {"view", {{"theta", b.referenceView.thetaDegrees()}, {"phi", b.referenceView.phiDegrees()}}}};
    side["layers"] = nlohmann::json::array();
    for (const ViewLayer& layer : b.layers) {
        nlohmann::json provenance = nlohmann::json::array();
        for (Provenance p : layer.gridProvenance) provenance.push_back(provenanceName(p));
        side["layers"].push_back({{"view", {{"theta", layer.view.thetaDegrees()}, {"phi", layer.view.phiDegrees()}}},
                                  {"node_provenance", provenance}});
    }
    std::filesystem::path sidecar = std::filesystem::path(o.output).replace_extension(".json");
    // Both files are complete on disk before either is renamed into place.
    const Bytes png = encodePng(atlas, 16);
    const std::string text = jsonText(side);
    std::vector<FileContents> files{{o.output, png.data(), png.size()}, {sidecar.string(), text.data(), text.size()}};
    for (const auto& [path, bytes] : textures) files.push_back({path, bytes.data(), bytes.size()});
    if (Status s = writeFilesAtomically(files); !s) return s;
    std::cout << "wrote " << o.output << " (" << atlas.width << "x" << atlas.height << ", 16-bit), " << sidecar.string();
    if (!textures.empty()) std::cout << " and " << textures.size() << " textures beside them";
    std::cout << "\n";
    return success();
}

}  // namespace

void addExportCommand(CLI::App& root, Commands& commands) {
    auto o = std::make_shared<ExportOptions>();
    CLI::App* app = root.add_subcommand(
        "export", "Write a bank's LUT grid as a 16-bit PNG atlas with a JSON sidecar (and, for banks that blend "
                  "references, their textures)");
    app->add_option("BANK", o->bank, "M.btflut")->required();
    app->add_option("-o,--output", o->output, "atlas.png (the sidecar is atlas.json)")->required();
    commands.push_back({app, [o] { return runExport(*o); }});
}

}  // namespace btflut::cli

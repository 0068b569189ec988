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
    const std::uint64_t rows = static_cast<std::uint64_t>(cells) * b.layers.size();
    if (rows > 0x7FFFFFFFu || rows * static_cast<std::uint64_t>(b.entries) > maxImagePixels())
        return Error{o.bank + ": its atlas would be " + std::to_string(b.entries) + "x" + std::to_string(rows) +
                     " pixels, more than a PNG (or --max-pixels) allows; bake it with a smaller --grid"};
    // One row per grid node (layer-major, then j, then i), one column per LUT entry; RGB
    // banks use the three colour channels of the PNG.
    Image atlas(b.entries, cells * static_cast<int>(b.layers.size()), channels, 16);
    for (std::size_t l = 0; l < b.layers.size(); ++l)
        for (int cell = 0; cell < cells; ++cell)
            for (int c = 0; c < channels; ++c)
                for (int k = 0; k < b.entries; ++k)
                    atlas.at(k, static_cast<int>(l) * cells + cell, c) =
                        b.layers[l].gridLuts[(static_cast<std::size_t>(cell) * channels + c) * b.entries + k] /
                        65535.f;

    nlohmann::json side;
    side["format"] = "btflut-atlas";
    side["version"] = 1;
    side["atlas"] = std::filesystem::path(o.output).filename().string();
    side["entries"] = b.entries;
    side["colour"] = b.colour == ColourMode::Grey ? "grey" : "rgb";
    side["grid_size"] = b.gridSize;
    side["row_of_node"] = "layer * grid_size^2 + j * grid_size + i";
    side["entry_value"] = "column k holds LUT(k / (entries - 1)); 16-bit value / 65535";
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
    if (Status s = writeFilesAtomically({{o.output, png.data(), png.size()}, {sidecar.string(), text.data(), text.size()}}); !s)
        return s;
    std::cout << "wrote " << o.output << " (" << atlas.width << "x" << atlas.height
              << ", 16-bit) and " << sidecar.string() << "\n";
    return success();
}

}  // namespace

void addExportCommand(CLI::App& root, Commands& commands) {
    auto o = std::make_shared<ExportOptions>();
    CLI::App* app = root.add_subcommand(
        "export", "Write a bank's LUT grid as a 16-bit PNG atlas with a JSON sidecar");
    app->add_option("BANK", o->bank, "M.btflut")->required();
    app->add_option("-o,--output", o->output, "atlas.png (the sidecar is atlas.json)")->required();
    commands.push_back({app, [o] { return runExport(*o); }});
}

}  // namespace btflut::cli

// btflut export: a bank for engines (a folder: reference, 3D LUT texture, sidecar, shader
// include; docs/engines.md), as the older 16-bit PNG atlas, or its PTM as an RTI .ptm file.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/cli.h"
#include "core/bank/bank_file.h"
#include "core/io/json_text.h"
#include "core/predict/ptm_file.h"
#include "gl/shader.h"

namespace btflut::cli {

namespace {

struct ExportOptions {
    std::string bank;
    std::string output;
    std::string ptm;
    int grid = 0;
    bool force = false;
};

// The grid's LUTs as a 16-bit image: one row per grid node (layer-major, then j, then i) and
// region, one column per LUT entry (or quantile sample); RGB banks use the three colour
// channels. For a bank of LUTs (one region) its rows are, in memory, the 3D texture of width
// entries, height G and depth G x layers that `export -o DIR/` hands to engines.
Result<Image> gridImage(const ExportOptions& o, const LutBank& b, const std::string& what) {
    const int cells = b.gridSize * b.gridSize;
    const int channels = b.channels();
    const int width = static_cast<int>(b.segmentLength()), regions = b.makesLuts() ? b.blend.regions : 1;
    const std::uint64_t rows = static_cast<std::uint64_t>(cells) * b.layers.size() * static_cast<std::uint64_t>(regions);
    if (rows > 0x7FFFFFFFu || rows * static_cast<std::uint64_t>(width) > maxImagePixels())
        return Error{o.bank + ": its " + what + " would be " + std::to_string(width) + "x" + std::to_string(rows) +
                     " pixels, more than a PNG (or --max-pixels) allows; bake it with a smaller --grid"};
    Image image(width, static_cast<int>(rows), channels, 16);
    const std::vector<std::uint16_t> texels = b.gridTexels();  // the same order as the image's samples
    std::transform(texels.begin(), texels.end(), image.samples.begin(), [](std::uint16_t t) { return t / 65535.f; });
    return image;
}

Status exportAtlas(const ExportOptions& o, const LutBank& b) {
    Result<Image> grid = gridImage(o, b, "atlas");
    if (!grid) return Error{grid.error()};
    const Image& atlas = *grid;

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
        blend["match"] = bl.match;  // the LUT blended with the prediction's own distribution below 1
        blend["target"] = bl.target == LutBank::Blend::Target::Corrections ? "corrections" : "measured";
        blend["mask"] = texture("mask", byteImage(bl.mask.inside, b.reference.width, b.reference.height, 255));
        if (!bl.labels.empty()) blend["labels"] = texture("labels", byteImage(bl.labels, b.reference.width, b.reference.height, 1));
        if (!bl.albedo.samples.empty()) blend["albedo"] = texture("albedo", bl.albedo);
        if (bl.predictor == LutBank::Blend::Predictor::Model) {
            // The light model (docs/predictors.md; its LMDL chunk in docs/btflut-format.md).
            const LightModel& m = bl.model;
            nlohmann::json model{{"basis", lightBasisName(m.basis)}, {"name", lightModelName(m)}, {"planes", m.planes},
                                 {"planes_8bit", m.wide}, {"channels", m.channels}, {"order", m.order},
                                 {"scale", m.scale}, {"bias", m.bias}, {"images", nlohmann::json::array()}};
            if (m.basis == LightBasis::Rbf) {
                model["sigma"] = m.sigma;
                for (Direction d : m.lights) model["lights"].push_back(directionJson(d));
            }
            if (m.basis == LightBasis::Bilinear) model["grid"] = m.grid;
            if (!m.table.empty()) model["table"] = m.table;
            const std::vector<Image> images = lightModelImages(m);
            for (std::size_t k = 0; k < images.size(); ++k)
                model["images"].push_back(texture("model-" + std::to_string(k), images[k]));
            model["layout"] =
                "images: the 8-bit planes three to an image (R, G, B), then the 4-bit planes six to an image (two to a "
                "channel, the first in the high nibble), then the albedo if the model has one; value = (code - bias) * "
                "scale; table rows (per rbf light or bln grid node j * grid + i): the channels' offsets, then each "
                "plane's channel weights";
            blend["predictor"] = lightModelName(m);
            blend["model"] = model;
        } else if (bl.predictor == LutBank::Blend::Predictor::Ptm) {
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
                                               {"light", directionJson(bl.lights[k].light)}});
        }
        blend["how"] =
            "per light: blend the references of the Delaunay triangle (equal-area disk) around the light with "
            "barycentric weights (or relight the PTM or the light model), round the blend to its codes, and per region map its "
            "distribution over the mask's texels onto the quantile function blended from the atlas's nodes "
            "(see src/core/predict/relighter.h)";
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
                         {"light", directionJson(b.referenceLight)},
                         {"view", directionJson(b.referenceView)}};
    side["layers"] = nlohmann::json::array();
    for (const ViewLayer& layer : b.layers) {
        nlohmann::json provenance = nlohmann::json::array();
        for (Provenance p : layer.gridProvenance) provenance.push_back(provenanceName(p));
        side["layers"].push_back({{"view", directionJson(layer.view)},
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

// The folder an engine loads: reference.png (its own bit depth), luts.png (the LUT grid as a
// 3D texture's slices, 16-bit), material.json and btflut.glsl.
Status exportFolder(const ExportOptions& o, const LutBank& b) {
    namespace fs = std::filesystem;
    if (b.makesLuts())
        return Error{o.bank + ": this bank makes its LUTs at run time from its predictor (relighter.h), which no "
                              "single texture holds; export its atlas with -o atlas.png, or bake with --references 1"};
    if (b.reference.samples.empty()) return Error{o.bank + ": the bank holds no reference image (baked with --no-reference)"};
    std::error_code ec;
    if (fs::exists(o.output, ec)) {
        if (!fs::is_directory(o.output, ec)) return Error{o.output + ": exists and is not a folder"};
        if (!fs::is_empty(o.output, ec) && !o.force)
            return Error{o.output + ": the folder is not empty (--force writes over btflut's files in it)"};
    }
    const int g = b.gridSize, layers = static_cast<int>(b.layers.size()), channels = b.channels();
    // Row (layer * G + j) * G + i holds node (i, j)'s LUT (a bank of LUTs has one region).
    Result<Image> luts = gridImage(o, b, "LUT texture");
    if (!luts) return Error{luts.error()};
    nlohmann::json side{
        {"format", "btflut-material"},
        {"version", 1},
        {"shader", "btflut.glsl"},
        {"shader_version", 1},
        {"reference", {{"file", "reference.png"},
                       {"width", b.reference.width},
                       {"height", b.reference.height},
                       {"channels", b.reference.channels},
                       {"bit_depth", b.reference.bitDepth},
                       {"name", b.referenceName},
                       {"light", directionJson(b.referenceLight)},
                       {"view", directionJson(b.referenceView)}}},
        {"luts", {{"file", "luts.png"},
                  {"texture", "3D, width entries, height grid_size, depth grid_size x layers; 16-bit unorm, " +
                                  std::string(channels == 3 ? "RGB (one LUT per colour channel)" : "one channel")},
                  {"entries", b.entries},
                  {"grid_size", g},
                  {"layers", layers},
                  {"row_of_node", "(layer * grid_size + j) * grid_size + i"}}},
        {"colour", colourName(b.colour)},
        {"lut_input_code", inputCode(b.reference, b.colour)},
        {"lut_output_code", b.targetCode()},
        {"grid_mapping", "node (i, j) at disk point x = -1 + 2 i / (grid_size - 1), y likewise with j; a direction "
                         "(theta, phi) maps to sqrt(2) sin(theta / 2) (cos phi, sin phi); z = surface normal, x = "
                         "texture +u (image right), y = texture +v (image up)"},
        {"views", nlohmann::json::array()}};
    for (const ViewLayer& layer : b.layers) {
        nlohmann::json provenance = nlohmann::json::array();
        for (Provenance p : layer.gridProvenance) provenance.push_back(provenanceName(p));
        side["views"].push_back({{"view", directionJson(layer.view)}, {"node_provenance", provenance}});
    }
    if (!b.modelFill.empty()) side["model_fill"] = nlohmann::json::parse(b.modelFill, nullptr, false);

    const Bytes reference = encodePng(b.reference, b.reference.bitDepth), lutPng = encodePng(*luts, 16);
    const std::string text = jsonText(side);
    const std::string_view shader = embeddedShader("btflut.glsl");
    fs::create_directories(o.output, ec);
    if (ec) return Error{o.output + ": cannot create the folder (" + ec.message() + ")"};
    const fs::path dir(o.output);
    std::vector<FileContents> files{{(dir / "reference.png").string(), reference.data(), reference.size()},
                                    {(dir / "luts.png").string(), lutPng.data(), lutPng.size()},
                                    {(dir / "material.json").string(), text.data(), text.size()},
                                    {(dir / "btflut.glsl").string(), shader.data(), shader.size()}};
    if (Status s = writeFilesAtomically(files); !s) return s;
    std::cout << "wrote " << o.output << ": reference.png (" << b.reference.width << "x" << b.reference.height << ", "
              << b.reference.bitDepth << "-bit), luts.png (3D texture " << b.entries << "x" << g << "x" << g * layers
              << ", 16-bit), material.json, btflut.glsl\n";
    return success();
}

Status exportPtm(const ExportOptions& o, const LutBank& b) {
    if (Status s = requireExtension(o.ptm, {"ptm"}, "--ptm"); !s) return s;
    if (b.ptm.empty()) return Error{o.bank + ": the bank holds no PTM (bake it with --ptm)"};
    if (Status s = writeFileAtomically(o.ptm, encodePtmFile(b.ptm)); !s) return s;
    std::cout << "wrote " << o.ptm << " (PTM 1.2, LRGB, " << b.ptm.width << "x" << b.ptm.height << ")\n";
    return success();
}

Status runExport(const ExportOptions& o) {
    if (o.output.empty() && o.ptm.empty()) return Error{"give -o DIR (or -o atlas.png) and/or --ptm FILE.ptm"};
    Result<LutBank> bank = loadBank(o.bank);
    if (!bank) return Error{bank.error()};
    if (!o.ptm.empty())
        if (Status s = exportPtm(o, *bank); !s) return s;
    if (o.output.empty()) return success();
    if (o.grid > 0 && o.grid != bank->gridSize) {  // resampled from the measured directions
        if (bank->makesLuts()) return Error{o.bank + ": --grid: this bank makes its LUTs at run time"};
        const std::uint64_t bytes = static_cast<std::uint64_t>(o.grid) * o.grid * bank->lutLength() * 2 * bank->layers.size();
        if (bytes > (std::uint64_t{1} << 31)) return Error{"--grid " + std::to_string(o.grid) + ": the LUT texture would take " + std::to_string(bytes) + " bytes"};
        bank->gridSize = o.grid;
        bank->fillGrids();
    }
    return fileExtension(o.output) == "png" ? exportAtlas(o, *bank) : exportFolder(o, *bank);
}

}  // namespace

void addExportCommand(CLI::App& root, Commands& commands) {
    auto o = std::make_shared<ExportOptions>();
    CLI::App* app = root.add_subcommand(
        "export", "Export a bank for engines: a folder with the reference, the LUT grid as a 3D texture, a JSON sidecar "
                  "and the shader include (docs/engines.md); or the older atlas; or its PTM as an RTI .ptm file");
    app->add_option("BANK", o->bank, "M.btflut")->required();
    app->add_option("-o,--output", o->output,
                    "DIR: reference.png, luts.png, material.json, btflut.glsl; or atlas.png: the LUT grid as rows of a "
                    "16-bit PNG with atlas.json (banks that blend references: with their textures)");
    app->add_option("--ptm", o->ptm, "FILE.ptm: the bank's PTM (bake --ptm) as a PTM 1.2 LRGB file for RTI viewers");
    app->add_option("--grid", o->grid,
                    "resample the LUT grid at N x N light directions from the measured ones (default: the bank's; finer "
                    "follows the measured interpolation more closely, at N^2 x entries x 2 bytes per view)")
        ->check(CLI::Range(2, 257));
    app->add_flag("--force", o->force, "write into a folder that is not empty");
    commands.push_back({app, [o] { return runExport(*o); }});
}

}  // namespace btflut::cli

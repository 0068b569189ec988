// btflut export: a bank for engines (a folder: reference, 3D LUT texture, sidecar, shader
// include; docs/engines.md), as the older 16-bit PNG atlas, or its PTM as an RTI .ptm file.
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <regex>

#include "cli/command.h"
#include "cli/web_page.h"
#include "core/bank/bank_file.h"
#include "core/io/json_text.h"
#include "core/predict/light_model.h"
#include "core/predict/model_predictor.h"
#include "core/predict/ptm_file.h"
#include "core/predict/rti_file.h"
#include "core/relight/engine_material.h"
#include "core/relight/material_json.h"
#include "core/relight/relighter.h"
#include "gl/shader.h"

namespace btflut::cli {

namespace {

namespace fs = std::filesystem;

// The shader include in each shading language (tools/shader-forms.sh makes all but the first).
constexpr const char* kShaderIncludes[] = {"btflut.glsl", "btflut_es.glsl", "btflut.hlsl", "btflut.gdshaderinc"};
// The three.js recipe (examples/three/, docs/engines.md), so a folder is all an artist needs:
// its page (three.html) loads the material beside it with the two scripts.
constexpr std::pair<const char*, const char*> kThreeRecipe[] = {{"btflut_material.js", "btflut_material.js"},
                                                                {"btflut-three.js", "btflut-three.js"},
                                                                {"three.html", "relight.html"}};

struct ExportOptions {
    std::string bank;
    std::string output;
    std::string ptm;
    std::string rti;
    std::string web;
    int grid = 0;
    bool force = false;
    bool quiet = false;
    bool json = false;  // what was written, as JSON (nothing else on stdout)
};

// 16-bit texels as an image of `rows` rows of `width` (refused beyond what a PNG holds).
Result<Image> lutRows(const std::string& bankPath, int width, std::uint64_t rows, int channels,
                      const std::vector<std::uint16_t>& texels, const std::string& what) {
    if (rows > 0x7FFFFFFFu || rows * static_cast<std::uint64_t>(width) > maxImagePixels())
        return Error{bankPath + ": its " + what + " would be " + std::to_string(width) + "x" + std::to_string(rows) +
                     " pixels, more than a PNG (or --max-pixels) allows; bake it with a smaller --grid"};
    Image image(width, static_cast<int>(rows), channels, 16);
    std::transform(texels.begin(), texels.end(), image.samples.begin(), [](std::uint16_t t) { return t / 65535.f; });
    return image;
}

// The grid's LUTs as a 16-bit image: one row per grid node (layer-major, then j, then i) and
// region, one column per LUT entry (or quantile sample); RGB banks use the three colour
// channels (the atlas).
Result<Image> gridImage(const ExportOptions& o, const LutBank& b, const std::string& what) {
    const std::uint64_t rows = static_cast<std::uint64_t>(b.gridSize) * static_cast<std::uint64_t>(b.gridSize) *
                               b.layers.size() * static_cast<std::uint64_t>(b.makesLuts() ? b.prediction.regions : 1);
    return lutRows(o.bank, static_cast<int>(b.segmentLength()), rows, b.channels(), b.gridTexels(),
                   what);  // the same order as the image's samples
}

Status exportAtlas(const ExportOptions& o, const LutBank& b) {
    Result<Image> grid = gridImage(o, b, "atlas");
    if (!grid) return Error{grid.error()};
    const Image& atlas = *grid;

    // The textures a bank that blends references relights from, beside the atlas.
    std::vector<std::pair<std::string, Bytes>> textures;
    const std::filesystem::path out(o.output);
    const TextureWriter texture = [&](const std::string& suffix, const Image& image) {
        const std::string name = out.stem().string() + "-" + suffix + ".png";
        textures.push_back({(out.parent_path() / name).string(), encodePng(image, image.bitDepth)});
        return name;
    };
    nlohmann::json blend;
    if (b.makesLuts()) {
        const LutBank::Prediction& prediction = b.prediction;
        blend["quantiles"] = prediction.quantiles;
        blend["regions"] = prediction.regions;
        blend["match"] = prediction.match;  // the LUT blended with the prediction's own distribution below 1
        blend["target"] = prediction.target == LutBank::Prediction::Target::Corrections ? "corrections" : "measured";
        blend["mask"] = texture("mask", byteImage(prediction.mask.inside, b.reference.width, b.reference.height, 255));
        if (!prediction.labels.empty())
            blend["labels"] = texture("labels", byteImage(prediction.labels, b.reference.width, b.reference.height, 1));
        blend["predictor"] = b.predictorName();
        b.predictor().atlasSidecar(blend, texture);
        blend["how"] =
            "per light: blend the references of the Delaunay triangle (equal-area disk) around the light with "
            "barycentric weights (or relight the PTM or the light model), round the blend to its codes, and per region "
            "map its "
            "distribution over the mask's texels onto the quantile function blended from the atlas's nodes "
            "(see src/core/relight/relighter.h)";
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
    side["entry_value"] =
        b.makesLuts() ? "column k holds the target's quantile function at k / (quantiles - 1); 16-bit value / 65535"
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
        side["layers"].push_back({{"view", directionJson(layer.view)}, {"node_provenance", provenance}});
    }
    std::filesystem::path sidecar = std::filesystem::path(o.output).replace_extension(".json");
    // Both files are complete on disk before either is renamed into place.
    const Bytes png = encodePng(atlas, 16);
    const std::string text = jsonText(side);
    std::vector<FileContents> files{{o.output, png.data(), png.size()}, {sidecar.string(), text.data(), text.size()}};
    for (const auto& [path, bytes] : textures) files.push_back({path, bytes.data(), bytes.size()});
    if (Status s = writeFilesAtomically(files); !s) return s;
    if (o.quiet) return success();
    std::cout << "wrote " << o.output << " (" << atlas.width << "x" << atlas.height << ", 16-bit), "
              << sidecar.string();
    if (!textures.empty()) std::cout << " and " << textures.size() << " textures beside them";
    std::cout << "\n";
    return success();
}

// Writes `files` (names inside `folder`) so that a failure leaves no partial folder: a new
// folder is filled beside its place and renamed into it; an existing one (empty, or --force)
// gets every file complete before the first is renamed (writeFilesAtomically).
Status writeFolder(const std::string& folder, const std::vector<std::pair<std::string, std::string_view>>& files) {
    std::error_code ec;
    const bool exists = fs::exists(folder, ec);
    fs::path target(folder);
    if (target.filename().empty()) target = target.parent_path();  // DIR/
    const fs::path dir = exists ? target : fs::path(target.string() + ".partial-" + std::to_string(::getpid()));
    if (!exists) {
        if (!target.parent_path().empty()) fs::create_directories(target.parent_path(), ec);
        if (ec || !fs::create_directory(dir, ec) || ec)
            return Error{folder + ": cannot create the folder (" + (ec ? ec.message() : std::string("it exists")) +
                         ")"};
    }
    std::vector<FileContents> contents;
    for (const auto& [name, bytes] : files) contents.push_back({(dir / name).string(), bytes.data(), bytes.size()});
    Status written = writeFilesAtomically(contents);
    if (written && !exists) {
        fs::rename(dir, target, ec);
        if (ec) written = Error{folder + ": cannot move the finished folder into place (" + ec.message() + ")"};
    }
    if (!written && !exists) fs::remove_all(dir, ec);
    return written;
}

std::string_view asText(const Bytes& bytes) { return {reinterpret_cast<const char*>(bytes.data()), bytes.size()}; }

// A file name an export writes (material.json, luts.png, planes-N.png, ...).
bool exportFileName(const std::string& name) {
    static const std::regex planes(R"(planes-\d+\.png)");
    for (const char* file : {"reference.png", "luts.png", "material.json", "albedo.png", "labels.png", "weights.bin"})
        if (name == file) return true;
    for (const char* file : kShaderIncludes)
        if (name == file) return true;
    for (const char* file : kNetworkFiles)
        if (name == file) return true;
    for (const auto& [file, source] : kThreeRecipe)
        if (name == file) return true;
    return std::regex_match(name, planes);
}

// The export file an engine's import sidecar belongs to ("reference.png" for Godot's
// "reference.png.import" and Unity's "reference.png.meta"), or empty for any other name.
std::string sidecarOf(const std::string& name) {
    for (const std::string suffix : {".import", ".meta"})
        if (name.size() > suffix.size() && name.ends_with(suffix)) {
            const std::string base = name.substr(0, name.size() - suffix.size());
            if (exportFileName(base)) return base;
        }
    return {};
}

// What an existing -o folder holds: a previous export (a btflut material.json), and files
// that are neither an export's nor an engine's import sidecar of one (the user's).
struct FolderContents {
    bool previousExport = false, others = false;
};
FolderContents folderContents(const std::string& folder) {
    FolderContents c;
    std::error_code ec;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        const bool ours = it->is_regular_file(ec) && (exportFileName(name) || !sidecarOf(name).empty());
        c.others = c.others || !ours;
    }
    if (Result<Bytes> text = readFile((fs::path(folder) / "material.json").string()); text) {
        const nlohmann::json material = nlohmann::json::parse(text->begin(), text->end(), nullptr, false);
        c.previousExport =
            !material.is_discarded() && material.is_object() && material.value("format", "") == "btflut-material";
    }
    c.others = c.others || ec;
    return c;
}

// An engine export's files in memory (docs/engines.md): reference.png (its own bit depth),
// luts.png (the LUT grid as a 3D texture's slices, 16-bit), material.json and the shader
// includes; for a bank with a predictor also its planes (or references), albedo, weights and
// labels. What `-o DIR/` writes and `--web` puts in its page.
struct EngineExport {
    nlohmann::json side;                                     ///< material.json
    std::vector<std::pair<std::string, std::string>> files;  ///< name, bytes; material.json and the includes last
    std::string summary;  ///< "model material, luts.png (3D texture 256x17x17, 16-bit)"
};

Result<EngineExport> engineExport(const LutBank& b, const std::string& bankPath) {
    Result<EngineMaterial> made = engineMaterial(b, bankPath);
    if (!made) return Error{made.error()};
    const EngineMaterial& m = *made;
    const bool predictor = m.kind != PredictorKind::Luts;
    const int g = m.gridSize;
    // Row (block * G + j) * G + i holds node (i, j)'s LUT; a block is a view layer or a region.
    Result<Image> luts =
        lutRows(bankPath, m.entries, static_cast<std::uint64_t>(g) * g * static_cast<std::uint64_t>(m.blocks),
                m.lutChannels, m.lutTexels, "LUT texture");
    if (!luts) return Error{luts.error()};
    EngineExport out;
    std::vector<std::pair<std::string, Bytes>> pngs{{"reference.png", encodePng(b.reference, b.reference.bitDepth)},
                                                    {"luts.png", encodePng(*luts, 16)}};
    std::string weights;
    if (predictor) {
        for (std::size_t k = 0; k < m.images.size(); ++k)
            pngs.push_back({planeImageName(k), encodePng(m.images[k], 8)});
        if (!m.albedo.samples.empty()) pngs.push_back({"albedo.png", encodePng(m.albedo, 8)});
        if (!m.labels.samples.empty()) pngs.push_back({"labels.png", encodePng(m.labels, 8)});
        static_assert(std::endian::native == std::endian::little, "weights.bin is little-endian");
        weights.assign(reinterpret_cast<const char*>(m.weightGrid.data()), m.weightGrid.size() * sizeof(float));
    }
    for (auto& [name, bytes] : pngs) out.files.push_back({name, std::string(asText(bytes))});
    if (!weights.empty()) out.files.push_back({"weights.bin", weights});
    out.side = materialJson(b, m);
    out.files.push_back({"material.json", jsonText(out.side)});
    for (const char* include : kShaderIncludes) out.files.push_back({include, std::string(embeddedShader(include))});
    if (!m.networkGlsl.empty()) {  // the learned decoder specialised to this material
        out.files.push_back({kNetworkFiles[0], m.networkGlsl});
        out.files.push_back({kNetworkFiles[1], m.networkHlsl});
        out.files.push_back({kNetworkFiles[2], m.networkGlsl});
    }
    out.summary = out.side["kind"].get<std::string>() + " material, luts.png (3D texture " + std::to_string(m.entries) +
                  "x" + std::to_string(g) + "x" + std::to_string(g * m.blocks) + ", 16-bit)";
    return out;
}

// -o DIR/: whether the folder may be written (before anything is made), and whether it holds
// a previous export (a re-export: its stale files go). A folder of an export and the import
// sidecars Godot and Unity write beside its files (.import, .meta) is an asset pipeline's:
// exported into again without --force; one with other files needs --force.
Result<bool> folderReady(const ExportOptions& o) {
    std::error_code ec;
    if (!fs::exists(o.output, ec)) return false;
    if (!fs::is_directory(o.output, ec)) return Error{o.output + ": exists and is not a folder"};
    const FolderContents c = folderContents(o.output);
    if (c.others && !o.force)
        return Error{o.output +
                     ": the folder holds files that are neither a btflut export's nor an engine's import sidecars "
                     "of them (--force writes over btflut's files in it and keeps the others)"};
    return c.previousExport;
}

// A file's absolute file:// URL, percent-encoded: a relative path with '#' in a browser's
// command line is read as a host name, so the page's command is given whole.
std::string fileUrl(const std::string& path) {
    const std::string absolute = fs::absolute(path).lexically_normal().generic_string();
    std::string url = "file://";
    for (unsigned char c : absolute) {
        if (std::isalnum(c) || std::strchr("/-._~", c)) {
            url += static_cast<char>(c);
        } else {
            char escaped[4];
            std::snprintf(escaped, sizeof escaped, "%%%02X", c);
            url += escaped;
        }
    }
    return url;
}

// -o DIR/: the export's files in a folder.
Status exportFolder(const ExportOptions& o, const EngineExport& made, bool reexport) {
    std::error_code ec;
    std::vector<std::pair<std::string, std::string_view>> files;
    for (const auto& [name, bytes] : made.files) files.push_back({name, bytes});
    for (const auto& [name, source] : kThreeRecipe) files.push_back({name, embeddedWebFile(source)});
    if (Status s = writeFolder(o.output, files); !s) return s;
    // What a previous export wrote and this one did not (planes of a bigger model, weights),
    // and the engines' import sidecars of those files; the sidecars of files written again
    // stay (Unity's .meta holds the GUID that a scene's references use). Other files stay.
    auto written = [&](const std::string& name) {
        return std::any_of(files.begin(), files.end(), [&](const auto& f) { return f.first == name; });
    };
    std::vector<fs::path> stale;
    for (fs::directory_iterator it(o.output, ec), end; reexport && !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string(), base = sidecarOf(name);
        if ((exportFileName(name) && !written(name)) || (!base.empty() && !written(base))) stale.push_back(it->path());
    }
    for (const fs::path& path : stale) fs::remove(path, ec);
    if (o.quiet) return success();
    std::cout << "wrote " << o.output << ": " << made.summary;
    for (const auto& file : files)
        if (file.first != "luts.png") std::cout << ", " << file.first;
    std::cout << "\nin three.js (WebGL2, no server): chromium --allow-file-access-from-files '"
              << fileUrl((fs::path(o.output) / "three.html").string()) << "#light=30,90'\n";
    return success();
}

// --web M.html: one page that opens from disk and relights the material with WebGL2.
Status exportWeb(const ExportOptions& o, const EngineExport& made) {
    const std::string page = webPage(fs::path(o.bank).stem().string(), made.side, made.files);
    if (Status s = writeFileAtomically(o.web, page.data(), page.size()); !s) return s;
    std::size_t exported = 0;
    for (const auto& file : made.files) exported += file.second.size();
    if (!o.quiet) {
        char ratio[32];
        std::snprintf(ratio, sizeof ratio, "%.2f", static_cast<double>(page.size()) / static_cast<double>(exported));
        std::cout << "wrote " << o.web << ": " << made.summary << ", one page of " << page.size() << " bytes (" << ratio
                  << " x the export's files); open it in a browser (WebGL2, no server):\n  chromium '" << fileUrl(o.web)
                  << "#light=30,90'\n";
    }
    return success();
}

Status exportPtm(const ExportOptions& o, const LutBank& b) {
    if (Status s = requireExtension(o.ptm, {"ptm"}, "--ptm"); !s) return s;
    if (b.ptm.empty()) return Error{o.bank + ": the bank holds no PTM (bake it with --ptm)"};
    if (Status s = writeFileAtomically(o.ptm, encodePtmFile(b.ptm)); !s) return s;
    if (!o.quiet) std::cout << "wrote " << o.ptm << " (PTM 1.2, LRGB, " << b.ptm.width << "x" << b.ptm.height << ")\n";
    return success();
}

// --rti FILE.rti: an HSH model as RTIViewer's hemispherical-harmonics file.
Status exportRti(const ExportOptions& o, const LutBank& b) {
    if (Status s = requireExtension(o.rti, {"rti"}, "--rti"); !s) return s;
    const ModelPredictor* model = b.predictorAs<ModelPredictor>();
    if (!model || model->model().basis != LightBasis::Hsh)
        return Error{o.bank + ": its predictor is " +
                     (b.makesLuts() ? b.predictorName() : std::string("none (a bank of LUTs)")) +
                     "; an .rti file holds hemispherical harmonics: bake with --predictor hsh2 or hsh3 (or export "
                     "--ptm FILE.ptm from a bank baked with --ptm)"};
    if (Status s = writeFileAtomically(o.rti, encodeHshRtiFile(model->model())); !s) return s;
    if (!o.quiet)
        std::cout << "wrote " << o.rti << " (HSH order " << model->model().order << ", " << model->model().width << "x"
                  << model->model().height << ", RGB)\n";
    return success();
}

Status runExport(const ExportOptions& o) {
    if (o.output.empty() && o.ptm.empty() && o.web.empty() && o.rti.empty())
        return Error{"give -o DIR (or -o atlas.png), --web PAGE.html, --ptm FILE.ptm and/or --rti FILE.rti"};
    if (!o.web.empty())
        if (Status s = requireExtension(o.web, {"html", "htm"}, "--web"); !s) return s;
    Result<LutBank> bank = loadBank(o.bank);
    if (!bank) return Error{bank.error()};
    if (!o.ptm.empty())
        if (Status s = exportPtm(o, *bank); !s) return s;
    if (!o.rti.empty())
        if (Status s = exportRti(o, *bank); !s) return s;
    if (o.output.empty() && o.web.empty()) return success();
    if (Status s = drawnOnGpu(*bank); !s) return Error{o.bank + ": " + s.error()};
    if (o.grid > 0 && o.grid != bank->gridSize) {  // resampled from the measured directions
        const std::size_t length = bank->makesLuts() ? bank->matchLength() : bank->lutLength();
        const std::uint64_t bytes = static_cast<std::uint64_t>(o.grid) * o.grid * length * 2 * bank->layers.size();
        if (bytes > (std::uint64_t{1} << 31))
            return Error{"--grid " + std::to_string(o.grid) + ": the LUT texture would take " + std::to_string(bytes) +
                         " bytes"};
        bank->gridSize = o.grid;
        bank->fillGrids();
        if (bank->makesLuts()) bakeMatchGrid(*bank);  // the match LUTs at the new nodes
    }
    const bool folder = !o.output.empty() && fileExtension(o.output) != "png";
    bool reexport = false;
    if (folder) {  // refused before anything is made or written
        Result<bool> ready = folderReady(o);
        if (!ready) return Error{ready.error()};
        reexport = *ready;
    }
    if (folder || !o.web.empty()) {
        // The folder and the page hold the same files: made once.
        Result<EngineExport> made = engineExport(*bank, o.bank);
        if (!made) return Error{made.error()};
        if (!o.web.empty())
            if (Status s = exportWeb(o, *made); !s) return s;
        if (folder) return exportFolder(o, *made, reexport);
    }
    return o.output.empty() ? success() : exportAtlas(o, *bank);
}

// --json: runs the export quietly, then says what it wrote.
Status runExportReporting(ExportOptions o) {
    const bool json = o.json;
    if (json) o.quiet = true;
    if (Status s = runExport(o); !s || !json) return s;
    nlohmann::json out = nlohmann::json::object();
    if (!o.ptm.empty()) out["ptm"] = o.ptm;
    if (!o.rti.empty()) out["rti"] = o.rti;
    if (!o.web.empty()) out["web"] = {{"page", o.web}, {"open", "chromium '" + fileUrl(o.web) + "#light=30,90'"}};
    if (!o.output.empty() && fileExtension(o.output) == "png") {
        out["atlas"] = o.output;
    } else if (!o.output.empty()) {
        std::vector<std::string> files;
        std::error_code ec;
        for (fs::directory_iterator it(o.output, ec), end; !ec && it != end; it.increment(ec))
            files.push_back(it->path().filename().string());
        std::sort(files.begin(), files.end());
        out["folder"] = {{"path", o.output}, {"files", files}};
    }
    std::cout << jsonText(out);
    return success();
}

}  // namespace

void addExportCommand(CLI::App& root, Commands& commands) {
    auto o = std::make_shared<ExportOptions>();
    CLI::App* app = root.add_subcommand(
        "export",
        "Export a bank for engines: a folder with the reference, the LUT grid as a 3D texture, a JSON sidecar "
        "and the shader include (docs/engines.md); or the older atlas; or its PTM as an RTI .ptm file");
    app->add_option("BANK", o->bank, "M.btflut")->required();
    app->add_option("-o,--output", o->output,
                    "DIR: reference.png, luts.png, material.json, btflut.glsl (and its GLSL ES, HLSL and Godot forms); "
                    "or atlas.png: the LUT grid as rows of a "
                    "16-bit PNG with atlas.json (banks that blend references: with their textures)");
    app->add_option(
        "--web", o->web,
        "PAGE.html: one page that opens from disk (no network) and relights the material with WebGL2: the "
        "export's files inside it, the light on a disk, 2D and a sphere; #light=THETA,PHI&zoom=1&view=2d|sphere&ui=0");
    app->add_option("--ptm", o->ptm, "FILE.ptm: the bank's PTM (bake --ptm) as a PTM 1.2 LRGB file for RTI viewers");
    app->add_option("--rti", o->rti,
                    "FILE.rti: the bank's HSH model (bake --predictor hsh2 or hsh3) as RTIViewer's hemispherical-"
                    "harmonics file");
    app->add_option(
           "--grid", o->grid,
           "resample the LUT grid at N x N light directions from the measured ones (default: the bank's; finer "
           "follows the measured interpolation more closely, at N^2 x entries x 2 bytes per view)")
        ->check(CLI::Range(2, 257));
    app->add_flag("--force", o->force, "write into a folder that is not empty");
    addQuietFlag(*app, o->quiet);
    app->add_flag("--json", o->json,
                  "print what was written as JSON: the folder and its files, the page and the command that opens it, "
                  "the PTM, the atlas");
    commands.push_back({app, [o] { return runExportReporting(*o); }});
}

}  // namespace btflut::cli

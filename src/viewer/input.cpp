#include "viewer/input.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <optional>

#include "core/bake/auto_bake.h"
#include "core/bake/bake.h"
#include "core/bank/bank_file.h"
#include "core/data/dataset.h"
#include "core/io/json_text.h"
#include "viewer/bake_cache.h"

namespace btflut {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// The parameters `btflut synth` recorded in a dataset's manifest, if any.
json manifestParameters(const std::string& datasetPath) {
    fs::path manifest =
        fs::is_directory(datasetPath) ? fs::path(datasetPath) / "btflut-dataset.json" : fs::path(datasetPath);
    if (manifest.extension() != ".json" || !fs::exists(manifest)) return {};
    Result<Bytes> bytes = readFile(manifest.string());
    if (!bytes) return {};
    Result<json> doc = parseJsonText(std::string(bytes->begin(), bytes->end()), manifest.string());
    return doc && doc->is_object() && doc->contains("synth") ? (*doc)["synth"] : json{};
}

// The bundled material: $BTFLUT_DEFAULT_MATERIAL, else beside the executable (a build tree's
// assets/default), else where `cmake --install` puts it (PREFIX/share/btflut/default).
std::string defaultMaterial() {
    if (const char* set = std::getenv("BTFLUT_DEFAULT_MATERIAL"); set && *set) return set;
    std::error_code ec;
    const fs::path bin = fs::read_symlink("/proc/self/exe", ec).parent_path();
    const fs::path installed = bin.parent_path() / "share" / "btflut" / "default";
    for (const fs::path& folder : {bin / "assets" / "default", installed})
        if (fs::exists(folder / "btflut-dataset.json", ec)) return folder.string();
    return installed.string();  // named in the error
}

// The options a dataset is baked with, as text for the cache's key.
std::string bakeSettings(const BakeOptions& bake, bool validate) {
    std::string text = "validate " + std::to_string(validate) + " references " + std::to_string(bake.references) +
                       " regions " + std::to_string(bake.regions) + " colour " +
                       std::to_string(static_cast<int>(bake.colour)) + " grid " + std::to_string(bake.gridSize);
    if (bake.fit) text += " " + bake.fit->settings();
    return text;
}

}  // namespace

Result<ViewerInput> openInput(const ViewerOptions& o) {
    ViewerInput in;
    const std::string path = o.input.empty() ? defaultMaterial() : o.input;
    in.title = "btflut view - " + path;
    if (!fs::exists(path)) return Error{path + ": cannot open (no such file or folder)"};
    const std::string extension = fs::path(path).extension().string();
    if (!fs::is_directory(path) && extension != ".btflut" && extension != ".json" && extension != ".lp")
        return Error{path + ": not a bank (.btflut), a dataset (folder, .json manifest, .lp) or a scene file (.json)"};
    if (fs::path(path).extension() == ".json" && !fs::is_directory(path)) {
        Result<Bytes> bytes = readFile(path);
        if (!bytes) return Error{bytes.error()};
        Result<json> doc = parseJsonText(std::string(bytes->begin(), bytes->end()), path);
        if (!doc) return Error{doc.error()};
        if (doc->is_object() && doc->contains("quads")) {
            Result<Scene> scene = loadScene(path);
            if (!scene) return Error{scene.error()};
            in.scene = std::move(*scene);
            return in;
        }
    }
    std::string bank = path, images = o.images;
    std::optional<LutBank> opened;                  // the bank, once read or baked: read once
    if (fs::path(path).extension() != ".btflut") {  // a dataset: bake it (or find it baked)
        Result<Dataset> dataset = openDataset(path);
        if (!dataset) return Error{dataset.error()};
        // What `btflut bake DATASET` writes (the validated choice), unless a predictor is named;
        // kept in the cache so the dataset opens at once next time (--rebake bakes again).
        BakeOptions bake = o.bake;
        bake.ptm = true;
        const std::string cached = bakeCachePath(*dataset, bakeSettings(bake, o.validate));
        std::error_code ec;
        if (!o.rebake && fs::exists(cached, ec))
            if (Result<LutBank> found = loadBank(cached, {.ptm = false})) opened = std::move(*found);
        in.bakeReused = opened.has_value();
        if (in.bakeReused) {
            bank = cached;
        } else {
            auto make = [&] { return o.validate ? bakeAuto(*dataset, {.base = bake}) : bakeBank(*dataset, bake); };
            Result<LutBank> baked = make();
            if (!baked && baked.error().find("a PTM needs") != std::string::npos) {
                bake.ptm = false;  // too few lights for a PTM: mode ptm stays off
                baked = make();
            }
            if (!baked) return Error{baked.error()};
            fs::create_directories(fs::path(cached).parent_path(), ec);
            if (saveBank(*baked, cached)) {
                bank = cached;
            } else {                          // no cache to write to (a read-only home): a file for this session
                static int sessionBanks = 0;  // a session may open several datasets
                in.temporaryBank = (fs::temp_directory_path() / ("btflut-view-" + std::to_string(::getpid()) + "-" +
                                                                 std::to_string(sessionBanks++) + ".btflut"))
                                       .string();
                if (Status s = saveBank(*baked, in.temporaryBank); !s) return Error{s.error()};
                bank = in.temporaryBank;
            }
            opened = std::move(*baked);
        }
        if (bank == cached) pruneBakeCache(cached);
        images = path;
        in.modelParameters = manifestParameters(path);
        in.bakedBank = bank;
        const std::string shown = opened->makesLuts() ? opened->predictorName() : "the one-reference bank";
        std::cout << "view: " << (in.bakeReused ? "opened the bank of " : "baked ") << path
                  << (in.bakeReused ? " baked earlier" : "") << " as `btflut bake` would"
                  << (o.validate ? " (the validated choice: " : " (") << shown << ")"
                  << (in.bakeReused ? "; --rebake bakes it again" : "") << "\n";
    } else {
        Result<LutBank> read = loadBank(bank, {.ptm = false});
        if (!read) return Error{read.error()};
        opened = std::move(*read);
    }
    const double aspect = static_cast<double>(opened->reference.width) / opened->reference.height;
    in.singleQuad = true;
    in.scene.file = path;
    in.scene.fovDegrees = 40;
    in.scene.materials["material"] = {bank, images};
    in.scene.quads = {{"material", {0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 2 * aspect, 2, 1, RenderMode::Lut}};
    in.scene.eye = {0, -1.5, 2.6};  // from 60 degrees above the quad
    in.scene.target = {0, 0, 0};
    return in;
}

TemporaryFile::~TemporaryFile() {
    std::error_code ec;
    if (!path.empty()) fs::remove(path, ec);
}

}  // namespace btflut

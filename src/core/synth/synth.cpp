#include "core/synth/synth.h"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "core/image/image.h"
#include "core/io/file_io.h"
#include "core/io/json_text.h"
#include "core/synth/render.h"

namespace btflut {

namespace fs = std::filesystem;

Result<SynthMaterial> synthPreset(const std::string& name) {
    SynthMaterial m;
    m.surface.roughness = 0.4;
    if (name == "concrete") {
        m.model.brdf = {.kd = 1, .ks = 0};
    } else if (name == "foil") {
        m.model.brdf = {.kd = 0, .ks = 1, .sigma = 0.13, .ior = 1.5};
    } else if (name == "plastic") {
        m.model.brdf = {.kd = 0.7, .ks = 0.3, .sigma = 0.13, .ior = 1.5};
    } else if (name == "corduroy") {
        m.surface.roughness = 0.6;
        m.surface.roughnessAcross = 0.15;
        m.model.brdf = {.kd = 1, .ks = 0};
    } else {
        return Error{"--preset '" + name + "' is not concrete, foil, plastic or corduroy"};
    }
    m.model.roughness = m.surface.roughness;
    return m;
}

Status validateSynthMaterial(const SynthMaterial& m) {
    if (Status s = validateHeightFieldSpec(m.surface); !s) return s;
    if (Status s = validateModel(m.model, "--"); !s) return s;
    if (!(m.albedoVariation >= 0 && m.albedoVariation <= 1)) return Error{"--albedo-variation must be within [0, 1]"};
    if (!(m.ambient >= 0) || !std::isfinite(m.ambient)) return Error{"--ambient must be >= 0"};
    if (!(m.noise >= 0) || !std::isfinite(m.noise)) return Error{"--noise must be >= 0"};
    return success();
}

namespace {

// Albedo 1 - variation * Phi(g), g a smooth unit-variance Gaussian field (another seed).
Result<std::vector<double>> albedoMap(const SynthMaterial& m) {
    HeightFieldSpec spec = m.surface;
    spec.seed = m.surface.seed * 7919 + 17;
    spec.roughnessAcross = 0;
    spec.correlationLength = std::min(2 * m.surface.correlationLength, m.surface.size / 4.0);
    Result<HeightField> g = synthesizeHeightField(spec);
    if (!g) return Error{g.error()};
    double sum2 = 0;
    for (double h : g->height) sum2 += h * h;
    const double rms = std::sqrt(sum2 / static_cast<double>(g->height.size()));
    std::vector<double> albedo(g->height.size());
    for (std::size_t i = 0; i < albedo.size(); ++i)
        albedo[i] = 1 - m.albedoVariation * 0.5 * std::erfc(-g->height[i] / rms / std::numbers::sqrt2);
    return albedo;
}

// The files an earlier `btflut synth` wrote into `folder` (its manifest says so), as plain
// names inside it; refuses a folder that synth did not write.
Result<std::vector<std::string>> synthFilesIn(const std::string& folder) {
    const std::string manifestPath = (fs::path(folder) / "btflut-dataset.json").string();
    const std::string refuse = folder + ": --force replaces only a folder written by btflut synth, and this one ";
    std::error_code ec;
    if (!fs::exists(manifestPath, ec)) return Error{refuse + "has no btflut-dataset.json"};
    Result<Bytes> text = readFile(manifestPath);
    if (!text) return Error{text.error()};
    Result<nlohmann::json> doc = parseJsonText(std::string(text->begin(), text->end()), manifestPath);
    if (!doc) return Error{doc.error()};
    if (!doc->is_object() || !doc->contains("synth") || !(*doc)["images"].is_array())
        return Error{refuse + "has a manifest synth did not write"};
    std::vector<std::string> names{"btflut-dataset.json", "mask.png", "synth.lp"};
    for (const nlohmann::json& image : (*doc)["images"])
        if (image.is_object() && image.contains("file") && image["file"].is_string()) {
            const std::string name = image["file"].get<std::string>();
            // Only a plain file name: a manifest must not point the removal elsewhere.
            if (fs::path(name).filename() == name && name != "." && name != "..") names.push_back(name);
        }
    return names;
}

std::string lpLine(const std::string& file, Direction light) {
    const Vec3 l = toVector(light);
    char buf[64];
    std::snprintf(buf, sizeof buf, " %.9f %.9f %.9f\n", l.x, l.y, l.z);
    return file + buf;
}

}  // namespace

Status writeSynthDataset(const SynthMaterial& m, const std::vector<Geometry>& geometry, const std::string& folder,
                         const SynthOutput& out) {
    if (Status s = validateSynthMaterial(m); !s) return s;
    if (geometry.empty()) return Error{"--geometry gives no directions"};
    for (const Geometry& g : geometry)
        if (g.light.thetaDegrees() >= 90 || g.view.thetaDegrees() >= 90)
            return Error{"--geometry " + g.name + ": light and view must be above the horizon (theta < 90)"};
    if (out.bitDepth != 8 && out.bitDepth != 16) return Error{"--depth must be 8 or 16"};
    std::error_code ec;
    // --force replaces what an earlier `btflut synth` wrote there, and nothing else.
    std::vector<std::string> replaced;
    if (fs::exists(folder, ec)) {
        if (!fs::is_directory(folder, ec)) return Error{folder + ": exists and is not a folder"};
        if (!fs::is_empty(folder, ec)) {
            if (!out.force) return Error{folder + ": exists and is not empty (use --force to replace it)"};
            Result<std::vector<std::string>> earlier = synthFilesIn(folder);
            if (!earlier) return Error{earlier.error()};
            replaced = std::move(*earlier);
        }
    }
    Result<HeightField> field = synthesizeHeightField(m.surface);
    if (!field) return Error{field.error()};
    std::vector<double> albedo;
    if (m.albedoVariation > 0) {
        Result<std::vector<double>> a = albedoMap(m);
        if (!a) return Error{a.error()};
        albedo = std::move(*a);
    }
    SurfaceModel model = m.model;
    model.roughness = m.surface.roughness;

    // A new folder of our own beside the target (mkdtemp: exclusive, random name), in a
    // parent made first when missing.
    std::string pattern = fs::path(folder).lexically_normal().string();
    while (pattern.size() > 1 && pattern.back() == '/') pattern.pop_back();
    if (const fs::path parent = fs::path(pattern).parent_path(); !parent.empty()) fs::create_directories(parent, ec);
    pattern += ".tmp.XXXXXX";
    if (!::mkdtemp(pattern.data()))
        return Error{folder + ": cannot create a folder beside it (" + std::strerror(errno) + ")"};
    const fs::path tmp = pattern;
    auto fail = [&](const std::string& message) {
        fs::remove_all(tmp, ec);
        return Error{message};
    };
    // Every image is rendered in the frontal frame (the mean plane's grid), whatever its view.
    nlohmann::json manifest{
        {"btflut_dataset", 1}, {"mask", "mask.png"}, {"rectified", true}, {"images", nlohmann::json::array()}};
    manifest["synth"] = {{"size", m.surface.size},
                         {"roughness", m.surface.roughness},
                         {"roughness_across", m.surface.roughnessAcross},
                         {"angle_degrees", m.surface.angle / kDegree},
                         {"correlation_length", m.surface.correlationLength},
                         {"seed", m.surface.seed},
                         {"kd", model.brdf.kd},
                         {"ks", model.brdf.ks},
                         {"sigma", model.brdf.sigma},
                         {"ior", model.brdf.ior},
                         {"gain", model.gain},
                         {"albedo_variation", m.albedoVariation},
                         {"ambient", m.ambient},
                         {"noise", m.noise},
                         {"samples_per_axis", out.samplesPerAxis}};
    bool fixedView = true;
    std::string lp = std::to_string(geometry.size()) + "\n";
    for (std::size_t k = 0; k < geometry.size(); ++k) {
        const Geometry& g = geometry[k];
        RenderOptions options{.samplesPerAxis = out.samplesPerAxis,
                              .threads = out.threads,
                              .albedo = albedo.empty() ? nullptr : &albedo,
                              .ambient = m.ambient,
                              .noise = m.noise,
                              .noiseSeed = m.surface.seed * 1000003 + k};
        Image image = renderHeightField(*field, model, g.light, g.view, options);
        const std::string file = g.name + ".png";
        if (Status s = savePng(image, (tmp / file).string(), out.bitDepth); !s) return fail(s.error());
        manifest["images"].push_back({{"file", file},
                                      {"name", g.name},
                                      {"light", {{"theta", g.light.thetaDegrees()}, {"phi", g.light.phiDegrees()}}},
                                      {"view", {{"theta", g.view.thetaDegrees()}, {"phi", g.view.phiDegrees()}}}});
        fixedView = fixedView && angleBetween(g.view, geometry.front().view) < 1e-12;
        lp += lpLine(file, g.light);
        if (out.progress) out.progress(k + 1, geometry.size());
    }
    Image mask(m.surface.size, m.surface.size, 1);
    std::fill(mask.samples.begin(), mask.samples.end(), 1.f);
    if (Status s = savePng(mask, (tmp / "mask.png").string()); !s) return fail(s.error());
    if (Status s = writeFileAtomically((tmp / "btflut-dataset.json").string(), jsonText(manifest)); !s)
        return fail(s.error());
    if (fixedView && geometry.front().view.theta == 0)
        if (Status s = writeFileAtomically((tmp / "synth.lp").string(), lp); !s) return fail(s.error());
    // Into place, only now: a new folder moves as a whole; into an existing one, the earlier
    // synth files go and the new ones move in, other files stay.
    if (!fs::exists(folder, ec)) {
        fs::rename(tmp, folder, ec);
        if (ec) return fail(folder + ": cannot move into place (" + ec.message() + ")");
        return success();
    }
    for (const std::string& name : replaced) fs::remove(fs::path(folder) / name, ec);
    for (fs::directory_iterator it(tmp, ec), end; !ec && it != end; it.increment(ec)) {
        std::error_code moved;
        fs::rename(it->path(), fs::path(folder) / it->path().filename(), moved);
        if (moved)
            return fail(folder + ": cannot move " + it->path().filename().string() + " into place (" + moved.message() +
                        ")");
    }
    fs::remove_all(tmp, ec);
    return success();
}

}  // namespace btflut

#include "core/physics/model_bank.h"

#include <nlohmann/json.hpp>

#include "core/io/file_io.h"
#include "core/io/json_text.h"

#include "core/parallel.h"

namespace btflut {

Result<ModelBankParams> parseModelParams(const std::string& text, const std::string& file) {
    using nlohmann::json;
    Result<json> parsed = parseJsonText(text, file);
    if (!parsed) return Error{parsed.error()};
    json doc = std::move(*parsed);
    if (!doc.is_object()) return Error{file + ": expected a JSON object of model parameters"};
    const std::string where = file + ": ";
    auto number = [&](const char* key, double fallback) -> Result<double> {
        if (!doc.contains(key)) return fallback;
        if (!doc[key].is_number()) return Error{where + "\"" + key + "\" must be a number"};
        return doc[key].get<double>();
    };
    auto optionalNumber = [&](const char* key) -> Result<std::optional<double>> {
        if (!doc.contains(key)) return std::optional<double>{};
        if (!doc[key].is_number()) return Error{where + "\"" + key + "\" must be a number"};
        return std::optional<double>(doc[key].get<double>());
    };
    if (!doc.contains("roughness")) return Error{where + "no \"roughness\""};
    Result<double> roughness = number("roughness", 0), sigma = number("sigma", 0.13), ior = number("ior", 1.5),
                   gain = number("gain", 1), smooth = number("smooth", 0), bins = number("bins", 1024),
                   nodes = number("nodes", 48), samples = number("samples", 50000), seed = number("seed", 1);
    Result<std::optional<double>> kd = optionalNumber("kd"), ks = optionalNumber("ks");
    for (const auto* r : {&roughness, &sigma, &ior, &gain, &smooth, &bins, &nodes, &samples, &seed})
        if (!*r) return Error{r->error()};
    if (!kd) return Error{kd.error()};
    if (!ks) return Error{ks.error()};
    for (const char* key : {"brdf", "method"})
        if (doc.contains(key) && !doc[key].is_string()) return Error{where + "\"" + key + "\" must be a string"};
    const std::string brdf = doc.value("brdf", std::string("lambert"));
    Result<SurfaceModel> model = makeSurfaceModel(*roughness, brdf, *kd, *ks, *sigma, *ior, *gain, where);
    if (!model) return Error{model.error()};

    ModelBankParams p;
    p.model = *model;
    Result<SimulationMethod> method = parseSimulationMethod(doc.value("method", std::string("quadrature")));
    if (!method) return Error{where + method.error()};
    p.simulation.method = *method;
    if (*bins < 2 || *bins > 65536) return Error{where + "\"bins\" must be within [2, 65536]"};
    if (*nodes < 1 || *nodes > 4096) return Error{where + "\"nodes\" must be within [1, 4096]"};
    if (!(*samples >= 1 && *samples <= 0x1p40)) return Error{where + "\"samples\" must be within [1, 2^40]"};
    if (!(*seed >= 0 && *seed <= 0x1p53)) return Error{where + "\"seed\" must be an integer within [0, 2^53]"};
    if (!(*smooth >= 0)) return Error{where + "\"smooth\" must be >= 0"};
    p.simulation.bins = static_cast<int>(*bins);
    p.simulation.nodes = static_cast<int>(*nodes);
    p.simulation.samples = static_cast<std::uint64_t>(*samples);
    p.simulation.seed = static_cast<std::uint64_t>(*seed);
    p.simulation.smooth = *smooth;

    auto direction = [&](const json& d, const std::string& what) -> Result<Direction> {
        if (!d.is_object() || !d.contains("theta") || !d.contains("phi") || !d["theta"].is_number() ||
            !d["phi"].is_number())
            return Error{where + what + ": expected {\"theta\": degrees, \"phi\": degrees}"};
        return directionFromDegrees(d["theta"].get<double>(), d["phi"].get<double>(), where + what);
    };
    if (doc.contains("view")) {
        Result<Direction> view = direction(doc["view"], "view");
        if (!view) return Error{view.error()};
        p.view = *view;
    }
    if (doc.contains("lights")) {
        if (!doc["lights"].is_array() || doc["lights"].empty())
            return Error{where + "\"lights\" must be a non-empty array of directions"};
        for (std::size_t i = 0; i < doc["lights"].size(); ++i) {
            Result<Direction> light = direction(doc["lights"][i], "lights[" + std::to_string(i) + "]");
            if (!light) return Error{light.error()};
            p.lights.push_back(*light);
        }
    } else {
        p.lights.push_back(Direction::fromDegrees(0, 0));
        for (int theta = 10; theta <= 80; theta += 10)
            for (int phi = 0; phi < 360; phi += 30) p.lights.push_back(Direction::fromDegrees(theta, phi));
    }
    return p;
}

Result<ModelBankParams> loadModelParams(const std::string& path) {
    Result<Bytes> text = readFile(path);
    if (!text) return Error{text.error()};
    return parseModelParams(std::string(text->begin(), text->end()), path);
}

std::string modelParamsText(const ModelBankParams& params) {
    const LocalBrdf& b = params.model.brdf;
    const char* brdf = b.ks == 0 ? "lambert" : b.kd == 0 ? "ts" : "mix";
    return jsonText(nlohmann::json{{"brdf", brdf},
                                   {"roughness", params.model.roughness},
                                   {"kd", b.kd},
                                   {"ks", b.ks},
                                   {"sigma", b.sigma},
                                   {"ior", b.ior},
                                   {"gain", params.model.gain},
                                   {"smooth", params.simulation.smooth}},
                    -1);
}

Result<LutBank> bakeModelBank(const ModelBankParams& params, const Image& reference, const Mask& mask,
                              const ModelReference& about) {
    LevelCounts refLevels = countGreyLevels(reference, mask);
    if (refLevels.presentCodes() < 2)
        return Error{about.name +
                     ": reference image is constant over the sample, so no LUT can give it "
                     "another histogram"};
    LutBank bank;
    bank.colour = ColourMode::Grey;
    bank.gridSize = about.gridSize;
    bank.entries = about.entries ? about.entries : (reference.bitDepth == 16 ? 1024 : 256);
    bank.referenceName = about.name;
    bank.referenceLight = about.light;
    bank.referenceView = params.view;
    bank.reference = reference;
    const std::vector<double> refMass(refLevels.counts.begin(), refLevels.counts.end());
    std::vector<DirectionalLut> luts(params.lights.size());
    // Directions in parallel; each simulation then runs on one thread.
    SimulationOptions simulation = params.simulation;
    simulation.threads = 1;
    parallelFor(params.lights.size(), 0, [&](std::size_t i) {
        std::vector<double> histogram = simulateHistogram(params.model, params.lights[i], params.view, simulation);
        // Bin b covers [b, b + 1) / bins: the cell of code b + 1 on a bins + 1 code scale.
        std::vector<double> target(histogram.size() + 1, 0.0);
        std::copy(histogram.begin(), histogram.end(), target.begin() + 1);
        char name[48];
        std::snprintf(name, sizeof name, "model %.1f,%.1f", params.lights[i].thetaDegrees(),
                      params.lights[i].phiDegrees());
        luts[i] = {name, params.lights[i], params.view, matchLut(refMass, target, bank.entries).values};
    });
    if (Status s = setNodes(bank, luts, BankDomain::Layers, about.name); !s) return Error{s.error()};
    return bank;
}

}  // namespace btflut

#include "core/data/scene.h"

#include <cmath>
#include <filesystem>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include "core/io/json_text.h"

#include "core/io/file_io.h"

namespace btflut {

namespace {

using nlohmann::json;

glm::dvec3 g(const Vec3& v) { return {v.x, v.y, v.z}; }
Vec3 v3(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

Result<Vec3> readVector(const json& j, const std::string& where) {
    if (!j.is_array() || j.size() != 3) return Error{where + ": expected [x, y, z]"};
    Vec3 v;
    double* out[] = {&v.x, &v.y, &v.z};
    for (int i = 0; i < 3; ++i) {
        if (!j[static_cast<std::size_t>(i)].is_number()) return Error{where + ": expected numbers"};
        *out[i] = j[static_cast<std::size_t>(i)].get<double>();
        // Far beyond any scene's scale, and kept small enough that no product overflows.
        if (!(std::abs(*out[i]) <= 1e9)) return Error{where + ": coordinates must be finite and within +-1e9"};
    }
    return v;
}

// A scene image's width or height: an integer in 1..16384, read wide so that a value
// beyond int is refused rather than wrapped.
std::optional<int> imageSide(const json& v) {
    const bool inRange = v.is_number_unsigned() ? v.get<std::uint64_t>() - 1 < 16384
                                                : v.get<std::int64_t>() >= 1 && v.get<std::int64_t>() <= 16384;
    return inRange ? std::optional(static_cast<int>(v.get<std::int64_t>())) : std::nullopt;
}

Result<double> readNumber(const json& parent, const char* key, double fallback, const std::string& where) {
    if (!parent.contains(key)) return fallback;
    if (!parent[key].is_number() || !std::isfinite(parent[key].get<double>()))
        return Error{where + "." + key + ": expected a finite number"};
    return parent[key].get<double>();
}

}  // namespace

const char* renderModeName(RenderMode mode) {
    switch (mode) {
        case RenderMode::Lut:
            return "lut";
        case RenderMode::Brdf:
            return "brdf";
        case RenderMode::Ptm:
            return "ptm";
        case RenderMode::Flat:
            return "flat";
        case RenderMode::Nearest:
            return "nearest";
    }
    return "?";
}

Result<RenderMode> parseRenderMode(const std::string& name) {
    for (RenderMode m : {RenderMode::Lut, RenderMode::Brdf, RenderMode::Ptm, RenderMode::Flat, RenderMode::Nearest})
        if (name == renderModeName(m)) return m;
    return Error{"mode '" + name + "' is not lut, brdf, ptm, flat or nearest"};
}

namespace {

// "camera": its position, target and up, and its field of view or orthographic height.
Status parseCamera(const json& c, Scene& scene, const std::string& at) {
    for (auto [key, out] : {std::pair{"position", &scene.eye}, {"target", &scene.target}, {"up", &scene.up}})
        if (c.contains(key)) {
            Result<Vec3> v = readVector(c[key], at + "camera." + key);
            if (!v) return Error{v.error()};
            *out = *v;
        }
    Result<double> fov = readNumber(c, "fov_degrees", 45, at + "camera");
    if (!fov) return Error{fov.error()};
    scene.fovDegrees = *fov;
    if (c.contains("orthographic_height")) {
        Result<double> height = readNumber(c, "orthographic_height", 0, at + "camera");
        if (!height) return Error{height.error()};
        if (!(*height > 0 && std::isfinite(*height)))
            return Error{at + "camera.orthographic_height must be a positive number (the height the image spans)"};
        scene.orthographicHeight = *height;
    }
    return success();
}

// One of "quads" (`where` names it), its material one of the scene's.
Result<SceneQuad> parseQuad(const json& q, const Scene& scene, const std::string& where) {
    if (!q.is_object()) return Error{where + ": expected an object"};
    if (Status s = requireKnownKeys(q, {"material", "center", "normal", "tangent", "size", "uv_scale", "mode"}, where);
        !s)
        return Error{s.error()};
    SceneQuad quad;
    if (!q.contains("material") || !q["material"].is_string()) return Error{where + ": no \"material\""};
    quad.material = q["material"].get<std::string>();
    if (!scene.materials.count(quad.material))
        return Error{where + ": material '" + quad.material + "' is not in \"materials\""};
    for (auto [key, out] : {std::pair{"center", &quad.center}, {"normal", &quad.normal}, {"tangent", &quad.tangent}}) {
        if (!q.contains(key)) return Error{where + ": no \"" + key + "\""};
        Result<Vec3> v = readVector(q[key], where + "." + key);
        if (!v) return Error{v.error()};
        *out = *v;
    }
    const std::optional<Vec3> n = normalized(quad.normal), t = normalized(quad.tangent);
    if (!n || !t) return Error{where + ": zero normal or tangent"};
    const glm::dvec3 nn = g(*n);
    const glm::dvec3 tt = g(*t) - glm::dot(g(*t), nn) * nn;  // tangent made orthogonal to the normal
    if (glm::length(tt) < 1e-9) return Error{where + ": tangent is parallel to the normal (degenerate quad)"};
    quad.normal = *n;
    quad.tangent = v3(glm::normalize(tt));
    if (q.contains("size")) {
        if (!q["size"].is_array() || q["size"].size() != 2 || !q["size"][0].is_number() || !q["size"][1].is_number())
            return Error{where + ".size: expected [width, height]"};
        quad.width = q["size"][0].get<double>();
        quad.height = q["size"][1].get<double>();
    }
    if (!(quad.width > 0 && quad.height > 0 && quad.width <= 1e9 && quad.height <= 1e9))
        return Error{where + ".size: width and height must be positive (degenerate quad) and within 1e9"};
    Result<double> uv = readNumber(q, "uv_scale", 1, where);
    if (!uv) return Error{uv.error()};
    if (!(*uv > 0)) return Error{where + ".uv_scale must be positive"};
    quad.uvScale = *uv;
    if (q.contains("mode") && !q["mode"].is_string())
        return Error{where + ".mode: expected a string (lut, brdf, ptm, flat or nearest)"};
    Result<RenderMode> mode = parseRenderMode(q.value("mode", std::string("lut")));
    if (!mode) return Error{where + "." + mode.error()};
    quad.mode = *mode;
    return quad;
}

}  // namespace

Result<Scene> parseScene(const std::string& text, const std::string& file, const std::string& folder) {
    Result<json> parsed = parseJsonText(text, file);
    if (!parsed) return Error{parsed.error()};
    json doc = std::move(*parsed);
    if (!doc.is_object()) return Error{file + ": expected a JSON object (a btflut scene)"};
    Scene scene;
    scene.file = file;
    const std::string at = file + ": ";
    // Every key is one the scene format knows (docs/scene.md): a misspelt one is refused with
    // the nearest, not ignored.
    if (Status s = requireKnownKeys(
            doc, {"btflut_scene", "image", "camera", "light", "materials", "interpolation", "dither", "quads"}, file);
        !s)
        return Error{s.error()};
    if (doc.contains("btflut_scene") && doc["btflut_scene"] != kSceneVersion)
        return Error{at + "btflut_scene " + jsonText(doc["btflut_scene"], -1) +
                     " is not a scene version this btflut reads (" + std::to_string(kSceneVersion) + ")"};
    for (const auto& [key, known] : {std::pair<const char*, std::vector<std::string>>{"image", {"width", "height"}},
                                     {"camera", {"position", "target", "up", "fov_degrees", "orthographic_height"}},
                                     {"light", {"direction"}}})
        if (doc.contains(key))
            if (Status s = requireKnownKeys(doc[key], known, at + key); !s) return Error{s.error()};
    if (doc.contains("image")) {
        const json& im = doc["image"];
        if (!im.is_object() || !im.contains("width") || !im.contains("height") || !im["width"].is_number_integer() ||
            !im["height"].is_number_integer())
            return Error{at + "image: expected {\"width\": pixels, \"height\": pixels}"};
        const std::optional<int> width = imageSide(im["width"]), height = imageSide(im["height"]);
        if (!width || !height)
            return Error{at + "image size " + jsonText(im["width"], -1) + "x" + jsonText(im["height"], -1) +
                         " is not within 1..16384"};
        scene.width = *width;
        scene.height = *height;
    }
    if (doc.contains("camera"))
        if (Status st = parseCamera(doc["camera"], scene, at); !st) return Error{st.error()};
    const glm::dvec3 forward = g(scene.target) - g(scene.eye);
    if (glm::length(forward) < 1e-12) return Error{at + "camera: position and target coincide"};
    if (glm::length(glm::cross(forward, g(scene.up))) < 1e-12 * glm::length(forward))
        return Error{at + "camera: up is parallel to the viewing direction"};
    if (!(scene.fovDegrees > 0 && scene.fovDegrees < 180))
        return Error{at + "camera.fov_degrees must be within (0, 180)"};

    if (!doc.contains("light") || !doc["light"].is_object() || !doc["light"].contains("direction"))
        return Error{at + "light: expected {\"direction\": [x, y, z]} (towards the light, world frame)"};
    Result<Vec3> light = readVector(doc["light"]["direction"], at + "light.direction");
    if (!light) return Error{light.error()};
    const std::optional<Vec3> lightUnit = normalized(*light);
    if (!lightUnit) return Error{at + "light.direction is a zero vector"};
    scene.light = *lightUnit;

    if (!doc.contains("materials") || !doc["materials"].is_object() || doc["materials"].empty())
        return Error{at + "materials: expected {\"name\": \"bank.btflut\", ...}"};
    auto resolve = [&](const json& path) {
        return (std::filesystem::path(folder) / path.get<std::string>()).lexically_normal().string();
    };
    for (const auto& [name, entry] : doc["materials"].items()) {
        SceneMaterial& m = scene.materials[name];
        if (entry.is_string()) {
            m.bank = resolve(entry);
        } else if (Status s = requireKnownKeys(entry, {"bank", "images"}, at + "materials." + name); !s) {
            return Error{s.error()};
        } else if (entry.is_object() && entry.contains("bank") && entry["bank"].is_string() &&
                   (!entry.contains("images") || entry["images"].is_string())) {
            m.bank = resolve(entry["bank"]);
            if (entry.contains("images")) m.images = resolve(entry["images"]);
        } else {
            return Error{at + "materials." + name +
                         ": expected a .btflut path or {\"bank\": path, \"images\": dataset path}"};
        }
    }
    if (doc.contains("interpolation")) {
        const json& i = doc["interpolation"];
        if (i != "linear" && i != "nearest" && i != "exact")
            return Error{at +
                         "interpolation: expected \"linear\", \"exact\" or \"nearest\" (between the LUTs' directions)"};
        scene.interpolateLuts = i != "nearest";
        scene.exactMatch = i == "exact";
    }
    if (doc.contains("dither")) {
        if (!doc["dither"].is_boolean()) return Error{at + "dither: expected true or false"};
        scene.dither = doc["dither"].get<bool>();
    }
    if (!doc.contains("quads") || !doc["quads"].is_array() || doc["quads"].empty())
        return Error{at + "quads: expected a non-empty array"};
    for (std::size_t i = 0; i < doc["quads"].size(); ++i) {
        Result<SceneQuad> quad = parseQuad(doc["quads"][i], scene, at + "quads[" + std::to_string(i) + "]");
        if (!quad) return Error{quad.error()};
        scene.quads.push_back(*quad);
    }
    return scene;
}

std::string sceneToJson(const Scene& scene, const std::string& folder) {
    auto vec = [](const Vec3& v) { return json::array({v.x, v.y, v.z}); };
    json doc{{"btflut_scene", kSceneVersion},
             {"image", {{"width", scene.width}, {"height", scene.height}}},
             {"camera",
              {{"position", vec(scene.eye)},
               {"target", vec(scene.target)},
               {"up", vec(scene.up)},
               {"fov_degrees", scene.fovDegrees}}},
             {"light", {{"direction", vec(scene.light)}}},
             {"interpolation", !scene.interpolateLuts ? "nearest"
                               : scene.exactMatch     ? "exact"
                                                      : "linear"},
             {"dither", scene.dither},
             {"materials", json::object()},
             {"quads", json::array()}};
    if (scene.orthographicHeight > 0) doc["camera"]["orthographic_height"] = scene.orthographicHeight;
    // Inside the folder the file will be in: relative to it (parseScene resolves them there),
    // so the folder moves with its files; outside it: absolute, which a move does not break
    // (a ../../.. path would).
    auto path = [&](const std::string& p) {
        const std::filesystem::path absolute = std::filesystem::absolute(p).lexically_normal();
        if (folder.empty()) return absolute.string();
        const std::filesystem::path relative =
            absolute.lexically_relative(std::filesystem::absolute(folder).lexically_normal());
        const bool inside = !relative.empty() && *relative.begin() != "..";
        return inside ? relative.string() : absolute.string();
    };
    for (const auto& [name, m] : scene.materials) {
        if (m.images.empty())
            doc["materials"][name] = path(m.bank);
        else
            doc["materials"][name] = {{"bank", path(m.bank)}, {"images", path(m.images)}};
    }
    for (const SceneQuad& q : scene.quads)
        doc["quads"].push_back({{"material", q.material},
                                {"center", vec(q.center)},
                                {"normal", vec(q.normal)},
                                {"tangent", vec(q.tangent)},
                                {"size", {q.width, q.height}},
                                {"uv_scale", q.uvScale},
                                {"mode", renderModeName(q.mode)}});
    return jsonText(doc);
}

Result<Scene> loadScene(const std::string& path) {
    Result<Bytes> bytes = readFile(path);
    if (!bytes) return Error{bytes.error()};
    std::string folder = std::filesystem::path(path).parent_path().string();
    return parseScene(std::string(bytes->begin(), bytes->end()), path, folder.empty() ? "." : folder);
}

std::array<float, 16> viewProjection(const Scene& s) {
    const glm::dmat4 view = glm::lookAt(g(s.eye), g(s.target), g(s.up));
    const double distance = glm::length(g(s.target) - g(s.eye));
    const double aspect = static_cast<double>(s.width) / s.height, half = s.orthographicHeight / 2;
    const glm::dmat4 projection =
        s.orthographicHeight > 0
            ? glm::ortho(-half * aspect, half * aspect, -half, half, distance * 1e-3, distance * 1e3)
            : glm::perspective(glm::radians(s.fovDegrees), aspect, distance * 1e-3, distance * 1e3);
    const glm::mat4 m(projection * view);
    std::array<float, 16> out;
    std::copy(glm::value_ptr(m), glm::value_ptr(m) + 16, out.begin());
    return out;
}

std::vector<std::size_t> visibleQuads(const Scene& s) {
    const glm::dmat4 m = glm::dmat4(glm::make_mat4(viewProjection(s).data()));
    std::vector<std::size_t> visible;
    for (std::size_t i = 0; i < s.quads.size(); ++i) {
        const SceneQuad& q = s.quads[i];
        const glm::dvec3 t = g(q.tangent), b = glm::cross(g(q.normal), t), c = g(q.center);
        glm::dvec4 corners[4];
        int k = 0;
        for (double su : {-0.5, 0.5})
            for (double sv : {-0.5, 0.5}) corners[k++] = m * glm::dvec4(c + su * q.width * t + sv * q.height * b, 1);
        // Outside when all four corners lie beyond one clip plane.
        bool outside = false;
        for (int axis = 0; axis < 3 && !outside; ++axis)
            for (double sign : {-1.0, 1.0}) {
                bool allBeyond = true;
                for (const glm::dvec4& p : corners) allBeyond = allBeyond && sign * p[axis] > p.w;
                outside = outside || allBeyond;
            }
        if (!outside) visible.push_back(i);
    }
    return visible;
}

std::optional<std::array<double, 2>> quadTextureAt(const Scene& scene, const SceneQuad& quad, int x, int row) {
    return PixelRays(scene).quadTextureAt(quad, x, row);
}

PixelRays::PixelRays(const Scene& scene) : m_width(scene.width), m_height(scene.height) {
    const glm::dmat4 inverse = glm::inverse(glm::dmat4(glm::make_mat4(viewProjection(scene).data())));
    std::copy(glm::value_ptr(inverse), glm::value_ptr(inverse) + 16, m_inverse.begin());
}

std::optional<std::array<double, 2>> PixelRays::quadTextureAt(const SceneQuad& quad, int x, int row) const {
    const std::optional<QuadHit> h = hit(quad, x, row);
    if (!h) return std::nullopt;
    return h->uv;
}

std::optional<PixelRays::QuadHit> PixelRays::hit(const SceneQuad& quad, int x, int row) const {
    const glm::dmat4 inverse = glm::make_mat4(m_inverse.data());
    const double nx = (x + 0.5) / m_width * 2 - 1, ny = 1 - (row + 0.5) / m_height * 2;
    const glm::dvec4 near = inverse * glm::dvec4(nx, ny, -1, 1), far = inverse * glm::dvec4(nx, ny, 1, 1);
    const glm::dvec3 origin = glm::dvec3(near) / near.w, direction = glm::dvec3(far) / far.w - origin;
    const glm::dvec3 n = g(quad.normal), t = g(quad.tangent), b = glm::cross(n, t), c = g(quad.center);
    const double along = glm::dot(n, direction);
    if (std::abs(along) < 1e-12 * glm::length(direction)) return std::nullopt;
    const double at = glm::dot(n, c - origin) / along;  // from the near plane, in units of `direction`
    const glm::dvec3 point = origin + direction * at;
    return QuadHit{{(0.5 + glm::dot(point - c, t) / quad.width) * quad.uvScale,
                    (0.5 - glm::dot(point - c, b) / quad.height) * quad.uvScale},
                   at * glm::length(direction)};
}

Vec3 bitangentOf(const SceneQuad& quad) { return v3(glm::cross(g(quad.normal), g(quad.tangent))); }

Vec3 toQuadFrame(const SceneQuad& q, const Vec3& world) {
    const glm::dvec3 t = g(q.tangent), n = g(q.normal), b = glm::cross(n, t), w = g(world);
    return {glm::dot(w, t), glm::dot(w, b), glm::dot(w, n)};
}

}  // namespace btflut

#include <doctest/doctest.h>

#include <nlohmann/json.hpp>

#include "core/data/scene.h"

using namespace btflut;

namespace {
const char* kScene = R"({
  "image": {"width": 64, "height": 48},
  "camera": {"position": [0, -3, 2], "target": [0, 0, 0], "up": [0, 0, 1], "fov_degrees": 50},
  "light": {"direction": [0, 0, 2]},
  "materials": {"a": "a.btflut", "b": {"bank": "sub/b.btflut", "images": "../data/b"}},
  "interpolation": "nearest",
  "quads": [
    {"material": "a", "center": [0, 0, 0], "normal": [0, 0, 3], "tangent": [1, 0, 0.5], "size": [2, 1], "uv_scale": 2},
    {"material": "b", "center": [0, -10, 0], "normal": [0, 1, 0], "tangent": [1, 0, 0], "mode": "flat"}
  ]
})";
}

TEST_CASE("scenes parse, normalise their frames and cull what the camera cannot see") {
    auto scene = parseScene(kScene, "s.json", "/scenes");
    REQUIRE(scene.ok());
    CHECK(scene->materials.at("b").bank == "/scenes/sub/b.btflut");
    CHECK(scene->materials.at("b").images == "/data/b");
    CHECK(scene->materials.at("a").images.empty());
    CHECK_FALSE(scene->interpolateLuts);
    const SceneQuad& q = scene->quads[0];
    CHECK(q.normal.z == doctest::Approx(1));
    CHECK(q.tangent.z == doctest::Approx(0));  // made orthogonal to the normal
    CHECK(q.tangent.x == doctest::Approx(1));
    CHECK(scene->light.z == doctest::Approx(1));
    CHECK(scene->quads[1].mode == RenderMode::Flat);
    auto visible = visibleQuads(*scene);
    REQUIRE(visible.size() == 1);  // the second quad is behind the camera
    CHECK(visible[0] == 0);
    const Vec3 local = toQuadFrame(q, scene->light);
    CHECK(local.z == doctest::Approx(1));
}

TEST_CASE("the example scene docs/scene.md ships reads, with only the keys it documents") {
    Result<Scene> scene = loadScene(std::string(BTFLUT_SOURCE_DIR) + "/examples/scene/wall.json");
    REQUIRE_MESSAGE(scene.ok(), scene.error());
    CHECK(scene->quads.size() == 2);
    CHECK(scene->materials.at("default").bank.ends_with("examples/scene/default.btflut"));
    CHECK(scene->quads[1].mode == RenderMode::Brdf);
}

TEST_CASE("a scene written as JSON reads back the same") {
    auto scene = parseScene(kScene, "s.json", "/scenes");
    REQUIRE(scene.ok());
    auto back = parseScene(sceneToJson(*scene), "back.json", "/elsewhere");
    REQUIRE(back.ok());
    CHECK(back->width == 64);
    CHECK(back->fovDegrees == 50);
    CHECK(back->eye.y == -3);
    CHECK(back->materials.at("b").bank == "/scenes/sub/b.btflut");
    CHECK(back->materials.at("b").images == "/data/b");
    CHECK_FALSE(back->interpolateLuts);
    REQUIRE(back->quads.size() == 2);
    CHECK(back->quads[0].width == 2);
    CHECK(back->quads[0].uvScale == 2);
    CHECK(back->quads[0].tangent.x == doctest::Approx(scene->quads[0].tangent.x));
    CHECK(back->quads[1].mode == RenderMode::Flat);
    // "exact": interpolated, the match LUTs made at the light
    std::string exact = kScene;
    exact.replace(exact.find("\"nearest\""), 9, "\"exact\"");
    auto e = parseScene(exact, "e.json", "/scenes");
    REQUIRE(e.ok());
    CHECK(e->interpolateLuts);
    CHECK(e->exactMatch);
    auto eBack = parseScene(sceneToJson(*e), "back.json", "/elsewhere");
    REQUIRE(eBack.ok());
    CHECK(eBack->exactMatch);
}

TEST_CASE("bad scenes are refused naming the file and the field") {
    struct Case {
        const char* text;
        const char* needle;
    } cases[] = {
        {"{", "s.json: not valid JSON"},
        {R"({"image": {"width": 0, "height": 10}, "light": {"direction": [0,0,1]}, "materials": {"a": "a.btflut"},
             "quads": [{"material": "a", "center": [0,0,0], "normal": [0,0,1], "tangent": [1,0,0]}]})",
         "image size 0x10"},
        {R"({"light": {"direction": [0,0,0]}, "materials": {"a": "a.btflut"}, "quads": []})",
         "light.direction is a zero vector"},
        {R"({"light": {"direction": [0,"x",1]}, "materials": {"a": "a.btflut"}, "quads": []})",
         "light.direction: expected numbers"},
        {R"({"light": {"direction": [0,0,1]}, "materials": {"a": "a.btflut"},
             "quads": [{"material": "z", "center": [0,0,0], "normal": [0,0,1], "tangent": [1,0,0]}]})",
         "material 'z' is not in \"materials\""},
        {R"({"light": {"direction": [0,0,1]}, "materials": {"a": "a.btflut"},
             "quads": [{"material": "a", "center": [0,0,0], "normal": [0,0,1], "tangent": [0,0,2]}]})",
         "degenerate quad"},
        {R"({"light": {"direction": [0,0,1]}, "materials": {"a": "a.btflut"},
             "quads": [{"material": "a", "center": [0,0,0], "normal": [0,0,1], "tangent": [1,0,0], "size": [0, 1]}]})",
         "degenerate quad"},
        {R"({"light": {"direction": [0,0,1]}, "materials": {"a": "a.btflut"},
             "quads": [{"material": "a", "center": [0,0,0], "normal": [0,0,1], "tangent": [1,0,0], "mode": "glossy"}]})",
         "mode 'glossy' is not lut, brdf, ptm, flat or nearest"},
        {R"({"light": {"direction": [0,0,1]}, "materials": {"a": {"images": "ds"}},
             "quads": [{"material": "a", "center": [0,0,0], "normal": [0,0,1], "tangent": [1,0,0]}]})",
         "materials.a: expected a .btflut path or {\"bank\": path, \"images\": dataset path}"},
        {R"({"light": {"direction": [0,0,1]}, "materials": {"a": "a.btflut"}, "interpolation": "cubic",
             "quads": [{"material": "a", "center": [0,0,0], "normal": [0,0,1], "tangent": [1,0,0]}]})",
         "interpolation: expected \"linear\", \"exact\" or \"nearest\""},
        {R"({"camera": {"position": [0,0,1], "target": [0,0,1]}, "light": {"direction": [0,0,1]}, "materials": {"a": "a.btflut"},
             "quads": [{"material": "a", "center": [0,0,0], "normal": [0,0,1], "tangent": [1,0,0]}]})",
         "position and target coincide"},
        {R"({"camera": {"orthographic_height": -2}, "light": {"direction": [0,0,1]}, "materials": {"a": "a.btflut"},
             "quads": [{"material": "a", "center": [0,0,0], "normal": [0,0,1], "tangent": [1,0,0]}]})",
         "camera.orthographic_height must be a positive number"},
        // Misspelt keys are refused with the nearest known one, at every level; so are versions.
        {R"({"light": {"direction": [0,0,1]}, "materials": {"a": "a.btflut"}, "interpolaton": "nearest",
             "quads": [{"material": "a", "center": [0,0,0], "normal": [0,0,1], "tangent": [1,0,0]}]})",
         "s.json: unknown key 'interpolaton' (did you mean 'interpolation'?)"},
        {R"({"light": {"direction": [0,0,1]}, "materials": {"a": "a.btflut"},
             "quads": [{"material": "a", "center": [0,0,0], "normal": [0,0,1], "tangent": [1,0,0], "uv_scael": 2}]})",
         "s.json: quads[0]: unknown key 'uv_scael' (did you mean 'uv_scale'?)"},
        {R"({"camera": {"fov": 30}, "light": {"direction": [0,0,1]}, "materials": {"a": "a.btflut"},
             "quads": [{"material": "a", "center": [0,0,0], "normal": [0,0,1], "tangent": [1,0,0]}]})",
         "s.json: camera: unknown key 'fov'"},
        {R"({"light": {"direction": [0,0,1]}, "materials": {"a": {"bank": "a.btflut", "image": "ds"}},
             "quads": [{"material": "a", "center": [0,0,0], "normal": [0,0,1], "tangent": [1,0,0]}]})",
         "s.json: materials.a: unknown key 'image' (did you mean 'images'?)"},
        {R"({"light": {"direction": [0,0,1]}, "materials": {"a": "a.btflut"}, "zzz": 1,
             "quads": [{"material": "a", "center": [0,0,0], "normal": [0,0,1], "tangent": [1,0,0]}]})",
         "unknown key 'zzz' (known: btflut_scene, image, camera, light, materials, interpolation, dither, quads)"},
        {R"({"btflut_scene": 2, "light": {"direction": [0,0,1]}, "materials": {"a": "a.btflut"},
             "quads": [{"material": "a", "center": [0,0,0], "normal": [0,0,1], "tangent": [1,0,0]}]})",
         "s.json: btflut_scene 2 is not a scene version this btflut reads (1)"},
    };
    for (const Case& c : cases) {
        INFO(c.text);
        auto r = parseScene(c.text, "s.json", ".");
        REQUIRE_FALSE(r.ok());
        CHECK(r.error().rfind("s.json", 0) == 0);
        CHECK(r.error().find(c.needle) != std::string::npos);
    }
}

TEST_CASE("an orthographic camera: the same view direction everywhere, written and read back") {
    Scene s;
    s.width = 40;
    s.height = 20;
    s.eye = {0, 0, 5};
    s.up = {0, 1, 0};
    s.orthographicHeight = 2;  // the image spans 2 units high, 4 wide
    SceneQuad q{"a", {0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 4, 2, 1, RenderMode::Lut};
    s.quads = {q};
    s.materials["a"] = {"a.btflut", ""};
    // Each pixel sees the quad point straight below its centre: texel (x + 1/2) / 40.
    for (int x : {0, 13, 39})
        for (int row : {0, 7, 19}) {
            auto uv = quadTextureAt(s, q, x, row);
            REQUIRE(uv.has_value());
            CHECK((*uv)[0] == doctest::Approx((x + 0.5) / 40));
            CHECK((*uv)[1] == doctest::Approx((row + 0.5) / 20));
        }
    // Distances along the ray: a quad nearer the camera is hit first; one behind it, never.
    const PixelRays rays(s);
    SceneQuad raised = q, behind = q;
    raised.center.z = 1, behind.center.z = 6;
    const auto low = rays.hit(q, 20, 10), high = rays.hit(raised, 20, 10), back = rays.hit(behind, 20, 10);
    REQUIRE((low && high && back));
    CHECK(high->distance < low->distance);
    CHECK(low->distance - high->distance == doctest::Approx(1));
    CHECK(back->distance < 0);
    {
        // Saved into a folder: banks inside it relative, banks elsewhere absolute (not ../../..).
        Scene placed = s;
        placed.materials.clear();
        placed.materials["in"] = {"/data/scenes/banks/in.btflut", {}};
        placed.materials["out"] = {"/other/place/out.btflut", {}};
        const nlohmann::json saved = nlohmann::json::parse(sceneToJson(placed, "/data/scenes"));
        CHECK(saved["materials"]["in"] == "banks/in.btflut");
        CHECK(saved["materials"]["out"] == "/other/place/out.btflut");
    }
    auto written = parseScene(sceneToJson(s), "s.json", ".");
    REQUIRE(written.ok());
    CHECK(written->orthographicHeight == 2);
    s.orthographicHeight = 0;
    CHECK(parseScene(sceneToJson(s), "s.json", ".")->orthographicHeight == 0);  // perspective: not written
}

TEST_CASE("a pixel's ray finds the texture coordinates of the quad point it shows") {
    Scene s;
    s.width = 64;
    s.height = 48;
    s.eye = {0.3, -2, 2.5};
    s.target = {0, 0, 0};
    SceneQuad q{"a", {0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 2, 1, 3, RenderMode::Lut};
    s.quads = {q};
    // Project known quad points to pixels, and come back.
    const auto m = viewProjection(s);
    for (auto [su, sv] : {std::pair{0.5, 0.5}, {0.1, 0.8}, {0.9, 0.3}}) {
        const double wx = (su - 0.5) * q.width, wy = (0.5 - sv) * q.height;  // texture y runs down the bitangent
        const double cx = m[0] * wx + m[4] * wy + m[12], cy = m[1] * wx + m[5] * wy + m[13],
                     cw = m[3] * wx + m[7] * wy + m[15];
        const double px = (cx / cw + 1) / 2 * s.width, py = (1 - cy / cw) / 2 * s.height;
        auto uv = quadTextureAt(s, q, static_cast<int>(px), static_cast<int>(py));
        REQUIRE(uv.has_value());
        // Within the pixel's footprint (a pixel spans about 0.05 quad units here), times uv_scale 3.
        CHECK((*uv)[0] == doctest::Approx(su * 3).epsilon(0.06));
        CHECK((*uv)[1] == doctest::Approx(sv * 3).epsilon(0.06));
    }
}

TEST_CASE("a key given twice in one object is refused, at any depth; in different objects it is fine") {
    std::string twice = kScene;
    twice.replace(twice.find(R"("interpolation")"), 0, R"("light": {"direction": [1, 0, 1]}, )");
    Result<Scene> scene = parseScene(twice, "s.json", "/scenes");
    REQUIRE_FALSE(scene.ok());
    CHECK(scene.error() ==
          "s.json: the key \"light\" is given twice in one object (JSON would keep the last "
          "silently); give it once");
    std::string inner = kScene;
    inner.replace(inner.find(R"("size": [2, 1])"), 0, R"("size": [1, 1], )");
    REQUIRE_FALSE(parseScene(inner, "s.json", "/scenes").ok());
    CHECK(parseScene(inner, "s.json", "/scenes").error().find("\"size\" is given twice") != std::string::npos);
    CHECK(parseScene(kScene, "s.json", "/scenes").ok());  // "material" in two quads: two objects
}

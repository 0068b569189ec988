// Into engines and pipelines: `export -o DIR/` with the example program that loads only its
// files (examples/relight_quad.cpp), `export --ptm` (the RTI .ptm format), `compare`.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>

#include "core/bank/bank_file.h"
#include "core/image/canvas.h"
#include "core/predict/gpu_constants.h"
#include "core/predict/ptm_file.h"
#include "helpers.h"

using namespace btflut;
using namespace btflut::test;
namespace fs = std::filesystem;

namespace {

// The example's output against `relight --grid` (the same grid, on the CPU) and against the
// exact relight, at one light; `tolerance` as `compare` takes it.
void checkExample(const TempDir& dir, const std::string& bank, const std::string& folder, const std::string& light,
                  const std::string& tolerance = "max=2") {
    const std::string example = dir / "example.png", grid = dir / "grid.png", exact = dir / "exact.png";
    // Under the sanitizers: leaks are not checked in the example, whose only ones are those the
    // GL driver keeps until exit (btflut's own tests pin the driver so they can be suppressed).
    const std::string command = "ASAN_OPTIONS=detect_leaks=0 " + std::string(BTFLUT_EXAMPLE_QUAD) + " " + folder +
                                " --light " + light + " -o " + example + " > /dev/null";
    REQUIRE(std::system(command.c_str()) == 0);
    REQUIRE(runCli({"relight", bank, "--grid", "--light", light, "-o", grid, "-q"}).status == 0);
    REQUIRE(runCli({"relight", bank, "--light", light, "-o", exact, "-q"}).status == 0);
    const CliRun same = runCli({"compare", example, grid, "--tolerance", tolerance, "--json"});
    const nlohmann::json sameJson = nlohmann::json::parse(same.out);
    const nlohmann::json nodes = nlohmann::json::parse(runCli({"compare", example, exact, "--json"}).out);
    MESSAGE(fs::path(bank).filename().string()
            << " at " << light << ": example against relight --grid: max " << sameJson["max_255"].get<double>()
            << "/255, p99 " << sameJson["p99_255"].get<double>() << "/255, mean " << sameJson["mean_255"].get<double>()
            << "/255; against the exact relight: " << (nodes["psnr"].is_null() ? 99.0 : nodes["psnr"].get<double>())
            << " dB");
    INFO(bank << " at " << light << ": " << same.out << same.err);
    CHECK(same.status == 0);
}

}  // namespace

TEST_SUITE("gl") {
    TEST_CASE("export -o DIR/: an engine program that loads only its files matches relight within 2/255") {
        TempDir dir;
        std::vector<std::pair<std::string, std::vector<std::string>>> banks{
            {"default", {"bake", BTFLUT_DEFAULT_MATERIAL, "--references", "1", "-q"}}};
        if (haveSharedData("psm-rock")) {
            banks.push_back({"rock-grey", {"bake", sharedDataDir() + "/psm-rock", "--references", "1", "-q"}});
            banks.push_back({"rock-rgb", {"bake", sharedDataDir() + "/psm-rock", "--colour", "rgb", "-q"}});
        }
        for (auto& [name, bake] : banks) {
            const std::string bank = dir / (name + ".btflut"), folder = dir / name;
            bake.insert(bake.end(), {"-o", bank});
            REQUIRE(runCli(bake).status == 0);
            CliRun run = runCli({"export", bank, "-o", folder});
            REQUIRE_MESSAGE(run.status == 0, run.err);
            // The material, the include, and the three.js recipe: the folder is all an artist needs
            // (tests/browser_check.sh opens its three.html).
            for (const char* file : {"reference.png", "luts.png", "material.json", "btflut.glsl", "btflut_es.glsl",
                                     "btflut_material.js", "btflut-three.js", "three.html"})
                CHECK(fs::exists(folder + "/" + file));
            CHECK(run.out.find("chromium --allow-file-access-from-files 'file://") != std::string::npos);
            const nlohmann::json material = readJson(folder + "/material.json");
            CHECK(material["format"] == "btflut-material");
            Result<Image> luts = loadImage(folder + "/luts.png");
            REQUIRE(luts.ok());
            CHECK(luts->bitDepth == 16);
            CHECK(luts->width == material["luts"]["entries"].get<int>());
            CHECK(luts->height == 17 * 17);
            Result<LutBank> loaded = loadBank(bank);
            REQUIRE(loaded.ok());
            // A measured direction, a grid node, and directions in between (grazing too).
            const Direction measured = loaded->layers[0].nodes[1].light;
            char at[64];
            std::snprintf(at, sizeof at, "%.6f,%.6f", measured.thetaDegrees(), measured.phiDegrees());
            for (const std::string& light : {std::string(at), std::string("41.40962,90"), std::string("40,250"),
                                             std::string("63,17"), std::string("80,300")})
                checkExample(dir, bank, folder, light);
            // Below the horizon the include draws black, as btflut's renderer does.
            const std::string below = dir / "below.png";
            REQUIRE(std::system(("ASAN_OPTIONS=detect_leaks=0 " + std::string(BTFLUT_EXAMPLE_QUAD) + " " + folder +
                                 " --light 95,30 -o " + below + " > /dev/null")
                                    .c_str()) == 0);
            Result<Image> black = loadImage(below);
            REQUIRE(black.ok());
            CHECK(*std::max_element(black->samples.begin(), black->samples.end()) == 0.f);
        }
    }
}

TEST_SUITE("gl") {
    // Banks with a predictor: their planes (or references), weights and match LUTs, drawn by
    // btflut.glsl's second btflutRelight. The prediction is rounded to a code before its LUT;
    // btflut's CPU rounds a fixed-point sum (the twin of its texture-space pass), the example
    // a float one, so about 1% of the texels sit one code apart, and where a LUT is steep
    // (a spike of shadowed texels spread over many output codes) that moves them up to 20/255:
    // hence the 99th percentile and the mean, not the largest difference.
    TEST_CASE(
        "export -o DIR/ of every bank with a predictor: the example matches relight --grid (references within 2/255, "
        "models p99)") {
        TempDir dir;
        std::vector<std::pair<std::string, std::vector<std::string>>> banks{
            {"ptm", {"bake", BTFLUT_DEFAULT_MATERIAL, "--predictor", "ptm"}},
            {"hsh2", {"bake", BTFLUT_DEFAULT_MATERIAL, "--predictor", "hsh2"}},
            {"rbf9", {"bake", BTFLUT_DEFAULT_MATERIAL, "--predictor", "rbf9"}},
            {"bln5c", {"bake", BTFLUT_DEFAULT_MATERIAL, "--predictor", "bln5c"}},
            {"neural5", {"bake", BTFLUT_DEFAULT_MATERIAL, "--predictor", "neural5"}},
            {"references", {"bake", BTFLUT_DEFAULT_MATERIAL, "--references", "3"}}};
        if (haveSharedData("psm-rock")) {
            const std::string rock = sharedDataDir() + "/psm-rock";
            banks.push_back({"rock-ptm-albedo", {"bake", rock, "--predictor", "ptm"}});
            banks.push_back({"rock-rbf-rgb", {"bake", rock, "--predictor", "rbf9", "--colour", "rgb"}});
            banks.push_back({"rock-neural4-rgb", {"bake", rock, "--predictor", "neural4", "--colour", "rgb"}});
            banks.push_back({"rock-references-rgb-regions",
                             {"bake", rock, "--references", "3", "--colour", "rgb", "--regions", "2"}});
            banks.push_back({"rock-references-lrgb", {"bake", rock, "--references", "4", "--colour", "lrgb"}});
        }
        for (auto& [name, bake] : banks) {
            const std::string bank = dir / (name + ".btflut"), folder = dir / name;
            bake.insert(bake.end(), {"-o", bank, "-q"});
            REQUIRE_MESSAGE(runCli(bake).status == 0, name);
            CliRun run = runCli({"export", bank, "-o", folder});
            REQUIRE_MESSAGE(run.status == 0, run.err);
            const nlohmann::json material = readJson(folder + "/material.json");
            CHECK(material["version"] == 2);
            CHECK(material["shader_version"] ==
                  (name.find("neural") != std::string::npos ? 5 : 2));  // learned models: include version 5
            // psm-rock's mask gives the sample's rectangle (what a sphere wraps); the default
            // material has none: the whole image is the sample.
            CHECK(material.contains("sample") == (name.rfind("rock", 0) == 0));
            if (material.contains("sample"))
                CHECK(material["sample"]["width"].get<int>() * material["sample"]["height"].get<int>() > 200 * 150);
            const nlohmann::json& predictor = material["predictor"];
            for (const auto& image : predictor["images"]) {
                Result<Image> planes = loadImage(folder + "/" + image.get<std::string>());
                REQUIRE(planes.ok());
                CHECK(planes->bitDepth == 8);
            }
            if (predictor["kind"] == "model" || predictor["kind"] == "learned")
                CHECK(predictor["scale"].size() == predictor["planes"].get<std::size_t>());
            // A learned material's decoder specialised to it, in each language (what the example draws by).
            CHECK(predictor.contains("network") == (predictor["kind"] == "learned"));
            if (predictor.contains("network"))
                for (const char* language : {"glsl", "hlsl", "godot"})
                    CHECK(readText(folder + "/" + predictor["network"][language].get<std::string>())
                              .find("btflutNetworkValue(") != std::string::npos);
            CHECK(predictor["kind_index"] == (predictor["kind"] == "model"     ? BTFLUT_KIND_MODEL
                                              : predictor["kind"] == "learned" ? BTFLUT_KIND_LEARNED
                                                                               : BTFLUT_KIND_REFERENCES));
            // The weights in closed form for ptm and hsh, a grid over the light disk otherwise.
            const bool closed = predictor.value("basis", "") == "ptm" || predictor.value("basis", "") == "hsh";
            CHECK(predictor["weights"].is_null() == closed);
            if (!closed)
                CHECK(fs::file_size(folder + "/weights.bin") ==
                      predictor["weights"]["grid_size"].get<std::size_t>() *
                          predictor["weights"]["grid_size"].get<std::size_t>() *
                          predictor["weights"]["layers"].get<std::size_t>() * 16);
            // References blend in btflut's own 1/4096 steps: exact. Models and learned models: see above.
            const std::string tolerance = predictor["kind"] == "references" ? "max=2" : "p99=2,mean=0.2";
            for (const std::string light : {"40,250", "63,17", "80,300"})
                checkExample(dir, bank, folder, light, tolerance);
        }
        // The example refuses a shader include older than the sidecar asks for, and a sidecar
        // newer than it reads: one line naming the file and the versions.
        const std::string folder = dir / "references", include = folder + "/btflut.glsl";
        std::string text = readText(include);
        text.replace(text.find("#define BTFLUT_GLSL_VERSION 5"), 29, "#define BTFLUT_GLSL_VERSION 1");
        std::ofstream(include, std::ios::binary) << text;
        auto example = [&](const std::string& errors) {
            const std::string command = "ASAN_OPTIONS=detect_leaks=0 " + std::string(BTFLUT_EXAMPLE_QUAD) + " " +
                                        folder + " --light 40,250 -o " + (dir / "refused.png") + " > /dev/null 2> " +
                                        errors;
            return std::system(command.c_str());
        };
        CHECK(example(dir / "old.txt") != 0);
        CHECK(readText(dir / "old.txt").find(include + ": the shader include is version 1, older than the version 2") !=
              std::string::npos);
        nlohmann::json newer = readJson(folder + "/material.json");
        newer["version"] = 3;
        std::ofstream(folder + "/material.json") << newer.dump();
        CHECK(example(dir / "newer.txt") != 0);
        CHECK(readText(dir / "newer.txt").find("material.json: version 3, this program reads versions 1 and 2") !=
              std::string::npos);
        CHECK_FALSE(fs::exists(dir / "refused.png"));
    }
}

TEST_CASE("export: the folder refused when not empty (unless --force); a failed export leaves no partial folder") {
    TempDir dir;
    const std::string bank = dir / "m.btflut";
    REQUIRE(runCli({"bake", BTFLUT_DEFAULT_MATERIAL, "--references", "1", "-o", bank, "-q"}).status == 0);
    fs::create_directories(dir / "busy");
    std::ofstream(dir / "busy/notes.txt") << "mine";
    requireOneLineError(runCli({"export", bank, "-o", dir / "busy"}), "the folder holds files that are neither");
    CHECK_FALSE(fs::exists(dir / "busy/luts.png"));
    CHECK(runCli({"export", bank, "-o", dir / "busy", "--force"}).status == 0);
    CHECK(readText(dir / "busy/notes.txt") == "mine");
    // A folder that holds a previous export and nothing else is exported into again without
    // --force (an asset pipeline), and what the new export does not write goes.
    REQUIRE(runCli({"bake", BTFLUT_DEFAULT_MATERIAL, "--predictor", "rbf9", "-o", dir / "rbf.btflut", "-q"}).status ==
            0);
    REQUIRE(runCli({"export", dir / "rbf.btflut", "-o", dir / "asset"}).status == 0);
    CHECK(fs::exists(dir / "asset/weights.bin"));
    // The engines' import sidecars beside the files (Godot's .import, Unity's .meta) do not make
    // it the user's folder; those of files written again stay, those of stale files go.
    for (const char* sidecar :
         {"reference.png.import", "reference.png.meta", "weights.bin.import", "planes-0.png.meta"})
        std::ofstream(dir / ("asset/" + std::string(sidecar))) << "engine";
    CliRun again = runCli({"export", bank, "-o", dir / "asset"});
    REQUIRE_MESSAGE(again.status == 0, again.err);
    CHECK(readJson(dir / "asset/material.json")["kind"] == "luts");
    CHECK_FALSE(fs::exists(dir / "asset/weights.bin"));
    CHECK_FALSE(fs::exists(dir / "asset/planes-0.png"));
    CHECK_FALSE(fs::exists(dir / "asset/weights.bin.import"));
    CHECK_FALSE(fs::exists(dir / "asset/planes-0.png.meta"));
    CHECK(readText(dir / "asset/reference.png.import") == "engine");
    CHECK(readText(dir / "asset/reference.png.meta") == "engine");
    // --force in a folder with the user's files: the previous export's stale files go, the user's stay.
    REQUIRE(runCli({"export", dir / "rbf.btflut", "-o", dir / "busy", "--force"}).status == 0);
    CHECK(fs::exists(dir / "busy/weights.bin"));
    REQUIRE(runCli({"export", bank, "-o", dir / "busy", "--force"}).status == 0);
    CHECK_FALSE(fs::exists(dir / "busy/weights.bin"));
    CHECK(readText(dir / "busy/notes.txt") == "mine");
    requireOneLineError(runCli({"export", bank, "--ptm", dir / "m.ptm"}), "the bank holds no PTM (bake it with --ptm)");
    requireOneLineError(runCli({"export", bank}), "give -o DIR");
    // An existing file where the folder goes, and a folder that cannot be made under a file:
    // one line, and nothing left beside them (the folder is filled apart, then renamed).
    REQUIRE(runCli({"bake", BTFLUT_DEFAULT_MATERIAL, "--references", "3", "-o", dir / "k3.btflut", "-q"}).status == 0);
    std::ofstream(dir / "taken") << "a file";
    requireOneLineError(runCli({"export", dir / "k3.btflut", "-o", dir / "taken"}), "exists and is not a folder");
    requireOneLineError(runCli({"export", dir / "k3.btflut", "-o", dir / "taken/k3"}), "cannot create the folder");
    CHECK(readText(dir / "taken") == "a file");
    for (const auto& entry : fs::directory_iterator(dir.path()))
        CHECK_MESSAGE(entry.path().filename().string().find("partial") == std::string::npos, entry.path());
    // A bank with a predictor exports whole (kind "references"), into a new folder.
    CliRun run = runCli({"export", dir / "k3.btflut", "-o", dir / "new/k3"});
    REQUIRE_MESSAGE(run.status == 0, run.err);
    CHECK(readJson(dir / "new/k3/material.json")["kind"] == "references");
    // --grid resamples its match LUTs too.
    run = runCli({"export", dir / "k3.btflut", "-o", dir / "k3g", "--grid", "9"});
    REQUIRE_MESSAGE(run.status == 0, run.err);
    CHECK(readJson(dir / "k3g/material.json")["luts"]["grid_size"] == 9);
    Result<Image> luts = loadImage(dir / "k3g/luts.png");
    REQUIRE(luts.ok());
    CHECK(luts->height == 9 * 9);
}

TEST_CASE(
    "export --web: one page holding the export's files; bad outputs refused (the browser test: "
    "tests/browser_check.sh)") {
    TempDir dir;
    const std::string bank = dir / "m.btflut";
    REQUIRE(runCli({"bake", BTFLUT_DEFAULT_MATERIAL, "--references", "3", "-o", bank, "-q"}).status == 0);
    CliRun run = runCli({"export", bank, "--web", dir / "m.html", "-o", dir / "m"});
    REQUIRE_MESSAGE(run.status == 0, run.err);
    CHECK(run.out.find("wrote " + std::string(dir / "m.html")) != std::string::npos);
    // The command that opens it, as written: an absolute file:// URL (a relative path with '#' is a host).
    CHECK(run.out.find("chromium 'file://" + fs::absolute(dir / "m.html").lexically_normal().generic_string() +
                       "#light=30,90'") != std::string::npos);
    // --json: what was written, nothing else.
    const CliRun json = runCli({"export", bank, "--web", dir / "j.html", "-o", dir / "j", "--json"});
    REQUIRE(json.status == 0);
    const nlohmann::json written = nlohmann::json::parse(json.out);
    CHECK(written["web"]["page"] == dir / "j.html");
    CHECK(written["folder"]["path"] == dir / "j");
    const auto files = written["folder"]["files"].get<std::vector<std::string>>();
    CHECK(std::find(files.begin(), files.end(), "material.json") != files.end());
    const std::string page = readText(dir / "m.html");
    const std::string tag = "id=\"btflut-data\">";
    const std::size_t open = page.find(tag) + tag.size(), close = page.find("</script>", open);
    REQUIRE(open > tag.size());
    const nlohmann::json data = nlohmann::json::parse(page.substr(open, close - open));
    CHECK(data["material"] == readJson(dir / "m/material.json"));  // the same sidecar
    CHECK(data["name"] == "m");
    for (const char* file : {"luts.png", "planes-0.png", "planes-2.png", "weights.bin"}) {
        INFO(file);
        REQUIRE(data["files"].contains(file));
        CHECK(data["files"][file].get<std::string>().rfind("data:", 0) == 0);
    }
    CHECK(data["material"]["views"][0]["lights"].size() == 25);  // the disk's measured directions
    std::size_t exported = 0;
    for (const auto& entry : fs::directory_iterator(dir / "m")) exported += fs::file_size(entry.path());
    CHECK(page.size() <= 1.4 * static_cast<double>(exported));
    // Bad outputs: one line, nothing written.
    requireOneLineError(runCli({"export", bank, "--web", dir / "m.txt"}), "--web");
    // -o and --web in one run: the files are made once; a folder refused leaves no page either.
    fs::create_directories(dir / "busy");
    std::ofstream(dir / "busy/notes.txt") << "mine";
    requireOneLineError(runCli({"export", bank, "-o", dir / "busy", "--web", dir / "both.html"}),
                        "the folder holds files that are neither");
    CHECK_FALSE(fs::exists(dir / "both.html"));
    fs::create_directories(dir / "taken.html");
    requireOneLineError(runCli({"export", bank, "--web", dir / "taken.html"}), "taken.html");
    CHECK(fs::is_directory(dir / "taken.html"));
    CHECK(runCli({"export", bank, "--web", dir / "new/deeper/m.html", "-q"}).status ==
          0);  // folders made, as for every output
    CHECK(fs::exists(dir / "new/deeper/m.html"));
}

TEST_CASE("export --ptm: a PTM 1.2 LRGB file, rows bottom first, that reads back to the same relighting") {
    TempDir dir;
    const std::string bank = dir / "m.btflut", file = dir / "m.ptm";
    // The bank's PTM beside any predictor (hsh2: auto's validation is not what this tests).
    REQUIRE(runCli({"bake", BTFLUT_DEFAULT_MATERIAL, "--predictor", "hsh2", "--ptm", "-o", bank, "-q"}).status == 0);
    CliRun run = runCli({"export", bank, "--ptm", file});
    REQUIRE_MESSAGE(run.status == 0, run.err);
    Result<Bytes> bytes = readFile(file);
    REQUIRE(bytes.ok());
    const std::string text(bytes->begin(), bytes->end());
    CHECK(text.rfind("PTM_1.2\nPTM_FORMAT_LRGB\n256\n256\n", 0) == 0);
    Result<LutBank> original = loadBank(bank);
    REQUIRE(original.ok());
    const LightModel& ptm = original->ptm;
    // The payload's first record is the bottom row's first texel.
    const std::size_t payload = bytes->size() - ptm.texels() * 9,
                      bottom = ptm.texels() - static_cast<std::size_t>(ptm.width);
    Result<LightModel> back = decodePtmFile(*bytes, file);
    REQUIRE_MESSAGE(back.ok(), back.error());
    CHECK(std::abs(int{(*bytes)[payload + ptm.texels() * 6]} - int{ptm.albedo[bottom * 3]}) == 0);
    CHECK(back->albedo == ptm.albedo);
    for (Direction light :
         {Direction::fromDegrees(0, 0), Direction::fromDegrees(45, 120), Direction::fromDegrees(70, 300)}) {
        const Image a = ptm.render(light), b = back->render(light);
        double worst = 0;
        for (std::size_t i = 0; i < a.samples.size(); ++i)
            worst = std::max(worst, std::abs(double{a.samples[i]} - b.samples[i]));
        INFO("light " << light.thetaDegrees() << "," << light.phiDegrees());
        CHECK(worst * 255 <= 2.0);  // integer biases: each coefficient byte moved by at most half a code
    }
    // Bad files: one line naming the file.
    Bytes truncated(bytes->begin(), bytes->end() - 5);
    Result<LightModel> bad = decodePtmFile(truncated, "cut.ptm");
    REQUIRE_FALSE(bad.ok());
    CHECK(bad.error().find("cut.ptm") != std::string::npos);
    std::string rgb = text;
    rgb.replace(8, 15, "PTM_FORMAT_RGB\n");
    CHECK_FALSE(decodePtmFile(Bytes(rgb.begin(), rgb.end()), "rgb.ptm").ok());
}

TEST_CASE("compare: exit 0 within the tolerance, 1 outside, 2 on bad input; the diff; golden updates") {
    TempDir dir;
    Image a = randomGreyImage(64, 48, 1), b = a, other(32, 48, 1), colour(64, 48, 3);
    b.samples[100] = std::min(1.f, b.samples[100] + 3 / 255.f);  // one pixel 3 codes off
    REQUIRE(savePng(a, dir / "a.png").ok());
    REQUIRE(savePng(b, dir / "b.png").ok());
    REQUIRE(savePng(other, dir / "small.png").ok());
    REQUIRE(savePng(colour, dir / "colour.png").ok());
    CliRun same = runCli({"compare", dir / "a.png", dir / "a.png"});
    CHECK(same.status == 0);
    CHECK(same.out.find("psnr inf (identical)") != std::string::npos);
    CliRun off =
        runCli({"compare", dir / "a.png", dir / "b.png", "--tolerance", "max=2,psnr=40", "--diff", dir / "d.png"});
    CHECK(off.status == 1);
    CHECK(off.out.find("max 3") != std::string::npos);
    // p99: one sample in 3072 off by 3 is within p99=2; a third of them is not.
    const CliRun few = runCli({"compare", dir / "a.png", dir / "b.png", "--tolerance", "p99=2", "--json"});
    CHECK(few.status == 0);
    CHECK(nlohmann::json::parse(few.out)["p99_255"].get<double>() == 0);
    Image many = a;
    for (std::size_t i = 0; i < many.samples.size(); i += 3)
        many.samples[i] = std::min(1.f, many.samples[i] + 3 / 255.f);
    REQUIRE(savePng(many, dir / "many.png").ok());
    CHECK(runCli({"compare", dir / "a.png", dir / "many.png", "--tolerance", "p99=2"}).status == 1);
    Result<Image> diff = loadImage(dir / "d.png");
    REQUIRE(diff.ok());
    CHECK(diff->samples[100 * 3] > 0.2f);  // the pixel that differs is red
    CHECK(diff->samples[101 * 3] < 0.31f);
    CHECK(runCli({"compare", dir / "a.png", dir / "b.png", "--tolerance", "max=3"}).status == 0);
    const nlohmann::json json = nlohmann::json::parse(runCli({"compare", dir / "a.png", dir / "b.png", "--json"}).out);
    CHECK_FALSE(json["within"].get<bool>());
    CHECK(json["failed"][0] == "max");

    auto bad = [](const CliRun& run, const std::string& needle) {
        CHECK(run.status == 2);
        CHECK(run.err.find(needle) != std::string::npos);
    };
    bad(runCli({"compare", dir / "a.png", dir / "small.png"}), "images of different sizes");
    // Grey against RGB: the grey in all three channels, compared as RGB (not refused).
    Image greyAsRgb(64, 48, 3);
    for (std::size_t i = 0; i < a.samples.size(); ++i)
        for (std::size_t c = 0; c < 3; ++c) greyAsRgb.samples[i * 3 + c] = a.samples[i];
    REQUIRE(savePng(greyAsRgb, dir / "grey-as-rgb.png").ok());
    CHECK(runCli({"compare", dir / "a.png", dir / "grey-as-rgb.png"}).out.find("identical") != std::string::npos);
    CHECK(runCli({"compare", dir / "grey-as-rgb.png", dir / "a.png"}).status == 0);
    CHECK(runCli({"compare", dir / "a.png", dir / "colour.png"}).status == 1);
    bad(runCli({"compare", dir / "a.png", dir / "b.png", "--tolerance", "ssim=1.5"}), "ssim is at most 1");
    // --crop: only the rectangle (pixel 100, row 1, differs; rows 10.. do not).
    CHECK(runCli({"compare", dir / "a.png", dir / "b.png", "--crop", "0,10,64,38"}).out.find("identical") !=
          std::string::npos);
    CHECK(runCli({"compare", dir / "a.png", dir / "b.png", "--crop", "30,0,10,5", "--tolerance", "max=2"}).status == 1);
    bad(runCli({"compare", dir / "a.png", dir / "b.png", "--crop", "0,10,65,38"}), "outside");
    bad(runCli({"compare", dir / "a.png", dir / "b.png", "--crop", "0,10,64"}), "expected X,Y,W,H");
    bad(runCli({"compare", dir / "a.png", dir / "b.png", "--tolerance", "psnr"}), "expected NAME=VALUE");
    bad(runCli({"compare", dir / "a.png", dir / "b.png", "--tolerance", "psnr=-1"}), "not a non-negative number");
    bad(runCli({"compare", dir / "a.png", dir / "missing.png"}), "missing.png");

    // Golden files: --update creates a missing one and replaces one outside the tolerance.
    CHECK(runCli({"compare", dir / "a.png", dir / "golden.png", "--update"}).status == 0);
    CHECK(readText(dir / "golden.png") == readText(dir / "a.png"));
    CliRun updated = runCli({"compare", dir / "b.png", dir / "golden.png", "--update", "--tolerance", "max=2"});
    CHECK(updated.status == 0);
    CHECK(updated.out.find("updated") != std::string::npos);
    // It was outside the tolerance, and says so: not "within".
    CHECK(updated.out.find("OUTSIDE the tolerance") != std::string::npos);
    CHECK(updated.out.find("within") == std::string::npos);
    CHECK(readText(dir / "golden.png") == readText(dir / "b.png"));
    REQUIRE(savePng(a, dir / "golden2.png").ok());
    const nlohmann::json u =
        nlohmann::json::parse(runCli({"compare", dir / "b.png", dir / "golden2.png", "--update", "--json"}).out);
    CHECK_FALSE(u["within"].get<bool>());
    CHECK(u["updated"].get<bool>());
    CHECK(u["failed"][0] == "max");
    CHECK(runCli({"compare", dir / "b.png", dir / "golden2.png", "-q", "--update"}).out.empty());  // now within
}

TEST_CASE("compare holds the alpha channel to the tolerance: the same colours, transparent, are another image") {
    TempDir dir;
    Image opaque(16, 8, 4), clear(16, 8, 4), rgb(16, 8, 3);
    for (std::size_t i = 0; i < opaque.pixelCount(); ++i)
        for (int c = 0; c < 4; ++c) {
            const float v = c == 3 ? 1.f : static_cast<float>((i * 7 + c * 40) % 256) / 255.f;
            opaque.samples[i * 4 + c] = v;
            clear.samples[i * 4 + c] = c == 3 ? 0.f : v;
            if (c < 3) rgb.samples[i * 3 + c] = v;
        }
    REQUIRE(savePng(opaque, dir / "opaque.png").ok());
    REQUIRE(savePng(clear, dir / "clear.png").ok());
    REQUIRE(savePng(rgb, dir / "rgb.png").ok());
    const CliRun differs = runCli({"compare", dir / "opaque.png", dir / "clear.png"});
    CHECK(differs.status == 1);
    CHECK(differs.out.find("OUTSIDE") != std::string::npos);
    CHECK(differs.out.find("alpha: max 255.00/255, pixels 100.000%") != std::string::npos);
    CHECK(differs.out.find("(identical)") == std::string::npos);
    const nlohmann::json json =
        nlohmann::json::parse(runCli({"compare", dir / "opaque.png", dir / "clear.png", "--json"}).out);
    CHECK_FALSE(json["identical"].get<bool>());
    CHECK(json["alpha_max_255"].get<double>() == 255);
    // Within a tolerance that allows it; an image with no alpha is opaque.
    CHECK(runCli({"compare", dir / "opaque.png", dir / "clear.png", "--tolerance", "max=255"}).status == 0);
    const CliRun same = runCli({"compare", dir / "opaque.png", dir / "rgb.png"});
    CHECK(same.status == 0);
    CHECK(same.out.find("psnr inf (identical)") != std::string::npos);
    CHECK(runCli({"compare", dir / "rgb.png", dir / "clear.png"}).status == 1);
}

TEST_CASE("compare as a CI tool: pixels over a threshold, parsing, output folders, folders of images, JUnit") {
    TempDir dir;
    Image a = randomGreyImage(64, 48, 1), b = a;
    for (std::size_t i = 0; i < 31; ++i)
        b.samples[i * 97] = std::min(1.f, b.samples[i * 97] + 3 / 255.f);  // 1% of the pixels
    REQUIRE(savePng(a, dir / "a.png").ok());
    REQUIRE(savePng(b, dir / "b.png").ok());
    // pixels: the share (per cent) of pixels more than `threshold` off.
    const nlohmann::json j = nlohmann::json::parse(
        runCli({"compare", dir / "a.png", dir / "b.png", "--json", "--tolerance", "pixels=2%, threshold=1"}).out);
    CHECK(j["within"].get<bool>());
    CHECK(j["pixels_percent"].get<double>() > 0.9);
    CHECK(j["pixels_percent"].get<double>() < 1.1);
    CHECK(runCli({"compare", dir / "a.png", dir / "b.png", "--tolerance", "pixels=0.5,threshold=2"}).status == 1);
    CHECK(runCli({"compare", dir / "a.png", dir / "b.png", "--tolerance", "pixels=0.5,threshold=3"}).status == 0);
    // Identical images: psnr inf, not a capped figure.
    const CliRun same = runCli({"compare", dir / "a.png", dir / "a.png", "--json"});
    CHECK(nlohmann::json::parse(same.out)["psnr"].is_null());
    CHECK(nlohmann::json::parse(same.out)["identical"].get<bool>());
    // A name given twice: one line, exit 2.
    const CliRun twice = runCli({"compare", dir / "a.png", dir / "b.png", "--tolerance", "max=20,max=10"});
    CHECK(twice.status == 2);
    CHECK(twice.err.find("max is given twice") != std::string::npos);
    // Outputs into folders that do not exist yet; the side-by-side image is three panes wide.
    CHECK(runCli({"compare", dir / "a.png", dir / "b.png", "--tolerance", "max=3", "--diff", dir / "new/d.png",
                  "--side-by-side", dir / "new2/s.png"})
              .status == 0);
    Result<Image> side = loadImage(dir / "new2/s.png");
    REQUIRE(side.ok());
    CHECK(side->width == 3 * 64);
    CHECK(side->height == loadImage(dir / "a.png")->height + Canvas::kTextHeight + 6);  // a strip naming each pane
    bool inked = false;  // the strip's label over the first pane
    for (int x = 0; x < 64; ++x)
        for (int y = 0; y < Canvas::kTextHeight + 6; ++y) inked = inked || side->at(x, y, 0) < 0.5f;
    CHECK(inked);
    REQUIRE(runCli({"bake", BTFLUT_DEFAULT_MATERIAL, "--references", "1", "-o", dir / "m.btflut", "-q"}).status == 0);
    // bake --json: the summary, and nothing else on stdout.
    const CliRun baked = runCli(
        {"bake", BTFLUT_DEFAULT_MATERIAL, "--predictor", "hsh2", "--match", "0.5", "-o", dir / "h.btflut", "--json"});
    REQUIRE(baked.status == 0);
    const nlohmann::json summary = nlohmann::json::parse(baked.out);
    CHECK(summary["output"] == dir / "h.btflut");
    CHECK(summary["predictor"] == "hsh2");
    CHECK(summary["match"].get<double>() == doctest::Approx(0.5));
    CHECK(summary["bytes"].get<std::uint64_t>() == fs::file_size(dir / "h.btflut"));
    CHECK(summary["measured_nodes"].get<int>() > 0);
    CHECK(runCli({"relight", dir / "m.btflut", "--light", "30,0", "-o", dir / "made/x.png", "-q"}).status == 0);
    CHECK(fs::exists(dir / "made/x.png"));
    // Folders: every image of either by name, one line each, every failure listed, JUnit.
    fs::create_directories(dir / "out");
    fs::create_directories(dir / "golden");
    REQUIRE(savePng(a, dir / "out/one.png").ok());
    REQUIRE(savePng(a, dir / "golden/one.png").ok());
    REQUIRE(savePng(b, dir / "out/two.png").ok());
    REQUIRE(savePng(a, dir / "golden/two.png").ok());
    REQUIRE(savePng(a, dir / "golden/three.png").ok());
    const CliRun folders = runCli(
        {"compare", dir / "out", dir / "golden", "--junit", dir / "reports/compare.xml", "--diff", dir / "diffs"});
    CHECK(folders.status == 1);
    CHECK(folders.out.find("one.png: psnr inf") != std::string::npos);
    CHECK(folders.out.find("two.png: psnr") != std::string::npos);
    CHECK(folders.out.find("three.png: no three.png in") != std::string::npos);
    CHECK(folders.out.find("compared 3 image(s): 2 failed") != std::string::npos);
    CHECK(fs::exists(dir / "diffs/two.diff.png"));
    const std::string junit = readText(dir / "reports/compare.xml");
    // two.png is outside the tolerance (a failure), three.png could not be compared (an error).
    CHECK(junit.find("tests=\"3\" failures=\"1\" errors=\"1\"") != std::string::npos);
    CHECK(junit.find("<testcase classname=\"btflut.compare\" name=\"one.png\"/>") != std::string::npos);
    CHECK(junit.find("<error message=\"no three.png in") != std::string::npos);
    CHECK(junit.find("<failure message=\"outside") != std::string::npos);
    // --update creates the missing golden images and replaces those outside the tolerance.
    REQUIRE(savePng(a, dir / "out/three.png").ok());
    REQUIRE(savePng(a, dir / "out/four.png").ok());
    const CliRun update = runCli({"compare", dir / "out", dir / "golden", "--update"});
    CHECK(update.status == 0);
    CHECK(update.out.find("compared 4 image(s): 0 failed, 2 updated") != std::string::npos);  // two.png and four.png
    CHECK(fs::exists(dir / "golden/four.png"));
    CHECK(runCli({"compare", dir / "out", dir / "golden"}).status == 0);
    // Subfolders are compared by their path, as golden-image suites lay them out.
    fs::create_directories(dir / "out/sub");
    fs::create_directories(dir / "golden/sub");
    REQUIRE(savePng(b, dir / "out/sub/x.png").ok());
    REQUIRE(savePng(a, dir / "golden/sub/x.png").ok());
    const CliRun nested = runCli({"compare", dir / "out", dir / "golden", "--diff", dir / "nested-diffs"});
    CHECK(nested.status == 1);
    CHECK(nested.out.find("sub/x.png: psnr") != std::string::npos);
    CHECK(nested.out.find("compared 5 image(s): 1 failed") != std::string::npos);
    CHECK(fs::exists(dir / "nested-diffs/sub/x.diff.png"));
    fs::remove(dir / "golden/sub/x.png");
    CHECK(runCli({"compare", dir / "out", dir / "golden"}).out.find("sub/x.png: no golden image") != std::string::npos);
}

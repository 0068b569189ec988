// The btflut command end to end, in-process: outputs, and bad input refused with one line
// naming the file, a non-zero exit and no (or an untouched) output file.
#include <doctest/doctest.h>

#include "core/bank/bank_file.h"
#include "core/predict/model_predictor.h"
#include "helpers.h"

using namespace btflut;
using namespace btflut::test;

namespace {
const std::vector<SyntheticShot> kCliShots{
    {0, 0, 0, 0, 0, 1}, {30, 0, 0, 0, 40, 1}, {30, 120, 0, 0, 0, 2}, {30, 240, 0, 0, 100, 1}};
}

TEST_CASE("btflut --help and every subcommand's --help succeed") {
    CHECK(runCli({"--help"}).status == 0);
    for (const char* cmd : {"hist", "bake", "relight", "info", "export", "match"}) {
        CliRun r = runCli({cmd, "--help"});
        INFO(cmd);
        CHECK(r.status == 0);
        CHECK(r.out.find("Usage") != std::string::npos);
    }
    CHECK(runCli({"bench", "bake", "--help"}).status == 0);
    const CliRun bare = runCli({});  // no command: the help
    CHECK(bare.status == 0);
    CHECK(bare.out.find("Usage") != std::string::npos);
    requireOneLineError(runCli({"frobnicate"}), "frobnicate");
    // Misspellings: the nearest name, and the help to read.
    requireOneLineError(runCli({"bak"}), "unknown command 'bak' (did you mean bake?); see btflut --help");
    requireOneLineError(
        runCli({"relight", "m.btflut", "--ligth", "30,0", "-o", "x.png"}),
        "btflut relight: error: unknown option --ligth (did you mean --light?); see btflut relight --help");
    requireOneLineError(runCli({"compare", "a.png", "b.png", "--tolerence=max=2"}), "did you mean --tolerance?");
    requireOneLineError(runCli({"relight", "m.btflut", "-o", "x.png"}), "see btflut relight --help");
    CHECK(runCli({"view", "--help"}).out.find("{false}") == std::string::npos);
    requireOneLineError(
        runCli({"bench", "render", "m.btflut", "--sise", "8x8"}),
        "btflut bench render: error: unknown option --sise (did you mean --size?); see btflut bench render --help");
    // Angles as people write them.
    requireOneLineError(runCli({"relight", "m.btflut", "--light", "95,0", "-o", "x.png"}), "theta 95 degrees");
    // Negative numbers are values, not options.
    CHECK(runCli({"relight", "m.btflut", "--light", "30,-20", "-o", "x.png"}).err.find("unknown option") ==
          std::string::npos);
}

TEST_CASE("-q, --json and --force mean one thing on every command") {
    // -q on every command that prints progress or what it wrote; --force where the output is a
    // folder that may hold other files; --json where the printed figures are the result.
    for (const char* cmd : {"hist", "fit", "bake", "relight", "export", "match", "simulate", "plot", "synth", "render",
                            "eval", "compare"}) {
        INFO(cmd);
        CHECK(runCli({cmd, "--help"}).out.find("-q,--quiet") != std::string::npos);
    }
    for (const char* cmd : {"fit", "orient", "classify", "info", "render", "eval", "compare"}) {
        INFO(cmd);
        CHECK(runCli({cmd, "--help"}).out.find("--json") != std::string::npos);
    }
    for (const char* cmd : {"export", "synth"}) CHECK(runCli({cmd, "--help"}).out.find("--force") != std::string::npos);

    TempDir dir;
    const std::string manifest = writeSyntheticDataset(dir, kCliShots);
    auto quiet = [&](std::vector<std::string> args) {
        args.push_back("-q");
        const CliRun r = runCli(args);
        INFO(args.front() << ": " << r.err);
        CHECK(r.status == 0);
        CHECK(r.out.empty());
    };
    quiet({"hist", manifest, "-o", dir / "h.csv"});
    quiet({"simulate", "--roughness", "0.4", "--geometry", "curet-c2", "--nodes", "8", "-o", dir / "s.csv"});
    quiet({"plot", dir / "h.csv", "-o", dir / "h.png"});
    quiet({"match", dir / "shot0.png", dir / "shot1.png", "-o", dir / "m.png"});
    quiet({"bake", manifest, "-o", dir / "m.btflut", "--grid", "5"});
    quiet({"export", dir / "m.btflut", "-o", dir / "export"});
    quiet({"compare", dir / "shot0.png", dir / "shot0.png"});
    // compare -q still says what is outside the tolerance.
    const CliRun differs = runCli({"compare", dir / "shot0.png", dir / "shot1.png", "-q"});
    CHECK(differs.status == 1);
    CHECK(differs.out.find("OUTSIDE the tolerance") != std::string::npos);
    requireOneLineError(runCli({"eval", manifest, "-q"}), "-q leaves eval's figures only in -o DIR's files: give -o");
}

TEST_CASE("docs/eval.md's usage lists every option of eval") {
    const std::string doc = readText(std::string(BTFLUT_SOURCE_DIR) + "/docs/eval.md");
    const std::string usage = doc.substr(0, doc.find("```", doc.find("```") + 3));
    const std::string help = runCli({"eval", "--help"}).out;
    std::size_t options = 0;
    for (std::size_t at = help.find("\n  -"); at != std::string::npos; at = help.find("\n  -", at + 1)) {
        std::string name = help.substr(at + 3, help.find_first_of(" \n", at + 3) - at - 3);
        name = name.substr(name.rfind(',') == std::string::npos ? 0 : name.rfind(',') + 1);  // -o,--output: --output
        if (name == "--help" || name == "-h") continue;
        if (name == "--output") name = "-o";
        ++options;
        INFO(name);
        CHECK(usage.find(name) != std::string::npos);
    }
    CHECK(options > 10);
}

TEST_CASE("hist writes the documented CSV and JSON") {
    TempDir dir;
    std::string manifest = writeSyntheticDataset(dir, kCliShots);
    CliRun r = runCli({"hist", manifest, "--bins", "8", "-o", dir / "h.csv"});
    REQUIRE(r.status == 0);
    auto rows = parseHistogramCsv(readText(dir / "h.csv"), "h.csv");
    REQUIRE(rows.ok());
    REQUIRE(rows->size() == kCliShots.size());
    CHECK((*rows)[1].light.thetaDegrees() == doctest::Approx(30));
    double sum = 0;
    for (double v : (*rows)[2].bins) sum += v;
    CHECK(sum == doctest::Approx(1.0).epsilon(1e-12));
    CHECK(readText(dir / "h.csv").rfind("name,theta_i,phi_i,theta_r,phi_r,b0,b1,b2,b3,b4,b5,b6,b7\nshot0,", 0) == 0);

    REQUIRE(runCli({"hist", manifest, "-o", dir / "h.json"}).status == 0);
    auto doc = nlohmann::json::parse(readText(dir / "h.json"));
    CHECK(doc["bins"] == 64);
    CHECK(doc["histograms"].size() == kCliShots.size());
    const CliRun written = runCli({"hist", manifest, "-o", dir / "h2.json", "--json"});
    REQUIRE(written.status == 0);
    CHECK(nlohmann::json::parse(written.out)["histograms"] == kCliShots.size());
    CHECK(nlohmann::json::parse(written.out)["output"] == dir / "h2.json");

    requireOneLineError(runCli({"hist", manifest, "--channels", "rgb", "-o", dir / "rgb.csv"}), "needs colour images");
    CHECK_FALSE(fs::exists(dir / "rgb.csv"));
    requireOneLineError(runCli({"hist", manifest, "--bins", "1", "-o", dir / "b.csv"}), "--bins");
    requireOneLineError(runCli({"hist", manifest, "-o", dir / "h.txt"}), "h.txt: output must be a .csv or .json file");
}

TEST_CASE("bake, info, relight and export work from files") {
    TempDir dir;
    std::string manifest = writeSyntheticDataset(dir, kCliShots);
    CliRun bake = runCli({"bake", manifest, "-o", dir / "m.btflut", "--grid", "5", "--references", "1"});
    REQUIRE(bake.status == 0);
    CHECK(bake.out.find("wrote") != std::string::npos);
    CliRun info = runCli({"info", dir / "m.btflut"});
    REQUIRE(info.status == 0);
    CHECK(info.out.find("256 entries") != std::string::npos);
    CHECK(info.out.find("5x5") != std::string::npos);
    CHECK(info.out.find("4 light nodes") != std::string::npos);

    REQUIRE(runCli({"relight", dir / "m.btflut", "--light", "30,0", "-o", dir / "r.png", "--no-dither"}).status == 0);
    auto relit = loadImage(dir / "r.png");
    REQUIRE(relit.ok());
    auto measured = loadImage(dir / "shot1.png");
    for (std::size_t i = 0; i < relit->samples.size(); ++i)
        REQUIRE(std::lround(relit->samples[i] * 255) == std::lround(measured->samples[i] * 255));

    CliRun ex = runCli({"export", dir / "m.btflut", "-o", dir / "atlas.png"});
    REQUIRE(ex.status == 0);
    auto atlas = loadImage(dir / "atlas.png");
    REQUIRE(atlas.ok());
    CHECK(atlas->bitDepth == 16);
    CHECK(atlas->width == 256);
    CHECK(atlas->height == 25);
    auto side = nlohmann::json::parse(readText(dir / "atlas.json"));
    CHECK(side["grid_size"] == 5);
    CHECK(side["layers"][0]["node_provenance"].size() == 25);
    // The centre row (the pole, shot0's light) is the identity on the reference's codes.
    for (int code = 0; code < 100; ++code) CHECK(std::lround(atlas->at(code, 12, 0) * 255) == code);
}

TEST_CASE("one exit-code convention: bad input 1 (values out of range too), usage 2, compare 2 on bad input") {
    TempDir dir;
    const std::string manifest = writeSyntheticDataset(dir, kCliShots);
    for (const std::vector<std::string>& bad :
         {std::vector<std::string>{"bake", manifest, "--grid", "0", "-o", dir / "m.btflut"},
          {"bake", manifest, "--references", "1000", "-o", dir / "m.btflut"},
          {"bake", manifest, "--grid", "seven", "-o", dir / "m.btflut"},
          {"hist", manifest, "--bins", "0", "-o", dir / "h.csv"},
          {"bake", manifest, "--budget", "0", "-o", dir / "m.btflut"},
          {"bake", dir / "nothing", "-o", dir / "m.btflut"}}) {
        const CliRun r = runCli(bad);
        INFO(bad[0] << " " << bad[2] << " " << bad[3] << ": " << r.err);
        CHECK(r.status == 1);
        CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
        CHECK(r.err.find("btflut " + bad[0] + ": error: ") == 0);
    }
    for (const std::vector<std::string>& usage :
         {std::vector<std::string>{"bake", manifest, "--gird", "5"}, {"bake"}, {"bakke", manifest}, {"hist"}}) {
        INFO(usage[0]);
        CHECK(runCli(usage).status == 2);
    }
    // compare: 0 within, 1 outside, 2 bad input, values out of range included.
    CHECK(runCli({"compare", dir / "shot0.png", dir / "shot0.png", "--tolerance", "psnr=-5"}).status == 2);
    CHECK(runCli({"compare", dir / "shot0.png", dir / "none.png"}).status == 2);
    CHECK(runCli({"--help"}).out.find("Exit status: 0 done; 1 bad input") != std::string::npos);
}

TEST_CASE("bake says which images share a light direction, the node their LUTs are averaged into") {
    TempDir dir;
    const std::string manifest = writeSyntheticDataset(dir, kCliShots);
    // shot3 at shot1's light: 4 images, 3 nodes.
    std::ofstream(dir / "twice.lp") << "4\nshot0.png 0 0 1\nshot1.png 0.5 0 0.8660254\nshot2.png -0.25 0.4330127 "
                                       "0.8660254\nshot3.png 0.5 0 0.8660254\n";
    const CliRun r = runCli({"bake", dir / "twice.lp", "--references", "1", "-o", dir / "t.btflut"});
    REQUIRE_MESSAGE(r.status == 0, r.err);
    CHECK(r.out.find("4 images, 1 view layer(s), 3 measured nodes (averaged into one node, a light direction twice: "
                     "shot3 at shot1's)") != std::string::npos);
    const CliRun json = runCli({"bake", dir / "twice.lp", "--references", "1", "-o", dir / "t.btflut", "--json"});
    CHECK(nlohmann::json::parse(json.out)["images_sharing_a_node"] == nlohmann::json{"shot3 at shot1's"});
    const CliRun plain = runCli({"bake", manifest, "--references", "1", "-o", dir / "p.btflut"});
    CHECK(plain.status == 0);
    CHECK(plain.out.find("4 measured nodes,") != std::string::npos);
}

TEST_CASE("bad input: one line naming the file, non-zero exit, outputs untouched") {
    TempDir dir;
    std::string manifest = writeSyntheticDataset(dir, kCliShots);
    REQUIRE(runCli({"bake", manifest, "-o", dir / "m.btflut"}).status == 0);
    std::ofstream(dir / "keep.btflut") << "precious";
    std::ofstream(dir / "keep.png") << "precious";

    SUBCASE("missing dataset") {
        requireOneLineError(runCli({"bake", dir / "nothing", "-o", dir / "keep.btflut"}),
                            "nothing: no such file or folder");
    }
    SUBCASE("corrupt image in the dataset") {
        std::ofstream(dir / "shot2.png", std::ios::binary) << "\x89PNG\r\n\x1a\n";
        requireOneLineError(runCli({"bake", manifest, "-o", dir / "keep.btflut"}), "shot2.png");
    }
    SUBCASE("NaN and below-horizon lights in an .lp file") {
        std::ofstream(dir / "nan.lp") << "2\nshot0.png 0 0 1\nshot1.png nan 0 1\n";
        requireOneLineError(runCli({"bake", dir / "nan.lp", "-o", dir / "keep.btflut"}), "nan.lp:3");
        std::ofstream(dir / "low.lp") << "2\nshot0.png 0 0 1\nshot1.png 0.6 0 -0.8\n";
        requireOneLineError(runCli({"hist", dir / "low.lp", "-o", dir / "h.csv"}), "below the horizon");
        CHECK_FALSE(fs::exists(dir / "h.csv"));
    }
    SUBCASE("truncated and bit-flipped banks") {
        std::string bytes = readText(dir / "m.btflut");
        std::ofstream(dir / "cut.btflut", std::ios::binary)
            .write(bytes.data(), static_cast<std::streamsize>(bytes.size() / 2));
        requireOneLineError(runCli({"relight", dir / "cut.btflut", "--light", "10,0", "-o", dir / "keep.png"}),
                            "cut.btflut: truncated");
        bytes[bytes.size() / 3] ^= 4;
        std::ofstream(dir / "flip.btflut", std::ios::binary) << bytes;
        requireOneLineError(runCli({"info", dir / "flip.btflut"}), "flip.btflut: checksum mismatch");
        requireOneLineError(runCli({"export", dir / "flip.btflut", "-o", dir / "keep.png"}), "flip.btflut");
    }
    SUBCASE("bad directions") {
        requireOneLineError(runCli({"relight", dir / "m.btflut", "--light", "nan,0", "-o", dir / "keep.png"}),
                            "--light");
        requireOneLineError(runCli({"relight", dir / "m.btflut", "--light", "90,0", "-o", dir / "keep.png"}),
                            "horizon");
        requireOneLineError(
            runCli({"relight", dir / "m.btflut", "--light", "30,0", "--view", "95,0", "-o", dir / "keep.png"}),
            "--view");
    }
    SUBCASE("a constant reference, a bad reference name") {
        requireOneLineError(runCli({"bake", manifest, "--reference", "zzz", "-o", dir / "keep.btflut"}),
                            "no image named 'zzz'");
        Image flat(40, 30, 1);
        std::fill(flat.samples.begin(), flat.samples.end(), 0.25f);
        REQUIRE(savePng(flat, dir / "shot0.png").ok());
        requireOneLineError(
            runCli({"bake", manifest, "--references", "1", "--reference", "shot0", "-o", dir / "keep.btflut"}),
            "reference image is constant");
        // The default bakes it all the same: a light model carries the brightness.
        CliRun automatic = runCli({"bake", manifest, "-o", dir / "auto.btflut", "-q"});
        CHECK(automatic.status == 0);
        Result<LutBank> bank = loadBank(dir / "auto.btflut");
        REQUIRE(bank.ok());
        CHECK(bank->predictorAs<ModelPredictor>() != nullptr);
    }
    CHECK(readText(dir / "keep.btflut") == "precious");
    CHECK(readText(dir / "keep.png") == "precious");
    for (const auto& entry : fs::directory_iterator(dir.path()))
        CHECK(entry.path().string().find(".tmp.") == std::string::npos);
}

TEST_CASE("simulate writes hist's CSV and refuses bad parameters") {
    TempDir dir;
    CliRun ok =
        runCli({"simulate", "--roughness", "0.4", "--geometry", "curet-c2", "--nodes", "16", "-o", dir / "s.csv"});
    REQUIRE(ok.status == 0);
    auto rows = parseHistogramCsv(readText(dir / "s.csv"), "s.csv");
    REQUIRE(rows.ok());
    REQUIRE(rows->size() == 11);
    CHECK((*rows)[5].name == "c2-6");
    CHECK((*rows)[5].light.thetaDegrees() == doctest::Approx(22.5));
    REQUIRE(runCli({"simulate", "--roughness", "0.4", "--brdf", "mix", "--kd", "0.6", "--ks", "0.4", "--geometry",
                    "curet-specular", "--method", "mc", "--samples", "2000", "-o", dir / "s.json"})
                .status == 0);
    CHECK(nlohmann::json::parse(readText(dir / "s.json"))["histograms"].size() == 7);

    const std::vector<std::pair<std::vector<std::string>, std::string>> bad{
        {{"--roughness", "0"}, "roughness 0 must be > 0"},
        {{"--roughness", "-1"}, "roughness -1 must be > 0"},
        {{"--roughness", "0.4", "--brdf", "ts", "--sigma", "0"}, "sigma 0 must be > 0"},
        {{"--roughness", "0.4", "--brdf", "ts", "--ior", "0.9"}, "ior 0.9 must be >= 1"},
        {{"--roughness", "0.4", "--brdf", "mix"}, "--brdf mix needs kd and ks"},
        {{"--roughness", "0.4", "--brdf", "phong"}, "--brdf"},
        {{"--roughness", "0.4", "--method", "magic"}, "--method 'magic'"},
        {{"--roughness", "0.4", "--bins", "1"}, "--bins"},
        {{"--roughness", "nan"}, "roughness nan must be > 0"},
    };
    for (const auto& [flags, needle] : bad) {
        std::vector<std::string> args{"simulate", "--geometry", "curet-c2", "-o", dir / "bad.csv"};
        args.insert(args.end(), flags.begin(), flags.end());
        INFO(needle);
        requireOneLineError(runCli(args), needle);
    }
    requireOneLineError(runCli({"simulate", "--roughness", "0.4", "--geometry", "curet-c3", "-o", dir / "bad.csv"}),
                        "curet-c3");
    requireOneLineError(runCli({"simulate", "--roughness", "0.4", "--geometry", "10,0,95,0", "-o", dir / "bad.csv"}),
                        "theta");
    CHECK_FALSE(fs::exists(dir / "bad.csv"));
}

TEST_CASE("plot draws histogram CSV files as a figure; bad files refused") {
    TempDir dir;
    REQUIRE(runCli({"simulate", "--roughness", "0.4", "--geometry", "curet-c2", "--nodes", "12", "-o", dir / "a.csv"})
                .status == 0);
    REQUIRE(
        runCli({"simulate", "--roughness", "0.6", "--geometry", "curet-specular", "--nodes", "12", "-o", dir / "b.csv"})
            .status == 0);
    CliRun ok = runCli({"plot", dir / "a.csv", dir / "b.csv", "-o", dir / "fig.png"});
    REQUIRE(ok.status == 0);
    auto fig = loadImage(dir / "fig.png");
    REQUIRE(fig.ok());
    CHECK(fig->height > 11 * 60);  // a row per position of the longer file
    CHECK(fig->width > 2 * 256);   // a column per file
    // Bars are drawn: the figure is not blank, and the L/S/C marks are red.
    std::size_t blue = 0, red = 0;
    for (std::size_t i = 0; i < fig->pixelCount(); ++i) {
        const float* p = &fig->samples[i * 3];
        blue += p[2] > 0.6f && p[0] < 0.35f;
        red += p[0] > 0.6f && p[1] < 0.3f;
    }
    CHECK(blue > 5000);
    CHECK(red > 50);
    std::ofstream(dir / "bad.csv") << "name,theta_i,phi_i,theta_r,phi_r,b0,b1\nx,1,2,3,4,0.5\n";
    requireOneLineError(runCli({"plot", dir / "bad.csv", "-o", dir / "x.png"}), "bad.csv:2");
    std::ofstream(dir / "empty.csv") << "name,theta_i,phi_i,theta_r,phi_r,b0,b1\n";
    requireOneLineError(runCli({"plot", dir / "empty.csv", "-o", dir / "x.png"}), "no histograms");
    requireOneLineError(runCli({"plot", dir / "none.csv", "-o", dir / "x.png"}), "none.csv: cannot open");
    CHECK_FALSE(fs::exists(dir / "x.png"));
}

TEST_CASE("small things: hist of one image, info --json, match --mask, plot --overlay, commands say what they wrote") {
    TempDir dir;
    std::string manifest = writeSyntheticDataset(dir, kCliShots);
    CliRun hist = runCli({"hist", dir / "shot1.png", "-o", dir / "one.csv"});
    REQUIRE_MESSAGE(hist.status == 0, hist.err);
    CHECK(hist.out.find("wrote " + std::string(dir / "one.csv") + ": 1 histogram(s) of 64 bins") != std::string::npos);
    Result<std::vector<HistogramRow>> rows = parseHistogramCsv(readText(dir / "one.csv"), "one.csv");
    REQUIRE(rows.ok());
    REQUIRE(rows->size() == 1);
    CHECK(rows->front().name == "shot1");
    CliRun simulate =
        runCli({"simulate", "--roughness", "0.4", "--geometry", "curet-c2", "--nodes", "8", "-o", dir / "s.csv"});
    CHECK(simulate.out.find("11 histogram(s) of 64 bins") != std::string::npos);

    REQUIRE(runCli({"bake", manifest, "-o", dir / "m.btflut", "--grid", "5", "-q"}).status == 0);
    CliRun info = runCli({"info", dir / "m.btflut", "--json"});
    REQUIRE(info.status == 0);
    const nlohmann::json json = nlohmann::json::parse(info.out);
    CHECK(json["entries"] == 256);
    CHECK(json["layers"][0]["light_nodes"] == 4);
    CHECK(json["layers"][0]["modelled_nodes"] == 0);

    // match --mask: the statistics of the masked pixels (the left half: codes of x < 20).
    Image mask(40, 30, 1);
    for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 20; ++x) mask.at(x, y, 0) = 1;
    REQUIRE(savePng(mask, dir / "mask.png").ok());
    CHECK(runCli({"match", dir / "shot0.png", dir / "shot1.png", "--mask", dir / "mask.png", "--target-mask",
                  dir / "mask.png", "-o", dir / "matched.png"})
              .status == 0);
    const CliRun matched = runCli({"match", dir / "shot0.png", dir / "shot1.png", "-o", dir / "m2.png", "--json"});
    REQUIRE(matched.status == 0);
    CHECK(nlohmann::json::parse(matched.out)["output"] == dir / "m2.png");
    CHECK(nlohmann::json::parse(matched.out)["entries"] == 256);
    requireOneLineError(
        runCli({"match", dir / "shot0.png", dir / "shot1.png", "--mask", dir / "small.png", "-o", dir / "x.png"}),
        "small.png");

    CliRun overlay = runCli({"plot", dir / "one.csv", dir / "s.csv", "--overlay", "-o", dir / "o.png"});
    REQUIRE(overlay.status == 0);
    Result<Image> figure = loadImage(dir / "o.png");
    REQUIRE(figure.ok());
    CHECK(figure->width < 2 * 256);  // one panel per position
}

// Hardening (issue 10) through the command line: bad input gives one line naming the file,
// a non-zero exit and no output; options are honoured or refused, never ignored; banks of
// the paper's own measurement geometry follow the light.
#include <doctest/doctest.h>
#include <unistd.h>

#include "core/bank/bank_file.h"
#include "core/histogram/histogram.h"
#include "helpers.h"

using namespace btflut;
using namespace btflut::test;

namespace {
const std::vector<SyntheticShot> kShots{
    {0, 0, 0, 0, 0, 1}, {30, 0, 0, 0, 40, 1}, {30, 120, 0, 0, 0, 2}, {30, 240, 0, 0, 100, 1}};

std::string regression(const std::string& target, const std::string& name) {
    return (fs::path(BTFLUT_SOURCE_DIR) / "tests" / "fuzz" / "regressions" / target / name).string();
}

double meanOf(const Image& image) {
    double sum = 0;
    for (float v : image.samples) sum += v;
    return sum / static_cast<double>(image.samples.size());
}
}  // namespace

TEST_CASE("image and bank bombs: refused from their headers, one line, nothing written") {
    TempDir dir;
    for (const char* name : {"png-claims-20000x20000.png", "tga-claims-65535x65535.tga", "jpeg-claims-60000x60000.jpg",
                             "bmp-claims-16777217x20000.bmp"}) {
        INFO(name);
        requireOneLineError(
            runCli({"match", regression("image", name), regression("image", name), "-o", dir / "out.png"}),
            "pixels, over the limit of 268435456 pixels (raise it with --max-pixels)");
    }
    requireOneLineError(runCli({"match", regression("image", "tga-rle-8000x8000-data-missing.tga"),
                                regression("image", "tga-rle-8000x8000-data-missing.tga"), "-o", dir / "out.png"}),
                        "truncated TGA (run-length data ends early)");
    requireOneLineError(runCli({"info", regression("bank", "ptm-claims-60000x60000-reference-16x16.btflut")}),
                        "the PTM (60000x60000) does not match the reference image's size");
    requireOneLineError(runCli({"relight", regression("bank", "reference-and-ptm-claim-60000x60000.btflut"), "--light",
                                "10,0", "-o", dir / "out.png"}),
                        "reference image: image is 60000x60000 pixels, over the limit");
    requireOneLineError(runCli({"info", regression("bank", "embedded-reference-claims-16000x16000.btflut")}),
                        "image is 16000x16000, expected 16x16");
    CHECK_FALSE(fs::exists(dir / "out.png"));
}

TEST_CASE("--max-pixels bounds every image a command reads, before or after the subcommand") {
    TempDir dir;
    std::string manifest = writeSyntheticDataset(dir, kShots);  // 40 x 30 = 1200 pixels
    requireOneLineError(runCli({"--max-pixels", "1000", "hist", manifest, "-o", dir / "h.csv"}),
                        "shot0.png: image is 40x30 pixels, over the limit of 1000 pixels");
    requireOneLineError(runCli({"hist", manifest, "-o", dir / "h.csv", "--max-pixels", "1199"}),
                        "over the limit of 1199");
    CHECK(runCli({"hist", manifest, "-o", dir / "h.csv", "--max-pixels", "1200"}).status == 0);
    CHECK(runCli({"hist", manifest, "-o", dir / "h2.csv"}).status == 0);  // the default again
    CHECK(runCli({"--max-pixels", "0", "hist", manifest, "-o", dir / "h3.csv"}).status != 0);
}

TEST_CASE("no exception escapes: numbers out of range, wrong JSON types, odd file names") {
    TempDir dir;
    std::string manifest = writeSyntheticDataset(dir, kShots);
    std::ofstream(dir / "big.json") << R"({"images": [{"file": "shot0.png", "light": {"theta": 1e999, "phi": 0}}]})";
    requireOneLineError(runCli({"bake", dir / "big.json", "-o", dir / "m.btflut"}), "big.json: not valid JSON");
    REQUIRE(runCli({"bake", manifest, "--references", "1", "-o", dir / "m.btflut", "-q"}).status == 0);
    std::ofstream(dir / "s.json") << R"({"light": {"direction": [0,0,1]}, "materials": {"a": "m.btflut"},
        "quads": [{"material": "a", "center": [0,0,0], "normal": [0,0,1], "tangent": [1,0,0], "mode": 5}]})";
    requireOneLineError(runCli({"render", dir / "s.json", "-o", dir / "r.png"}), "quads[0].mode: expected a string");
    std::ofstream(dir / "w.json") << R"({"image": {"width": 4294967360, "height": 64}, "light": {"direction": [0,0,1]},
        "materials": {"a": "m.btflut"}, "quads": [{"material": "a", "center": [0,0,0], "normal": [0,0,1], "tangent": [1,0,0]}]})";
    requireOneLineError(runCli({"render", dir / "w.json", "-o", dir / "r.png"}),
                        "image size 4294967360x64 is not within 1..16384");
    CHECK_FALSE(fs::exists(dir / "r.png"));

    // A photometric-stereo image number beyond any integer.
    fs::create_directories(dir / "psm");
    std::ofstream(dir / "psm/lights.txt") << "1\n0 0 1\n";
    fs::copy_file(dir / "shot0.png", dir / "psm/rock.0.png");
    fs::copy_file(dir / "shot0.png", dir / "psm/rock.99999999999999999999.png");
    requireOneLineError(runCli({"hist", dir / "psm", "-o", dir / "h.csv"}),
                        "image number 99999999999999999999 is out of range");

    // Image names that are not UTF-8 go into JSON as U+FFFD.
    fs::copy_file(dir / "shot1.png", dir / "\xff\xfe.png");
    std::ofstream(dir / "odd.lp") << "2\nshot0.png 0 0 1\n\xff\xfe.png 0.5 0 0.8660254\n";
    REQUIRE(runCli({"hist", dir / "odd.lp", "-o", dir / "h.json"}).status == 0);
    auto doc = nlohmann::json::parse(readText(dir / "h.json"));
    CHECK(doc["histograms"][1]["name"] == "\xef\xbf\xbd\xef\xbf\xbd");
}

TEST_CASE("outputs go through exclusive temporary files: a planted symlink is not followed") {
    TempDir dir;
    std::string manifest = writeSyntheticDataset(dir, kShots);
    REQUIRE(runCli({"bake", manifest, "--references", "1", "-o", dir / "m.btflut", "-q"}).status == 0);
    std::ofstream(dir / "victim") << "precious";
    // The name the old scheme used (PATH.tmp.PID); the new one is random and made with O_EXCL.
    fs::create_symlink(dir / "victim", dir / ("out.png.tmp." + std::to_string(::getpid())));
    REQUIRE(runCli({"relight", dir / "m.btflut", "--light", "30,0", "-o", dir / "out.png", "-q"}).status == 0);
    CHECK(readText(dir / "victim") == "precious");
    CHECK(fs::is_regular_file(fs::symlink_status(dir / "out.png")));
    CHECK(loadImage(dir / "out.png").ok());
}

TEST_CASE("simulate --smooth 1e9 stays finite") {
    TempDir dir;
    REQUIRE(runCli({"simulate", "--roughness", "0.4", "--geometry", "10,0,0,0", "--nodes", "8", "--bins", "16",
                    "--smooth", "1e9", "-o", dir / "s.csv"})
                .status == 0);
    auto rows = parseHistogramCsv(readText(dir / "s.csv"), "s.csv");
    REQUIRE(rows.ok());
    double sum = 0;
    for (double v : (*rows)[0].bins) sum += v;
    CHECK(sum == doctest::Approx(1.0));
}

TEST_CASE("options are honoured or refused, never ignored") {
    TempDir dir;
    std::string manifest = writeSyntheticDataset(dir, kShots);
    REQUIRE(runCli({"bake", manifest, "--references", "1", "-o", dir / "m.btflut", "-q", "--grid", "2"}).status == 0);
    const std::string bank = dir / "m.btflut";
    std::ofstream(dir / "s.json") << R"({"light": {"direction": [0,0,1]}, "materials": {"a": "m.btflut"},
        "quads": [{"material": "a", "center": [0,0,0], "normal": [0,0,1], "tangent": [1,0,0]}]})";
    const std::string out = dir / "out.png";
    requireOneLineError(runCli({"render", bank, "--native", "--light", "30,0", "--mode", "flat", "-o", out}),
                        "--native draws the lut mode");
    requireOneLineError(runCli({"render", bank, "--native", "--light", "30,0", "--mode", "bogus", "-o", out}),
                        "mode 'bogus' is not lut, brdf, ptm, flat or nearest");
    requireOneLineError(runCli({"render", dir / "s.json", "--mode", "bogus", "-o", out}), "mode 'bogus'");
    requireOneLineError(runCli({"render", bank, "--native", "--light", "30,0", "--stats", "-o", out}),
                        "--stats reports on scenes");
    requireOneLineError(runCli({"render", bank, "--native", "--light", "30,0", "--size", "8x8", "-o", out}),
                        "--size is for scenes");
    requireOneLineError(runCli({"render", dir / "s.json", "--view", "30,0", "-o", out}),
                        "a scene's camera sets the view");
    requireOneLineError(
        runCli({"relight", bank, "--light", "60,30", "--view", "30,0", "-o", out}),
        "the bank holds one view direction (0.000000, 0.000000 degrees); it cannot relight for --view 30,0");
    CHECK(runCli({"relight", bank, "--light", "60,30", "--view", "0,0", "-o", out, "-q"}).status == 0);
    fs::remove(out);

    Image other(20, 30, 1);
    REQUIRE(savePng(other, dir / "other.png").ok());
    requireOneLineError(runCli({"relight", bank, "--light", "30,0", "--reference-image", dir / "other.png", "-o", out}),
                        "other.png: the bank's reference is 40x30 with 1 channel(s) at 8 bits, this image is 20x30");
    CHECK_FALSE(fs::exists(out));

    CliRun info = runCli({"info", bank});
    REQUIRE(info.status == 0);
    CHECK(info.out.find("nan") == std::string::npos);
    CHECK(info.out.find("of light directions covered") != std::string::npos);

    requireOneLineError(runCli({"bake", manifest, "--references", "1", "-o", dir / "huge.btflut", "--grid", "257",
                                "--entries", "32768"}),
                        "over the .btflut format's 4 GiB chunk limit");
}

TEST_CASE("export replaces its two files together or not at all") {
    TempDir dir;
    std::string manifest = writeSyntheticDataset(dir, kShots);
    REQUIRE(runCli({"bake", manifest, "--references", "1", "-o", dir / "m.btflut", "-q", "--grid", "3"}).status == 0);
    std::ofstream(dir / "atlas.json") << "precious";
    fs::create_directories(dir / "atlas.png");  // the atlas cannot be renamed into place
    CliRun r = runCli({"export", dir / "m.btflut", "-o", dir / "atlas.png"});
    requireOneLineError(r, "atlas.png: cannot write");
    CHECK(readText(dir / "atlas.json") == "precious");
    for (const auto& entry : fs::directory_iterator(dir.path()))
        CHECK(entry.path().string().find(".tmp.") == std::string::npos);
}

TEST_CASE("synth --force replaces only what synth wrote") {
    TempDir dir;
    const std::vector<std::string> synth{"synth", "--size", "16", "--correlation-length", "4", "-q"};
    auto with = [&](std::vector<std::string> extra) {
        std::vector<std::string> args = synth;
        args.insert(args.end(), extra.begin(), extra.end());
        return runCli(args);
    };
    REQUIRE(with({"-o", dir / "new/folders/out", "--geometry", "rti-1"}).status == 0);  // parents are made
    REQUIRE(with({"-o", dir / "out", "--geometry", "rti-3"}).status == 0);
    std::ofstream(dir / "out/notes.txt") << "mine";
    requireOneLineError(with({"-o", dir / "out", "--geometry", "rti-3"}), "exists and is not empty");
    REQUIRE(with({"-o", dir / "out", "--force", "--geometry", "rti-2"}).status == 0);
    CHECK(readText(dir / "out/notes.txt") == "mine");
    CHECK(openDataset(dir / "out")->images.size() == 2);
    std::size_t pngs = 0;
    for (const auto& entry : fs::directory_iterator(dir / "out")) pngs += entry.path().extension() == ".png";
    CHECK(pngs == 3);  // two images and the mask: the third image of the first run is gone

    fs::create_directories(dir / "mine");
    std::ofstream(dir / "mine/thesis.tex") << "years of work";
    requireOneLineError(with({"-o", dir / "mine", "--force"}),
                        "--force replaces only a folder written by btflut synth");
    CHECK(readText(dir / "mine/thesis.tex") == "years of work");
}

TEST_CASE("the paper's geometry (curet-c2: light and view move together) bakes a bank that follows the light") {
    TempDir dir;
    REQUIRE(
        runCli({"synth", "--preset", "plastic", "--size", "48", "--correlation-length", "6", "-q", "-o", dir / "c2"})
            .status == 0);
    CliRun bake = runCli({"bake", dir / "c2", "-o", dir / "c2.btflut"});
    REQUIRE(bake.status == 0);
    CHECK(bake.out.find("domain isotropic") != std::string::npos);
    auto bank = loadBank(dir / "c2.btflut");
    REQUIRE(bank.ok());
    CHECK(bank->domain == BankDomain::Isotropic);
    CHECK(bankFormatVersion(*bank) == 2);

    // Each measured light/view pair gives its own histogram back.
    auto dataset = openDataset(dir / "c2");
    REQUIRE(dataset.ok());
    for (const DatasetImage& im : dataset->images) {
        const BankLookup lut = bank->lookup(im.light, im.view);
        CHECK(lut.provenance == Provenance::Measured);
        const Image relit = applyLuts(bank->reference, bank->colour, lut.values, bank->entries, bank->targetCode());
        const Image measured = *loadImage(im.path);
        const Mask all = fullMask(relit.width, relit.height);
        const auto a = binHistogram(countGreyLevels(relit, all), 64),
                   b = binHistogram(countGreyLevels(measured, all), 64);
        double l1 = 0;
        for (std::size_t k = 0; k < a.size(); ++k) l1 += std::abs(a[k] - b[k]);
        INFO(im.name);
        CHECK(l1 < 0.1);
    }
    // Different lights at one view give different images (the bug: byte-identical).
    REQUIRE(runCli({"relight", dir / "c2.btflut", "--light", "10,0", "-o", dir / "a.png", "-q"}).status == 0);
    REQUIRE(runCli({"relight", dir / "c2.btflut", "--light", "70,180", "-o", dir / "b.png", "-q"}).status == 0);
    CHECK(std::abs(meanOf(*loadImage(dir / "a.png")) - meanOf(*loadImage(dir / "b.png"))) > 0.02);

    requireOneLineError(
        runCli({"bake", dir / "c2", "--domain", "layers", "-o", dir / "l.btflut"}),
        "each view direction has one light direction, so a bank over view layers cannot follow the light");
    CHECK_FALSE(fs::exists(dir / "l.btflut"));
}

TEST_CASE("a dataset that cannot vary with the light is refused; layered banks stay format version 1") {
    TempDir dir;
    std::string one = writeSyntheticDataset(dir, {{0, 0, 0, 0, 0, 1}});
    requireOneLineError(runCli({"bake", one, "-o", dir / "one.btflut"}),
                        "no bank baked from them can follow the light");
    CHECK_FALSE(fs::exists(dir / "one.btflut"));

    TempDir other;
    std::string manifest = writeSyntheticDataset(other, kShots);
    REQUIRE(runCli({"bake", manifest, "--references", "1", "-o", other / "m.btflut", "-q"}).status == 0);
    const std::string bytes = readText(other / "m.btflut");
    CHECK(bytes.substr(8, 4) == std::string("\x01\x00\x00\x00", 4));
}

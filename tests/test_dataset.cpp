#include <doctest/doctest.h>

#include <cmath>
#include <fstream>

#include "core/data/dataset.h"
#include "helpers.h"

using namespace btflut;
using namespace btflut::test;

TEST_CASE(".lp files: paths with spaces, blank lines, CRLF") {
    auto ds = parseLpFile("3\r\nimg 1.png 0 0 1\r\n\r\nsub/img2.jpg 0.6 0 0.8\nc.png -0.6 0 0.8\n", "cap.lp", "/data");
    REQUIRE(ds.ok());
    REQUIRE(ds->images.size() == 3);
    CHECK(ds->images[0].path == "/data/img 1.png");
    CHECK(ds->images[0].name == "img 1");
    CHECK(ds->images[1].path == "/data/sub/img2.jpg");
    CHECK(ds->images[1].light.thetaDegrees() == doctest::Approx(36.8699));
    CHECK(ds->images[2].light.phiDegrees() == doctest::Approx(180));
    CHECK(ds->fixedView());
}

TEST_CASE(".lp files: malformed lines are refused with file and line") {
    struct Case {
        const char* text;
        const char* needle;
    } cases[] = {
        {"", "cap.lp: empty file"},
        {"x\na.png 0 0 1\n", "cap.lp:1: expected a positive image count"},
        {"0\n", "cap.lp:1: expected a positive image count"},
        {"2\na.png 0 0 1\n", "declares 2 images but lists 1"},
        {"1\na.png 0 0 1\nb.png 0 0 1\n", "cap.lp:3: more image lines"},
        {"1\na.png 0 1\n", "cap.lp:2: expected 'path x y z'"},
        {"1\na.png 0 zero 1\n", "cap.lp:2: 'zero' is not a number"},
        {"1\na.png nan 0 1\n", "cap.lp:2: direction (nan, 0, 1) is not a finite vector"},
        {"1\na.png 0 0 2\n", "cap.lp:2: direction (0, 0, 2) is not a unit vector"},
        {"1\na.png 1 0 0\n", "cap.lp:2: direction (1, 0, 0) is at or below the horizon"},
        {"1\na.png 0 0.6 -0.8\n", "below the horizon"},
        {"1\n0 0 1\n", "cap.lp:2: expected 'path x y z'"},
    };
    for (const Case& c : cases) {
        INFO(c.text);
        auto r = parseLpFile(c.text, "cap.lp", ".");
        REQUIRE_FALSE(r.ok());
        CHECK(r.error().find(c.needle) != std::string::npos);
    }
}

TEST_CASE(".lp files as RTIBuilder writes them: Windows paths found beside the file, rounded vectors normalised") {
    TempDir dir;
    const Image grey = randomGreyImage(8, 8, 3);
    for (const char* name : {"image01.jpg", "image02.png"}) REQUIRE(savePng(grey, dir / name).ok());
    // Absolute Windows paths from another machine, CRLF, and a vector 1.0021 long.
    std::ofstream(dir / "win.lp") << "2\r\nC:\\Users\\me\\capture\\jpeg-exports\\image01.jpg 0 0 1\r\n"
                                     "D:\\rti\\image02.png 0.21 -0.24 0.95\r\n";
    Result<Dataset> ds = openDataset(dir / "win.lp");
    REQUIRE_MESSAGE(ds.ok(), ds.error());
    CHECK(ds->images[0].path == dir / "image01.jpg");
    CHECK(ds->images[0].name == "image01");
    CHECK(ds->images[1].path == dir / "image02.png");
    const Vec3 l = toVector(ds->images[1].light);
    CHECK(std::sqrt(l.x * l.x + l.y * l.y + l.z * l.z) == doctest::Approx(1.0));
    REQUIRE(ds->notes.size() == 2);
    CHECK(ds->notes[0].find("1 light vector(s) up to 2% from unit length") != std::string::npos);
    CHECK(ds->notes[1].find("2 image path(s) not found as written") != std::string::npos);
    // An image found nowhere: the error names its line.
    std::ofstream(dir / "missing.lp") << "2\nimage01.jpg 0 0 1\nC:\\shots\\gone.jpg 0 0 1\n";
    Result<Dataset> missing = openDataset(dir / "missing.lp");
    REQUIRE_FALSE(missing.ok());
    CHECK(missing.error().find("missing.lp:3: image ") != std::string::npos);
    CHECK(missing.error().find("nor gone.jpg beside the .lp file") != std::string::npos);
    // Beyond 2% from unit length: refused as before.
    Result<Dataset> far = parseLpFile("1\na.png 0 0 1.03\n", "cap.lp", ".");
    REQUIRE_FALSE(far.ok());
    CHECK(far.error().find("cap.lp:2: direction (0, 0, 1.03) is not a unit vector") != std::string::npos);
    // Through the command line: the notes said once on stderr, the bake done.
    const CliRun run = runCli({"hist", dir / "win.lp", "-o", dir / "h.csv"});
    CHECK(run.status == 0);
    CHECK(run.err.find("note: " + (dir / "win.lp") + ": 2 image path(s)") != std::string::npos);
}

TEST_CASE("lights.txt: count line then one vector per image") {
    auto l = parseLightsTxt("2\n0 0 1\n0.6 0 0.8\n", "lights.txt");
    REQUIRE(l.ok());
    CHECK(l->size() == 2);
    CHECK(parseLightsTxt("2\n0 0 1\n", "lights.txt").error() == "lights.txt: declares 2 lights but lists 1");
    CHECK(parseLightsTxt("1\n0 0 1 4\n", "lights.txt").error().find("lights.txt:2: expected 'x y z'") == 0);
    CHECK(parseLightsTxt("1\n0 0 0.5\n", "lights.txt").error().find("not a unit vector") != std::string::npos);
    std::size_t normalised = 0;
    CHECK(parseLightsTxt("2\n0 0 1.01\n0.6 0 0.8\n", "lights.txt", &normalised).ok());
    CHECK(normalised == 1);
}

TEST_CASE("Bonn UBO2003 names give light and view") {
    auto im = parseBonnName("tl015 pl030 tv060 pv345.jpg", "/btf");
    REQUIRE(im.ok());
    CHECK(im->light.thetaDegrees() == doctest::Approx(15));
    CHECK(im->light.phiDegrees() == doctest::Approx(30));
    CHECK(im->view.thetaDegrees() == doctest::Approx(60));
    CHECK(im->view.phiDegrees() == doctest::Approx(345));
    CHECK(parseBonnName("tl000_pl000_tv075_pv000.png", "/btf").ok());
    CHECK_FALSE(parseBonnName("tl015 pl030 tv060.jpg", "/btf").ok());
    CHECK_FALSE(parseBonnName("tl090 pl030 tv060 pv000.jpg", "/btf").ok());  // horizon
    CHECK_FALSE(parseBonnName("rock.1.jpg", "/btf").ok());
}

TEST_CASE("manifests: directions in degrees, optional view and mask, errors named") {
    auto ds = parseManifest(
        R"({"btflut_dataset": 1, "mask": "m.png", "images": [
            {"file": "a.png", "light": {"theta": 30, "phi": 10}},
            {"file": "b.png", "name": "bee", "light": {"theta": 0, "phi": 0}, "view": {"theta": 20, "phi": 90}}]})",
        "set.json", "/d");
    REQUIRE(ds.ok());
    CHECK(ds->maskPath == "/d/m.png");
    CHECK(ds->images[1].name == "bee");
    CHECK(ds->images[1].view.thetaDegrees() == doctest::Approx(20));
    CHECK_FALSE(ds->fixedView());
    struct Case {
        const char* text;
        const char* needle;
    } cases[] = {
        {"{", "set.json: not valid JSON"},
        {"{}", "no \"images\" array"},
        {R"({"images": []})", "lists no images"},
        {R"({"images": [{"light": {"theta": 1, "phi": 2}}]})", "images[0]: expected an object with a \"file\""},
        {R"({"images": [{"file": "a.png"}]})", "images[0]: no \"light\""},
        {R"({"images": [{"file": "a.png", "light": {"theta": 95, "phi": 0}}]})", "images[0].light: theta 95"},
        {R"({"images": [{"file": "a.png", "light": [1, 2]}]})", "images[0].light: expected"},
        {R"({"btflut_dataset": 2, "images": [{"file": "a.png", "light": {"theta": 1, "phi": 2}}]})",
         "unsupported manifest version"},
    };
    for (const Case& c : cases) {
        INFO(c.text);
        auto r = parseManifest(c.text, "set.json", ".");
        REQUIRE_FALSE(r.ok());
        CHECK(r.error().find(c.needle) != std::string::npos);
    }
}

TEST_CASE("openDataset recognises each form from one path") {
    TempDir dir;
    // A photometric-stereo folder.
    fs::create_directories(dir.path() / "psm");
    std::ofstream(dir / "psm/lights.txt") << "2\n0 0 1\n0.6 0 0.8\n";
    for (const char* f : {"psm/obj.0.png", "psm/obj.1.png", "psm/obj.mask.png"})
        REQUIRE(savePng(randomGreyImage(4, 4, 1), dir / f).ok());
    auto psm = openDataset(dir / "psm");
    REQUIRE(psm.ok());
    CHECK(psm->format == "psm");
    CHECK(psm->images.size() == 2);
    CHECK(psm->maskPath.find("obj.mask.png") != std::string::npos);
    CHECK(psm->images[1].light.thetaDegrees() == doctest::Approx(36.8699));

    std::ofstream(dir / "psm/lights.txt") << "3\n0 0 1\n0.6 0 0.8\n0 0.6 0.8\n";
    auto missing = openDataset(dir / "psm");
    REQUIRE_FALSE(missing.ok());
    CHECK(missing.error().find("obj.2.* is missing") != std::string::npos);

    // An RTI folder with one .lp file, and the .lp file itself.
    fs::create_directories(dir.path() / "rti");
    std::ofstream(dir / "rti/cap.lp") << "1\nx.png 0 0 1\n";
    REQUIRE(savePng(randomGreyImage(4, 4, 1), dir / "rti/x.png").ok());
    CHECK(openDataset(dir / "rti")->format == "rti");
    CHECK(openDataset(dir / "rti/cap.lp")->format == "rti");

    // A Bonn folder.
    fs::create_directories(dir.path() / "bonn");
    for (const char* f : {"bonn/tl000 pl000 tv000 pv000.png", "bonn/tl015 pl090 tv030 pv000.png"})
        REQUIRE(savePng(randomGreyImage(4, 4, 1), dir / f).ok());
    auto bonn = openDataset(dir / "bonn");
    REQUIRE(bonn.ok());
    CHECK(bonn->format == "bonn");
    CHECK(bonn->images.size() == 2);

    fs::create_directories(dir.path() / "empty");
    CHECK(openDataset(dir / "empty").error().find("not a dataset") != std::string::npos);
    CHECK(openDataset(dir / "nowhere").error().find("no such file or folder") != std::string::npos);
}

#include <doctest/doctest.h>

#include "core/bake/bake.h"
#include "core/bank/bank_file.h"
#include "core/bank/lut_bank.h"
#include "core/inverse/model_fill.h"
#include "core/physics/geometry.h"
#include "core/relight/relighter.h"
#include "helpers.h"

using namespace btflut;
using namespace btflut::test;

namespace {
const std::vector<SyntheticShot> kShots{{0, 0, 0, 0, 0, 1},      {30, 0, 0, 0, 40, 1},  {30, 120, 0, 0, 0, 2},
                                        {30, 240, 0, 0, 100, 1}, {55, 60, 0, 0, 20, 2}, {55, 300, 0, 0, 150, 1}};

Dataset openSynthetic(const TempDir& dir, const std::vector<SyntheticShot>& shots = kShots) {
    auto ds = openDataset(writeSyntheticDataset(dir, shots));
    REQUIRE(ds.ok());
    return *ds;
}
}  // namespace

TEST_CASE("a bank reproduces every measured direction exactly") {
    TempDir dir;
    Dataset ds = openSynthetic(dir);
    auto bank = bakeBank(ds, {});
    REQUIRE(bank.ok());
    CHECK(bank->referenceName == "shot0");  // frontal light
    CHECK(bank->entries == 256);
    REQUIRE(bank->layers.size() == 1);
    CHECK(bank->layers[0].nodes.size() == kShots.size());
    for (const SyntheticShot& s : kShots) {
        BankLookup lut = bank->lookup(Direction::fromDegrees(s.thetaI, s.phiI));
        CHECK(lut.provenance == Provenance::Measured);
        for (int code = 0; code < 100; ++code)
            REQUIRE(lut.values[static_cast<std::size_t>(code)] * 255.f ==
                    doctest::Approx(s.offset + s.slope * code).epsilon(1e-5));
    }
}

TEST_CASE("between two nodes the LUT is their quantile blend, monotonic, exact at the nodes") {
    TempDir dir;
    Dataset ds = openSynthetic(dir, {{20, 0, 0, 0, 0, 1}, {40, 0, 0, 0, 100, 2}});
    auto bank = bakeBank(ds, {});
    REQUIRE(bank.ok());
    const Direction a = Direction::fromDegrees(20, 0), b = Direction::fromDegrees(40, 0);
    auto la = bank->lookup(a), lb = bank->lookup(b);
    for (double t : {0.0, 0.25, 0.5, 0.9, 1.0}) {
        DiskPoint pa = toDisk(a), pb = toDisk(b);
        Direction mid = fromDisk({pa.x + t * (pb.x - pa.x), pa.y + t * (pb.y - pa.y)});
        BankLookup lut = bank->lookup(mid);
        REQUIRE(isValidLut(lut.values.data(), lut.values.size()));
        CHECK(lut.provenance == (t == 0.0 || t == 1.0 ? Provenance::Measured : Provenance::Interpolated));
        for (std::size_t k = 0; k < lut.values.size(); ++k)
            REQUIRE(lut.values[k] == doctest::Approx((1 - t) * la.values[k] + t * lb.values[k]).epsilon(1e-6));
    }
    CHECK(bank->lookup(Direction::fromDegrees(30, 90)).provenance == Provenance::Clamped);
}

TEST_CASE("grid nodes carry their provenance and the blended LUT at 16 bits") {
    TempDir dir;
    Dataset ds = openSynthetic(dir);
    auto bank = bakeBank(ds, {.gridSize = 9});
    REQUIRE(bank.ok());
    const ViewLayer& layer = bank->layers[0];
    const std::size_t centre = 4 * 9 + 4;  // the pole, where shot0 was measured
    CHECK(layer.gridProvenance[centre] == Provenance::Measured);
    CHECK(layer.gridProvenance[0] == Provenance::Clamped);  // a corner: beyond the horizon
    for (std::size_t k = 0; k < 256; ++k)
        REQUIRE(std::abs(layer.gridLuts[centre * 256 + k] / 65535.0 - layer.nodeLuts[k]) <= 0.5 / 65535 + 1e-9);
    for (int j = 0; j < 9; ++j)
        for (int i = 0; i < 9; ++i) {
            DiskPoint p = bank->gridPoint(i, j);
            if (p.x * p.x + p.y * p.y > 1) continue;
            BankLookup lut = bank->lookup(fromDisk(p));
            const std::size_t cell = static_cast<std::size_t>(j) * 9 + i;
            CHECK(lut.provenance == layer.gridProvenance[cell]);
            for (std::size_t k = 0; k < 256; k += 17)
                REQUIRE(std::abs(layer.gridLuts[cell * 256 + k] / 65535.0 - lut.values[k]) < 1e-4);
        }
}

TEST_CASE("view layers: one per view direction, blended between views") {
    TempDir dir;
    Dataset ds =
        openSynthetic(dir, {{10, 0, 0, 0, 0, 1}, {30, 0, 0, 0, 20, 1}, {10, 0, 40, 0, 50, 1}, {30, 0, 40, 0, 80, 1}});
    auto bank = bakeBank(ds, {});
    REQUIRE(bank.ok());
    REQUIRE(bank->layers.size() == 2);
    BankLookup v0 = bank->lookup(Direction::fromDegrees(10, 0), Direction::fromDegrees(0, 0));
    BankLookup v1 = bank->lookup(Direction::fromDegrees(10, 0), Direction::fromDegrees(40, 0));
    CHECK(v0.values[10] * 255 == doctest::Approx(10));
    CHECK(v1.values[10] * 255 == doctest::Approx(60));
    BankLookup mid =
        bank->lookup(Direction::fromDegrees(10, 0), fromDisk({toDisk(Direction::fromDegrees(40, 0)).x / 2, 0}));
    CHECK(mid.provenance == Provenance::Interpolated);
    CHECK(mid.values[10] * 255 == doctest::Approx(35));
}

TEST_CASE("results do not depend on the thread count") {
    TempDir dir;
    Dataset ds = openSynthetic(dir);
    auto one = bakeBank(ds, {.threads = 1});
    auto two = bakeBank(ds, {.threads = 2});
    REQUIRE(one.ok());
    REQUIRE(two.ok());
    CHECK(encodeBank(*one) == encodeBank(*two));
}

TEST_CASE("bad datasets are refused with the file and the problem") {
    TempDir dir;
    Dataset ds = openSynthetic(dir);

    SUBCASE("an image of another size") {
        REQUIRE(savePng(Image(10, 10, 1), ds.images[3].path).ok());
        auto r = bakeBank(ds, {});
        REQUIRE_FALSE(r.ok());
        CHECK(r.error().find("shot3.png: image is 10x10 but") != std::string::npos);
    }
    SUBCASE("a constant reference") {
        Image flat(40, 30, 1);
        std::fill(flat.samples.begin(), flat.samples.end(), 0.5f);
        REQUIRE(savePng(flat, ds.images[0].path).ok());
        auto r = bakeBank(ds, BakeOptions{.referenceName = "shot0"});
        REQUIRE_FALSE(r.ok());
        CHECK(r.error().find("shot0.png: reference image is constant") != std::string::npos);
        // The default passes over it (one grey level holds the whole sample) to the next
        // image nearest frontal; where every image is constant, it is refused all the same.
        auto chosen = bakeBank(ds, {});
        REQUIRE(chosen.ok());
        CHECK(chosen->referenceName != "shot0");
        for (const DatasetImage& im : ds.images) REQUIRE(savePng(flat, im.path).ok());
        auto none = bakeBank(ds, {});
        REQUIRE_FALSE(none.ok());
        CHECK(none.error().find("reference image is constant") != std::string::npos);
    }
    SUBCASE("an empty mask, a mask of another size") {
        REQUIRE(savePng(Image(40, 30, 1), dir / "empty.png").ok());
        ds.maskPath = dir / "empty.png";
        auto empty = bakeBank(ds, {});
        REQUIRE_FALSE(empty.ok());
        CHECK(empty.error().find("empty.png: mask has no sample pixels") != std::string::npos);
        REQUIRE(savePng(Image(41, 30, 1), dir / "wide.png").ok());
        ds.maskPath = dir / "wide.png";
        auto wide = bakeBank(ds, {});
        REQUIRE_FALSE(wide.ok());
        CHECK(wide.error().find("wide.png: mask is 41x30") != std::string::npos);
    }
    SUBCASE("a corrupt image") {
        std::ofstream(ds.images[2].path, std::ios::binary) << "\x89PNG\r\n\x1a\n garbage";
        auto r = bakeBank(ds, {});
        REQUIRE_FALSE(r.ok());
        CHECK(r.error().find("shot2.png") != std::string::npos);
    }
    SUBCASE("an unknown reference name") {
        auto r = bakeBank(ds, {.referenceName = "nope"});
        REQUIRE_FALSE(r.ok());
        CHECK(r.error().find("no image named 'nope'") != std::string::npos);
    }
}

TEST_CASE("grey-mode relighting sets each pixel's grey to LUT(grey) and keeps its colour") {
    Image im(3, 1, 3);
    const float px[3][3] = {{0.2f, 0.1f, 0.3f}, {0.8f, 0.4f, 0.6f}, {0, 0, 0}};
    for (int i = 0; i < 3; ++i)
        for (int c = 0; c < 3; ++c) im.samples[i * 3 + c] = px[i][c];
    std::vector<float> brighten(256);
    for (std::size_t k = 0; k < 256; ++k) brighten[k] = std::min(1.f, static_cast<float>(k) / 255.f * 1.6f + 0.05f);
    Image out = applyLuts(im, ColourMode::Grey, brighten, 256, /*targetCode=*/0.f);
    for (std::size_t i = 0; i < 3; ++i) {
        float want = Lut::applyLut(brighten.data(), 256, im.grey(i));
        CHECK(out.grey(i) == doctest::Approx(want).epsilon(1e-5));
        for (int c = 0; c < 3; ++c) CHECK(out.samples[i * 3 + c] <= 1.f);
    }
    // Unclipped: colour ratios kept. Clipped (pixel 1): desaturated towards grey.
    CHECK(out.samples[0] / out.samples[1] == doctest::Approx(2.0));
    CHECK(out.samples[3] == doctest::Approx(1.0));
    CHECK(out.samples[8] == doctest::Approx(0.05));  // black takes LUT(0), as grey
}

TEST_CASE("rgb mode bakes one exact LUT per channel") {
    TempDir dir;
    // Three lights; each channel of each image is its own injective code map of the
    // reference's channel, so every channel LUT is known exactly.
    nlohmann::json manifest{{"images", nlohmann::json::array()}};
    const int offsets[3][3] = {{0, 0, 0}, {10, 50, 90}, {100, 20, 5}};
    for (int s = 0; s < 3; ++s) {
        Image im(20, 10, 3);
        for (int y = 0; y < 10; ++y)
            for (int x = 0; x < 20; ++x)
                for (int c = 0; c < 3; ++c)
                    im.at(x, y, c) = static_cast<float>(offsets[s][c] + (x * 3 + y * 7 + c * 11) % 100) / 255.f;
        std::string name = "c" + std::to_string(s) + ".png";
        REQUIRE(savePng(im, dir / name).ok());
        manifest["images"].push_back({{"file", name}, {"light", {{"theta", 25.0 * s}, {"phi", 40.0 * s}}}});
    }
    std::ofstream(dir / "set.json") << manifest.dump();
    auto ds = openDataset(dir / "set.json");
    REQUIRE(ds.ok());
    auto bank = bakeBank(*ds, {.colour = ColourMode::Rgb});
    REQUIRE(bank.ok());
    CHECK(bank->lutLength() == 3 * 256);
    BankLookup lut = bank->lookup(Direction::fromDegrees(50, 80));
    for (int c = 0; c < 3; ++c)
        for (int code = 0; code < 100; ++code)
            REQUIRE(lut.values[static_cast<std::size_t>(c * 256 + code)] * 255 ==
                    doctest::Approx(offsets[2][c] + code).epsilon(1e-5));
    Image relit = relight(*bank, Direction::fromDegrees(50, 80), {}, /*dither=*/false);
    auto measured = loadImage(dir / "c2.png");
    for (std::size_t i = 0; i < relit.samples.size(); ++i)
        REQUIRE(std::lround(relit.samples[i] * 255) == std::lround(measured->samples[i] * 255));
    // Grey images cannot be baked in rgb mode.
    Dataset grey = openSynthetic(dir);
    auto refused = bakeBank(grey, {.colour = ColourMode::Rgb});
    REQUIRE_FALSE(refused.ok());
    CHECK(refused.error().find("needs colour images") != std::string::npos);
}

TEST_CASE("lookups say how the light and the view were obtained; coverage is the hull's solid angle") {
    TempDir dir;
    Dataset ds = openSynthetic(dir);
    auto bank = bakeBank(ds, {});
    REQUIRE(bank.ok());
    // One frontal view layer: any other view is clamped to it, while the light is measured.
    const BankLookup oblique = bank->lookup(Direction::fromDegrees(30, 0), Direction::fromDegrees(40, 0));
    CHECK(oblique.lightProvenance == Provenance::Measured);
    CHECK(oblique.viewProvenance == Provenance::Clamped);
    CHECK(oblique.provenance == Provenance::Clamped);
    const BankLookup between = bank->lookup(Direction::fromDegrees(20, 30));
    CHECK(between.lightProvenance == Provenance::Interpolated);
    CHECK(between.viewProvenance == Provenance::Measured);
    CHECK(bank->lookup(Direction::fromDegrees(80, 180)).lightProvenance == Provenance::Clamped);
    CHECK(bank->nearestNode(Direction::fromDegrees(50, 65)).node == 4);  // (55, 60)

    // The hull of the six lights reaches theta 55 at most: within the cap of theta <= 55,
    // which holds 1 - cos 55 = 43% of the hemisphere.
    const double coverage = bank->lightCoverage(0);
    CHECK(coverage > 0.05);
    CHECK(coverage < 1 - std::cos(55 * M_PI / 180) + 0.01);
    TempDir ringDir;
    std::vector<SyntheticShot> ring{{0, 0, 0, 0, 0, 1}};
    for (int k = 0; k < 24; ++k) ring.push_back({89, 15.0 * k, 0, 0, 1 + k % 3, 1});
    auto full = bakeBank(openSynthetic(ringDir, ring), {});
    REQUIRE(full.ok());
    CHECK(full->lightCoverage(0) > 0.95);  // a 24-gon at theta 89 covers 97% of the disk
}

TEST_CASE("layers domain: a light beyond one view's measured lights takes the nearest view that measured it") {
    TempDir dir;
    // View A measured lights up to 30 degrees; view B also at 70 degrees (a brighter offset).
    auto ds = openDataset(writeSyntheticDataset(dir, {{0, 0, 0, 0, 0, 1},
                                                      {30, 0, 0, 0, 10, 1},
                                                      {30, 120, 0, 0, 10, 1},
                                                      {30, 240, 0, 0, 10, 1},
                                                      {0, 0, 40, 0, 0, 1},
                                                      {70, 0, 40, 0, 60, 1},
                                                      {70, 120, 40, 0, 60, 1},
                                                      {70, 240, 40, 0, 60, 1}}));
    REQUIRE(ds.ok());
    auto bank = bakeBank(*ds, {.gridSize = 9, .domain = BankDomain::Layers});
    REQUIRE(bank.ok());
    const Direction grazing = Direction::fromDegrees(70, 0), viewA{}, viewB = Direction::fromDegrees(40, 0);
    const BankLookup a = bank->lookup(grazing, viewA), b = bank->lookup(grazing, viewB);
    CHECK(a.lightProvenance == Provenance::Interpolated);  // from view B's measurements, not clamped
    REQUIRE(a.values.size() == b.values.size());
    for (std::size_t k = 0; k < a.values.size(); ++k) CHECK(a.values[k] == doctest::Approx(b.values[k]).epsilon(1e-5));
    // Measurements come before the model: filled from it, the bank still takes view B's.
    LutBank filled = *bank;
    REQUIRE(fillFromModel(filled, {}, "{}").ok());
    REQUIRE(filled.layers[0].nodes.size() > filled.layers[0].measuredNodes);  // view A has modelled lights
    const BankLookup fromB = filled.lookup(grazing, viewA);
    CHECK(fromB.lightProvenance == Provenance::Interpolated);
    for (std::size_t k = 0; k < a.values.size(); ++k)
        CHECK(fromB.values[k] == doctest::Approx(b.values[k]).epsilon(1e-5));
    // Within view A's lights nothing changes: its own measurement.
    const BankLookup own = bank->lookup(Direction::fromDegrees(30, 0), viewA);
    CHECK(own.provenance == Provenance::Measured);
    // A bank of one view clamps as before: nothing else measured that light.
    auto single =
        bakeBank(*openDataset(writeSyntheticDataset(
                     dir, {{0, 0, 0, 0, 0, 1}, {30, 0, 0, 0, 10, 1}, {30, 120, 0, 0, 10, 1}, {30, 240, 0, 0, 10, 1}})),
                 {.gridSize = 9});
    REQUIRE(single.ok());
    CHECK(single->lookup(grazing).lightProvenance == Provenance::Clamped);
}

TEST_CASE("isotropic domain: a pair beyond the hull takes the nearest measured pair, not a face bridging far pairs") {
    // CUReT's light and view move together: the pairs lie on two arms of a path, and the
    // hull's faces join the arms' ends. Without c2-1 (the end of one arm), its pair lies
    // beyond the face joining c2-2 to c2-11, a grazing pair measured far away.
    TempDir dir;
    std::vector<SyntheticShot> shots;
    const std::vector<Geometry> path = curetC2();
    for (std::size_t k = 1; k < path.size(); ++k)
        shots.push_back({path[k].light.theta * 180 / M_PI, path[k].light.phi * 180 / M_PI,
                         path[k].view.theta * 180 / M_PI, path[k].view.phi * 180 / M_PI, static_cast<int>(10 * k), 1});
    auto ds = openDataset(writeSyntheticDataset(dir, shots));
    REQUIRE(ds.ok());
    auto bank = bakeBank(*ds, {.referenceName = "shot6", .domain = BankDomain::Isotropic});  // c2-8: frontal camera
    REQUIRE(bank.ok());
    const BankLookup held = bank->lookup(path[0].light, path[0].view);
    const BankLookup nearest = bank->lookup(path[1].light, path[1].view);  // c2-2, measured
    CHECK(held.provenance == Provenance::Clamped);
    CHECK(nearest.provenance == Provenance::Measured);
    for (std::size_t k = 0; k < held.values.size(); ++k)
        CHECK(held.values[k] == doctest::Approx(nearest.values[k]).epsilon(1e-5));
    // Between the hull and one grid step out, the clamped blend gives way gradually: no jump.
    const Direction nearLight = Direction::fromDegrees(23, 0), nearView = Direction::fromDegrees(68, 0);
    const BankLookup close = bank->lookup(nearLight, nearView);
    double largest = 0;
    for (std::size_t k = 0; k < close.values.size(); ++k)
        largest = std::max(largest, static_cast<double>(std::abs(close.values[k] - nearest.values[k])));
    CHECK(largest < 0.02);
}

TEST_CASE("the default reference passes over a frontal image whose sample is mostly one grey level") {
    TempDir dir;
    Dataset ds = openSynthetic(dir);
    // shot0 (frontal light) more than half black: a LUT cannot spread that tie.
    Image tied = *loadImage(ds.images[0].path);
    for (std::size_t i = 0; i < tied.samples.size() * 6 / 10; ++i) tied.samples[i] = 0;
    REQUIRE(savePng(tied, ds.images[0].path).ok());
    auto bank = bakeBank(ds, {});
    REQUIRE(bank.ok());
    CHECK(bank->referenceName == "shot1");  // the next nearest to frontal light
    // A frontal image with a tie of a fifth is kept: frontal light shows the least shadow.
    TempDir other;
    Dataset fifth = openSynthetic(other);
    tied = *loadImage(fifth.images[0].path);
    for (std::size_t i = 0; i < tied.samples.size() * 2 / 10; ++i) tied.samples[i] = 0;
    REQUIRE(savePng(tied, fifth.images[0].path).ok());
    auto kept = bakeBank(fifth, {});
    REQUIRE(kept.ok());
    CHECK(kept->referenceName == "shot0");
}

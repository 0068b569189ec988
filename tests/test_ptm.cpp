#include <doctest/doctest.h>

#include <cmath>

#include "core/bake/bake.h"
#include "core/bank/bank_file.h"
#include "core/predict/model_predictor.h"
#include "core/predict/ptm.h"
#include "core/relight/relighter.h"
#include "helpers.h"

using namespace btflut;
using namespace btflut::test;

namespace {

const std::vector<Direction> kLights = {
    Direction::fromDegrees(0, 0),    Direction::fromDegrees(30, 0),   Direction::fromDegrees(30, 90),
    Direction::fromDegrees(45, 180), Direction::fromDegrees(45, 270), Direction::fromDegrees(60, 45),
    Direction::fromDegrees(60, 225), Direction::fromDegrees(20, 300), Direction::fromDegrees(70, 135)};

// A colour image that a PTM reproduces exactly: per texel an albedo and six coefficients.
Image polynomialImage(int w, int h, Direction light) {
    const std::vector<double> t = basisTerms(LightBasis::Ptm, 0, light);
    Image im(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const double a[kPtmTerms] = {-0.2 * std::sin(x * 0.3),  -0.25 + 0.1 * std::cos(y * 0.2),
                                         0.1 * std::sin(x + y),     0.2 * std::cos(x * 0.7),
                                         -0.15 * std::sin(y * 0.5), 0.6 + 0.05 * std::cos(x * y)};
            double luminance = 0;
            for (std::size_t k = 0; k < t.size(); ++k) luminance += a[k] * t[k];
            const double albedo[3] = {1.0, 0.8 + 0.1 * std::sin(x), 0.5 + 0.2 * std::cos(y)};
            for (int c = 0; c < 3; ++c)
                im.at(x, y, c) = static_cast<float>(std::clamp(albedo[c] * luminance, 0.0, 1.0));
        }
    return im;
}

float maxDifference(const Image& a, const Image& b) {
    float worst = 0;
    for (std::size_t i = 0; i < a.samples.size(); ++i) worst = std::max(worst, std::abs(a.samples[i] - b.samples[i]));
    return worst;
}

}  // namespace

TEST_CASE("a PTM fitted to images made by a PTM reproduces them to its byte quantisation") {
    PtmFitter fitter(16, 12);
    for (Direction l : kLights) fitter.add(polynomialImage(16, 12, l), l);
    Result<LightModel> ptm = fitter.finish("poly");
    REQUIRE(ptm.ok());
    for (Direction l : kLights) CHECK(maxDifference(ptm->render(l), polynomialImage(16, 12, l)) < 0.012f);
    // Also between the fitted lights.
    const Direction between = Direction::fromDegrees(40, 100);
    CHECK(maxDifference(ptm->render(between), polynomialImage(16, 12, between)) < 0.012f);

    // It is the light model of basis ptm: fitLightModel's fit of the same images (the same
    // least squares, held in double) agrees to a code, and the layout is the LRGB one.
    CHECK(ptm->basis == LightBasis::Ptm);
    CHECK(ptm->planes == kPtmTerms);
    CHECK(ptm->albedo.size() == ptm->texels() * 3);
    std::vector<Image> images;
    for (Direction l : kLights) images.push_back(polynomialImage(16, 12, l));
    std::vector<const Image*> pointers;
    for (const Image& image : images) pointers.push_back(&image);
    Result<LightModel> model = fitLightModel(pointers, kLights, Mask{}, {.basis = LightBasis::Ptm}, "poly");
    REQUIRE(model.ok());
    for (Direction l : {kLights[3], between}) CHECK(maxDifference(ptm->render(l), model->render(l)) < 1.5f / 255);
}

TEST_CASE("a PTM needs six light directions that determine its terms") {
    PtmFitter few(4, 4);
    for (std::size_t i = 0; i < 5; ++i) few.add(polynomialImage(4, 4, kLights[i]), kLights[i]);
    Result<LightModel> r = few.finish("five.lp");
    REQUIRE_FALSE(r.ok());
    CHECK(r.error().rfind("five.lp: a PTM needs at least six light directions", 0) == 0);

    PtmFitter ring(4, 4);  // eight lights on one cone: u^2 + v^2 is constant, so a0 + a1 and a5 mix
    for (int k = 0; k < 8; ++k) {
        const Direction l = Direction::fromDegrees(40, 45.0 * k);
        ring.add(polynomialImage(4, 4, l), l);
    }
    CHECK_FALSE(ring.finish("ring").ok());
}

TEST_CASE("bake --ptm stores the PTM in the bank; readers may skip it") {
    TempDir dir;
    std::vector<SyntheticShot> shots;
    for (Direction l : kLights) shots.push_back({l.thetaDegrees(), l.phiDegrees()});
    Result<Dataset> ds = openDataset(writeSyntheticDataset(dir, shots, 10, 8));
    REQUIRE(ds.ok());
    Result<LutBank> bank = bakeBank(*ds, {.gridSize = 3, .ptm = true});
    REQUIRE(bank.ok());
    REQUIRE_FALSE(bank->ptm.empty());
    CHECK(bank->ptm.width == 10);

    const Bytes bytes = encodeBank(*bank);
    Result<LutBank> back = decodeBank(bytes, "p.btflut");
    REQUIRE(back.ok());
    CHECK(back->ptm.coefficients == bank->ptm.coefficients);
    CHECK(back->ptm.albedo == bank->ptm.albedo);
    CHECK(back->ptm.scale == bank->ptm.scale);
    CHECK(encodeBank(*back) == bytes);
    Result<LutBank> withoutPtm = decodeBank(bytes, "p.btflut", {.ptm = false});
    REQUIRE(withoutPtm.ok());
    CHECK(withoutPtm->ptm.empty());
    CHECK(withoutPtm->ptmInFile);

    REQUIRE(writeFileAtomically(dir / "p.btflut", bytes).ok());
    Result<LightModel> alone = loadBankPtm(dir / "p.btflut");
    REQUIRE(alone.ok());
    CHECK(alone->coefficients == bank->ptm.coefficients);
    REQUIRE(saveBank(*withoutPtm, dir / "none.btflut").ok());
    Result<LightModel> none = loadBankPtm(dir / "none.btflut");
    REQUIRE_FALSE(none.ok());
    CHECK(none.error().find("holds no PTM (bake it with --ptm)") != std::string::npos);

    // The synthetic images are all alike (one code map), so the PTM is their constant image.
    Result<Image> first = loadImage(ds->images[1].path);
    REQUIRE(first.ok());
    const Image relit = bank->ptm.render(ds->images[1].light);
    double mean = 0;
    for (std::size_t i = 0; i < first->pixelCount(); ++i) mean += std::abs(relit.samples[i * 3] - first->samples[i]);
    CHECK(mean / static_cast<double>(first->pixelCount()) < 0.005);
}

TEST_CASE("a bank whose PTM was its predictor (an earlier file) reads as the light model it is") {
    // Format version 5, HEAD's predictor 1: the PTMC chunk predicts, without an LMDL chunk.
    const std::string path =
        std::string(BTFLUT_SOURCE_DIR) + "/tests/fuzz/regressions/bank/valid-ptm-predictor-r2.btflut";
    Result<LutBank> bank = loadBank(path);
    REQUIRE_MESSAGE(bank.ok(), bank.error());
    REQUIRE(bank->makesLuts());
    const auto* model = bank->predictorAs<ModelPredictor>();
    REQUIRE(model != nullptr);
    CHECK(model->model().basis == LightBasis::Ptm);
    CHECK(model->model().coefficients == bank->ptm.coefficients);
    CHECK(bank->predictorName() == "ptm");

    // Written back as any light model (LMDL beside the PTM), it relights the same.
    Result<LutBank> back = decodeBank(encodeBank(*bank), "again.btflut");
    REQUIRE_MESSAGE(back.ok(), back.error());
    const Direction light = Direction::fromDegrees(25, 40);
    const Relighter before(*bank), after(*back);
    CHECK(before.apply(before.frame(light), true).samples == after.apply(after.frame(light), true).samples);
    CHECK(encodeBank(*back) == encodeBank(*bank));
}

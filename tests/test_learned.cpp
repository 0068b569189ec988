// The learned predictor (core/predict/learned_model.h) and the networks it trains
// (core/learn/network.h): gradients against finite differences, the fit between the lights,
// its bank chunk, determinism and degenerate captures.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>

#include "cli/eval/neural_rti.h"
#include "core/bake/auto_bake.h"
#include "core/bake/bake.h"
#include "core/bank/bank_file.h"
#include "core/data/dataset.h"
#include "core/eval/metrics.h"
#include "core/learn/network.h"
#include "core/predict/learned_decoder.h"
#include "core/predict/learned_predictor.h"
#include "core/predict/learned_training.h"
#include "core/relight/engine_material.h"
#include "core/relight/relighter.h"
#include "helpers.h"

using namespace btflut;
using namespace btflut::test;

namespace {

// Every parameter's gradient (and the inputs') against central differences of `loss`, in
// double over float networks: relative to the gradient's scale, within 2%.
template <class Loss, class Parameter>
void checkGradient(const std::string& what, float analytic, Parameter& p, const Loss& loss, double& worst) {
    const float saved = p;
    const float h = 1e-2f * std::max(1.f, std::abs(saved));
    p = saved + h;
    const double up = loss();
    p = saved - h;
    const double down = loss();
    p = saved;
    const double numeric = (up - down) / (2.0 * h);
    const double error = std::abs(numeric - analytic) / std::max(1e-2, std::abs(numeric) + std::abs(analytic));
    INFO(what << ": analytic " << analytic << ", numeric " << numeric);
    CHECK(error < 0.02);
    worst = std::max(worst, error);
}

Matrix randomMatrix(Eigen::Index rows, Eigen::Index cols, Random& random) {
    Matrix m(rows, cols);
    for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = static_cast<float>(random.uniform() * 2 - 1);
    return m;
}

// The relief the learned model's tests bake: enough lights that it trains past its linear start.
const Relief kRelief{.size = 32};
std::vector<Direction> reliefLights() { return dome(24, 70); }

}  // namespace

TEST_CASE("dense kernels: the four products, stored or added, into a block; the ELU and its gradient") {
    Random random(7);
    auto draw = [&](Eigen::Index rows, Eigen::Index cols) {
        Matrix m(rows, cols);
        for (float& v : m.reshaped()) v = static_cast<float>(random.uniform() * 2 - 1);
        return m;
    };
    auto naive = [](const Matrix& a, const Matrix& b) {  // plain loops, in double
        Matrix out(a.rows(), b.cols());
        for (Eigen::Index i = 0; i < a.rows(); ++i)
            for (Eigen::Index j = 0; j < b.cols(); ++j) {
                double sum = 0;
                for (Eigen::Index k = 0; k < a.cols(); ++k) sum += static_cast<double>(a(i, k)) * b(k, j);
                out(i, j) = static_cast<float>(sum);
            }
        return out;
    };
    // Sizes on either side of Eigen's switch from coefficient products to its packed kernel.
    for (Eigen::Index n : {3, 37}) {
        const Matrix a = draw(n, 5), b = draw(5, n + 2), aT = a.transpose(), bT = b.transpose();
        const Matrix want = naive(a, b);
        for (auto [left, aForm, right, bForm] : {std::tuple{&a, dense::Plain, &b, dense::Plain},
                                                 {&aT, dense::Transposed, &b, dense::Plain},
                                                 {&a, dense::Plain, &bT, dense::Transposed},
                                                 {&aT, dense::Transposed, &bT, dense::Transposed}}) {
            Matrix out = Matrix::Constant(n + 4, n + 6, 9.f);  // the product in a block of a larger matrix
            auto block = out.block(1, 2, n, n + 2);
            dense::multiply(block, *left, aForm, *right, bForm);
            CHECK((out.block(1, 2, n, n + 2) - want).cwiseAbs().maxCoeff() < 1e-5f);
            dense::multiply(block, *left, aForm, *right, bForm, dense::Add);
            CHECK((out.block(1, 2, n, n + 2) - 2 * want).cwiseAbs().maxCoeff() < 1e-5f);
            out.block(1, 2, n, n + 2).setConstant(9.f);
            CHECK((out.array() == 9.f).all());  // nothing written outside the block
        }
    }
    Matrix a(1, 4);
    a << -2.f, -0.5f, 0.f, 1.5f;
    Matrix activated = a;
    dense::addToColumns(activated, Vector::Constant(1, 0.25f));
    dense::elu(activated);
    Matrix delta, back = Matrix::Constant(1, 4, 2.f);
    dense::eluBackward(delta, back, activated);
    for (Eigen::Index i = 0; i < 4; ++i) {
        const float x = a(0, i) + 0.25f;
        CHECK(activated(0, i) == doctest::Approx(x > 0 ? x : std::exp(x) - 1));
        CHECK(delta(0, i) == doctest::Approx(2 * (x > 0 ? 1 : std::exp(x))));
    }
}

TEST_CASE("network: the backward pass is the finite differences of the forward one") {
    Random random(3);
    const Network start = Network::random({5, 7, 6, 3}, random);
    Network net = start;
    Matrix input = randomMatrix(5, 4, random);
    const Matrix target = randomMatrix(3, 4, random);
    auto loss = [&] {
        NetworkPass pass;
        net.forward(input, pass);
        return 0.5 * static_cast<double>((pass.output() - target).squaredNorm());
    };
    NetworkPass pass;
    net.forward(input, pass);
    const NetworkGradient g = net.backward(pass, pass.output() - target, true);
    double worst = 0;
    for (std::size_t k = 0; k < net.layers(); ++k) {
        for (Eigen::Index i = 0; i < net.weights(k).size(); ++i)
            checkGradient("weight", g.weights[k].data()[i], net.weights(k).data()[i], loss, worst);
        for (Eigen::Index i = 0; i < net.bias(k).size(); ++i)
            checkGradient("bias", g.biases[k](i), net.bias(k)(i), loss, worst);
    }
    for (Eigen::Index i = 0; i < input.size(); ++i)
        checkGradient("input", g.input.data()[i], input.data()[i], loss, worst);
    MESSAGE("network gradients: worst relative error " << worst);
    // Parameters travel in a fixed order.
    CHECK(Network::fromParameters(start.sizes(), start.parameters()).parameters() == start.parameters());
    CHECK(start.parameters().size() == Network::parameterCount({5, 7, 6, 3}));
}

TEST_CASE("learned decoder: the light network's, the residual's and the codes' gradients") {
    Random random(5);
    const int N = 4, C = 3;
    LearnedDecoder d{Network::random({kLearnedLightFeatures, C * (N + 1)}, random),
                     Network::random({N + kLearnedLightFeatures, 6, C}, random)};
    Matrix codes = randomMatrix(N, 3, random);
    Matrix lights(kLearnedLightFeatures, 2);
    for (int l = 0; l < 2; ++l) {
        const std::vector<float> h = learnedLightFeatures(Direction::fromDegrees(20 + 30 * l, 40 + 100 * l));
        lights.col(l) = Eigen::Map<const Vector>(h.data(), kLearnedLightFeatures);
    }
    const Matrix target = randomMatrix(C, 6, random);
    auto loss = [&] {
        LearnedDecoder::Pass pass;
        d.forward(codes, lights, pass);
        return 0.5 * static_cast<double>((pass.output - target).squaredNorm());
    };
    LearnedDecoder::Pass pass;
    d.forward(codes, lights, pass);
    const LearnedDecoder::Gradient g = d.backward(pass, pass.output - target);
    double worst = 0;
    for (Eigen::Index i = 0; i < d.light.weights(0).size(); ++i)
        checkGradient("light weight", g.light.weights[0].data()[i], d.light.weights(0).data()[i], loss, worst);
    for (std::size_t k = 0; k < d.residual.layers(); ++k)
        for (Eigen::Index i = 0; i < d.residual.weights(k).size(); ++i)
            checkGradient("residual weight", g.residual.weights[k].data()[i], d.residual.weights(k).data()[i], loss,
                          worst);
    for (Eigen::Index i = 0; i < codes.size(); ++i)
        checkGradient("code", g.codes.data()[i], codes.data()[i], loss, worst);
    MESSAGE("decoder gradients: worst relative error " << worst);
}

TEST_CASE("quantised codes: 8 bits over the inside texels' range, nearest or truncated, others clamped") {
    // Two codes over four texels; texel 3 is outside the mask and beyond the range.
    const std::vector<float> codes{0.f, 10.f, 1.f, 10.f, 0.25f, 10.f, 7.f, -3.f};
    const std::vector<std::uint32_t> inside{0, 1, 2};
    const QuantisedCodes q = QuantisedCodes::quantise(codes, inside, 2);
    REQUIRE(q.count() == 2);
    CHECK(q.scale[0] == doctest::Approx(1.0 / 255));
    CHECK(q.bytes == std::vector<std::uint8_t>{0, 0, 255, 0, 64, 0, 255, 0});  // 63.75 the nearest; 7 clamps
    CHECK(q.scale[1] == 1.f);  // a constant code keeps scale 1 and decodes to its value
    CHECK(q.value(1, 1) == doctest::Approx(10));
    CHECK(q.value(2, 0) == doctest::Approx(64.0 / 255));
    const QuantisedCodes truncated = QuantisedCodes::quantise(codes, inside, 2, true);
    CHECK(truncated.bytes[4] == 63);  // NeuralRTI's: the byte below
    const Matrix values = codeValues(q, std::vector<std::uint32_t>{2, 0});
    CHECK(values(0, 0) == doctest::Approx(q.value(2, 0)));
    CHECK(values(1, 1) == doctest::Approx(10));
}

TEST_CASE("learned model: validation chooses the residual network's weight decay among the candidates") {
    TempDir dir;
    Result<Dataset> dataset = openDataset(writeRelief(dir, kRelief, reliefLights()));
    REQUIRE(dataset.ok());
    auto residualOf = [&](std::vector<float> decays) {
        BakeOptions options{.fit = learnedFit(LearnedOptions{.steps = 300, .weightDecays = std::move(decays)})};
        options.threads = 1;
        Result<LutBank> bank = bakeBank(*dataset, options);
        REQUIRE_MESSAGE(bank.ok(), bank.error());
        return bank->predictorAs<LearnedPredictor>()->model().decoder->residual.parameters();
    };
    const std::vector<float> strong = residualOf({0.1f}), weak = residualOf({0.01f});
    CHECK(strong != weak);  // the relief trains past its linear start, and the decay shapes it
    const std::vector<float> chosen = residualOf({0.1f, 0.01f});
    CHECK((chosen == strong || chosen == weak));  // one candidate's fit, whole
    for (const std::vector<float>& bad : {std::vector<float>{}, {-0.1f}, {1.f}, {NAN}}) {
        BakeOptions options{.fit = learnedFit(LearnedOptions{.steps = 10, .weightDecays = bad})};
        Result<LutBank> bank = bakeBank(*dataset, options);
        REQUIRE(!bank.ok());
        CHECK(bank.error().find("invalid learned model options") != std::string::npos);
    }
}

TEST_CASE("learned model: a relief between the measured lights, its bank and chunk, the same bytes every run") {
    TempDir dir;
    const Relief& relief = kRelief;
    const std::vector<Direction> lights = reliefLights();
    Result<Dataset> dataset = openDataset(writeRelief(dir, relief, lights));
    REQUIRE(dataset.ok());
    BakeOptions options{.colour = ColourMode::Rgb, .fit = learnedFit(LearnedOptions{.steps = 300})};
    options.threads = 1;
    Result<LutBank> bank = bakeBank(*dataset, options);
    REQUIRE_MESSAGE(bank.ok(), bank.error());
    const LearnedPredictor* learned = bank->predictorAs<LearnedPredictor>();
    REQUIRE(learned);
    const LearnedModel& m = learned->model();
    CHECK(bank->predictorName() == "neural9");
    CHECK(learned->bytesPerTexel() == 9);
    CHECK(m.channels == 3);
    CHECK(LearnedModel::parameterCount(m.decoderSizes()) + LearnedModel::parameterCount(m.lightSizes()) <= 4096);

    // Between the lights it predicts the relief better than the nearest measured image.
    double psnr = 0, nearest = 0;
    const Mask mask = fullMask(relief.size, relief.size);
    for (Direction l :
         {Direction::fromDegrees(25, 10), Direction::fromDegrees(45, 200), Direction::fromDegrees(60, 300)}) {
        const Image truth = reliefImage(relief, l);
        psnr += compareImages(m.render(l), truth, mask).psnr / 3;
        std::size_t n = 0;
        for (std::size_t i = 1; i < lights.size(); ++i)
            if (angleBetween(lights[i], l) < angleBetween(lights[n], l)) n = i;
        nearest += compareImages(reliefImage(relief, lights[n]), truth, mask).psnr / 3;
    }
    INFO("neural9 " << psnr << " dB, the nearest image " << nearest << " dB");
    CHECK(psnr > nearest + 3);
    CHECK(psnr > 30);

    // Relit and matched: finite, in range.
    const Image relit = relight(*bank, Direction::fromDegrees(40, 75), {});
    for (float v : relit.samples) REQUIRE((std::isfinite(v) && v >= 0 && v <= 1));

    // Version 8, byte-exact round trip; the same seed and options give the same bytes, on one
    // thread, two or three (a training step's shards summed in their order whatever thread
    // computed them).
    CHECK(bankFormatVersion(*bank) == 8);
    const Bytes bytes = encodeBank(*bank);
    Result<LutBank> back = decodeBank(bytes, "learned.btflut");
    REQUIRE_MESSAGE(back.ok(), back.error());
    CHECK(encodeBank(*back) == bytes);
    const LearnedDecoder& decoded = *back->predictorAs<LearnedPredictor>()->model().decoder;
    CHECK(decoded.residual.parameters() == m.decoder->residual.parameters());
    CHECK(decoded.light.parameters() == m.decoder->light.parameters());
    for (int threads : {2, 3}) {
        options.threads = threads;
        Result<LutBank> again = bakeBank(*dataset, options);
        REQUIRE(again.ok());
        CHECK(encodeBank(*again) == bytes);
    }

    // The chunk is checked: counts, sizes, finite numbers; an older reader refuses the kind.
    auto corrupt = [&](const std::function<void(LearnedModel&)>& change, const std::string& needle) {
        LutBank b = *bank;
        LearnedModel changed = m;
        change(changed);
        b.prediction.predictor = std::make_shared<LearnedPredictor>(std::move(changed), true);
        Result<LutBank> read = decodeBank(encodeBank(b), "bad.btflut");
        REQUIRE_FALSE(read.ok());
        CHECK_MESSAGE(read.error().find(needle) != std::string::npos, read.error());
        CHECK(read.error().find("bad.btflut") == 0);
    };
    auto withDecoder = [](LearnedModel& c, const std::function<void(LearnedDecoder&)>& change) {
        LearnedDecoder d = *c.decoder;
        change(d);
        c.decoder = std::make_shared<const LearnedDecoder>(std::move(d));
    };
    corrupt([&](LearnedModel& c) { withDecoder(c, [](LearnedDecoder& d) { d.residual.weights(0)(0, 7) = NAN; }); },
            "LRND chunk: a network parameter is not finite");
    corrupt([&](LearnedModel& c) { withDecoder(c, [](LearnedDecoder& d) { d.light.bias(0)(0) = INFINITY; }); },
            "LRND chunk: a network parameter is not finite");
    corrupt([](LearnedModel& c) { c.hidden[0] -= 1; }, "LRND chunk: a network's parameters do not fit its sizes");
    corrupt([](LearnedModel& c) { c.quantised.scale[2] = 0; }, "LRND chunk: invalid scale or bias");
    corrupt([](LearnedModel& c) { c.hidden.assign(9, 4); }, "LRND chunk: invalid layer count");
    corrupt([](LearnedModel& c) { c.hidden[0] = 300; }, "LRND chunk: invalid hidden layer width");

    // The GPU's decoder (btflut.glsl): its texture's head, and a network wider than the
    // shader's arrays refused by every GPU path in one line (relit on the CPU).
    CHECK(m.fitsGpu());
    const LearnedModel::GpuNetwork gpu = m.gpuNetwork();
    CHECK(gpu.texels.size() == static_cast<std::size_t>(gpu.size * gpu.size * 4));
    CHECK(std::vector<float>(gpu.texels.begin(), gpu.texels.begin() + 16) ==
          std::vector<float>{9, 3, 2, 0, 24, 24, 0, 0, 0, 0, 0, 0, 9, 0, 0, 0});
    CHECK(gpu.texels[16] == m.quantised.scale[0]);
    CHECK(drawnOnGpu(*bank).ok());
    LutBank wide = *bank;
    LearnedModel wider = m;
    wider.hidden = {80, 24};
    wider.decoder = std::make_shared<const LearnedDecoder>(LearnedDecoder{
        m.decoder->light, Network::fromParameters(wider.decoderSizes(), std::vector<float>(LearnedModel::parameterCount(
                                                                            wider.decoderSizes())))});
    wide.prediction.predictor = std::make_shared<LearnedPredictor>(std::move(wider), true);
    Result<EngineMaterial> refused = engineMaterial(wide, "wide.btflut");
    REQUIRE_FALSE(refused.ok());
    CHECK_MESSAGE(
        refused.error().find("wide.btflut: its learned model (neural9) has networks larger than the GPU") == 0,
        refused.error());
    CHECK(refused.error().find('\n') == std::string::npos);
    // The atlas export: the codes as images, the networks in its sidecar.
    REQUIRE(saveBank(*bank, dir / "n.btflut").ok());
    REQUIRE(runCli({"export", dir / "n.btflut", "-o", dir / "atlas.png", "-q"}).status == 0);
    const nlohmann::json atlas = readJson(dir / "atlas.json");
    CHECK(atlas["blend"]["predictor"] == "neural9");
    CHECK(atlas["blend"]["learned"]["images"].size() == 3);
    CHECK(atlas["blend"]["learned"]["residual"].size() == m.decoder->residual.parameters().size());
    CHECK(fs::exists(dir / "atlas-codes-2.png"));

    Bytes older = bytes;
    older[8] = 7;
    Result<LutBank> read = decodeBank(older, "old.btflut");
    REQUIRE_FALSE(read.ok());
    CHECK_MESSAGE(read.error().find("predictor, match or target out of range") != std::string::npos, read.error());
    Bytes truncated(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(bytes.size() / 2));
    CHECK_FALSE(decodeBank(truncated, "cut.btflut").ok());
}

TEST_CASE("learned model names: neuralN and neuralNwW, the residual's hidden width, and back") {
    const auto wide = learnedModelNamed("neural9w32");
    REQUIRE((wide && *wide));
    CHECK((*wide)->codes == 9);
    CHECK((*wide)->hidden == std::vector<int>{32, 32});
    const auto plain = learnedModelNamed("neural5");
    REQUIRE((plain && *plain));
    CHECK((*plain)->hidden == LearnedOptions{}.hidden);
    // A kind named (bake, eval) or chosen by auto trains for the default time (its steps
    // priced in multiply-adds), not LearnedOptions' bare steps.
    CHECK((*plain)->seconds == kDefaultTrainingSeconds);
    CHECK(AutoBakeOptions{}.seconds == 3 * kDefaultTrainingSeconds);
    BakeOptions named;
    REQUIRE(setModelNamed(named, "neural9"));
    REQUIRE(dynamic_cast<const LearnedFit*>(named.fit.get()));
    CHECK(dynamic_cast<const LearnedFit&>(*named.fit).options().seconds == kDefaultTrainingSeconds);
    for (const char* bad : {"neural9w0", "neural9w65", "neural0w24"}) {
        const auto refused = learnedModelNamed(bad);
        REQUIRE(refused);
        CHECK_FALSE(*refused);
    }
    CHECK_FALSE(learnedModelNamed("neural9w"));  // not a learned model's name at all
    CHECK_FALSE(learnedModelNamed("neural9wx"));
    LearnedModel m;
    m.codes = 9;
    m.hidden = {32, 32};
    CHECK(learnedModelName(m) == "neural9w32");
    m.hidden = LearnedOptions{}.hidden;
    CHECK(learnedModelName(m) == "neural9");
}

TEST_CASE("learned model: a time budget sets the steps, the same on every machine") {
    // 1 second of neural9 on grey (1218 multiply-adds a sample's forward pass): 1.2e10 / (3 x
    // 1218 x 2048 a step x 2.2 runs) = 728 steps, whatever the default steps (a time given is
    // used: 120 s trains 87,466 steps where the default is 6000); the epochs may be fewer, and
    // a network twice the size trains half the steps.
    CHECK(stepBudget(6000, 32768, 49, 1.0, 1218) == 728);
    CHECK(stepBudget(6000, 32768, 49, 0.0, 1218) == 6000);
    CHECK(stepBudget(100, 32768, 49, 1.0, 1218) == 728);
    CHECK(stepBudget(6000, 32768, 49, 1.0, 2436) == 364);
    CHECK(stepBudget(6000, 327680, 49, 120.0, 1218) == 87466);
    CHECK(stepBudget(6000, 32768, 49, 120.0, 1218) == 39250);  // 50 passes over its samples
    CHECK(stepBudget(6000, 100, 20, 60.0, 1218) == 50);        // 50 passes over 2000 samples
    // A time past what a step count holds still stops at the passes (no overflowing cast).
    CHECK(stepBudget(6000, 32768, 49, 1e300, 1218) == 39250);
    TempDir dir;
    const std::string manifest = writeRelief(dir, Relief{.size = 24}, dome(20, 70));
    std::string bytes;
    for (int run = 0; run < 2; ++run) {
        const std::string bank = dir / ("t" + std::to_string(run) + ".btflut");
        REQUIRE(runCli({"bake", manifest, "--predictor", "neural4", "--budget", "0.2s", "-o", bank, "-q"}).status == 0);
        if (run == 1) CHECK(readText(bank) == bytes);
        bytes = readText(bank);
    }
    REQUIRE(runCli({"bake", manifest, "--budget", "4,0.3s", "-o", dir / "auto.btflut", "-q"}).status == 0);
    // A bound on the decoding: neural4 (4 x 3 + 4 x 24 + 24 x 24 + 24 x 3 = 756 multiply-adds, RGB)
    // is no candidate within 100, and the choice is within it.
    REQUIRE(runCli({"bake", manifest, "--budget", "4,0.3s,100mac", "-o", dir / "cheap.btflut", "-q"}).status == 0);
    Result<LutBank> cheap = loadBank(dir / "cheap.btflut");
    REQUIRE(cheap.ok());
    const nlohmann::json selection = nlohmann::json::parse(cheap->selection);
    CHECK(selection["decode_budget"] == 100);
    CHECK(selection["chosen"]["multiply_adds"].get<std::size_t>() <= 100);
    bool skipped = false;
    for (const nlohmann::json& c : selection["candidates"])
        if (c["name"] == "neural4") {
            CHECK(c["multiply_adds"] == 4 * 3 + 4 * 24 + 24 * 24 + 24 * 3);
            skipped = c.value("skipped", "").find("past the bound of 100") != std::string::npos;
        }
    CHECK(skipped);
}

TEST_CASE("learned model: few lights, constant and black images, 16-bit images and masks bake finite banks") {
    TempDir dir;
    auto bake = [&](const std::string& manifest, const std::string& what) {
        Result<Dataset> dataset = openDataset(manifest);
        REQUIRE_MESSAGE(dataset.ok(), dataset.error());
        Result<LutBank> bank = bakeBank(*dataset, {.fit = learnedFit(LearnedOptions{.steps = 120})});
        INFO(what);
        REQUIRE_MESSAGE(bank.ok(), bank.error());
        const LearnedModel& m = bank->predictorAs<LearnedPredictor>()->model();
        REQUIRE((m.decoder->residual.finite() && m.decoder->light.finite()));
        for (const std::vector<float>* v : {&m.quantised.scale, &m.quantised.bias})
            for (float x : *v) REQUIRE(std::isfinite(x));
        const Image relit = relight(*bank, Direction::fromDegrees(35, 120), {});
        for (float v : relit.samples) REQUIRE((std::isfinite(v) && v >= 0 && v <= 1));
    };
    for (int count : {3, 5, 12}) {
        TempDir sub;
        bake(writeRelief(sub, Relief{.size = 24, .border = 3}, dome(count, 60)), std::to_string(count) + " lights");
    }
    {  // clustered within 5 degrees
        TempDir sub;
        std::vector<Direction> clustered;
        for (int i = 0; i < 20; ++i) clustered.push_back(Direction::fromDegrees(30 + 0.2 * i, 40 + 0.2 * (i % 5)));
        bake(writeRelief(sub, Relief{.size = 24}, clustered), "clustered lights");
    }
    // Images of `value(texel, light)` under 18 lights, at a bit depth.
    auto images = [&](const TempDir& sub, int depth, const std::function<float(int, int)>& value) {
        nlohmann::json manifest{{"btflut_dataset", 1}, {"images", nlohmann::json::array()}};
        const std::vector<Direction> lights = dome(18, 65);
        for (int l = 0; l < 18; ++l) {
            Image im(20, 20, 1, depth);
            for (int i = 0; i < 400; ++i) im.samples[static_cast<std::size_t>(i)] = value(i, l);
            const std::string name = "i" + std::to_string(l) + ".png";
            REQUIRE(savePng(im, sub / name, depth).ok());
            manifest["images"].push_back({{"file", name},
                                          {"light",
                                           {{"theta", lights[static_cast<std::size_t>(l)].thetaDegrees()},
                                            {"phi", lights[static_cast<std::size_t>(l)].phiDegrees()}}}});
        }
        std::ofstream(sub / "btflut-dataset.json") << manifest.dump(1);
        return sub / "btflut-dataset.json";
    };
    {  // black but for two texels' levels (the reference must not be constant)
        TempDir sub;
        bake(images(sub, 8, [](int i, int l) { return i < 2 ? static_cast<float>(10 * i + l) / 255.f : 0.f; }),
             "black images");
    }
    {  // 16-bit, a smooth ramp that grows with the light
        TempDir sub;
        bake(images(sub, 16, [](int i, int l) { return std::round((i / 400.f) * (0.3f + 0.03f * l) * 65535) / 65535; }),
             "16-bit images");
    }
    {  // training that diverges (an absurd rate): refused in one line, never a NaN in a bank
        TempDir sub;
        Result<Dataset> relief = openDataset(writeRelief(sub, Relief{.size = 16}, dome(20, 60)));
        REQUIRE(relief.ok());
        Result<LutBank> diverged = bakeBank(*relief, {.fit = learnedFit(LearnedOptions{.steps = 50, .rate = 1e30f})});
        REQUIRE_FALSE(diverged.ok());
        CHECK_MESSAGE(diverged.error().find("training the learned model diverged") != std::string::npos,
                      diverged.error());
    }
    {
        TempDir sub;
        Result<Dataset> few = openDataset(writeRelief(sub, Relief{.size = 16}, dome(2, 50)));
        REQUIRE(few.ok());
        Result<LutBank> refused = bakeBank(*few, {.fit = learnedFit(LearnedOptions{.steps = 50})});
        REQUIRE_FALSE(refused.ok());
        CHECK_MESSAGE(refused.error().find("a learned model needs at least 3 lights") != std::string::npos,
                      refused.error());
    }
}

TEST_CASE("neuralrti: the published schedule cuts the rate after 4 stalled epochs and stops after 5") {
    PlateauSchedule s(1e-2f);
    CHECK(s.epochEnded(1.0));
    CHECK(s.epochEnded(0.5));
    // Below the best, but by less than ReduceLROnPlateau's relative 1e-4: a stall for the rate,
    // an improvement for EarlyStopping.
    CHECK(s.epochEnded(0.49999));
    CHECK(s.rate() == doctest::Approx(1e-2f));
    for (int k = 0; k < 3; ++k) CHECK(s.epochEnded(0.6));  // stalled: 4 for the rate, 3 for stopping
    CHECK(s.rate() == doctest::Approx(1e-3f));
    CHECK(s.epochEnded(0.6));        // 4th stalled epoch for stopping
    CHECK_FALSE(s.epochEnded(0.6));  // the 5th: stop
}

TEST_CASE("neuralrti: AMSGrad divides by the largest second moment so far") {
    Random random(3);
    const Network start = Network::random({2, 1}, random, WeightInit::Torch);
    CHECK(start.bias(0)(0) != 0);  // PyTorch's initialisation draws the biases too
    auto lastStep = [&](bool amsgrad) {
        Network net = start;
        Adam adam(net, amsgrad);
        NetworkGradient g{{Matrix::Constant(1, 2, 100.f)}, {Vector::Constant(1, 100.f)}, {}};
        adam.step(net, g, 0.1f);
        g.weights[0].setConstant(0.01f);
        g.biases[0].setConstant(0.01f);
        for (int k = 0; k < 3000; ++k) adam.step(net, g, 0.1f);  // Adam's second moment decays to 1/20
        const float before = net.bias(0)(0);
        adam.step(net, g, 0.1f);
        return std::abs(net.bias(0)(0) - before);
    };
    CHECK(lastStep(true) < 0.5f * lastStep(false));
}

TEST_CASE("neuralrti: the published recipe converges on a relief, the same bytes for a seed and thread count") {
    const Relief relief{.size = 16};
    const std::vector<Direction> lights = dome(24, 70);
    std::vector<Image> images;
    std::vector<const Image*> pointers;
    for (Direction l : lights) images.push_back(reliefImage(relief, l));
    for (const Image& image : images) pointers.push_back(&image);
    const Mask mask = fullMask(relief.size, relief.size);
    const NeuralRtiOptions options{.maxEpochs = 12, .threads = 2};
    Result<NeuralRti> baseline = fitNeuralRti(pointers, lights, mask, options, "relief");
    REQUIRE_MESSAGE(baseline.ok(), baseline.error());
    CHECK(baseline->quantised.bytes.size() == 9 * images.front().pixelCount());
    // 90% of 16 x 16 x 24 pairs in batches of 64: 87 steps an epoch.
    REQUIRE(!baseline->epochs.empty());
    CHECK(baseline->epochs.front().steps == 87);
    CHECK(baseline->epochs.front().rate == doctest::Approx(1e-2f));
    const double first = baseline->epochs.front().validationLoss, last = baseline->epochs.back().validationLoss;
    MESSAGE("NeuralRTI on a 16 x 16 relief: validation MSE " << first << " after an epoch, " << last << " after "
                                                             << baseline->epochs.size() << " (" << baseline->stopped
                                                             << ")");
    CHECK(last < 0.5 * first);
    // The weights kept are the best validation's.
    REQUIRE(baseline->bestEpoch >= 1);
    REQUIRE(baseline->bestEpoch <= static_cast<int>(baseline->epochs.size()));
    for (const NeuralRtiEpoch& e : baseline->epochs)
        CHECK(baseline->epochs[static_cast<std::size_t>(baseline->bestEpoch - 1)].validationLoss <= e.validationLoss);
    double psnr = 0;
    for (Direction l :
         {Direction::fromDegrees(25, 10), Direction::fromDegrees(45, 200), Direction::fromDegrees(60, 300)}) {
        const Image truth = reliefImage(relief, l), predicted = baseline->render(l);
        for (float v : predicted.samples) REQUIRE((std::isfinite(v) && v >= 0 && v <= 1));
        psnr += compareImages(predicted, truth, mask).psnr / 3;
    }
    MESSAGE("relief between the lights: NeuralRTI " << psnr << " dB");
    CHECK(psnr > 25);

    Result<NeuralRti> again = fitNeuralRti(pointers, lights, mask, options, "relief");
    REQUIRE(again.ok());
    CHECK(again->quantised.bytes == baseline->quantised.bytes);
    CHECK(again->decoder == baseline->decoder);

    // A time bound: the steps this machine trains in about that long, the same everywhere.
    NeuralRtiOptions bounded = options;
    bounded.seconds = 0.5;
    Result<NeuralRti> quick = fitNeuralRti(pointers, lights, mask, bounded, "relief");
    REQUIRE(quick.ok());
    CHECK(quick->stopped == "time bound");
    CHECK(quick->epochs.back().steps < baseline->epochs.back().steps);
    bounded.seconds = 1e-6;
    Result<NeuralRti> none = fitNeuralRti(pointers, lights, mask, bounded, "relief");
    REQUIRE_FALSE(none.ok());
    CHECK(none.error().find("no step") != std::string::npos);
    std::vector<const Image*> two(pointers.begin(), pointers.begin() + 2);
    CHECK_FALSE(fitNeuralRti(two, {lights[0], lights[1]}, mask, {}, "relief").ok());
}

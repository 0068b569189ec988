// btflut bench decoder: a learned bank's decoder against a plain shader of the same network
// (shaders/bench_decoder.frag), per fragment and in texture space, side by side in one context
// (issue 46): what btflut's specialised decoder costs next to what the hardware gives a
// shader written plainly by hand. Ratios, never pass/fail.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include "cli/bench_timing.h"
#include "cli/command.h"
#include "core/bank/bank_file.h"
#include "core/io/json_text.h"
#include "core/learn/network.h"
#include "core/predict/learned_decoder.h"
#include "core/predict/learned_half.h"
#include "core/predict/learned_predictor.h"
#include "core/predict/learned_shader.h"
#include "gl/context.h"
#include "gl/prediction_textures.h"
#include "gl/relight_pass.h"
#include "gl/scene_renderer.h"
#include "gl/shader.h"
#include "gl/textures.h"

namespace btflut::cli {

namespace {

struct BenchDecoderOptions {
    std::string bank;
    std::string size = "1920x1080";
    GlBenchOptions timing;
};

constexpr double kMagnification = 1.5;  // screen pixels per texel across, per fragment (a near quad)

// The plain shader's #defines and its uniform block (std140: an array of vec4 is packed).
std::vector<std::string> plainDefines(const LearnedModel& m) {
    const std::vector<int> sizes = m.decoderSizes();
    return {"PLAIN",
            "CODES " + std::to_string(m.codes),
            "LAYERS " + std::to_string((m.codes + 3) / 4),
            "CHANNELS " + std::to_string(m.channels),
            "WIDTH1 " + std::to_string(sizes[1]),
            "WIDTH2 " + std::to_string(sizes[2])};
}

std::vector<float> plainBlock(const LearnedModel& m) {
    const Network& net = m.decoder->residual;
    const auto groups = [](Eigen::Index n) { return (n + 3) / 4; };
    std::vector<float> out;
    auto codes = [&](const std::vector<float>& values) {
        for (int k = 0; k < (m.codes + 3) / 4 * 4; ++k)
            out.push_back(k < m.codes ? values[static_cast<std::size_t>(k)] : 0.f);
    };
    codes(m.quantised.scale);
    codes(m.quantised.bias);
    // Layer l's weights as vec4 columns: input i's to outputs 4 o .. 4 o + 3 at [i * groups + o]
    // (the first layer's code inputs alone: its light inputs are folded into the frame).
    auto columns = [&](const Matrix& w, Eigen::Index inputs) {
        for (Eigen::Index i = 0; i < inputs; ++i)
            for (Eigen::Index o = 0; o < groups(w.rows()) * 4; ++o) out.push_back(o < w.rows() ? w(o, i) : 0.f);
    };
    auto bias = [&](const Vector& b) {
        for (Eigen::Index o = 0; o < groups(b.size()) * 4; ++o) out.push_back(o < b.size() ? b(o) : 0.f);
    };
    columns(net.weights(0), m.codes);
    columns(net.weights(1), net.weights(1).cols());
    bias(net.bias(1));
    columns(net.weights(2), net.weights(2).cols());
    bias(net.bias(2));
    return out;
}

// One quad filling the frame under a frontal camera, its texture repeating `uvScale` times:
// the scene renderer's per-fragment path over every pixel.
Scene fullFrameScene(const std::string& bank, int w, int h, double uvScale) {
    constexpr double kFov = 45;
    Scene s;
    s.file = "bench";
    s.width = w;
    s.height = h;
    s.fovDegrees = kFov;
    s.eye = {0, 0, 1 / std::tan(kFov / 2 * M_PI / 180)};
    s.target = {0, 0, 0};
    s.up = {0, 1, 0};
    s.materials["m"] = {bank, {}};
    s.quads = {{"m", {0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 2.0 * w / h, 2, uvScale, RenderMode::Lut}};
    return s;
}

// An RGBA8 render target without depth, as a relight pass draws into.
struct ColourTarget {
    GlTexture colour;
    GlFramebuffer framebuffer;
};
ColourTarget colourTarget(int w, int h) {
    ColourTarget t{allocateTexture2D(w, h, GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE), makeFramebuffer()};
    gl.BindFramebuffer(GL_FRAMEBUFFER, t.framebuffer.id());
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, t.colour.id(), 0);
    return t;
}

// A row: a draw of `pixels` shaded pixels, timed over many.
struct Row {
    std::string name;
    double pixels = 0;
    std::function<Status()> draw;
    std::vector<double> msPerMpx;
};

void setFrame(const ShaderProgram& p, const std::vector<ShaderValues>& values) {
    for (const ShaderValues& v : values) {  // predictLearned.basis: frame.basis, ...
        const std::string name = "frame" + v.name.substr(v.name.find('.'));
        const auto count = static_cast<GLsizei>(v.values.size() / static_cast<std::size_t>(v.size));
        if (v.size == 4)
            gl.Uniform4fv(p[name], count, v.values.data());
        else
            gl.Uniform3fv(p[name], count, v.values.data());
    }
}

// The codes as the plain shader and btflut's read them: RGBA8 layers, four codes a texel.
GlTexture uploadCodes(const LearnedPredictor& learned) {
    const LearnedModel& m = learned.model();
    const PredictorPlanes planes = learned.planes();
    const int layers = static_cast<int>(planes.layers.size());
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(layers) * m.texels() * 4);
    for (std::size_t i = 0; i < bytes.size(); ++i)
        bytes[i] = static_cast<std::uint8_t>(
            std::lround(planes.layers[i / (m.texels() * 4)].samples[i % (m.texels() * 4)] * 255));
    std::size_t uploaded = 0;
    return uploadTextureArray(m.width, m.height, layers, 4, bytes.data(), uploaded);
}

// The programs every row draws with, by key ("plain fragment", "btflut texture", "flat
// fragment", ...): the plain reference shader, btflut's generated decoder and a flat texture,
// per fragment and in texture space, with the frame's uniforms set.
Result<std::map<std::string, ShaderProgram>> decoderPrograms(const LearnedPredictor& learned,
                                                             const std::vector<ShaderValues>& frame) {
    const std::string source = learned.shaderSource();  // the ShaderFile views it
    const std::vector<ShaderFile> generated{{learned.name() + " decoder (generated)", source}};
    std::map<std::string, ShaderProgram> programs;
    auto program = [&](const std::string& key, std::vector<std::string> defines) -> Status {
        Result<ShaderProgram> p = buildProgram(
            {"quad.vert"}, {"btflut.glsl", "bench_decoder.frag"}, defines,
            defines.front() == "PLAIN" || defines.front() == "FLAT" ? std::vector<ShaderFile>{} : generated);
        if (!p) return Error{p.error()};
        const ShaderProgram& made = programs[key] = std::move(*p);
        gl.UseProgram(made.id());
        gl.Uniform1i(made["planes"], 0);
        setFrame(made, frame);
        if (defines.front() == "PLAIN")
            gl.UniformBlockBinding(made.id(), gl.GetUniformBlockIndex(made.id(), "PlainNetwork"), 0);
        return success();
    };
    for (const bool textureSpace : {false, true}) {
        const std::string at = textureSpace ? " texture" : " fragment";
        std::vector<std::string> space;
        if (textureSpace) space.push_back("TEXTURE_SPACE");
        std::vector<std::string> plain = plainDefines(learned.model()), ours{"BTFLUT"}, flat{"FLAT"};
        plain.insert(plain.end(), space.begin(), space.end());
        ours.insert(ours.end(), space.begin(), space.end());
        if (Status s = program("plain" + at, plain); !s) return Error{s.error()};
        if (Status s = program("btflut" + at, ours); !s) return Error{s.error()};
        if (!textureSpace)
            if (Status s = program("flat" + at, flat); !s) return Error{s.error()};
    }
    return programs;
}

// What one run measured beside its rows' times.
struct DecoderRun {
    std::string context;
    int width = 0, height = 0, passes = 0;
    bool timer = false;
    double differs = 0;  ///< the plain shader's frame against btflut's, in codes
    HalfPrecisionError half;
};

// The rows' medians and ratios, as JSON (--json) or text.
void reportDecoder(const BenchDecoderOptions& o, const LearnedModel& m, const std::vector<Row>& rows,
                   const DecoderRun& run) {
    const LearnedShaderCost cost = learnedShaderCost(m);
    auto ms = [&](const std::string& name) {
        for (const Row& row : rows)
            if (row.name == name) return median(row.msPerMpx);
        BTFLUT_CHECK(false);
        return 0.0;
    };
    const double fragmentRatio = ms("plain, per fragment") / ms("btflut, per fragment"),
                 textureRatio = ms("plain, texture space") / ms("btflut, texture space");
    nlohmann::json out{
        {"context", run.context},
        {"bank", o.bank},
        {"decoder", learnedModelName(m)},
        {"multiply_adds_per_texel", cost.texelMultiplyAdds},
        {"frame_multiply_adds", cost.frameMultiplyAdds},
        {"shader_constants", cost.constants},
        {"width", run.width},
        {"height", run.height},
        {"texture_space_passes", run.passes},
        {"timer", run.timer ? "GL_TIME_ELAPSED" : "wall"},
        {"plain_against_btflut_max_codes", run.differs},
        {"half_precision",
         {{"max_codes", run.half.max}, {"p99_codes", run.half.p99}, {"share_over_one_code", run.half.overOneCode}}},
        {"btflut_over_plain_throughput_per_fragment", fragmentRatio},
        {"btflut_over_plain_throughput_texture_space", textureRatio},
        {"ms_per_mpx", nlohmann::json::object()}};
    for (const Row& row : rows) out["ms_per_mpx"][row.name] = median(row.msPerMpx);
    if (o.timing.json) {
        std::cout << jsonText(out);
        return;
    }
    std::printf(
        "decoder of %s (%s: %zu multiply-adds a texel, the frame %zu), %s; ms per million pixels (%s), "
        "median of %d rounds of %d draws\n",
        o.bank.c_str(), learnedModelName(m).c_str(), cost.texelMultiplyAdds, cost.frameMultiplyAdds,
        run.context.c_str(), run.timer ? "GPU timer" : "wall", o.timing.repeat, o.timing.frames);
    std::printf("  per fragment at %dx%d (the codes bilinear, magnified %.1fx); texture space at %dx%d, %d passes\n",
                run.width, run.height, kMagnification, m.width, m.height, run.passes);
    for (const Row& row : rows) std::printf("    %-32s %10.3f\n", row.name.c_str(), median(row.msPerMpx));
    std::printf(
        "  btflut's decoder / the plain shader, throughput: per fragment %.3f, texture space %.3f (their "
        "frames differ by at most %.0f/255)\n",
        fragmentRatio, textureRatio, run.differs);
    std::printf(
        "  per fragment, x flat: plain %.1f, btflut %.1f; in a scene (depth tested), btflut matched %.1f x "
        "the scene drawn flat\n",
        ms("plain, per fragment") / ms("flat, per fragment"), ms("btflut, per fragment") / ms("flat, per fragment"),
        ms("btflut matched, scene per fragment") / ms("flat, scene"));
    std::printf(
        "  in half precision (binary16, emulated on the CPU at 3 lights): max %.2f/255, p99 %.2f/255 from float; "
        "%.4f%% of values more than one code off (the contract: none)\n",
        run.half.max, run.half.p99, 100 * run.half.overOneCode);
}

Status runBenchDecoder(const BenchDecoderOptions& o) {
    Result<FrameSize> size = parseFrameSize(o.size);
    if (!size) return Error{size.error()};
    const int w = size->width, h = size->height;
    Result<GlBackend> backend = parseGlBackend(o.timing.backend);
    if (!backend) return Error{backend.error()};
    Result<std::unique_ptr<HeadlessContext>> context = createHeadlessContext(*backend);
    if (!context) return Error{context.error()};
    Result<LutBank> loaded = loadBank(o.bank, {.ptm = false});
    if (!loaded) return Error{loaded.error()};
    const LutBank& bank = *loaded;
    const LearnedPredictor* learned = bank.makesLuts() ? bank.predictorAs<LearnedPredictor>() : nullptr;
    if (!learned) return Error{o.bank + ": not a learned bank (bake --predictor neuralN)"};
    const LearnedModel& m = learned->model();
    if (!hasLearnedShader(m))
        return Error{o.bank + ": its decoder is past a shader's " + std::to_string(kMaxShaderConstants) +
                     " constants (drawn by the include's texture path)"};
    if (m.hidden.size() != 2 || m.viewFeatures > 0)
        return Error{o.bank + ": the plain reference shader is of one view and two hidden layers, as bake trains them"};
    // GPU time where the GPU keeps it; llvmpipe's timer ends a query when the draw is queued,
    // not when its tiles are shaded (it reads ~0 for one draw), so there the wall time.
    GLint timerBits = 0;
    gl.GetQueryiv(GL_TIME_ELAPSED, GL_QUERY_COUNTER_BITS, &timerBits);
    const bool timer = timerBits > 0 && !softwareRasteriser();

    // What every row reads: the codes, and the frame at one light.
    const Direction light = Direction::fromDegrees(45, 250);
    const int texelsX = m.width, texelsY = m.height;
    const GlTexture codes = uploadCodes(*learned);
    const std::vector<ShaderValues> frame = learned->shaderValues(learned->frameAt(light, {}));
    const std::vector<float> block = plainBlock(m);
    GlBuffer buffer = makeBuffer();
    gl.BindBuffer(GL_UNIFORM_BUFFER, buffer.id());
    gl.BufferData(GL_UNIFORM_BUFFER, static_cast<GLsizeiptr>(block.size() * sizeof(float)), block.data(),
                  GL_STATIC_DRAW);
    gl.BindBufferBase(GL_UNIFORM_BUFFER, 0, buffer.id());

    // Per fragment: the frame's size, the texture magnified; texture space: the codes' size,
    // passes enough for about the same pixels.
    const double uvScale = w / (kMagnification * texelsX);
    const int passes = std::max(1, static_cast<int>(std::lround(static_cast<double>(w) * h / m.texels())));
    const ColourTarget screen = colourTarget(w, h), relit = colourTarget(texelsX, texelsY);
    GlVertexArray vertexArray = makeVertexArray();
    Result<std::map<std::string, ShaderProgram>> built = decoderPrograms(*learned, frame);
    if (!built) return Error{built.error()};
    const std::map<std::string, ShaderProgram>& programs = *built;
    // A full-screen draw of one program into a target.
    auto fullScreen = [&](const std::string& key, const ColourTarget& target, int tw, int th, int count) {
        return [&, key, tw, th, count]() -> Status {
            const ShaderProgram& p = programs.at(key);
            gl.BindFramebuffer(GL_FRAMEBUFFER, target.framebuffer.id());
            gl.Viewport(0, 0, tw, th);
            gl.Disable(GL_DEPTH_TEST);
            gl.UseProgram(p.id());
            gl.ActiveTexture(GL_TEXTURE0);
            gl.BindTexture(GL_TEXTURE_2D_ARRAY, codes.id());
            gl.Uniform2f(p["frameSize"], static_cast<float>(tw), static_cast<float>(th));
            gl.Uniform1f(p["uvScale"], static_cast<float>(uvScale));
            gl.BindVertexArray(vertexArray.id());
            for (int k = 0; k < count; ++k) gl.DrawArrays(GL_TRIANGLES, 0, 3);
            return success();
        };
    };
    // btflut's own paths with their match LUTs: the relight pass (a moving light in texture
    // space) and the scene renderer's quad per fragment.
    std::size_t planeBytes = 0;
    const PredictionTextures planes = PredictionTextures::upload(bank, planeBytes);
    RelightPass pass(bank, 0, &planes);
    const std::vector<GlTexture> passLuts = pass.makeLuts();
    const RelightFrame relightFrame = Relighter(bank).gridFrame(light);
    GlTexture passTarget = allocateRelitTexture(bank.reference);
    Result<std::unique_ptr<SceneRenderer>> scene =
        SceneRenderer::create(fullFrameScene(o.bank, w, h, uvScale), {.lutPath = LutPath::PerFragment});
    if (!scene) return Error{scene.error()};
    const double screenPixels = static_cast<double>(w) * h, passPixels = static_cast<double>(m.texels()) * passes;
    std::vector<Row> rows{
        {"flat, per fragment", screenPixels, fullScreen("flat fragment", screen, w, h, 1)},
        {"plain, per fragment", screenPixels, fullScreen("plain fragment", screen, w, h, 1)},
        {"btflut, per fragment", screenPixels, fullScreen("btflut fragment", screen, w, h, 1)},
        {"flat, scene", screenPixels, [&]() { return (*scene)->draw(toVector(light), RenderMode::Flat); }},
        {"btflut matched, scene per fragment", screenPixels, [&]() { return (*scene)->draw(toVector(light)); }},
        {"plain, texture space", passPixels, fullScreen("plain texture", relit, texelsX, texelsY, passes)},
        {"btflut, texture space", passPixels, fullScreen("btflut texture", relit, texelsX, texelsY, passes)},
        {"btflut matched, texture space", passPixels, [&]() -> Status {
             for (int k = 0; k < passes; ++k)
                 if (Status s = pass.run(relightFrame, passLuts, passTarget.id(), true); !s) return s;
             return success();
         }}};
    for (Row& row : rows)  // compiled, uploaded and warm before the clock starts
        if (Status s = row.draw(); !s) return s;
    gl.Finish();
    // The plain shader computes what btflut's decoder does: the largest difference of their
    // frames per fragment, in codes.
    auto frameOf = [&](const std::string& name) {
        for (Row& row : rows)
            if (row.name == name) (void)row.draw();
        return readFramebufferRgb(screen.framebuffer.id(), w, h);
    };
    const Image plainFrame = frameOf("plain, per fragment"), btflutFrame = frameOf("btflut, per fragment");
    double differs = 0;
    for (std::size_t i = 0; i < plainFrame.samples.size(); ++i)
        differs =
            std::max(differs, std::abs(static_cast<double>(plainFrame.samples[i] - btflutFrame.samples[i])) * 255);
    for (int r = 0; r < o.timing.repeat; ++r)  // interleaved, so drift hits every row alike
        for (Row& row : rows) {
            Result<DrawTimes> t = timeDraws(o.timing.frames, timer, row.draw);  // GPU time where it has a timer
            if (!t) return Error{t.error()};
            row.msPerMpx.push_back((timer ? t->gpu : t->wall) * 1e3 / (row.pixels * 1e-6));
        }
    if (GLenum error = gl.GetError(); error != GL_NO_ERROR)
        return Error{"OpenGL error " + std::to_string(error) + " in bench decoder"};

    // Whether half floats would hold the contract: the decoder in binary16 on the CPU.
    const Direction halfLights[] = {light, Direction::fromDegrees(20, 30), Direction::fromDegrees(70, 140)};
    const DecoderRun run{(*context)->description(), w, h, passes, timer, differs, halfPrecisionError(m, halfLights)};
    reportDecoder(o, m, rows, run);
    return success();
}

}  // namespace

void addBenchDecoderCommand(CLI::App& bench, Commands& commands) {
    auto o = std::make_shared<BenchDecoderOptions>();
    CLI::App* decoder = bench.add_subcommand(
        "decoder",
        "A learned bank's decoder against a plain shader of the same network (weights in a uniform block, "
        "loops of constant bounds), per fragment and in texture space, side by side: ms per million pixels "
        "and their ratio");
    decoder->add_option("BANK", o->bank, "M.btflut with a learned predictor (bake --predictor neuralN)")->required();
    decoder->add_option("--size", o->size, "the per-fragment target, WxH")->capture_default_str();
    addGlBenchOptions(*decoder, o->timing, "draws");
    commands.push_back({decoder, [o] { return runBenchDecoder(*o); }});
}

}  // namespace btflut::cli

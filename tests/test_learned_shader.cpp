// A learned model's decoder specialised to it (core/predict/learned_shader.h): the sources
// compile in every language for every network shape the baker makes, and on a GPU its frame and
// its values are the CPU's (LearnedModel::lightFrame, predict).
#include <doctest/doctest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>

#include "core/learn/network.h"
#include "core/predict/gpu_constants.h"
#include "core/predict/learned_decoder.h"
#include "core/predict/learned_half.h"
#include "core/predict/learned_predictor.h"
#include "core/predict/learned_shader.h"
#include "gl/context.h"
#include "gl/shader.h"
#include "gl/textures.h"
#include "helpers.h"

using namespace btflut;
using namespace btflut::test;

namespace {

struct Shape {
    int codes = 9, channels = 3, viewFeatures = 0;
    std::vector<int> hidden{24, 24}, lightHidden;
    bool constantResidual = false;  // its last layer's weights zero (the linear start)
};

// A model of random weights and codes, w x h texels.
LearnedModel randomModel(const Shape& shape, int w, int h, std::uint64_t seed) {
    Random random(seed);
    LearnedModel m;
    m.width = w;
    m.height = h;
    m.codes = shape.codes;
    m.channels = shape.channels;
    m.viewFeatures = shape.viewFeatures;
    m.hidden = shape.hidden;
    m.lightHidden = shape.lightHidden;
    for (int k = 0; k < m.codes; ++k) {
        m.quantised.scale.push_back(static_cast<float>(0.01 + 0.02 * random.uniform()));
        m.quantised.bias.push_back(static_cast<float>(255 * random.uniform()));
    }
    m.quantised.bytes.resize(m.texels() * static_cast<std::size_t>(m.codes));
    for (std::uint8_t& c : m.quantised.bytes) c = static_cast<std::uint8_t>(random.uniform() * 255.99);
    Network residual = Network::random(m.decoderSizes(), random);
    if (shape.constantResidual) {
        residual.weights(residual.layers() - 1).setZero();
        residual.bias(residual.layers() - 1).setConstant(0.05f);
    }
    LearnedDecoder decoder{Network::random(m.lightSizes(), random), std::move(residual)};
    for (std::size_t layer = 0; layer < decoder.light.layers(); ++layer) {  // a basis of moderate weights,
        decoder.light.weights(layer) *= 0.2f;                               // so the values span [0, 1]
        decoder.light.bias(layer) *= 0.2f;
    }
    m.decoder = std::make_shared<const LearnedDecoder>(std::move(decoder));
    return m;
}

// What engines compile: the include's form, the decoder, and a main that calls every function.
std::string glslEsProgram(const std::string& network) {
    return "#version 300 es\n" + std::string(embeddedShader("btflut_es.glsl")) + network + R"(
uniform sampler3D luts;
uniform sampler2DArray planes;
uniform highp sampler2D labels;
uniform BtflutPredictor predictor;
uniform vec3 lightTangent;
uniform BtflutLearnedFrame frame;
in vec2 uv;
out vec4 colour;
void main() {
    uvec2 pixel = uvec2(gl_FragCoord.xy);
    BtflutPrediction a = btflutNetworkPrediction(planes, uv, btflutNetworkFrame(lightTangent, vec3(0.0, 0.0, 1.0)));
    BtflutPrediction b = btflutNetworkPrediction(planes, uv, frame);
    colour = vec4(btflutRelightPrediction(luts, planes, labels, predictor, uv, lightTangent, 0, pixel, a) + b.colour, 1.0);
}
)";
}

std::string hlslProgram() {
    return R"(#include "btflut.hlsl"
#include "btflut_network.hlsl"
Texture3D<float4> _Luts; SamplerState sampler_Luts;
Texture2DArray<float4> _Planes; SamplerState sampler_Planes;
Texture2D<float4> _Labels; SamplerState sampler_Labels;
cbuffer Material { float3 _LightTangent; float4 _Codes; BtflutLearnedFrame _Frame; };
float4 main(float2 uv : TEXCOORD0, float4 position : SV_Position) : SV_Target {
    uint2 pixel = uint2(position.xy);
    BtflutPredictor p = (BtflutPredictor)0;
    p.kind = 3; p.regions = 1; p.codes = _Codes.x; p.outputCode = _Codes.y; p.dither = true;
    BtflutPrediction a = btflutNetworkPrediction(_Planes, sampler_Planes, uv, btflutNetworkFrame(_LightTangent, float3(0.0, 0.0, 1.0)));
    BtflutPrediction b = btflutNetworkPrediction(_Planes, sampler_Planes, uv, _Frame);
    return float4(btflutRelightPrediction(_Luts, sampler_Luts, _Planes, sampler_Planes, _Labels, sampler_Labels, p, uv,
                                          _LightTangent, 0, pixel, a) + b.colour, 1.0);
}
)";
}

void writeText(const std::string& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

}  // namespace

TEST_CASE("learned shader: the decoder in half precision is within a code of float, and not float") {
    const Direction lights[] = {Direction::fromDegrees(45, 250), Direction::fromDegrees(70, 140)};
    for (const bool constant : {false, true}) {
        INFO("the residual constant: " << constant);
        const LearnedModel m = randomModel(Shape{.constantResidual = constant}, 24, 20, 3);
        const HalfPrecisionError e = halfPrecisionError(m, lights, 2);
        CHECK(e.max > 0.01);  // binary16 has an 11-bit significand: it is not float's arithmetic
        CHECK(e.max < 2);
        CHECK(e.p99 <= e.max);
        CHECK(e.overOneCode < 0.001);
        CHECK(halfPrecisionError(m, lights, 1).max == e.max);  // blocks of a fixed size: any thread count
    }
    CHECK(halfPrecisionError(randomModel(Shape{}, 4, 4, 3), {}).max == 0);  // no lights, nothing compared
}

TEST_CASE("learned shader: the specialised decoder compiles as GLSL ES and HLSL for every network the baker makes") {
    TempDir dir;
    writeText(dir / "btflut.hlsl", std::string(embeddedShader("btflut.hlsl")));
    std::vector<Shape> shapes;
    for (int codes = 1; codes <= LearnedModel::kMaxCodes; ++codes) shapes.push_back({.codes = codes});  // neural1..16
    shapes.push_back({.codes = 9, .channels = 1});                                                      // grey
    shapes.push_back({.codes = 9, .channels = 3, .viewFeatures = kLearnedViewFeatures});  // a model of views
    shapes.push_back({.codes = 5, .channels = 1, .hidden = {8}, .lightHidden = {12, 12}});
    shapes.push_back({.codes = 16, .channels = 3, .hidden = {64, 64, 64}, .lightHidden = {64}});
    shapes.push_back({.codes = 9, .channels = 1, .constantResidual = true});
    for (const Shape& shape : shapes) {
        const LearnedModel m = randomModel(shape, 4, 4, 7);
        INFO("codes " << shape.codes << ", channels " << shape.channels << ", views " << shape.viewFeatures << ", "
                      << shape.hidden.size() << " hidden layers");
        REQUIRE(hasLearnedShader(m));
        const std::string glsl = learnedShaderSource(m, ShaderLanguage::Glsl, "test");
        // Its sizes as constants: no run-time loop bound, no texelFetch of a weight.
        CHECK(glsl.find("texelFetch") == std::string::npos);
        CHECK(glsl.find("#define BTFLUT_NETWORK_CODES " + std::to_string(shape.codes) + "\n") != std::string::npos);
        writeText(dir / "es.frag", glslEsProgram(glsl));
        CHECK(std::system(("glslangValidator " + (dir / "es.frag") + " > " + (dir / "log") + " 2>&1").c_str()) == 0);
        std::ifstream log(dir / "log");
        INFO(std::string(std::istreambuf_iterator<char>(log), {}));
        writeText(dir / "btflut_network.hlsl", learnedShaderSource(m, ShaderLanguage::Hlsl, "test"));
        writeText(dir / "main.hlsl", hlslProgram());
        CHECK(std::system(("glslangValidator -D -V -S frag -e main -I" + dir.path().string() + " " +
                           (dir / "main.hlsl") + " -o " + (dir / "main.spv") + " > " + (dir / "log") + " 2>&1")
                              .c_str()) == 0);
    }
    // A residual network that adds a constant (validation kept the linear start) is left out: the
    // texel decodes in the codes' basis alone, and the frame computes no residual part.
    const LearnedModel linear = randomModel({.codes = 9, .channels = 3, .constantResidual = true}, 2, 2, 5);
    CHECK(linear.residualConstant());
    CHECK_FALSE(randomModel({.codes = 9}, 2, 2, 5).residualConstant());
    CHECK(linear.decoderCost() == 27);
    CHECK(learnedShaderCost(linear).texelMultiplyAdds == 27);
    CHECK(learnedShaderCost(linear).frameMultiplyAdds ==
          learnedShaderCost(randomModel({.codes = 9}, 2, 2, 5)).frameMultiplyAdds - 9 * 24);
    CHECK(learnedShaderSource(linear, ShaderLanguage::Glsl, "linear").find("h1_0") == std::string::npos);
    // The largest network a GPU draws (BTFLUT_LEARNED_HIDDEN layers of BTFLUT_LEARNED_WIDTH) holds
    // fewer constants than every target's 64 KB; a larger one is refused (relit on the CPU).
    const LearnedModel largest =
        randomModel({.codes = 16, .hidden = std::vector<int>(BTFLUT_LEARNED_HIDDEN, BTFLUT_LEARNED_WIDTH)}, 2, 2, 3);
    CHECK(largest.fitsGpu());
    CHECK(learnedShaderCost(largest).constants <= kMaxShaderConstants);
    CHECK(hasLearnedShader(largest));
    CHECK_FALSE(LearnedPredictor(largest, true).shaderSource().empty());
    const LearnedModel wider = randomModel({.codes = 16, .hidden = {BTFLUT_LEARNED_WIDTH + 4}}, 2, 2, 3);
    CHECK_FALSE(wider.fitsGpu());
    CHECK_FALSE(hasLearnedShader(wider));
}

TEST_SUITE("gl") {
    TEST_CASE("learned shader: its frame per fragment and its values are the CPU's") {
        auto context = createHeadlessContext(GlBackend::Auto);
        if (!context.ok()) FAIL(context.error());
        // Each texel's value at the light, from the frame computed per fragment, as floats.
        const char* main = R"(
uniform sampler2DArray planes;
uniform vec3 lightTangent, viewTangent;
out vec4 colour;
void main() {
    vec4 codes[BTFLUT_MAX_LAYERS];
    for (int l = 0; l < BTFLUT_MAX_LAYERS; ++l)
        codes[l] = l < (BTFLUT_NETWORK_CODES + 3) / 4 ? floor(texelFetch(planes, ivec3(ivec2(gl_FragCoord.xy), l), 0) * 255.0 + 0.5) : vec4(0.0);
    colour = vec4(btflutNetworkValue(codes, btflutNetworkFrame(lightTangent, viewTangent)), 1.0);
}
)";
        for (const Shape& shape : {Shape{.codes = 9}, Shape{.codes = 6, .channels = 1},
                                   Shape{.codes = 4, .viewFeatures = kLearnedViewFeatures, .lightHidden = {16}},
                                   Shape{.codes = 9, .constantResidual = true}}) {
            const int w = 16, h = 8;
            const LearnedModel m = randomModel(shape, w, h, 11);
            const std::string source = learnedShaderSource(m, ShaderLanguage::Glsl, "test");
            Result<ShaderProgram> program =
                buildProgram({"quad.vert"}, {"btflut.glsl"}, {}, {{"decoder", source}, {"main", main}});
            REQUIRE_MESSAGE(program.ok(), program.error());
            const PredictorPlanes planes = LearnedPredictor(m, shape.channels == 3).planes();
            std::vector<std::uint8_t> bytes;
            for (const Image& layer : planes.layers)
                for (float v : layer.samples) bytes.push_back(static_cast<std::uint8_t>(std::lround(v * 255)));
            std::size_t uploaded = 0;
            const GlTexture codes =
                uploadTextureArray(w, h, static_cast<int>(planes.layers.size()), 4, bytes.data(), uploaded);
            GlTexture target = allocateTexture2D(w, h, GL_RGBA32F, GL_RGBA, GL_FLOAT);
            GlFramebuffer framebuffer = makeFramebuffer();
            gl.BindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
            gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target.id(), 0);
            GlVertexArray vertices = makeVertexArray();
            for (const auto& [light, view] : {std::pair{Direction::fromDegrees(30, 60), Direction{}},
                                              {Direction::fromDegrees(65, 250), Direction::fromDegrees(40, 10)}}) {
                gl.UseProgram(program->id());
                gl.ActiveTexture(GL_TEXTURE0);
                gl.BindTexture(GL_TEXTURE_2D_ARRAY, codes.id());
                gl.Uniform1i((*program)["planes"], 0);
                const Vec3 l = toVector(light), v = toVector(view);
                gl.Uniform3f((*program)["lightTangent"], static_cast<float>(l.x), static_cast<float>(l.y),
                             static_cast<float>(l.z));
                gl.Uniform3f((*program)["viewTangent"], static_cast<float>(v.x), static_cast<float>(v.y),
                             static_cast<float>(v.z));
                gl.Viewport(0, 0, w, h);
                gl.BindVertexArray(vertices.id());
                gl.DrawArrays(GL_TRIANGLES, 0, 3);
                std::vector<float> rgba(static_cast<std::size_t>(w) * h * 4);
                gl.ReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, rgba.data());
                // Row r of the target is texel row r (the planes are uploaded top row first).
                const std::vector<float> cpu = m.predict(light, {}, 1, view);
                double worst = 0;
                for (std::size_t i = 0; i < m.texels(); ++i)
                    for (int c = 0; c < 3; ++c)
                        worst = std::max(worst, std::abs(static_cast<double>(rgba[i * 4 + c]) -
                                                         cpu[i * static_cast<std::size_t>(m.channels) +
                                                             static_cast<std::size_t>(shape.channels == 3 ? c : 0)]));
                INFO("codes " << shape.codes << ", channels " << shape.channels << ", views " << shape.viewFeatures
                              << ": worst " << worst);
                CHECK(worst < 1e-4);
            }
        }
    }
}

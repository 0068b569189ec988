// What an engine does with a material from `btflut export M.btflut -o DIR/`: load the
// sidecar and the textures it names, include shaders/btflut.glsl, and draw a lit quad. Every
// kind: "luts" (the reference and its LUTs), "model" (a light model's planes: ptm, hsh, rbf,
// bln), "references" (references blended) and "learned" (codes and a decoder, specialised to the
// material in btflut_network.glsl), the last three with their match LUTs.
// It depends on nothing of btflut: EGL (headless), OpenGL 3.3 core, stb_image, nlohmann-json.
//
//   btflut_example_quad DIR --light THETA,PHI -o out.png [--no-dither]
//
// The quad covers the reference texel for pixel (frontal, 1:1), so the output can be compared
// with `btflut relight` (CI does: within 2/255). MIT licence, like btflut.glsl.
#define GL_GLEXT_PROTOTYPES
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace {

[[noreturn]] void fail(const std::string& what) {
    std::fprintf(stderr, "btflut_example_quad: error: %s\n", what.c_str());
    std::exit(1);
}

std::string readText(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path + ": cannot open");
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// A headless OpenGL 3.3 core context (Mesa's surfaceless platform, or the default display).
struct Context {
    EGLDisplay display;
    EGLContext context;
};

Context createContext() {
    auto getPlatformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    EGLDisplay display = getPlatformDisplay
                             ? getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr)
                             : eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (display == EGL_NO_DISPLAY || !eglInitialize(display, nullptr, nullptr) || !eglBindAPI(EGL_OPENGL_API))
        fail("EGL: no display with desktop OpenGL");
    const EGLint configAttributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT,
                                       EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!eglChooseConfig(display, configAttributes, &config, 1, &count) || count == 0) fail("EGL: no OpenGL config");
    const EGLint contextAttributes[] = {
        EGL_CONTEXT_MAJOR_VERSION,           3,       EGL_CONTEXT_MINOR_VERSION, 3, EGL_CONTEXT_OPENGL_PROFILE_MASK,
        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttributes);
    if (context == EGL_NO_CONTEXT || !eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context))
        fail("EGL: cannot make an OpenGL 3.3 core context current");
    return {display, context};
}

GLuint compile(GLenum type, const std::string& source) {
    const GLuint shader = glCreateShader(type);
    const char* text = source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[4096];
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        fail(std::string("shader: ") + log);
    }
    return shader;
}

const char* const kVertex = R"(#version 330 core
void main() {  // one triangle over the whole target
    vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
)";

// After btflut.glsl: the engine's fragment shader, for a bank of LUTs.
const char* const kFragment = R"(
uniform sampler2D reference;
uniform sampler3D luts;
uniform vec3 light;  // tangent frame
uniform BtflutMaterial material;
out vec4 colour;
void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);  // framebuffer row r = image row r (uploaded top row first)
    vec3 value = texelFetch(reference, texel, 0).rgb;
    colour = vec4(btflutRelight(luts, material, value, light, uvec2(texel)), 1.0);
}
)";

// ... and for a bank with a predictor: the planes sampled at the texel's centre.
const char* const kPredictorFragment = R"(
uniform sampler3D luts;
uniform sampler2DArray planes;
uniform sampler2DArray weights;
uniform sampler2D labels;
uniform BtflutPredictor predictor;
uniform vec3 light;
uniform vec3 view;  // a learned model of views reads it, and the LUTs of its nearest view layer
uniform int layer;
out vec4 colour;
void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    vec2 uv = (vec2(texel) + 0.5) / vec2(textureSize(planes, 0).xy);
    colour = vec4(btflutRelight(luts, planes, weights, labels, predictor, uv, light, view, layer, uvec2(texel)), 1.0);
}
)";

// ... and for a learned material with its decoder specialised to it (material.json's
// "network": btflut_network.glsl, after the include): its frame at the light computed per
// fragment, as a point light or a curved mesh needs (under a directional light a flat quad's
// frame is one per light change: an engine may compute it once, on the CPU, as a uniform).
const char* const kNetworkFragment = R"(
uniform sampler3D luts;
uniform sampler2DArray planes;
uniform sampler2D labels;
uniform BtflutPredictor predictor;
uniform vec3 light;
uniform vec3 view;
uniform int layer;
out vec4 colour;
void main() {
    ivec2 texel = ivec2(gl_FragCoord.xy);
    vec2 uv = (vec2(texel) + 0.5) / vec2(textureSize(planes, 0).xy);
    BtflutPrediction predicted = btflutNetworkPrediction(planes, uv, btflutNetworkFrame(light, view));
    colour = vec4(btflutRelightPrediction(luts, planes, labels, predictor, uv, light, layer, uvec2(texel), predicted), 1.0);
}
)";

// A direction (degrees) as a unit vector of the tangent frame.
std::array<float, 3> unitVector(double thetaDegrees, double phiDegrees) {
    const double t = thetaDegrees * M_PI / 180, p = phiDegrees * M_PI / 180;
    return {static_cast<float>(std::sin(t) * std::cos(p)), static_cast<float>(std::sin(t) * std::sin(p)),
            static_cast<float>(std::cos(t))};
}

// The version the shader include declares (#define BTFLUT_GLSL_VERSION N); 0 if none.
int includeVersion(const std::string& text) {
    const std::string key = "#define BTFLUT_GLSL_VERSION";
    const std::size_t at = text.find(key);
    return at == std::string::npos ? 0 : std::atoi(text.c_str() + at + key.size());
}

// A texture of one value per texel for a sampler the material does not use.
void bindUnused(GLenum target, GLuint texture) {
    glBindTexture(target, texture);
    const float zero[4] = {0, 0, 0, 0};
    if (target == GL_TEXTURE_2D_ARRAY)
        glTexImage3D(target, 0, GL_RGBA32F, 1, 1, 1, 0, GL_RGBA, GL_FLOAT, zero);
    else
        glTexImage2D(target, 0, GL_R8, 1, 1, 0, GL_RED, GL_FLOAT, zero);
    glTexParameteri(target, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
}

// The predictor's textures (units 2 .. 4) and uniforms, as material.json describes them;
// `w` and `h` get the planes' size.
void setUpPredictor(GLuint program, const std::string& folder, const nlohmann::json& p, const GLuint textures[3],
                    int& w, int& h) {
    // The planes (or references), then the albedo: layers of one RGBA8 array, linear, repeating.
    std::vector<std::string> files = p["images"].get<std::vector<std::string>>();
    if (p.contains("albedo")) files.push_back(p["albedo"]["file"]);
    std::vector<unsigned char> layers;
    for (const std::string& name : files) {
        int iw = 0, ih = 0, ic = 0;
        stbi_uc* image = stbi_load((folder + "/" + name).c_str(), &iw, &ih, &ic, 4);
        if (!image) fail(folder + "/" + name + ": cannot decode");
        if (layers.empty()) w = iw, h = ih;
        if (iw != w || ih != h) fail(folder + "/" + name + ": not the size of the other planes");
        layers.insert(layers.end(), image, image + static_cast<std::size_t>(w) * h * 4);
        stbi_image_free(image);
    }
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_2D_ARRAY, textures[0]);
    glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA8, w, h, static_cast<GLsizei>(files.size()), 0, GL_RGBA,
                 GL_UNSIGNED_BYTE, layers.data());
    for (GLenum f : {GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER}) glTexParameteri(GL_TEXTURE_2D_ARRAY, f, GL_LINEAR);
    // The weights over the light disk: float32 RGBA layers, read exactly (texelFetch).
    glActiveTexture(GL_TEXTURE3);
    if (p["weights"].is_null()) {
        bindUnused(GL_TEXTURE_2D_ARRAY, textures[1]);
    } else {
        const nlohmann::json& weights = p["weights"];
        const int size = weights["grid_size"], count = weights["layers"];
        const std::string path = folder + "/" + weights["file"].get<std::string>(), bytes = readText(path);
        if (bytes.size() != static_cast<std::size_t>(size) * size * count * 4 * sizeof(float))
            fail(path + ": not the " + std::to_string(size) + "x" + std::to_string(size) + "x" + std::to_string(count) +
                 " RGBA float32 layers material.json describes");
        glBindTexture(GL_TEXTURE_2D_ARRAY, textures[1]);
        glTexImage3D(GL_TEXTURE_2D_ARRAY, 0, GL_RGBA32F, size, size, count, 0, GL_RGBA, GL_FLOAT, bytes.data());
        for (GLenum f : {GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER})
            glTexParameteri(GL_TEXTURE_2D_ARRAY, f, GL_NEAREST);
    }
    // Each texel's region.
    glActiveTexture(GL_TEXTURE4);
    if (!p.contains("labels")) {
        bindUnused(GL_TEXTURE_2D, textures[2]);
    } else {
        int lw = 0, lh = 0, lc = 0;
        const std::string path = folder + "/" + p["labels"]["file"].get<std::string>();
        stbi_uc* labels = stbi_load(path.c_str(), &lw, &lh, &lc, 1);
        if (!labels || lw != w || lh != h) fail(path + ": cannot decode, or not the planes' size");
        glBindTexture(GL_TEXTURE_2D, textures[2]);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, lw, lh, 0, GL_RED, GL_UNSIGNED_BYTE, labels);
        for (GLenum f : {GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER}) glTexParameteri(GL_TEXTURE_2D, f, GL_NEAREST);
        stbi_image_free(labels);
    }
    auto uniform = [&](const std::string& name) {
        return glGetUniformLocation(program, ("predictor." + name).c_str());
    };
    const bool model = p["kind"] == "model";
    glUniform1i(glGetUniformLocation(program, "planes"), 2);
    glUniform1i(glGetUniformLocation(program, "weights"), 3);
    glUniform1i(glGetUniformLocation(program, "labels"), 4);
    glUniform1i(uniform("kind"), p["kind_index"].get<int>());  // BTFLUT_KIND_MODEL, _REFERENCES, _LEARNED
    glUniform1i(uniform("basis"), model ? p["basis_index"].get<int>() : 0);
    glUniform1i(uniform("order"), p.value("order", 0));
    glUniform1i(uniform("planes"), p["planes"].get<int>());
    glUniform1i(uniform("channels"), p["channels"].get<int>());
    glUniform1i(uniform("albedo"), !p.contains("albedo") ? 0 : p["albedo"]["use"] == "multiplies" ? 1 : 2);
    if (p.contains("scale"))  // a model's planes, a learned model's codes
        for (std::size_t k = 0; k < p["scale"].size(); ++k) {
            glUniform1f(uniform("scale[" + std::to_string(k) + "]"), p["scale"][k].get<float>());
            glUniform1f(uniform("bias[" + std::to_string(k) + "]"), p["bias"][k].get<float>());
        }
    glUniform1i(uniform("regions"), p["regions"].get<int>());
    glUniform1f(uniform("codes"), p["codes"].get<float>());
    glUniform1i(uniform("greyOutput"), p["output_channels"] == 1);
}

}  // namespace

int main(int argc, char** argv) {
    const std::string usage =
        "usage: btflut_example_quad DIR --light THETA,PHI [--view THETA,PHI] -o out.png [--no-dither]";
    std::string folder, output, lightText, viewText;
    bool dither = true;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--light" && i + 1 < argc)
            lightText = argv[++i];
        else if (a == "--view" && i + 1 < argc)
            viewText = argv[++i];
        else if (a == "-o" && i + 1 < argc)
            output = argv[++i];
        else if (a == "--no-dither")
            dither = false;
        else if (folder.empty() && a[0] != '-')
            folder = a;
        else
            fail(usage);
    }
    double theta = 0, phi = 0;
    if (folder.empty() || output.empty() || std::sscanf(lightText.c_str(), "%lf,%lf", &theta, &phi) != 2) fail(usage);

    // The sidecar says what the textures hold; this program reads versions 1 and 2.
    const std::string sidecar = folder + "/material.json";
    const nlohmann::json material = nlohmann::json::parse(readText(sidecar), nullptr, false);
    if (material.is_discarded() || material.value("format", "") != "btflut-material")
        fail(sidecar + ": not a btflut material");
    if (const int version = material.value("version", 0); version < 1 || version > 2)
        fail(sidecar + ": version " + std::to_string(version) + ", this program reads versions 1 and 2");
    const std::string shaderPath = folder + "/" + material["shader"].get<std::string>(), include = readText(shaderPath);
    if (const int have = includeVersion(include), need = material.value("shader_version", 1); have < need)
        fail(shaderPath + ": the shader include is version " + std::to_string(have) + ", older than the version " +
             std::to_string(need) + " material.json needs (copy the btflut.glsl that export wrote)");
    const std::string kind = material.value("kind", "luts");
    const bool predictor = kind != "luts";
    const int entries = material["luts"]["entries"], grid = material["luts"]["grid_size"];
    // A block per view layer, and with a predictor per region of each.
    const int blocks = material["luts"]["layers"].get<int>() * (predictor ? material["luts"]["regions"].get<int>() : 1);
    int lw = 0, lh = 0, lc = 0;
    stbi_us* luts = stbi_load_16((folder + "/luts.png").c_str(), &lw, &lh, &lc, 0);
    if (!luts || lw != entries || lh != grid * grid * blocks)
        fail(folder + "/luts.png: not the texture material.json describes");

    const Context egl = createContext();
    const GLenum format[] = {0, GL_RED, GL_RG, GL_RGB, GL_RGBA};
    GLuint textures[5];
    glGenTextures(5, textures);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    // The LUT grid: the PNG's rows are the 3D texture's (entries x G x G * blocks) memory.
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_3D, textures[1]);
    glTexImage3D(GL_TEXTURE_3D, 0, lc == 1 ? GL_R16 : GL_RGB16, entries, grid, grid * blocks, 0, format[lc],
                 GL_UNSIGNED_SHORT, luts);
    for (GLenum p : {GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER}) glTexParameteri(GL_TEXTURE_3D, p, GL_LINEAR);
    for (GLenum p : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTexParameteri(GL_TEXTURE_3D, p, GL_CLAMP_TO_EDGE);
    stbi_image_free(luts);

    // A learned material's specialised decoder, where export wrote one.
    const nlohmann::json* network =
        predictor && material["predictor"].contains("network") ? &material["predictor"]["network"] : nullptr;
    const std::string main = network ? readText(folder + "/" + (*network)["glsl"].get<std::string>()) + kNetworkFragment
                             : predictor ? kPredictorFragment
                                         : kFragment;
    const GLuint program = glCreateProgram();
    glAttachShader(program, compile(GL_VERTEX_SHADER, kVertex));
    glAttachShader(program, compile(GL_FRAGMENT_SHADER, "#version 330 core\n" + include + main));
    glLinkProgram(program);
    glUseProgram(program);
    glUniform1i(glGetUniformLocation(program, "luts"), 1);
    glUniform3fv(glGetUniformLocation(program, "light"), 1, unitVector(theta, phi).data());
    // The view (default: the reference's) and the view layer nearest it, whose LUTs are read.
    double viewTheta = material["reference"]["view"]["theta"], viewPhi = material["reference"]["view"]["phi"];
    if (!viewText.empty() && std::sscanf(viewText.c_str(), "%lf,%lf", &viewTheta, &viewPhi) != 2) fail(usage);
    const std::array<float, 3> view = unitVector(viewTheta, viewPhi);
    int layer = 0;
    float nearest = -2;
    for (std::size_t k = 0; k < material["views"].size(); ++k) {
        const nlohmann::json& v = material["views"][k]["view"];
        const std::array<float, 3> d = unitVector(v["theta"], v["phi"]);
        if (const float c = d[0] * view[0] + d[1] * view[1] + d[2] * view[2]; c > nearest)
            nearest = c, layer = static_cast<int>(k);
    }
    glUniform3fv(glGetUniformLocation(program, "view"), 1, view.data());
    glUniform1i(glGetUniformLocation(program, "layer"), layer);
    const bool rgbLuts = material["colour"] == "rgb";
    int w = 0, h = 0, channels = 0;
    if (predictor) {
        const nlohmann::json& settings = material["predictor"];
        setUpPredictor(program, folder, settings, textures + 2, w, h);
        channels = settings["output_channels"];
        glUniform1i(glGetUniformLocation(program, "predictor.rgbLuts"), rgbLuts);
        glUniform1f(glGetUniformLocation(program, "predictor.outputCode"), material["lut_output_code"].get<float>());
        glUniform1i(glGetUniformLocation(program, "predictor.dither"), dither);
    } else {
        const bool deep = material["reference"]["bit_depth"] == 16;
        const std::string path = folder + "/reference.png";
        void* reference = deep ? static_cast<void*>(stbi_load_16(path.c_str(), &w, &h, &channels, 0))
                               : static_cast<void*>(stbi_load(path.c_str(), &w, &h, &channels, 0));
        if (!reference) fail(path + ": cannot decode");
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, textures[0]);
        const GLint internal = deep ? (channels == 1 ? GL_R16 : GL_RGB16) : (channels == 1 ? GL_R8 : GL_RGB8);
        glTexImage2D(GL_TEXTURE_2D, 0, internal, w, h, 0, format[channels], deep ? GL_UNSIGNED_SHORT : GL_UNSIGNED_BYTE,
                     reference);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        stbi_image_free(reference);
        glUniform1i(glGetUniformLocation(program, "reference"), 0);
        glUniform1i(glGetUniformLocation(program, "material.layer"), layer);
        glUniform1i(glGetUniformLocation(program, "material.rgbLuts"), rgbLuts);
        glUniform1i(glGetUniformLocation(program, "material.greyReference"), channels == 1);
        glUniform1f(glGetUniformLocation(program, "material.inputCode"), material["lut_input_code"].get<float>());
        glUniform1f(glGetUniformLocation(program, "material.outputCode"), material["lut_output_code"].get<float>());
        glUniform1i(glGetUniformLocation(program, "material.dither"), dither);
    }

    GLuint framebuffer, target, vertexArray;
    glGenFramebuffers(1, &framebuffer);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glGenRenderbuffers(1, &target);
    glBindRenderbuffer(GL_RENDERBUFFER, target);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, target);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) fail("framebuffer incomplete");
    glGenVertexArrays(1, &vertexArray);
    glBindVertexArray(vertexArray);
    glViewport(0, 0, w, h);
    glDrawArrays(GL_TRIANGLES, 0, 3);

    std::vector<unsigned char> rgba(static_cast<std::size_t>(w) * h * 4),
        out(static_cast<std::size_t>(w) * h * channels);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    if (glGetError() != GL_NO_ERROR) fail("OpenGL error");
    for (std::size_t i = 0; i < static_cast<std::size_t>(w) * h; ++i)
        for (int c = 0; c < channels; ++c) out[i * channels + c] = rgba[i * 4 + c];
    if (!stbi_write_png(output.c_str(), w, h, channels, out.data(), w * channels)) fail(output + ": cannot write");
    std::printf("wrote %s (%dx%d, %s material)\n", output.c_str(), w, h, kind.c_str());

    glDeleteVertexArrays(1, &vertexArray);
    glDeleteRenderbuffers(1, &target);
    glDeleteFramebuffers(1, &framebuffer);
    glDeleteProgram(program);
    glDeleteTextures(5, textures);
    eglMakeCurrent(egl.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(egl.display, egl.context);
    eglTerminate(egl.display);
    return 0;
}

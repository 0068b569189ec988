// What an engine does with a material from `btflut export M.btflut -o DIR/`: load the
// reference, the LUT texture and the sidecar, include shaders/btflut.glsl, and draw a lit quad.
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

#include <cmath>
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
    auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    EGLDisplay display = getPlatformDisplay ? getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr)
                                            : eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (display == EGL_NO_DISPLAY || !eglInitialize(display, nullptr, nullptr) || !eglBindAPI(EGL_OPENGL_API))
        fail("EGL: no display with desktop OpenGL");
    const EGLint configAttributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (!eglChooseConfig(display, configAttributes, &config, 1, &count) || count == 0) fail("EGL: no OpenGL config");
    const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
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

// After btflut.glsl: the engine's fragment shader.
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

}  // namespace

int main(int argc, char** argv) {
    std::string folder, output, lightText;
    bool dither = true;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--light" && i + 1 < argc) lightText = argv[++i];
        else if (a == "-o" && i + 1 < argc) output = argv[++i];
        else if (a == "--no-dither") dither = false;
        else if (folder.empty() && a[0] != '-') folder = a;
        else fail("usage: btflut_example_quad DIR --light THETA,PHI -o out.png [--no-dither]");
    }
    double theta = 0, phi = 0;
    if (folder.empty() || output.empty() || std::sscanf(lightText.c_str(), "%lf,%lf", &theta, &phi) != 2)
        fail("usage: btflut_example_quad DIR --light THETA,PHI -o out.png [--no-dither]");

    // The sidecar says what the textures hold.
    const nlohmann::json material = nlohmann::json::parse(readText(folder + "/material.json"), nullptr, false);
    if (material.is_discarded() || material.value("format", "") != "btflut-material" || material.value("version", 0) != 1)
        fail(folder + "/material.json: not a version 1 btflut material");
    const int entries = material["luts"]["entries"], grid = material["luts"]["grid_size"], layers = material["luts"]["layers"];
    const bool rgbLuts = material["colour"] == "rgb";

    int w = 0, h = 0, channels = 0;
    const bool deep = material["reference"]["bit_depth"] == 16;
    void* reference = deep ? static_cast<void*>(stbi_load_16((folder + "/reference.png").c_str(), &w, &h, &channels, 0))
                           : static_cast<void*>(stbi_load((folder + "/reference.png").c_str(), &w, &h, &channels, 0));
    if (!reference) fail(folder + "/reference.png: cannot decode");
    int lw = 0, lh = 0, lc = 0;
    stbi_us* luts = stbi_load_16((folder + "/luts.png").c_str(), &lw, &lh, &lc, 0);
    if (!luts || lw != entries || lh != grid * grid * layers) fail(folder + "/luts.png: not the texture material.json describes");

    const Context egl = createContext();
    const GLenum format[] = {0, GL_RED, GL_RG, GL_RGB, GL_RGBA};
    GLuint textures[2];
    glGenTextures(2, textures);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, textures[0]);
    const GLint internal = deep ? (channels == 1 ? GL_R16 : GL_RGB16) : (channels == 1 ? GL_R8 : GL_RGB8);
    glTexImage2D(GL_TEXTURE_2D, 0, internal, w, h, 0, format[channels], deep ? GL_UNSIGNED_SHORT : GL_UNSIGNED_BYTE, reference);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    // The LUT grid: the PNG's rows are the 3D texture's (entries x G x G * layers) memory.
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_3D, textures[1]);
    glTexImage3D(GL_TEXTURE_3D, 0, lc == 1 ? GL_R16 : GL_RGB16, entries, grid, grid * layers, 0, format[lc], GL_UNSIGNED_SHORT, luts);
    for (GLenum p : {GL_TEXTURE_MIN_FILTER, GL_TEXTURE_MAG_FILTER}) glTexParameteri(GL_TEXTURE_3D, p, GL_LINEAR);
    for (GLenum p : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R}) glTexParameteri(GL_TEXTURE_3D, p, GL_CLAMP_TO_EDGE);

    const GLuint program = glCreateProgram();
    glAttachShader(program, compile(GL_VERTEX_SHADER, kVertex));
    glAttachShader(program, compile(GL_FRAGMENT_SHADER, "#version 330 core\n" + readText(folder + "/" + material["shader"].get<std::string>()) + kFragment));
    glLinkProgram(program);
    glUseProgram(program);
    glUniform1i(glGetUniformLocation(program, "reference"), 0);
    glUniform1i(glGetUniformLocation(program, "luts"), 1);
    const double t = theta * M_PI / 180, p = phi * M_PI / 180;
    glUniform3f(glGetUniformLocation(program, "light"), static_cast<float>(std::sin(t) * std::cos(p)),
                static_cast<float>(std::sin(t) * std::sin(p)), static_cast<float>(std::cos(t)));
    glUniform1i(glGetUniformLocation(program, "material.layer"), 0);
    glUniform1i(glGetUniformLocation(program, "material.rgbLuts"), rgbLuts);
    glUniform1i(glGetUniformLocation(program, "material.greyReference"), channels == 1);
    glUniform1f(glGetUniformLocation(program, "material.inputCode"), material["lut_input_code"].get<float>());
    glUniform1f(glGetUniformLocation(program, "material.outputCode"), material["lut_output_code"].get<float>());
    glUniform1i(glGetUniformLocation(program, "material.dither"), dither);

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

    std::vector<unsigned char> rgba(static_cast<std::size_t>(w) * h * 4), out(static_cast<std::size_t>(w) * h * channels);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    if (glGetError() != GL_NO_ERROR) fail("OpenGL error");
    for (std::size_t i = 0; i < static_cast<std::size_t>(w) * h; ++i)
        for (int c = 0; c < channels; ++c) out[i * channels + c] = rgba[i * 4 + c];
    if (!stbi_write_png(output.c_str(), w, h, channels, out.data(), w * channels)) fail(output + ": cannot write");
    std::printf("wrote %s (%dx%d)\n", output.c_str(), w, h);

    glDeleteVertexArrays(1, &vertexArray);
    glDeleteRenderbuffers(1, &target);
    glDeleteFramebuffers(1, &framebuffer);
    glDeleteProgram(program);
    glDeleteTextures(2, textures);
    stbi_image_free(reference);
    stbi_image_free(luts);
    eglMakeCurrent(egl.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(egl.display, egl.context);
    eglTerminate(egl.display);
    return 0;
}

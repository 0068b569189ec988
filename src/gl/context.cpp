#include "gl/context.h"

#include <dlfcn.h>
#include <sys/resource.h>
#include <unistd.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/osmesa.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "gl/gl_api.h"

namespace btflut {

namespace {

std::string glStrings() {
    auto str = [](GLenum e) {
        const GLubyte* s = gl.GetString(e);
        return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
    };
    return str(GL_RENDERER) + ", OpenGL " + str(GL_VERSION);
}

}  // namespace

bool softwareRasteriser() {
    const auto* name = reinterpret_cast<const char*>(gl.GetString(GL_RENDERER));
    const std::string renderer = name ? name : "";
    for (const char* software : {"llvmpipe", "softpipe", "SwiftShader", "swrast"})
        if (renderer.find(software) != std::string::npos) return true;
    return false;
}

namespace {

// OSMesa brings LLVM with it (tens of megabytes to relocate), so it is loaded when an OSMesa
// context is wanted, not when btflut starts: commands without OpenGL start in milliseconds.
struct OsMesaApi {
    decltype(&OSMesaCreateContextAttribs) createContextAttribs = nullptr;
    decltype(&OSMesaMakeCurrent) makeCurrent = nullptr;
    decltype(&OSMesaGetProcAddress) getProcAddress = nullptr;
    decltype(&OSMesaDestroyContext) destroyContext = nullptr;
};

const OsMesaApi* osMesa() {
    static const OsMesaApi api = [] {
        OsMesaApi a;
        void* library = ::dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);  // never closed
        if (!library) return a;
        a.createContextAttribs =
            reinterpret_cast<decltype(a.createContextAttribs)>(::dlsym(library, "OSMesaCreateContextAttribs"));
        a.makeCurrent = reinterpret_cast<decltype(a.makeCurrent)>(::dlsym(library, "OSMesaMakeCurrent"));
        a.getProcAddress = reinterpret_cast<decltype(a.getProcAddress)>(::dlsym(library, "OSMesaGetProcAddress"));
        a.destroyContext = reinterpret_cast<decltype(a.destroyContext)>(::dlsym(library, "OSMesaDestroyContext"));
        if (!a.createContextAttribs || !a.makeCurrent || !a.getProcAddress || !a.destroyContext) a = {};
        return a;
    }();
    return api.createContextAttribs ? &api : nullptr;
}

class OsMesaContext : public HeadlessContext {
public:
    static Result<std::unique_ptr<HeadlessContext>> create() {
        if (!osMesa()) return Error{"OSMesa: cannot load libOSMesa.so.8 (Debian package libosmesa6)"};
        const int attributes[] = {OSMESA_FORMAT,
                                  OSMESA_RGBA,
                                  OSMESA_DEPTH_BITS,
                                  0,
                                  OSMESA_PROFILE,
                                  OSMESA_CORE_PROFILE,
                                  OSMESA_CONTEXT_MAJOR_VERSION,
                                  3,
                                  OSMESA_CONTEXT_MINOR_VERSION,
                                  3,
                                  0};
        std::unique_ptr<OsMesaContext> c(new OsMesaContext());
        c->m_context = osMesa()->createContextAttribs(attributes, nullptr);
        if (!c->m_context) return Error{"OSMesa: cannot create an OpenGL 3.3 core context"};
        // Drawing goes to framebuffer objects; OSMesa still wants a buffer to be current.
        if (!osMesa()->makeCurrent(c->m_context, c->m_pixel.data(), GL_UNSIGNED_BYTE, 1, 1))
            return Error{"OSMesa: cannot make the context current"};
        if (const char* missing =
                loadGlFunctions([](const char* n) { return reinterpret_cast<void*>(osMesa()->getProcAddress(n)); }))
            return Error{std::string("OSMesa: missing ") + missing};
        return std::unique_ptr<HeadlessContext>(std::move(c));
    }
    ~OsMesaContext() override {
        if (m_context) osMesa()->destroyContext(m_context);
    }
    std::string description() const override { return "osmesa (" + glStrings() + ")"; }

private:
    OsMesaContext() : m_pixel(4) {}
    ::OSMesaContext m_context = nullptr;
    std::vector<unsigned char> m_pixel;
};

class EglContext : public HeadlessContext {
public:
    static Result<std::unique_ptr<HeadlessContext>> create() {
        std::unique_ptr<EglContext> c(new EglContext());
        auto getPlatformDisplay =
            reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
        c->m_display = getPlatformDisplay
                           ? getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr)
                           : eglGetDisplay(EGL_DEFAULT_DISPLAY);
        if (c->m_display == EGL_NO_DISPLAY) return Error{"EGL: no display"};
        if (!eglInitialize(c->m_display, nullptr, nullptr)) return Error{"EGL: cannot initialise the display"};
        c->m_initialised = true;
        if (!eglBindAPI(EGL_OPENGL_API)) return Error{"EGL: no desktop OpenGL API"};
        // eglChooseConfig defaults to window surfaces, which a surfaceless display has none of.
        const EGLint configAttributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT,
                                           EGL_NONE};
        EGLConfig config = nullptr;
        EGLint count = 0;
        if (!eglChooseConfig(c->m_display, configAttributes, &config, 1, &count) || count == 0)
            return Error{"EGL: no OpenGL config"};
        const EGLint contextAttributes[] = {
            EGL_CONTEXT_MAJOR_VERSION,           3,       EGL_CONTEXT_MINOR_VERSION, 3, EGL_CONTEXT_OPENGL_PROFILE_MASK,
            EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
        c->m_context = eglCreateContext(c->m_display, config, EGL_NO_CONTEXT, contextAttributes);
        if (c->m_context == EGL_NO_CONTEXT) return Error{"EGL: cannot create an OpenGL 3.3 core context"};
        if (!eglMakeCurrent(c->m_display, EGL_NO_SURFACE, EGL_NO_SURFACE, c->m_context))
            return Error{"EGL: cannot make a surfaceless context current"};
        if (const char* missing =
                loadGlFunctions([](const char* n) { return reinterpret_cast<void*>(eglGetProcAddress(n)); }))
            return Error{std::string("EGL: missing ") + missing};
        return std::unique_ptr<HeadlessContext>(std::move(c));
    }
    ~EglContext() override {
        if (m_context != EGL_NO_CONTEXT) {
            eglMakeCurrent(m_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            eglDestroyContext(m_display, m_context);
        }
        if (m_initialised) eglTerminate(m_display);
    }
    std::string description() const override { return "egl (" + glStrings() + ")"; }

private:
    EGLDisplay m_display = EGL_NO_DISPLAY;
    EGLContext m_context = EGL_NO_CONTEXT;
    bool m_initialised = false;
};

}  // namespace

Result<GlBackend> parseGlBackend(const std::string& name) {
    if (name == "auto") return GlBackend::Auto;
    if (name == "osmesa") return GlBackend::OsMesa;
    if (name == "egl") return GlBackend::Egl;
    return Error{"--backend '" + name + "' is not auto, osmesa or egl"};
}

void keepGlDriversLoadedForLeakChecks() {
#ifdef BTFLUT_SANITIZE
    // LeakSanitizer reports at exit, after Mesa has unloaded its driver modules, so the
    // allocations Mesa keeps until exit would come from no named module, and the
    // suppressions (tests/sanitizers/lsan.supp) could not match them. Loading the modules
    // once more with RTLD_NODELETE keeps them (the driver's own loads reuse them).
    static const bool pinned = [] {
        for (const char* module : {"libEGL_mesa.so.0", "libGLX_mesa.so.0", BTFLUT_DRI_DIR "/swrast_dri.so"})
            ::dlopen(module, RTLD_LAZY | RTLD_LOCAL | RTLD_NODELETE);
        return true;
    }();
    (void)pinned;
#endif
}

namespace {

// Under an address-space limit (ulimit -v) Mesa's llvmpipe fails to map memory in its shader
// compiler and rasteriser without a message, then dereferences what it did not get: a
// segmentation fault with no line. Where a limit is set, such a signal ends btflut with one
// line and exit 1 instead (written with write(2), which is safe in a signal handler). Without
// a limit signals are left alone, for debuggers and sanitizers.
char g_outOfMemoryLine[256];
std::size_t g_outOfMemoryLength = 0;

extern "C" void reportOutOfMemory(int) {
    if (::write(STDERR_FILENO, g_outOfMemoryLine, g_outOfMemoryLength) < 0) {
        // nothing more can be said
    }
    ::_exit(1);
}

// The address-space limit in MB, 0 for none.
unsigned long long addressSpaceLimitMb() {
    rlimit limit{};
    if (::getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return 0;
    return static_cast<unsigned long long>(limit.rlim_cur >> 20);
}

void reportDriverCrashesUnderMemoryLimit() {
    const unsigned long long mb = addressSpaceLimitMb();
    if (mb == 0 || g_outOfMemoryLength > 0) return;
    const int written = std::snprintf(g_outOfMemoryLine, sizeof g_outOfMemoryLine,
                                      "btflut: error: out of memory in the OpenGL driver under the address-space "
                                      "limit of %llu MB (ulimit -v); raise it (1 GB renders the bundled material)\n",
                                      mb);
    if (written <= 0) return;
    g_outOfMemoryLength = std::min(static_cast<std::size_t>(written), sizeof g_outOfMemoryLine - 1);
    struct sigaction action {};
    action.sa_handler = reportOutOfMemory;
    sigemptyset(&action.sa_mask);
    ::sigaction(SIGSEGV, &action, nullptr);
    ::sigaction(SIGBUS, &action, nullptr);
}

}  // namespace

Result<std::unique_ptr<HeadlessContext>> createHeadlessContext(GlBackend backend) {
    keepGlDriversLoadedForLeakChecks();
    reportDriverCrashesUnderMemoryLimit();
    // Mesa's EGL warns on stderr of each driver it fails to load ("libEGL warning: MESA-LOADER:
    // failed to open ..."), before btflut's own line says what failed: quiet unless asked for.
    ::setenv("EGL_LOG_LEVEL", "fatal", 0);
    if (backend == GlBackend::OsMesa) return OsMesaContext::create();
    if (backend == GlBackend::Egl) return EglContext::create();
    Result<std::unique_ptr<HeadlessContext>> egl = EglContext::create();
    if (egl) return egl;
    Result<std::unique_ptr<HeadlessContext>> osmesa = OsMesaContext::create();
    if (osmesa) return osmesa;
    const unsigned long long mb = addressSpaceLimitMb();
    return Error{"no OpenGL context: " + egl.error() + "; " + osmesa.error() +
                 (mb > 0 ? " (under the address-space limit of " + std::to_string(mb) +
                               " MB, ulimit -v: most likely out of memory)"
                         : "")};
}

}  // namespace btflut

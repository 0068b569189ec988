#include "viewer/window.h"

#include <GLFW/glfw3.h>

#include "gl/context.h"
#include "gl/gl_api.h"

namespace btflut {

namespace {

std::string g_lastGlfwError;

void recordGlfwError(int, const char* description) { g_lastGlfwError = description ? description : "unknown error"; }

}  // namespace

Result<std::unique_ptr<Window>> Window::create(int width, int height, const std::string& title, bool vsync) {
    glfwSetErrorCallback(recordGlfwError);
    g_lastGlfwError.clear();
    keepGlDriversLoadedForLeakChecks();
    if (!glfwInit())
        return Error{"no display (" + (g_lastGlfwError.empty() ? std::string("GLFW cannot start") : g_lastGlfwError) +
                     "): btflut view needs a window; for headless rendering use `btflut render`"};
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    std::unique_ptr<Window> w(new Window());
    w->m_window = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
    if (!w->m_window)
        return Error{"cannot open an OpenGL 3.3 window (" + g_lastGlfwError +
                     "); for headless rendering use `btflut render`"};
    glfwMakeContextCurrent(w->m_window);
    glfwSwapInterval(vsync ? 1 : 0);
    if (const char* missing =
            loadGlFunctions([](const char* name) { return reinterpret_cast<void*>(glfwGetProcAddress(name)); }))
        return Error{std::string("the window's OpenGL context lacks ") + missing};
    return w;
}

Window::~Window() {
    if (m_window) glfwDestroyWindow(m_window);
    glfwTerminate();
}

std::string Window::description() const {
    auto str = [](GLenum e) {
        const GLubyte* s = gl.GetString(e);
        return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
    };
    return str(GL_RENDERER) + ", OpenGL " + str(GL_VERSION);
}

}  // namespace btflut

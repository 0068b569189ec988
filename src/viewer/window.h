#pragma once
// The viewer's window: GLFW with an OpenGL 3.3 core context, current on this thread, gl.*
// loaded from it. Apart from the headless contexts (gl/context.h) so the renderer never
// knows which kind of context it draws in.
//
//   Result<std::unique_ptr<Window>> w = Window::create(1280, 800, "btflut", true);

#include <memory>
#include <string>

#include "core/result.h"

struct GLFWwindow;

namespace btflut {

class Window {
public:
    /// Fails with the windowing system's reason when there is no display or no GL 3.3.
    static Result<std::unique_ptr<Window>> create(int width, int height, const std::string& title, bool vsync);
    ~Window();
    Window(const Window&) = delete;
    Window& operator=(const Window&) = delete;

    GLFWwindow* handle() const { return m_window; }
    /// The GL renderer and version strings.
    std::string description() const;

private:
    Window() = default;
    GLFWwindow* m_window = nullptr;
};

}  // namespace btflut

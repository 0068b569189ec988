#pragma once
// Headless OpenGL 3.3 core contexts, kept apart from rendering: the renderer never knows
// whether OSMesa or EGL (surfaceless) made the context it draws in.
//
//   Result<std::unique_ptr<HeadlessContext>> ctx = createHeadlessContext(GlBackend::Auto);
//   // ctx is current on this thread; gl.* are loaded; draw into framebuffer objects.

#include <memory>
#include <string>

#include "core/result.h"

namespace btflut {

enum class GlBackend { Auto, OsMesa, Egl };

Result<GlBackend> parseGlBackend(const std::string& name);

class HeadlessContext {
public:
    virtual ~HeadlessContext() = default;
    /// "osmesa" or "egl", and the GL renderer and version strings.
    virtual std::string description() const = 0;
};

/// Creates a context and makes it current. Auto tries EGL (surfaceless), then OSMesa. The
/// error says what each backend answered.
Result<std::unique_ptr<HeadlessContext>> createHeadlessContext(GlBackend backend);

/// True when the current context is a software rasteriser (llvmpipe, softpipe, SwiftShader):
/// no GPU, so its costs (uniform arrays, timer queries) are not a GPU's.
bool softwareRasteriser();

/// In sanitized builds (BTFLUT_SANITIZE), keeps Mesa's driver modules loaded until exit so
/// that leak reports can name them; does nothing otherwise. Called before any context is made.
void keepGlDriversLoadedForLeakChecks();

}  // namespace btflut

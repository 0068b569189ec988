#include "gl/gl_api.h"

#include <string>

namespace btflut {

GlFunctions gl;

const char* loadGlFunctions(GlProcLoader load) {
#define BTFLUT_GL_LOAD(type, name)                      \
    gl.name = reinterpret_cast<type>(load("gl" #name)); \
    if (!gl.name) return "gl" #name;
    BTFLUT_GL_FUNCTIONS(BTFLUT_GL_LOAD)
#undef BTFLUT_GL_LOAD
    return nullptr;
}

}  // namespace btflut

#pragma once
// Move-only owners of GL objects (Magnum's habit): no copies, a moved-from object holds 0,
// the destructor deletes. They need the context that made them to be current.

#include <utility>

#include "gl/gl_api.h"

namespace btflut {

template <void (*Delete)(GLuint)>
class GlObject {
public:
    GlObject() = default;
    explicit GlObject(GLuint id) : m_id(id) {}
    GlObject(const GlObject&) = delete;
    GlObject& operator=(const GlObject&) = delete;
    GlObject(GlObject&& other) noexcept : m_id(std::exchange(other.m_id, 0)) {}
    GlObject& operator=(GlObject&& other) noexcept {
        if (this != &other) {
            reset();
            m_id = std::exchange(other.m_id, 0);
        }
        return *this;
    }
    ~GlObject() { reset(); }
    GLuint id() const { return m_id; }
    explicit operator bool() const { return m_id != 0; }

private:
    void reset() {
        if (m_id) Delete(m_id);
        m_id = 0;
    }
    GLuint m_id = 0;
};

namespace detail {
inline void deleteTexture(GLuint id) { gl.DeleteTextures(1, &id); }
inline void deleteFramebuffer(GLuint id) { gl.DeleteFramebuffers(1, &id); }
inline void deleteVertexArray(GLuint id) { gl.DeleteVertexArrays(1, &id); }
inline void deleteProgram(GLuint id) { gl.DeleteProgram(id); }
inline void deleteQuery(GLuint id) { gl.DeleteQueries(1, &id); }
inline void deleteBuffer(GLuint id) { gl.DeleteBuffers(1, &id); }
}  // namespace detail

using GlTexture = GlObject<detail::deleteTexture>;
using GlFramebuffer = GlObject<detail::deleteFramebuffer>;
using GlVertexArray = GlObject<detail::deleteVertexArray>;
using GlProgram = GlObject<detail::deleteProgram>;
using GlQuery = GlObject<detail::deleteQuery>;
using GlBuffer = GlObject<detail::deleteBuffer>;

static_assert(!std::is_copy_constructible_v<GlTexture> && std::is_nothrow_move_constructible_v<GlTexture>);

inline GlTexture makeTexture() {
    GLuint id = 0;
    gl.GenTextures(1, &id);
    return GlTexture(id);
}
inline GlFramebuffer makeFramebuffer() {
    GLuint id = 0;
    gl.GenFramebuffers(1, &id);
    return GlFramebuffer(id);
}
inline GlVertexArray makeVertexArray() {
    GLuint id = 0;
    gl.GenVertexArrays(1, &id);
    return GlVertexArray(id);
}
inline GlBuffer makeBuffer() {
    GLuint id = 0;
    gl.GenBuffers(1, &id);
    return GlBuffer(id);
}
inline GlQuery makeQuery() {
    GLuint id = 0;
    gl.GenQueries(1, &id);
    return GlQuery(id);
}

}  // namespace btflut

#pragma once
// The OpenGL 3.3 core functions btflut uses, loaded from the current context's
// GetProcAddress (OSMesa or EGL) into one table. Both headless backends may export GL symbols
// of their own, so btflut never links libGL and calls only through this table.
//
//   if (!loadGlFunctions(getProc)) ...;
//   gl.Clear(GL_COLOR_BUFFER_BIT);

#include <GL/glcorearb.h>

namespace btflut {

// GL 1.1 entry points whose pointer types this glcorearb.h leaves out.
typedef void(APIENTRYP PFNGLGENTEXTURESPROC)(GLsizei n, GLuint* textures);
typedef void(APIENTRYP PFNGLDELETETEXTURESPROC)(GLsizei n, const GLuint* textures);
typedef void(APIENTRYP PFNGLBINDTEXTUREPROC)(GLenum target, GLuint texture);
typedef void(APIENTRYP PFNGLTEXSUBIMAGE1DPROC)(GLenum target, GLint level, GLint xoffset, GLsizei width, GLenum format,
                                               GLenum type, const void* pixels);
typedef void(APIENTRYP PFNGLDRAWARRAYSPROC)(GLenum mode, GLint first, GLsizei count);
typedef void(APIENTRYP PFNGLTEXSUBIMAGE2DPROC)(GLenum target, GLint level, GLint xoffset, GLint yoffset, GLsizei width,
                                               GLsizei height, GLenum format, GLenum type, const void* pixels);

#define BTFLUT_GL_FUNCTIONS(X)                                 \
    X(PFNGLGETERRORPROC, GetError)                             \
    X(PFNGLGETSTRINGPROC, GetString)                           \
    X(PFNGLGETINTEGERVPROC, GetIntegerv)                       \
    X(PFNGLVIEWPORTPROC, Viewport)                             \
    X(PFNGLSCISSORPROC, Scissor)                               \
    X(PFNGLCLEARCOLORPROC, ClearColor)                         \
    X(PFNGLCLEARPROC, Clear)                                   \
    X(PFNGLFINISHPROC, Finish)                                 \
    X(PFNGLPIXELSTOREIPROC, PixelStorei)                       \
    X(PFNGLREADPIXELSPROC, ReadPixels)                         \
    X(PFNGLGENTEXTURESPROC, GenTextures)                       \
    X(PFNGLDELETETEXTURESPROC, DeleteTextures)                 \
    X(PFNGLBINDTEXTUREPROC, BindTexture)                       \
    X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                   \
    X(PFNGLTEXIMAGE1DPROC, TexImage1D)                         \
    X(PFNGLTEXIMAGE2DPROC, TexImage2D)                         \
    X(PFNGLTEXSUBIMAGE1DPROC, TexSubImage1D)                   \
    X(PFNGLTEXPARAMETERIPROC, TexParameteri)                   \
    X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)               \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)         \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)               \
    X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)     \
    X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus) \
    X(PFNGLCREATESHADERPROC, CreateShader)                     \
    X(PFNGLSHADERSOURCEPROC, ShaderSource)                     \
    X(PFNGLCOMPILESHADERPROC, CompileShader)                   \
    X(PFNGLGETSHADERIVPROC, GetShaderiv)                       \
    X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)             \
    X(PFNGLDELETESHADERPROC, DeleteShader)                     \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram)                   \
    X(PFNGLATTACHSHADERPROC, AttachShader)                     \
    X(PFNGLLINKPROGRAMPROC, LinkProgram)                       \
    X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                     \
    X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)           \
    X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                   \
    X(PFNGLUSEPROGRAMPROC, UseProgram)                         \
    X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)         \
    X(PFNGLGETACTIVEUNIFORMPROC, GetActiveUniform)             \
    X(PFNGLUNIFORM1IPROC, Uniform1i)                           \
    X(PFNGLUNIFORM1FPROC, Uniform1f)                           \
    X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)               \
    X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)         \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)               \
    X(PFNGLDRAWARRAYSPROC, DrawArrays)                         \
    X(PFNGLENABLEPROC, Enable)                                 \
    X(PFNGLDISABLEPROC, Disable)                               \
    X(PFNGLGENERATEMIPMAPPROC, GenerateMipmap)                 \
    X(PFNGLUNIFORM2FPROC, Uniform2f)                           \
    X(PFNGLUNIFORM3FPROC, Uniform3f)                           \
    X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)             \
    X(PFNGLTEXIMAGE3DPROC, TexImage3D)                         \
    X(PFNGLTEXSUBIMAGE3DPROC, TexSubImage3D)                   \
    X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer)               \
    X(PFNGLTEXSUBIMAGE2DPROC, TexSubImage2D)                   \
    X(PFNGLUNIFORM1FVPROC, Uniform1fv)                         \
    X(PFNGLUNIFORM1IVPROC, Uniform1iv)                         \
    X(PFNGLUNIFORM4FVPROC, Uniform4fv)                         \
    X(PFNGLUNIFORM2IPROC, Uniform2i)                           \
    X(PFNGLUNIFORM3FVPROC, Uniform3fv)                         \
    X(PFNGLGENQUERIESPROC, GenQueries)                         \
    X(PFNGLDELETEQUERIESPROC, DeleteQueries)                   \
    X(PFNGLBEGINQUERYPROC, BeginQuery)                         \
    X(PFNGLENDQUERYPROC, EndQuery)                             \
    X(PFNGLGETQUERYOBJECTUI64VPROC, GetQueryObjectui64v)       \
    X(PFNGLGETQUERYIVPROC, GetQueryiv)                         \
    X(PFNGLFLUSHPROC, Flush)                                   \
    X(PFNGLGENBUFFERSPROC, GenBuffers)                         \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                   \
    X(PFNGLBINDBUFFERPROC, BindBuffer)                         \
    X(PFNGLBUFFERDATAPROC, BufferData)                         \
    X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                 \
    X(PFNGLGETUNIFORMBLOCKINDEXPROC, GetUniformBlockIndex)     \
    X(PFNGLUNIFORMBLOCKBINDINGPROC, UniformBlockBinding)

struct GlFunctions {
#define BTFLUT_GL_MEMBER(type, name) type name = nullptr;
    BTFLUT_GL_FUNCTIONS(BTFLUT_GL_MEMBER)
#undef BTFLUT_GL_MEMBER
};

/// The table for the context current on this thread.
extern GlFunctions gl;

using GlProcLoader = void* (*)(const char* name);

/// Loads every function; returns the name of the first one missing, or nullptr.
const char* loadGlFunctions(GlProcLoader load);

}  // namespace btflut

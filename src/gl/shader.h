#pragma once
// Shader programs from the files in shaders/, embedded at build time. Each stage is
// "#version 330 core", the given #defines, then its files, each prefixed with #line so that
// a compile error's "N:LINE" names file N, listed after the driver's full log.
//
// Its uniforms' locations are found once, at link (as Magnum's shaders do), so a frame asks
// GL for none:
//
//   Result<ShaderProgram> p = buildProgram({"quad.vert"}, {"lut_common.glsl", "native.frag"}, {});
//   gl.UseProgram(p->id());
//   gl.Uniform1f((*p)["outCode"], 1.f / 255);

#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "core/result.h"
#include "gl/objects.h"

namespace btflut {

/// A linked program and the location of each of its active uniforms: by name, and each element
/// of an array by "name[i]" (a struct's members as "s.member", "s.array[i]").
class ShaderProgram {
public:
    ShaderProgram() = default;
    /// Takes a linked program and looks its uniforms up.
    explicit ShaderProgram(GlProgram program);

    GLuint id() const { return m_program.id(); }
    /// The location of a uniform; -1 (which GL's Uniform* calls ignore) for one the program
    /// does not have or the compiler removed.
    GLint operator[](std::string_view name) const;

private:
    struct Hash {
        using is_transparent = void;
        std::size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
    };
    GlProgram m_program;
    std::unordered_map<std::string, GLint, Hash, std::equal_to<>> m_locations;
};

/// The embedded text of shaders/NAME; empty view if there is no such file.
std::string_view embeddedShader(std::string_view name);

/// A shader file's name and text.
struct ShaderFile {
    std::string name;
    std::string_view text;
};

/// `generated`: sources made at run time (a learned model's decoder, Predictor::shaderSource),
/// in the fragment stage right after btflut.glsl, whose structs they use.
Result<ShaderProgram> buildProgram(const std::vector<std::string>& vertexFiles,
                                   const std::vector<std::string>& fragmentFiles,
                                   const std::vector<std::string>& defines,
                                   const std::vector<ShaderFile>& generated = {});

/// The same from given texts (buildProgram looks its files up in the embedded shaders).
Result<ShaderProgram> buildProgramFromSources(const std::vector<ShaderFile>& vertex,
                                              const std::vector<ShaderFile>& fragment,
                                              const std::vector<std::string>& defines);

}  // namespace btflut

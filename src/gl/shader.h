#pragma once
// Shader programs from the files in shaders/, embedded at build time. Each stage is
// "#version 330 core", the given #defines, then its files, each prefixed with #line so that
// a compile error's "N:LINE" names file N, listed after the driver's full log.
//
//   Result<GlProgram> p = buildProgram({"quad.vert"}, {"lut_common.glsl", "native.frag"}, {});

#include <string>
#include <string_view>
#include <vector>

#include "core/result.h"
#include "gl/objects.h"

namespace btflut {

/// The embedded text of shaders/NAME; empty view if there is no such file.
std::string_view embeddedShader(std::string_view name);

Result<GlProgram> buildProgram(const std::vector<std::string>& vertexFiles,
                               const std::vector<std::string>& fragmentFiles, const std::vector<std::string>& defines);

/// A shader file's name and text.
struct ShaderFile {
    std::string name;
    std::string_view text;
};

/// The same from given texts (buildProgram looks its files up in the embedded shaders).
Result<GlProgram> buildProgramFromSources(const std::vector<ShaderFile>& vertex,
                                          const std::vector<ShaderFile>& fragment,
                                          const std::vector<std::string>& defines);

}  // namespace btflut

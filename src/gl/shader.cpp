#include "gl/shader.h"

#include <regex>

namespace btflut {

namespace {

constexpr std::size_t kFileLines = 100000;

// Rewrites "S:LINE(" in a driver's log, LINE counted from file k's base, as "shaders/NAME:LINE(".
std::string nameLines(const std::string& log, const std::vector<ShaderFile>& files) {
    static const std::regex location(R"((\d+):(\d+)\()");
    std::string out;
    auto begin = std::sregex_iterator(log.begin(), log.end(), location);
    std::size_t copied = 0;
    for (auto it = begin; it != std::sregex_iterator(); ++it) {
        const std::size_t line = std::stoul((*it)[2]), file = line / kFileLines;
        if (file < 1 || file > files.size()) continue;
        out += log.substr(copied, static_cast<std::size_t>(it->position()) - copied);
        out += "shaders/" + files[file - 1].name + ":" + std::to_string(line - file * kFileLines) + "(";
        copied = static_cast<std::size_t>(it->position() + it->length());
    }
    return out + log.substr(copied);
}

Result<GLuint> compile(GLenum stage, const std::vector<ShaderFile>& files, const std::vector<std::string>& defines) {
    std::string source = "#version 330 core\n";
    for (const std::string& d : defines) source += "#define " + d + "\n";
    // File k starts at line k * kFileLines + 1: drivers (Mesa among them) ignore #line's
    // source-string number in their messages, but all report line numbers.
    for (std::size_t i = 0; i < files.size(); ++i)
        source += "#line " + std::to_string((i + 1) * kFileLines + 1) + "\n" + std::string(files[i].text) + "\n";
    GLuint shader = gl.CreateShader(stage);
    const char* text = source.c_str();
    gl.ShaderSource(shader, 1, &text, nullptr);
    gl.CompileShader(shader);
    GLint ok = 0;
    gl.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        gl.GetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
        std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
        gl.GetShaderInfoLog(shader, length, nullptr, log.data());
        gl.DeleteShader(shader);
        while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
        for (char& c : log)
            if (c == '\n') c = ' ';
        return Error{"shader does not compile: " + nameLines(log, files)};
    }
    return shader;
}

}  // namespace

Result<ShaderProgram> buildProgram(const std::vector<std::string>& vertexFiles,
                                   const std::vector<std::string>& fragmentFiles,
                                   const std::vector<std::string>& defines, const std::vector<ShaderFile>& generated) {
    std::vector<ShaderFile> stages[2];
    for (int s = 0; s < 2; ++s)
        for (const std::string& name : s == 0 ? vertexFiles : fragmentFiles) {
            std::string_view text = embeddedShader(name);
            if (text.empty()) return Error{"shaders/" + name + ": no such shader"};
            stages[s].push_back({name, text});
            if (s == 1 && name == "btflut.glsl") stages[s].insert(stages[s].end(), generated.begin(), generated.end());
        }
    return buildProgramFromSources(stages[0], stages[1], defines);
}

Result<ShaderProgram> buildProgramFromSources(const std::vector<ShaderFile>& vertexFiles,
                                              const std::vector<ShaderFile>& fragmentFiles,
                                              const std::vector<std::string>& defines) {
    Result<GLuint> vs = compile(GL_VERTEX_SHADER, vertexFiles, defines);
    if (!vs) return Error{vs.error()};
    Result<GLuint> fs = compile(GL_FRAGMENT_SHADER, fragmentFiles, defines);
    if (!fs) {
        gl.DeleteShader(*vs);
        return Error{fs.error()};
    }
    GlProgram program(gl.CreateProgram());
    gl.AttachShader(program.id(), *vs);
    gl.AttachShader(program.id(), *fs);
    gl.LinkProgram(program.id());
    gl.DeleteShader(*vs);
    gl.DeleteShader(*fs);
    GLint ok = 0;
    gl.GetProgramiv(program.id(), GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        gl.GetProgramInfoLog(program.id(), sizeof log, nullptr, log);
        return Error{std::string("shader program does not link: ") + log};
    }
    return ShaderProgram(std::move(program));
}

ShaderProgram::ShaderProgram(GlProgram program) : m_program(std::move(program)) {
    GLint count = 0, longest = 0;
    gl.GetProgramiv(id(), GL_ACTIVE_UNIFORMS, &count);
    gl.GetProgramiv(id(), GL_ACTIVE_UNIFORM_MAX_LENGTH, &longest);
    std::string name(static_cast<std::size_t>(std::max(longest, 1)), '\0');
    for (GLint u = 0; u < count; ++u) {
        GLsizei length = 0;
        GLint size = 0;
        GLenum type = 0;
        gl.GetActiveUniform(id(), static_cast<GLuint>(u), longest, &length, &size, &type, name.data());
        std::string uniform = name.substr(0, static_cast<std::size_t>(length));
        // An array is listed once, as "a[0]": each element by name (their locations need not
        // be consecutive), and the array by its bare name too.
        const bool array = uniform.size() > 3 && uniform.ends_with("[0]");
        const std::string base = array ? uniform.substr(0, uniform.size() - 3) : uniform;
        if (!array) {
            m_locations[uniform] = gl.GetUniformLocation(id(), uniform.c_str());
            continue;
        }
        m_locations[base] = gl.GetUniformLocation(id(), uniform.c_str());
        for (GLint i = 0; i < size; ++i) {
            const std::string element = base + "[" + std::to_string(i) + "]";
            m_locations[element] = gl.GetUniformLocation(id(), element.c_str());
        }
    }
}

GLint ShaderProgram::operator[](std::string_view name) const {
    const auto found = m_locations.find(name);
    return found == m_locations.end() ? -1 : found->second;
}

}  // namespace btflut

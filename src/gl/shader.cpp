#include "glint/gl/shader.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/log.h"
#include "glint/gl/embedded_shaders.h"

#include <algorithm>
#include <charconv>
#include <regex>
#include <set>
#include <sstream>

namespace glint::gl {
namespace fs = std::filesystem;

namespace {
fs::path& sourceDirectory() {
  static fs::path dir;
  return dir;
}

struct ShaderKind {
  static void destroy(GLuint id) { glDeleteShader(id); }
};

std::string firstErrorLine(const std::string& log) {
  std::istringstream in(log);
  std::string line;
  while (std::getline(in, line)) {
    if (line.find("error") != std::string::npos) return line;
  }
  in.clear();
  std::istringstream again(log);
  std::getline(again, line);
  return line;
}

// Files are told apart by line number, not by #line's source-string number: some
// drivers (Mesa, for some diagnostics) report source string 0 whatever #line said.
// File k's line n is numbered k * kLineStride + n, which survives every driver.
constexpr int kLineStride = 100000;

std::string lineDirective(int fileIndex, int line) { return fmt::format("#line {}\n", fileIndex * kLineStride + line); }

void expand(std::string_view path, std::vector<std::string>& files, std::set<std::string>& included,
            std::string& out, const std::vector<std::string>* defines) {
  const int fileIndex = int(files.size());
  files.emplace_back(path);
  included.emplace(path);
  std::istringstream in(ShaderSources::read(path));
  std::string line;
  int lineNumber = 0;
  static const std::regex includeRe(R"re(^\s*#\s*include\s+"([^"]+)"\s*$)re");
  while (std::getline(in, line)) {
    ++lineNumber;
    std::smatch m;
    if (lineNumber == 1 && defines) {
      if (line.rfind("#version", 0) != 0) {
        fail(ErrorKind::Internal, "shaders/{}:1: error: the first line must be #version", path);
      }
      out += line + "\n";
      for (const auto& d : *defines) out += "#define " + d + "\n";
      out += lineDirective(fileIndex, lineNumber + 1);
    } else if (std::regex_match(line, m, includeRe)) {
      const std::string target = m[1].str();
      if (!included.count(target)) {
        out += lineDirective(int(files.size()), 1);
        expand(target, files, included, out, nullptr);
      }
      out += lineDirective(fileIndex, lineNumber + 1);
    } else {
      out += line + "\n";
    }
  }
}
}  // namespace

void ShaderSources::setDirectory(const fs::path& dir) { sourceDirectory() = dir; }
const fs::path& ShaderSources::directory() { return sourceDirectory(); }

std::string ShaderSources::read(std::string_view path) {
  if (!sourceDirectory().empty()) {
    const fs::path file = sourceDirectory() / fs::path(path);
    std::error_code ec;
    if (fs::exists(file, ec)) return readTextFile(file);
  }
  const auto table = embeddedShaders();
  const auto it = std::lower_bound(table.begin(), table.end(), path,
                                   [](const EmbeddedShader& s, std::string_view p) { return std::string_view(s.path) < p; });
  if (it == table.end() || std::string_view(it->path) != path) {
    fail(ErrorKind::Internal, "shader 'shaders/{}' does not exist", path);
  }
  return it->source;
}

std::vector<std::string> ShaderSources::list() {
  std::vector<std::string> out;
  for (const auto& s : embeddedShaders()) out.emplace_back(s.path);
  return out;
}

PreprocessedShader preprocessShader(std::string_view path, const std::vector<std::string>& defines) {
  PreprocessedShader result;
  std::set<std::string> included;
  expand(path, result.files, included, result.source, &defines);
  return result;
}

std::string mapShaderLog(std::string_view log, const std::vector<std::string>& files) {
  // Mesa: "0:12(5): error: ..."   NVIDIA: "0(12) : error C1008: ..."
  static const std::regex lineRe(R"re(^(\d+)(?::(\d+)\(\d+\)|\((\d+)\))\s*:\s*(.*)$)re");
  std::istringstream in{std::string(log)};
  std::string line, out;
  while (std::getline(in, line)) {
    std::smatch m;
    long number = 0;
    bool matched = std::regex_match(line, m, lineRe);
    if (matched) {
      // A line number too long for a long is not one preprocessShader made: kept as it is.
      const std::string digits = m[2].matched ? m[2].str() : m[3].str();
      matched = std::from_chars(digits.data(), digits.data() + digits.size(), number).ec == std::errc();
    }
    if (matched) {
      const auto index = std::size_t(number / kLineStride);
      const std::string file = index < files.size() ? files[index] : "?";
      out += fmt::format("shaders/{}:{}: {}\n", file, number % kLineStride, m[4].str());
    } else if (!line.empty()) {
      out += line + "\n";
    }
  }
  return out;
}

GLenum shaderStageForPath(std::string_view path) {
  const auto ext = fs::path(path).extension().string();
  if (ext == ".vert") return GL_VERTEX_SHADER;
  if (ext == ".frag") return GL_FRAGMENT_SHADER;
  if (ext == ".geom") return GL_GEOMETRY_SHADER;
  if (ext == ".comp") return GL_COMPUTE_SHADER;
  if (ext == ".tesc") return GL_TESS_CONTROL_SHADER;
  if (ext == ".tese") return GL_TESS_EVALUATION_SHADER;
  return 0;
}

Program Program::fromFiles(std::initializer_list<std::string_view> files, const std::vector<std::string>& defines) {
  std::vector<std::string> v(files.begin(), files.end());
  return fromFiles(v, defines);
}

Program Program::fromFiles(const std::vector<std::string>& files, const std::vector<std::string>& defines) {
  std::vector<GLuint> shaders;
  auto cleanup = [&] {
    for (GLuint s : shaders) ShaderKind::destroy(s);
  };
  std::string names;
  try {
    for (const auto& path : files) {
      const GLenum stage = shaderStageForPath(path);
      if (!stage) fail(ErrorKind::Internal, "shaders/{}: unknown shader stage (extension)", path);
      const auto pre = preprocessShader(path, defines);
      const GLuint shader = glCreateShader(stage);
      shaders.push_back(shader);
      const char* src = pre.source.c_str();
      glShaderSource(shader, 1, &src, nullptr);
      glCompileShader(shader);
      GLint ok = 0;
      glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
      if (!ok) {
        GLint length = 0;
        glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
        std::string logText(std::size_t(std::max(length, 1)), '\0');
        glGetShaderInfoLog(shader, length, nullptr, logText.data());
        const std::string mapped = mapShaderLog(logText.c_str(), pre.files);
        log::debug("{}", mapped);
        fail(ErrorKind::Internal, "{}", firstErrorLine(mapped));
      }
      names += (names.empty() ? "" : "+") + path;
    }
    const GLuint program = glCreateProgram();
    Program result(program);
    for (GLuint s : shaders) glAttachShader(program, s);
    glLinkProgram(program);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    for (GLuint s : shaders) glDetachShader(program, s);
    cleanup();
    shaders.clear();
    if (!ok) {
      GLint length = 0;
      glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
      std::string logText(std::size_t(std::max(length, 1)), '\0');
      glGetProgramInfoLog(program, length, nullptr, logText.data());
      fail(ErrorKind::Internal, "linking {}: {}", names, firstErrorLine(logText.c_str()));
    }
    result.label(names);
    result.cacheActiveUniforms();
    return result;
  } catch (...) {
    cleanup();
    throw;
  }
}

void Program::cacheActiveUniforms() {
  GLint count = 0, longest = 0;
  glGetProgramInterfaceiv(m_id, GL_UNIFORM, GL_ACTIVE_RESOURCES, &count);
  glGetProgramInterfaceiv(m_id, GL_UNIFORM, GL_MAX_NAME_LENGTH, &longest);
  std::string name(std::size_t(std::max(longest, 1)), '\0');
  for (GLint i = 0; i < count; ++i) {
    GLsizei length = 0;
    glGetProgramResourceName(m_id, GL_UNIFORM, GLuint(i), GLsizei(name.size()), &length, name.data());
    const std::string uniform(name.data(), std::size_t(length));
    const GLint location = glGetProgramResourceLocation(m_id, GL_UNIFORM, uniform.c_str());
    if (location < 0) continue;  // in a uniform block: no location
    m_locations.emplace(uniform, location);
    // An array is listed as "a[0]"; GLSL also accepts plain "a" for its first element.
    if (uniform.ends_with("[0]")) m_locations.emplace(uniform.substr(0, uniform.size() - 3), location);
  }
}

GLint Program::uniformLocation(std::string_view name) const {
  if (auto it = m_locations.find(name); it != m_locations.end()) return it->second;
  const std::string key(name);
  const GLint location = glGetUniformLocation(m_id, key.c_str());
  m_locations.emplace(key, location);
  return location;
}

}  // namespace glint::gl

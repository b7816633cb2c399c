#pragma once
// glint/gl/shader.h — GLSL files → programs: the one shader loader.
//
// Contents
//   ShaderSources       where sources come from: embedded table, or a directory (hot reload)
//   preprocessShader    #include "common/x.glsl", prepended #defines, #line bookkeeping
//   Program             a linked program with cached uniform locations and DSA setters
//
// Shaders live under shaders/<technique>/<pass>.<stage> (stage from the extension:
// .vert .frag .geom .comp .tesc .tese). They are embedded at build time so an
// installed glint runs anywhere; the viewer points ShaderSources at the source
// tree to re-read them from disk when they change.
//
// Every file starts with `#version 450 core` (or `compatibility`). `#include
// "path"` (relative to shaders/) pastes a file once per program stage; includes
// are expanded before compilation and `#line` directives keep line numbers, so a
// compile error reads
//     shaders/env/reflect.frag:12: error: 'colr' undeclared
//
/// ```cpp
/// const auto program = glint::gl::Program::fromFiles({"env/reflect.vert", "env/reflect.frag"}, {"SPHERE_MAP"});
/// program.use();
/// program.set("uTint", glint::vec3(1.0f, 0.8f, 0.6f));
/// ```

#include "glint/gl/objects.h"

#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace glint::gl {

class ShaderSources {
public:
  /// Read sources from `dir` (a checkout's shaders/ folder) instead of the embedded
  /// copies; an empty path returns to the embedded table.
  static void setDirectory(const std::filesystem::path& dir);
  static const std::filesystem::path& directory();
  /// Source text of a shader file. Error(Internal) naming the path when it does not exist.
  static std::string read(std::string_view path);
  /// Every embedded shader path, sorted.
  static std::vector<std::string> list();
};

struct PreprocessedShader {
  std::string source;               ///< ready for glShaderSource
  std::vector<std::string> files;   ///< file k's line n is numbered k·100000 + n (see shader.cpp)
};

/// Expands includes and inserts `#define`s (each "NAME" or "NAME VALUE") after #version.
PreprocessedShader preprocessShader(std::string_view path, const std::vector<std::string>& defines = {});

/// Rewrites a driver's info log (Mesa "0:12(5): error", NVIDIA "0(12) : error"; line numbers
/// as preprocessShader numbered them) into
/// "shaders/<file>:<line>: error ..." lines using the file table.
std::string mapShaderLog(std::string_view log, const std::vector<std::string>& files);

struct ProgramKind {
  static constexpr GLenum kLabelType = GL_PROGRAM;
  static void destroy(GLuint id) { glDeleteProgram(id); }
};

class Program : public Object<ProgramKind> {
public:
  Program() = default;
  /// Compiles and links the files (one per stage). Throws Error(Internal) whose first
  /// line names the file and line of the first compile or link error.
  static Program fromFiles(std::initializer_list<std::string_view> files, const std::vector<std::string>& defines = {});
  static Program fromFiles(const std::vector<std::string>& files, const std::vector<std::string>& defines = {});

  void use() const { glUseProgram(m_id); }
  /// -1 when the uniform does not exist (or was optimised away); setters ignore -1 like GL.
  /// Every active uniform's location is read once after linking, so a lookup on the hot
  /// path is one hash of the name: no allocation, no GL call (names GL does not list,
  /// such as "a[2]" of an array listed as "a[0]", are asked once and remembered).
  GLint uniformLocation(std::string_view name) const;

  void set(std::string_view name, int v) const { glProgramUniform1i(m_id, uniformLocation(name), v); }
  void set(std::string_view name, bool v) const { glProgramUniform1i(m_id, uniformLocation(name), v ? 1 : 0); }
  void set(std::string_view name, unsigned v) const { glProgramUniform1ui(m_id, uniformLocation(name), v); }
  void set(std::string_view name, float v) const { glProgramUniform1f(m_id, uniformLocation(name), v); }
  void set(std::string_view name, vec2 v) const { glProgramUniform2fv(m_id, uniformLocation(name), 1, &v.x); }
  void set(std::string_view name, vec3 v) const { glProgramUniform3fv(m_id, uniformLocation(name), 1, &v.x); }
  void set(std::string_view name, vec4 v) const { glProgramUniform4fv(m_id, uniformLocation(name), 1, &v.x); }
  void set(std::string_view name, ivec2 v) const { glProgramUniform2iv(m_id, uniformLocation(name), 1, &v.x); }
  void set(std::string_view name, const mat3& m) const {
    glProgramUniformMatrix3fv(m_id, uniformLocation(name), 1, GL_FALSE, &m[0][0]);
  }
  void set(std::string_view name, const mat4& m) const {
    glProgramUniformMatrix4fv(m_id, uniformLocation(name), 1, GL_FALSE, &m[0][0]);
  }

private:
  explicit Program(GLuint id) : Object(id) {}
  void cacheActiveUniforms();

  // Transparent hashing: find() takes the string_view without building a std::string.
  struct NameHash {
    using is_transparent = void;
    std::size_t operator()(std::string_view s) const { return std::hash<std::string_view>{}(s); }
  };
  mutable std::unordered_map<std::string, GLint, NameHash, std::equal_to<>> m_locations;
};

/// Shader stage for a file extension (GL_VERTEX_SHADER for ".vert", ...); 0 if unknown.
GLenum shaderStageForPath(std::string_view path);

}  // namespace glint::gl

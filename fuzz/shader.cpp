// Fuzz harness: the shader loader's preprocessor (gl/shader.h preprocessShader: #include
// expansion, #define insertion, #line numbering) and the info-log mapper (mapShaderLog).
// The input is split at "\n@@\n" into main.frag, a.glsl and b.glsl in a scratch
// shaders/ directory (so includes can nest, repeat and cycle), and also read as a driver's
// info log. No GL context is needed: nothing is compiled.
#include "support.h"

#include "glint/core/log.h"
#include "glint/gl/shader.h"

#include <cstdint>
#include <fstream>
#include <string>

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glint::log::setLevel(glint::log::Level::Error);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace glint;
  const std::string text(reinterpret_cast<const char*>(data), size);
  static const char* const kNames[] = {"main.frag", "a.glsl", "b.glsl"};
  const auto dir = fuzz::scratchDirectory() / "shaders";
  std::filesystem::create_directories(dir);
  std::size_t start = 0;
  for (const char* name : kNames) {
    const std::size_t at = text.find("\n@@\n", start);
    std::ofstream(dir / name, std::ios::binary | std::ios::trunc)
        << text.substr(start, at == std::string::npos ? std::string::npos : at - start);
    start = at == std::string::npos ? text.size() : at + 4;
  }
  gl::ShaderSources::setDirectory(dir);
  fuzz::parse([&] {
    const gl::PreprocessedShader shader = gl::preprocessShader("main.frag", {"FUZZ", "VALUE 2"});
    fuzz::check(!shader.files.empty() && shader.files.front() == "main.frag", "the file table starts with the shader");
    (void)gl::mapShaderLog(text, shader.files);
  });
  (void)gl::mapShaderLog(text, {"main.frag", "a.glsl"});
  return 0;
}

// Every embedded GLSL stage validated by glslangValidator (Khronos' reference front end),
// independently of the driver: with no defines and with each define the file tests for.
#include "glint/core/file.h"
#include "glint/gl/shader.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace glint;

namespace {
// Names a shader (or its includes) tests with #ifdef / #if defined(...).
std::set<std::string> definesUsed(const std::string& source) {
  std::set<std::string> out;
  static const std::regex re(R"re(#\s*(?:ifdef|ifndef|if\s+defined\s*\(?|elif\s+defined\s*\(?)\s*([A-Za-z_]\w*))re");
  for (auto it = std::sregex_iterator(source.begin(), source.end(), re); it != std::sregex_iterator(); ++it)
    out.insert((*it)[1].str());
  return out;
}

std::string run(const std::string& command) {
  std::string output;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  char buffer[512];
  while (pipe && fgets(buffer, sizeof buffer, pipe)) output += buffer;
  const int status = pipe ? pclose(pipe) : -1;
  return status == 0 ? std::string() : output.empty() ? "failed" : output;
}
}  // namespace

TEST(Glslang, EveryShaderStageValidates) {
  const fs::path dir = fs::path(GLINT_TEST_OUTPUT_DIR) / "glslang";
  fs::create_directories(dir);
  int validated = 0;
  for (const auto& path : gl::ShaderSources::list()) {
    if (gl::shaderStageForPath(path) == 0) continue;
    const auto base = gl::preprocessShader(path);
    std::vector<std::vector<std::string>> defineSets = {{}};
    for (const auto& d : definesUsed(base.source)) defineSets.push_back({d});
    for (const auto& defines : defineSets) {
      const auto pre = gl::preprocessShader(path, defines);
      // Same stage extension so glslang infers the stage.
      const fs::path file = dir / (std::to_string(validated) + fs::path(path).extension().string());
      writeTextAtomically(file, pre.source);
      const std::string errors = run(std::string(GLSLANG_VALIDATOR) + " " + file.string());
      EXPECT_TRUE(errors.empty()) << "shaders/" << path << (defines.empty() ? "" : " with " + defines[0]) << ":\n"
                                  << gl::mapShaderLog(errors, pre.files);
      ++validated;
    }
  }
  EXPECT_GT(validated, 0);
}

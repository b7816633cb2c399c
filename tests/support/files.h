#pragma once
// Files for tests: a scratch directory per test module under the build's test output,
// files written into it byte for byte, and the glint::Error a call is expected to throw.
#include "glint/core/error.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

namespace glint::testing {

/// GLINT_TEST_OUTPUT_DIR/<module>, created.
inline std::filesystem::path testOutputDir(const std::string& module) {
  const std::filesystem::path dir = std::filesystem::path(GLINT_TEST_OUTPUT_DIR) / module;
  std::filesystem::create_directories(dir);
  return dir;
}

/// Writes `contents` to `dir`/`name` exactly (binary) and returns the path.
inline std::filesystem::path writeTestFile(const std::filesystem::path& dir, const std::string& name,
                                           std::string_view contents) {
  const std::filesystem::path path = dir / name;
  std::ofstream out(path, std::ios::binary);
  out.write(contents.data(), std::streamsize(contents.size()));
  return path;
}

/// The glint::Error `f` throws; a test failure (and an Internal error) when it throws none.
template <typename F>
Error captureError(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "no glint::Error thrown";
  return Error(ErrorKind::Internal, "");
}

}  // namespace glint::testing

// Linked into every test executable (tests/CMakeLists.txt's glint_add_test): the suite runs
// cold, as on a fresh machine, however it is started (ctest, make test, a test binary by
// hand). Set before main(), so the first GL context and every child process (the glint
// command under test) see it:
//   MESA_SHADER_CACHE_DISABLE=true  a cached shader compiles silently, so a warning a new
//                                   user's driver prints would never reach the tests that
//                                   count driver messages
//   XDG_CACHE_HOME                  a cache directory of the suite's own, not the user's
//   GLINT_CACHE_DIR                 glint's cached files (the pipedream stage's cut), shared
//                                   by the test processes of one run
// `make test` empties both directories before each run (Makefile).
//
// Where they are: under the build tree, or, when GLINT_TEST_ROOT is set, under that
// directory (test-home/cache, cache, test-output). scripts/gpu-check sets it for the test
// executables it ships in its pack, which run on a machine without the build tree.
#include "support/test_paths.h"

#include <cstdlib>
#include <string>

#if !defined(GLINT_TEST_CACHE_HOME) || !defined(GLINT_TEST_GLINT_CACHE) || !defined(GLINT_TEST_BUILD_OUTPUT_DIR)
#error "GLINT_TEST_CACHE_HOME, GLINT_TEST_GLINT_CACHE and GLINT_TEST_BUILD_OUTPUT_DIR must be defined"
#endif

namespace {
// GLINT_TEST_ROOT/<relative>, or the build tree's path when the variable is unset or empty.
std::string underRoot(const char* relative, const char* buildPath) {
  const char* root = std::getenv("GLINT_TEST_ROOT");
  return root && *root ? std::string(root) + "/" + relative : std::string(buildPath);
}

const std::string& outputDir() {
  static const std::string dir = underRoot("test-output", GLINT_TEST_BUILD_OUTPUT_DIR);
  return dir;
}

const bool kCold = [] {
  ::setenv("MESA_SHADER_CACHE_DISABLE", "true", 1);
  ::setenv("XDG_CACHE_HOME", underRoot("test-home/cache", GLINT_TEST_CACHE_HOME).c_str(), 1);
  ::setenv("GLINT_CACHE_DIR", underRoot("cache", GLINT_TEST_GLINT_CACHE).c_str(), 1);
  return true;
}();
}  // namespace

const char* glintTestOutputDir() noexcept { return outputDir().c_str(); }

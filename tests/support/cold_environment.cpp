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
// Where they are: test-home/cache, cache and test-output under the build tree, or, when
// GLINT_TEST_ROOT is set, under that directory. scripts/gpu-check sets it for the test
// executables it ships in its pack, which run on a machine without the build tree.
#include "support/test_paths.h"

#include <cstdlib>
#include <string>

#if !defined(GLINT_TEST_BUILD_DIR)
#error "GLINT_TEST_BUILD_DIR (the build tree) must be defined"
#endif

namespace {
// <root>/<relative>: root is $GLINT_TEST_ROOT, or the build tree when it is unset or empty.
std::string underRoot(const char* relative) {
  const char* root = std::getenv("GLINT_TEST_ROOT");
  return std::string(root && *root ? root : GLINT_TEST_BUILD_DIR) + "/" + relative;
}

const std::string& outputDir() {
  static const std::string dir = underRoot("test-output");
  return dir;
}

const bool kCold = [] {
  ::setenv("MESA_SHADER_CACHE_DISABLE", "true", 1);
  ::setenv("XDG_CACHE_HOME", underRoot("test-home/cache").c_str(), 1);
  ::setenv("GLINT_CACHE_DIR", underRoot("cache").c_str(), 1);
  return true;
}();
}  // namespace

const char* glintTestOutputDir() noexcept { return outputDir().c_str(); }

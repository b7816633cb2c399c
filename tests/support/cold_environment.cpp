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
#include <cstdlib>

#if !defined(GLINT_TEST_CACHE_HOME) || !defined(GLINT_TEST_GLINT_CACHE)
#error "GLINT_TEST_CACHE_HOME and GLINT_TEST_GLINT_CACHE must be defined"
#endif

namespace {
const bool kCold = [] {
  ::setenv("MESA_SHADER_CACHE_DISABLE", "true", 1);
  ::setenv("XDG_CACHE_HOME", GLINT_TEST_CACHE_HOME, 1);
  ::setenv("GLINT_CACHE_DIR", GLINT_TEST_GLINT_CACHE, 1);
  return true;
}();
}  // namespace

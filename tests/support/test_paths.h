#pragma once
// Included into every test source by glint_add_test (-include), so that the compile
// definition GLINT_TEST_OUTPUT_DIR, which expands to `glintTestOutputDir()`, names a
// declared function wherever a test uses it.

/// Where tests write their files: <build>/test-output, or $GLINT_TEST_ROOT/test-output
/// (support/cold_environment.cpp). Fixed for the process's life.
const char* glintTestOutputDir() noexcept;

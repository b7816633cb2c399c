#pragma once
// Shared fixture for tests that need OpenGL: one headless 4.5 core context per test
// binary (debug output on), and a check after every test that the GL debug callback
// reported no error. Use TEST_F(GlTest, ...) or derive from GlTest.
#include "glint/gl/context.h"
#include "glint/gl/debug.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <memory>

namespace glint::testing {

class GlTest : public ::testing::Test {
public:
  static void SetUpTestSuite() {
    if (!s_context) s_context = gl::HeadlessContext::create({.profile = gl::Profile::Core, .debug = true});
  }
  // The context lives until the process ends: GL objects in static test data may
  // outlive a suite, and recreating contexts per suite costs time on llvmpipe.

protected:
  void SetUp() override {
    s_context->makeCurrent();
    m_errorsBefore = gl::debugErrorCount();
  }
  void TearDown() override {
    if (!m_allowErrors) {
      EXPECT_EQ(gl::debugErrorCount(), m_errorsBefore) << "the GL debug callback reported errors (see the log above)";
    }
  }
  /// For tests that provoke GL errors on purpose (e.g. a shader that must fail to compile).
  void allowGlErrors() { m_allowErrors = true; }

  static inline std::unique_ptr<gl::HeadlessContext> s_context;

private:
  std::uint64_t m_errorsBefore = 0;
  bool m_allowErrors = false;
};

}  // namespace glint::testing

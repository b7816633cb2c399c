// GL tier: the RAII objects, readback and context limits on a real (headless) context.
#include "support/gl_test.h"

#include "glint/core/error.h"
#include "glint/gl/objects.h"
#include "glint/gl/render_target.h"
#include "glint/gl/timer.h"

#include <array>
#include <cstdint>
#include <span>
#include <string>

using namespace glint;
using glint::testing::GlTest;

TEST_F(GlTest, ContextIsOpenGL45CoreWithStencil) {
  const auto info = gl::queryContextInfo();
  EXPECT_EQ(info.profile, "core");
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  EXPECT_GE(major * 10 + minor, 45);
  EXPECT_EQ(info.stencilBits, 8);
  EXPECT_GE(info.maxAnisotropy, 1.0f);
}

TEST_F(GlTest, ObjectsAreMoveOnlyOwners) {
  gl::Texture a(GL_TEXTURE_2D, "a");
  const GLuint id = a.id();
  ASSERT_NE(id, 0u);
  gl::Texture b = std::move(a);
  EXPECT_EQ(a.id(), 0u);  // NOLINT(bugprone-use-after-move): moved-from is empty by contract
  EXPECT_EQ(b.id(), id);
  EXPECT_TRUE(glIsTexture(id));
  b.reset();
  EXPECT_FALSE(glIsTexture(id));
  static_assert(!std::is_copy_constructible_v<gl::Buffer>);
  static_assert(std::is_nothrow_move_constructible_v<gl::Buffer>);
}

TEST_F(GlTest, BufferStoresAndUpdates) {
  const std::array<float, 4> data{1, 2, 3, 4};
  gl::Buffer buffer(std::span<const float>(data), GL_DYNAMIC_STORAGE_BIT, "test-buffer");
  const float two = 20.0f;
  buffer.update(sizeof(float), sizeof(float), &two);
  std::array<float, 4> back{};
  buffer.read(0, sizeof(back), back.data());
  EXPECT_EQ(back, (std::array<float, 4>{1, 20, 3, 4}));
  float third = 0.0f;
  buffer.read(2 * sizeof(float), sizeof(float), &third);
  EXPECT_EQ(third, 3.0f);
  EXPECT_THROW(buffer.update(12, 8, &two), Error);
}

TEST_F(GlTest, TextureUploadAndReadbackRoundTripOddWidths) {
  // 3×2 RGB: rows of 9 bytes would be mangled by GL's default 4-byte alignment.
  Image img(3, 2, 3, PixelType::U8);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x)
      for (int c = 0; c < 3; ++c) img.set(x, y, c, float(10 * (x + 3 * y) + c) / 255.0f);
  gl::Texture tex(GL_TEXTURE_2D, "odd");
  tex.storage(GL_RGB8, 3, 2);
  Image flipped = img;
  flipped.flipVertical();  // GL rows go bottom-up
  tex.upload(0, 3, 2, GL_RGB, GL_UNSIGNED_BYTE, flipped.bytes().data());
  const Image back = gl::readTexture(tex, 0, 0, 3, PixelType::U8);
  EXPECT_EQ(compareImages(img, back).maxAbs, 0.0);
}

TEST_F(GlTest, FullMipChainLevels) {
  EXPECT_EQ(gl::mipLevelCount(1, 1), 1);
  EXPECT_EQ(gl::mipLevelCount(256, 256), 9);
  EXPECT_EQ(gl::mipLevelCount(640, 360), 10);
  gl::Texture tex(GL_TEXTURE_2D);
  tex.storage(GL_RGBA8, 640, 360, 1, 0);
  EXPECT_EQ(tex.levels(), 10);
}

TEST_F(GlTest, CubeMapFacesMustBeSquare) {
  gl::Texture cube(GL_TEXTURE_CUBE_MAP, "cube");
  try {
    cube.storage(GL_RGBA8, 64, 32);
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
  }
}

TEST_F(GlTest, IncompleteFramebufferNamesTheAttachment) {
  gl::Framebuffer fb = gl::Framebuffer::create("incomplete");
  // Colour texture 64×64 plus a depth renderbuffer of another size is complete in GL 4.5,
  // so use a colour texture without storage-compatible format: a depth format on COLOR0.
  gl::Texture depthAsColor(GL_TEXTURE_2D, "depth-as-color");
  depthAsColor.storage(GL_DEPTH_COMPONENT24, 16, 16);
  fb.attach(GL_COLOR_ATTACHMENT0, depthAsColor);
  try {
    fb.checkComplete();
    FAIL() << "expected an incomplete framebuffer";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("GL_COLOR_ATTACHMENT0"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

TEST_F(GlTest, RenderTargetHasDepthAndStencilAndReadsBackTopRowFirst) {
  gl::RenderTarget target({8, 4});
  target.target().bind();
  glClearColor(0, 0, 1, 1);
  glClearDepth(0.25);
  glClearStencil(7);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
  // Paint GL's bottom row (y = 0) red with a scissored clear: it must be the image's last row.
  glEnable(GL_SCISSOR_TEST);
  glScissor(0, 0, 8, 1);
  glClearColor(1, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  glDisable(GL_SCISSOR_TEST);
  const Image color = gl::readColor(target.framebuffer(), target.size());
  EXPECT_FLOAT_EQ(color.at(0, 3, 0), 1.0f);
  EXPECT_FLOAT_EQ(color.at(0, 0, 2), 1.0f);
  EXPECT_NEAR(gl::readDepth(target.framebuffer(), target.size()).at(5, 2, 0), 0.25f, 1e-6f);
  EXPECT_FLOAT_EQ(gl::readStencil(target.framebuffer(), target.size()).at(1, 1, 0) * 255.0f, 7.0f);
}

TEST_F(GlTest, GpuTimerMeasuresNonNegativeTime) {
  gl::RenderTarget target({64, 64});
  const double ms = gl::GpuTimer::measureMs([&] {
    target.target().bind();
    glClear(GL_COLOR_BUFFER_BIT);
  });
  EXPECT_GE(ms, 0.0);
  EXPECT_LT(ms, 1000.0);
}

// The debug callback counts what the gallery test asserts is absent: errors, and any
// message of medium or high severity (the driver's own, or inserted as here).
TEST_F(GlTest, DebugCallbackCountsErrorsAndNotableMessages) {
  allowGlErrors();
  const auto errors = gl::debugErrorCount(), notable = gl::debugNotableCount();
  glDebugMessageInsert(GL_DEBUG_SOURCE_APPLICATION, GL_DEBUG_TYPE_PERFORMANCE, 1, GL_DEBUG_SEVERITY_LOW, -1, "low: not notable");
  EXPECT_EQ(gl::debugNotableCount(), notable);
  glDebugMessageInsert(GL_DEBUG_SOURCE_APPLICATION, GL_DEBUG_TYPE_PERFORMANCE, 2, GL_DEBUG_SEVERITY_MEDIUM, -1, "medium");
  EXPECT_EQ(gl::debugNotableCount(), notable + 1);
  EXPECT_EQ(gl::debugErrorCount(), errors);
  glBindTexture(GL_TEXTURE_2D, 0xdeadbeef);  // not a texture name: GL_INVALID_OPERATION
  EXPECT_EQ(gl::debugErrorCount(), errors + 1);
  EXPECT_EQ(glGetError(), GLenum(GL_INVALID_OPERATION));
}

TEST_F(GlTest, TextureClearReadAndCopyFromAFramebuffer) {
  gl::Texture tex(GL_TEXTURE_2D, "cleared");
  tex.storage(GL_RGBA8, 4, 2);
  const std::array<std::uint8_t, 4> value{10, 20, 30, 40};
  tex.clear(0, GL_RGBA, GL_UNSIGNED_BYTE, value.data());
  std::array<std::uint8_t, 4 * 4 * 2> texels{};
  tex.read(0, GL_RGBA, GL_UNSIGNED_BYTE, texels.size(), texels.data());
  for (std::size_t i = 0; i < texels.size(); ++i) EXPECT_EQ(texels[i], value[i % 4]) << i;

  // A framebuffer cleared to one colour, blitted flipped into another, copied into the texture.
  gl::RenderTarget a({4, 2}, GL_RGBA8, "a"), b({4, 2}, GL_RGBA8, "b");
  const float red[4] = {1.0f, 0.0f, 0.0f, 1.0f}, blue[4] = {0.0f, 0.0f, 1.0f, 1.0f};
  a.framebuffer().clearColor(0, red);
  b.framebuffer().clearColor(0, blue);
  a.framebuffer().blitTo(b.framebuffer(), {0, 0, 4, 1}, {0, 2, 4, 1}, GL_COLOR_BUFFER_BIT);  // a's row 0 → b's row 1
  b.framebuffer().bind(GL_READ_FRAMEBUFFER);
  tex.copyFromReadFramebuffer(0, 0, 4, 2);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  tex.read(0, GL_RGBA, GL_UNSIGNED_BYTE, texels.size(), texels.data());
  EXPECT_EQ(texels[0], 0);     // GL row 0 of b: still blue
  EXPECT_EQ(texels[2], 255);
  EXPECT_EQ(texels[16], 255);  // GL row 1: red from a
  EXPECT_EQ(texels[18], 0);
}

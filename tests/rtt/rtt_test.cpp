// Render to texture (render/rtt/rtt.h): the copy method and the framebuffer-object method
// give the same texels, at level 0 and through the mip chain; the copy method refuses a
// window smaller than the texture instead of copying garbage.
#include "../support/gl_test.h"

#include "glint/core/error.h"
#include "glint/gl/render_target.h"
#include "glint/render/rtt/rtt.h"

#include <algorithm>
#include <string>

using namespace glint;
namespace rtt = glint::render::rtt;

namespace {
class RttGl : public glint::testing::GlTest {};
}

TEST_F(RttGl, CopyAndFramebufferObjectGiveTheSameTexels) {
  rtt::RttContent content;
  const auto draw = [&](ivec2 size) { content.draw(size, 0.8f); };
  for (int size : {64, 200}) {
    gl::RenderTarget window({size + 37, size + 11});  // larger than the texture, odd sizes
    rtt::CopyToTexture copy(size);
    rtt::FramebufferTexture fbo(size);
    copy.render(window.target(), draw);
    fbo.render(draw);
    for (int level : {0, 1, 3}) {
      const Image a = gl::readTexture(copy.texture(), level);
      const Image b = gl::readTexture(fbo.texture(), level);
      const ImageDifference d = compareImages(a, b);
      EXPECT_EQ(d.maxAbs, 0.0) << "size " << size << " level " << level;
      // Not trivially equal: the content has real detail.
      double spread = 0;
      for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) spread = std::max(spread, double(std::abs(a.at(x, y, 0) - a.at(0, 0, 0))));
      EXPECT_GT(spread, 0.3);
    }
  }
}

TEST_F(RttGl, CopyRefusesAWindowSmallerThanTheTexture) {
  rtt::RttContent content;
  rtt::CopyToTexture copy(256);
  gl::RenderTarget large({256, 256});
  copy.render(large.target(), [&](ivec2 size) { content.draw(size, 0.0f); });
  const Image before = gl::readTexture(copy.texture());
  gl::RenderTarget small({300, 200});
  try {
    copy.render(small.target(), [&](ivec2 size) { content.draw(size, 1.0f); });
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    const std::string message = e.what();
    EXPECT_NE(message.find("256x256"), std::string::npos) << message;
    EXPECT_NE(message.find("300x200"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos);
  }
  // Nothing was drawn or copied: the texture still holds the last good content.
  EXPECT_EQ(compareImages(before, gl::readTexture(copy.texture())).maxAbs, 0.0);
}

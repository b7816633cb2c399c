// render_post OUT.png — a grey ramp through glint's sepia effect on the GPU (headless), by
// a program that links glint::render alone.
#include <glint/core/error.h>
#include <glint/gl/context.h>
#include <glint/image/image.h>
#include <glint/render/post/chain.h>

#include <cstdio>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT.png\n", argv[0]);
    return 2;
  }
  try {
    const auto context = glint::gl::HeadlessContext::create();
    glint::Image ramp(64, 16, 4);
    for (int y = 0; y < ramp.height(); ++y)
      for (int x = 0; x < ramp.width(); ++x)
        for (int c = 0; c < 4; ++c) ramp.set(x, y, c, c == 3 ? 1.0f : float(x) / 63.0f);
    glint::render::post::Chain chain({ramp.width(), ramp.height()}, {glint::render::post::makeEffect("sepia")});
    glint::saveImage(chain.run(ramp), argv[1]);
  } catch (const glint::Error& e) {
    std::fprintf(stderr, "render_post: %s\n", e.what());
    return glint::exitCode(e.kind());
  }
  return 0;
}

// render_scene SCENE/VARIANT OUT.png — one of glint's registered scenes, rendered
// headless into an image file through the installed library (public headers only).
#include <glint/core/error.h>
#include <glint/gl/debug.h>
#include <glint/image/image.h>
#include <glint/scenes/runner.h>

#include <cstdio>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s SCENE/VARIANT OUT.png\n", argv[0]);
    return 2;
  }
  try {
    const auto variant = glint::scenes::Registry::builtin().resolve(argv[1]);  // e.g. "basics/triangle/color"
    glint::scenes::ContextPool contexts(/*debug=*/true);  // headless EGL; GL errors are logged and counted
    contexts.use(variant.scene->profile);
    const auto result = glint::scenes::renderVariant(variant);  // the scene's default size and time
    if (glint::gl::debugErrorCount() > 0) return 1;
    glint::saveImage(result.image, argv[2]);  // the format follows the extension; written atomically
  } catch (const glint::Error& e) {
    std::fprintf(stderr, "render_scene: %s\n", e.what());
    return glint::exitCode(e.kind());
  }
  return 0;
}

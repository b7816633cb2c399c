// glint info — what the OpenGL implementation offers.
#include "common.h"

#include "glint/scenes/runner.h"

#include <fmt/format.h>

namespace glint::app {

Command infoCommand(CLI::App& app, const GlobalOptions& global) {
  app.add_subcommand("info", "Show the OpenGL vendor, renderer, version and the limits glint uses");
  return Command{.run = [&global] {
    scenes::ContextPool contexts(global.glDebug);
    contexts.use(gl::Profile::Core);
    const auto info = gl::queryContextInfo();
    fmt::print("vendor:               {}\n", info.vendor);
    fmt::print("renderer:             {}{}\n", info.renderer, info.software ? "  (software rasterizer)" : "");
    fmt::print("version:              {}\n", info.version);
    fmt::print("GLSL:                 {}\n", info.glslVersion);
    fmt::print("max texture size:     {}\n", info.maxTextureSize);
    fmt::print("max cube map size:    {}\n", info.maxCubeMapSize);
    fmt::print("max anisotropy:       {}\n", info.maxAnisotropy);
    fmt::print("stencil bits:         {} (DEPTH24_STENCIL8)\n", info.stencilBits);
    fmt::print("max MSAA samples:     {}\n", info.maxSamples);
    fmt::print("max colour targets:   {}\n", info.maxColorAttachments);
    const bool compat = contexts.available(gl::Profile::Compatibility);
    fmt::print("compatibility 4.5:    {}\n",
               compat ? "yes (classic fixed-function variants run)"
                      : "no — " + contexts.unavailableReason(gl::Profile::Compatibility));
    return 0;
  }, .readsImages = false};
}

}  // namespace glint::app

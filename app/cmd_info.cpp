// glint info — what the OpenGL implementation offers.
#include "common.h"

#include "glint/scenes/runner.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <memory>

namespace glint::app {

Command infoCommand(CLI::App& app, const GlobalOptions& global) {
  CLI::App* cmd = app.add_subcommand("info", "Show the OpenGL vendor, renderer, version and the limits glint uses");
  auto json = std::make_shared<bool>(false);
  cmd->add_flag("--json", *json,
                "Print the same facts as one JSON object (scripts/gpu-check reads it; \"software\" is true on "
                "llvmpipe, softpipe and swrast)");
  return Command{.run = [&global, json] {
    scenes::ContextPool contexts(global.glDebug);
    contexts.use(gl::Profile::Core);
    const auto info = gl::queryContextInfo();
    const bool compat = contexts.available(gl::Profile::Compatibility);
    if (*json) {
      nlohmann::ordered_json j;
      j["vendor"] = info.vendor;
      j["renderer"] = info.renderer;
      j["software"] = info.software;
      j["version"] = info.version;
      j["glsl"] = info.glslVersion;
      j["max_texture_size"] = info.maxTextureSize;
      j["max_cube_map_size"] = info.maxCubeMapSize;
      j["max_anisotropy"] = info.maxAnisotropy;
      j["stencil_bits"] = info.stencilBits;
      j["max_msaa_samples"] = info.maxSamples;
      j["max_colour_targets"] = info.maxColorAttachments;
      j["compatibility_profile"] = compat;
      fmt::print("{}\n", j.dump(2));
      return 0;
    }
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
    fmt::print("compatibility 4.5:    {}\n",
               compat ? "yes (classic fixed-function variants run)"
                      : "no — " + contexts.unavailableReason(gl::Profile::Compatibility));
    return 0;
  }, .readsImages = false};
}

}  // namespace glint::app

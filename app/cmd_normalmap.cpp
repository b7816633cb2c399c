// glint normalmap — a height map → a tangent-space normal map (the VGP353 lecture's "Normal Map
// Generation"), on the CPU by default or with the GPU pass (--gpu).
#include "common.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/log.h"
#include "glint/image/normalmap.h"
#include "glint/render/bump/height_to_normal.h"
#include "glint/scenes/runner.h"

#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <string>

namespace glint::app {

namespace {
struct NormalMapArgs {
  std::string input;
  std::string output;
  std::string format;
  float scale = NormalMapOptions{}.scale;
  bool wrap = false;
  std::string formula = "gradient";
  bool gpu = false;
  bool check = false;
  bool objectSpace = false;
};

// --check: is the input a usable normal map? A report line, or Error(Input) saying why not.
int checkNormalMap(const NormalMapArgs& args) {
  const Image map = loadImage(args.input);
  NormalMapReport report;
  prepareNormalMap(map, args.input, args.objectSpace ? NormalSpace::Object : NormalSpace::Tangent, &report);
  fmt::print("{}: {}x{} {} {}-channel {} normal map; mean vector length {:.3f}, {:.1f}% pointing out{}\n",
             args.input, map.width(), map.height(), pixelTypeName(map.type()), map.channels(),
             args.objectSpace ? "object-space" : "tangent-space", report.meanLength, 100.0 * report.outwardFraction,
             report.conversion.empty() ? "" : "; " + report.conversion);
  return 0;
}

// The height map → the normal map, on the CPU or the GPU, written with the input's alpha.
int makeNormalMap(const NormalMapArgs& args, const GlobalOptions& global) {
  if (args.output.empty()) fail(ErrorKind::Usage, "normalmap needs -o OUTPUT (or --check)");
  const NormalMapOptions options{.scale = args.scale, .wrap = args.wrap, .formula = parseNormalFormula(args.formula)};
  if (!args.format.empty() && args.output != "-") {
    fail(ErrorKind::Usage, "--format is for -o - (stdout); a file's format follows its extension");
  }
  checkDistinctFiles({{args.input, "the height map"}}, {{args.output, "-o"}});
  checkImageOutput(args.output, args.format);  // fail before working, not after
  const Image input = loadImage(args.input);
  checkHeightMap(input, options, args.input);  // the checks glint.normalmap makes too (image/normalmap.h)
  Image normals;
  if (args.gpu) {
    scenes::ContextPool contexts(global.glDebug);
    contexts.use(gl::Profile::Core);
    normals = render::bump::heightToNormalMapGpu(input, options);
  } else {
    normals = heightToNormalMap(input, options);
  }
  const Image written = withHeightAlpha(normals, input);
  saveImage(written, args.output, args.format);
  log::info("{} ({}x{}, {}) → {} ({} normals, scale {}{})", args.input, input.width(), input.height(),
            pixelTypeName(input.type()), args.output, args.gpu ? "GPU" : "CPU", args.scale,
            args.wrap ? ", wrapped" : "");
  return 0;
}
}  // namespace

Command normalmapCommand(CLI::App& app, const GlobalOptions& global) {
  auto args = std::make_shared<NormalMapArgs>();
  auto* cmd = app.add_subcommand("normalmap", "Make a tangent-space normal map from a height map (the VGP353 lecture)");
  cmd->footer(
      "Each texel's normal comes from its four neighbours n, s, e, w: n = normalize(S·(w−e)/2, S·(s−n)/2, 1), with "
      "north up in the picture (OpenGL-style maps: green = up). The output is 8-bit RGB, (n + 1)/2; RGBA with the "
      "input's alpha when the height map has one.\n"
      "Examples:\n  glint normalmap height.png -o normal.png\n"
      "  glint normalmap bricks.png -o bricks_n.png --scale 12 --wrap\n"
      "  glint normalmap --check baked.png      (is this a usable normal map?)\n"
      "  convert photo.jpg -colorspace gray png:- | glint normalmap - -o - > normal.png\n"
      "Any size works (powers of two or not). A colour image is converted to its luminance (a warning says so).");
  cmd->add_option("height", args->input, "Height map (any image format; 8-bit, 16-bit or float; '-': stdin)")->required();
  cmd->add_option("-o,--output", args->output, "Output normal map; the format follows the extension (required; '-': "
                                               "stdout, see --format)");
  cmd->add_option("--format", args->format, "The image format of -o - (stdout): png (default), tga, tif, exr, ...");
  cmd->add_option("--scale", args->scale,
                  "Height of the full 0..1 range in texel widths: larger = bumpier (default 8; negative inverts)");
  cmd->add_flag("--wrap", args->wrap, "Neighbours wrap around the edges (tileable textures); default clamps");
  cmd->add_option("--formula", args->formula,
                  "gradient (the surface's true normal) or slide (the VGP353 lecture's formula as written: x mirrored, "
                  "z = 1 − |d|; --scale 2 reproduces it exactly)")
      ->check(CLI::IsMember({"gradient", "slide"}));
  cmd->add_flag("--gpu", args->gpu, "Use the GPU pass (full-screen quad into a framebuffer) instead of the CPU");
  cmd->add_flag("--check", args->check,
                "Instead: check that the input is a usable normal map (encoding, unit length, orientation) and "
                "report; exit 3 with the reason when it is not");
  cmd->add_flag("--object-space", args->objectSpace, "With --check: the map is object-space (any direction is fine)");
  return Command{.run = [args, &global] { return args->check ? checkNormalMap(*args) : makeNormalMap(*args, global); }};
}

}  // namespace glint::app

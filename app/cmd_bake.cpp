// glint bake LOW HIGH -o OUT — the normal mapper: high-poly detail into a texture for the
// low poly. Thin: options → bake::BakeOptions, files in and out, the report.
#include "common.h"

#include "glint/bake/baker.h"
#include "glint/bake/output.h"
#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/log.h"
#include "glint/image/image.h"
#include "glint/mesh/mesh.h"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <exception>
#include <filesystem>
#include <future>
#include <memory>
#include <optional>
#include <sstream>

namespace glint::app {

namespace {

struct BakeArgs {
  std::string low, high, output, size = "1024x1024", space = "tangent", worldMatrix;
  std::string maxFront = "5%", maxRear = "5%", aoDistance = "10%";
  std::string cage, detail, ao, height, missMask;
  int samples = 1, padding = 16, bits = 0, aoSamples = 16;
  float detailScale = 8.0f;
  bool directX = false, frontFirst = false, fillAll = false;
  ToolSettings tool;
};

/// "5%" → 5 % of the low poly's diagonal; "0.2" → 0.2 scene units.
bake::Distance parseDistance(const std::string& text, const char* option) {
  std::string number = text;
  const bool relative = !number.empty() && number.back() == '%';
  if (relative) number.pop_back();
  float value = -1.0f;
  try {
    value = parseFloat(number, option);  // the whole text, finite, no locale
  } catch (const Error&) {
    value = -1.0f;
  }
  if (!(value >= 0.0f)) {
    fail(ErrorKind::Usage, "{} must be a distance like 0.2 (scene units) or 5% (of the low poly's size), got '{}'",
         option, text);
  }
  return {relative ? value / 100.0f : value, relative};
}

mat4 parseMatrix(const std::string& text) {
  std::vector<float> v;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    v.push_back(parseFloat(item, "--world-matrix"));
  }
  if (v.size() != 16) fail(ErrorKind::Usage, "--world-matrix needs 16 comma-separated numbers (row by row), got {}", v.size());
  mat4 m;
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) m[col][row] = v[std::size_t(row * 4 + col)];
  return m;
}

constexpr const char* kFooter = R"(Examples:
  glint bake car_low.obj car_high.ply -o car_normal.png
  glint bake head_low.fbx head_high.fbx -o head.png --size 2048x2048 --samples 36 \
        --height-detail pores.png --detail-scale 4 --ao head_ao.png --json report.json

How it works: for every texel, rays start on the low poly (interpolated position) and
follow its interpolated normal forwards (--max-front) and backwards (--max-rear): the
low poly may be inside, outside or through the high poly. The hit's high-poly normal is
stored relative to the low poly's MikkTSpace tangent frame (the frame Blender, Unity,
Unreal, glTF and glint's renderer use), so the map decodes exactly where it is used.

Notes for artists:
  Shared normals   Rays follow the low poly's interpolated normals. At a hard edge (two
                   normals at one point) the rays fan apart and the high-poly detail in
                   the gap is never seen. Use smooth, shared normals on the low poly;
                   glint warns about hard edges. Or bake through a --cage.
  UV spacing       A normal map holds vectors, not colours: a texel that bleeds in from a
                   neighbouring island bends the lighting. Leave gaps between islands
                   (twice the padding at the smallest mip you use) and keep --padding on;
                   bilinear filtering and mipmaps read across island borders.
  Mirrored UVs     Fine in tangent space (the bitangent sign flips); overlapping UVs
                   share texels, so only one of the overlapping parts is baked.
  Micro detail     Model the big shapes, paint scars and pores into a height map and
                   combine them here (--height-detail): smooth ray-cast shape plus detail.

Exit status: 0 done, 2 bad option, 3 unreadable/unsuitable input, 4 output not
writable, 130 interrupted (Ctrl-C; no partial file is left).)";

}  // namespace

Command bakeCommand(CLI::App& app, const GlobalOptions& global) {
  auto a = std::make_shared<BakeArgs>();
  auto* cmd = app.add_subcommand("bake", "Bake a high-poly mesh's detail into a normal map for a low-poly mesh");
  cmd->footer(kFooter);
  cmd->add_option("low", a->low, "Low-poly mesh: positions, normals, one UV set (OBJ, PLY, glTF/GLB, FBX, ...)")->required();
  cmd->add_option("high", a->high, "High-poly mesh: positions and normals")->required();
  cmd->add_option("-o,--output", a->output, "Normal map to write; format from the extension: .png .tga .tif .exr")->required();
  cmd->add_option("--size", a->size, "Map size WIDTHxHEIGHT, any size")->capture_default_str();
  cmd->add_option("--samples", a->samples, "Rays per texel, a square: 1, 4, 9, 16, 36, 64 (stratified √N×√N grid, "
                  "averaged; 36 is smooth)")->capture_default_str();
  cmd->add_option("--space", a->space, "tangent (MikkTSpace), object, or world (see --world-matrix)")
      ->check(CLI::IsMember({"tangent", "object", "world"}))->capture_default_str();
  cmd->add_option("--world-matrix", a->worldMatrix, "Object-to-world matrix for --space world: 16 numbers, row by row");
  cmd->add_flag("--directx", a->directX, "Flip green (DirectX/Unreal convention); the default is OpenGL's +Y");
  cmd->add_option("--bits", a->bits, "Bits per channel of every map written: 8 or 16 for PNG/TIFF (default: 8 PNG/TGA, "
                  "16 TIFF, 32 float EXR)")
      ->check(CLI::IsMember({8, 16, 32}));
  cmd->add_option("--max-front", a->maxFront, "How far in front of the low poly rays look: 0.2 (scene units) or 5% "
                  "(of its bounding-box diagonal)")->capture_default_str();
  cmd->add_option("--max-rear", a->maxRear, "How far behind the low poly rays look (negative rays)")->capture_default_str();
  cmd->add_flag("--front-first", a->frontFirst, "Prefer hits in front of the low poly; default: the closest hit either way");
  cmd->add_option("--cage", a->cage, "Cage mesh: the low poly with vertices pushed outwards (same vertices and "
                  "triangles); rays then go from the cage inwards");
  cmd->add_option("--padding", a->padding, "Texels of dilation around UV islands (0: none)")->capture_default_str();
  cmd->add_flag("--fill-all", a->fillAll, "Dilate until every texel is filled");
  cmd->add_option("--height-detail", a->detail, "Painted height map (scars, pores) combined with the baked normals; "
                  "tiled over the UVs");
  cmd->add_option("--detail-scale", a->detailScale, "Bumpiness of --height-detail: the height of its 0..1 range in "
                  "texel widths (8: a black-to-white ramp over 8 texels is 45°; negative engraves)")->capture_default_str();
  cmd->add_option("--ao", a->ao, "Also bake ambient occlusion (hemisphere rays against the high poly) to this file");
  cmd->add_option("--ao-samples", a->aoSamples, "AO rays per sample")->capture_default_str();
  cmd->add_option("--ao-distance", a->aoDistance, "AO ray length: scene units or % of the low poly's diagonal")
      ->capture_default_str();
  cmd->add_option("--height", a->height, "Also bake height/displacement (signed ray distance) to this file; 8/16-bit "
                  "files map ±max(--max-front, --max-rear) to 0..1, EXR keeps distances");
  cmd->add_option("--miss-mask", a->missMask, "Also write the fraction of each texel's rays that found nothing (debug)");
  addToolOptions(*cmd, a->tool, "texels, rays, hit ratio, misses, BVH size");

  return Command{.run = [a, &global] {
    (void)global;
    ToolRun run("bake", a->tool);

    // Options and outputs first: fail in a millisecond, not after the bake. No output may
    // be an input or another output (by file identity: core/file.h).
    checkDistinctFiles({{a->low, "the low poly"}, {a->high, "the high poly"}, {a->cage, "--cage"},
                        {a->detail, "--height-detail"}},
                       {{a->output, "-o"}, {a->ao, "--ao"}, {a->height, "--height"}, {a->missMask, "--miss-mask"},
                        {a->tool.json, "--json"}});
    bake::BakeOptions options;
    const ivec2 size = parseSize(a->size);
    options.width = size.x;
    options.height = size.y;
    options.samples = a->samples;
    options.space = a->space == "object" ? NormalSpace::Object
                  : a->space == "world"  ? NormalSpace::World
                                         : NormalSpace::Tangent;
    if (!a->worldMatrix.empty()) options.objectToWorld = parseMatrix(a->worldMatrix);
    options.directX = a->directX;
    options.maxFront = parseDistance(a->maxFront, "--max-front");
    options.maxRear = parseDistance(a->maxRear, "--max-rear");
    options.selection = a->frontFirst ? bake::HitSelection::FrontFirst : bake::HitSelection::Closest;
    options.padding = a->padding;
    options.fillAll = a->fillAll;
    options.ambientOcclusion = !a->ao.empty();
    options.aoSamples = a->aoSamples;
    options.aoDistance = parseDistance(a->aoDistance, "--ao-distance");
    options.heightMap = !a->height.empty();
    options.missMask = !a->missMask.empty();
    options.progress = run.showProgress();
    options.cancel = &run.cancelFlag();
    bake::validateOptions(options);
    const PixelType normalType = bake::outputType(a->output, a->bits);
    options.normalType = normalType;  // quantized by the baker: no float copy of the map
    std::vector<std::string> outputs{a->output};
    for (const std::string* extra : {&a->ao, &a->height, &a->missMask}) {
      if (extra->empty()) continue;
      bake::outputType(*extra, a->bits);  // --bits applies to every map: check them all now
      outputs.push_back(*extra);
    }
    if (!a->tool.json.empty() && a->tool.json != "-") outputs.push_back(a->tool.json);
    for (const auto& path : outputs) checkWritable(path);
    run.checkMemory(bake::estimatePeakMemoryMiB(options, {a->low, a->high, a->cage}),
                    fmt::format("a {}x{} bake", size.x, size.y));
    // OpenImageIO is needed for a detail map and for outputs other than PNG (libspng).
    bool needsImageIo = !a->detail.empty();
    for (std::size_t i = 0; i < outputs.size(); ++i) {
      const bool json = !a->tool.json.empty() && a->tool.json != "-" && i + 1 == outputs.size();
      std::string ext = std::filesystem::path(outputs[i]).extension().string();
      for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
      if (!json && ext != ".png") needsImageIo = true;
    }
    if (needsImageIo) {
      requireImageIo();
      preloadImageIo();
    }

    // Inputs (never modified: loaded into memory, prepared there).
    // The high poly (the big file) is parsed here while a second thread reads the rest;
    // errors are reported in argument order: low, high, cage, detail.
    std::optional<ToolRun::Phase> loading(std::in_place, run, "load");
    auto others = std::async(std::launch::async, [&] {
      Mesh low = loadMesh(a->low);
      if (!a->cage.empty()) options.cage = loadMesh(a->cage);
      if (!a->detail.empty()) options.detail = bake::HeightDetail{loadImage(a->detail), a->detailScale};
      return low;
    });
    // Rays need no shared vertices: skipping Assimp's vertex joining halves the load.
    std::optional<Mesh> high;
    std::exception_ptr highError;
    try {
      high = loadMesh(a->high, {.joinVertices = false});
    } catch (...) {
      highError = std::current_exception();
    }
    const Mesh low = others.get();
    if (highError) std::rethrow_exception(highError);
    loading.reset();
    run.throwIfInterrupted();
    const bake::BakeResult result = bake::bake(low, *high, options);
    const bake::BakeStats& s = result.stats;
    run.addSeconds("prepare", s.prepareSeconds);
    run.addSeconds("trace", s.traceSeconds);
    run.addSeconds("dilate", s.dilateSeconds);

    std::optional<ToolRun::Phase> writing(std::in_place, run, "write");
    saveImage(result.normal, a->output);
    if (!a->ao.empty()) saveImage(bake::forOutput(result.ao, bake::outputType(a->ao, a->bits)), a->ao);
    if (!a->height.empty()) {
      const float range = std::max(result.stats.frontDistance, result.stats.rearDistance);
      saveImage(bake::heightForOutput(result.height, bake::outputType(a->height, a->bits), range), a->height);
    }
    if (!a->missMask.empty()) saveImage(bake::forOutput(result.missMask, bake::outputType(a->missMask, a->bits)), a->missMask);
    writing.reset();
    log::info("bake: {} ({} triangles) → {} ({}x{}, {} per texel): {} texels baked, {} padded; {} rays, hit ratio "
              "{:.4f}; {:.2f} s", a->high, high->triangleCount(), a->output, options.width, options.height,
              options.samples, s.coveredTexels, s.paddedTexels, s.rays, s.hitRatio(), run.elapsed());

    auto& report = run.report();
    report["low"] = a->low;
    report["high"] = a->high;
    report["output"] = a->output;
    report.update(bake::toJson(options));
    report.update(bake::toJson(s));
    for (const auto& w : result.warnings) run.recordWarning(w);
    run.finish();
    return 0;
  },
  // The OpenImageIO module is started by the command itself, only when it reads an image
  // or writes another format than PNG (libspng): its 0.3 s of dynamic linking would take
  // the second core from the mesh parser.
  .readsImages = false};
}

}  // namespace glint::app

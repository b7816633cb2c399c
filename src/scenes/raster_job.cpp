// glint raster's job (scenes/raster_job.h): the lecture's triangle, a mesh or a reference
// scene's draws through glint::raster, into five pictures and a text report.
#include "glint/scenes/raster_job.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/progress.h"
#include "glint/core/text.h"
#include "glint/image/image.h"
#include "glint/mesh/mesh.h"
#include "glint/raster/raster.h"
#include "glint/core/camera.h"
#include "glint/scenes/reference.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <span>

namespace fs = std::filesystem;

namespace glint::scenes {

namespace {

constexpr std::size_t kTrianglesPerStep = 4096;  // progress granularity for large meshes

/// One draw: its state, its vertices and (optionally) indices into them.
struct Draw {
  std::string what;
  raster::State state;
  std::vector<raster::Vertex> vertices;
  std::vector<std::uint32_t> indices;  // empty: non-indexed
  std::size_t triangleCount() const { return (indices.empty() ? vertices.size() : indices.size()) / 3; }
  const raster::Vertex& vertex(std::size_t triangle, int corner) const {
    const std::size_t k = 3 * triangle + std::size_t(corner);
    return vertices[indices.empty() ? k : std::size_t(indices[k])];
  }
};

struct Frame {
  ivec2 size{500, 500};
  vec4 clearColor{0.0f};
  float clearDepth = 1.0f;
  int clearStencil = 0;
  std::vector<Draw> draws;
};


/// Creates DIR when missing; Error(Output) when it cannot hold our files.
void prepareOutputDir(const std::string& dir) {
  if (dir.empty()) fail(ErrorKind::Usage, "an output directory is required (-o DIR)");
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) fail(ErrorKind::Output, "cannot write into '{}': not a directory", dir);
  fs::create_directories(dir, ec);
  if (ec) fail(ErrorKind::Output, "cannot create output directory '{}': {}", dir, ec.message());
  checkWritable(fs::path(dir) / "color.png");
}

// -- The three ways to get geometry --------------------------------------------------

Frame lectureFrame(ivec2 size) {
  const auto setup = scenes::referenceSetup("triangle", size);
  Frame f{.size = size, .clearColor = setup.clearColor, .clearDepth = setup.clearDepth, .clearStencil = setup.clearStencil};
  for (const auto& d : setup.draws) f.draws.push_back({d.what, d.state, d.vertices, {}});
  return f;
}

Frame sceneFrame(const std::string& name, ivec2 size) {
  const std::string prefix = "basics/reference/";
  if (name.rfind(prefix, 0) != 0) {
    std::string names;
    for (const auto& v : scenes::referenceVariants()) names += (names.empty() ? "" : ", ") + prefix + v;
    fail(ErrorKind::Usage, "only the basics/reference scenes describe their draws as data ({}), got '{}'", names, name);
  }
  const auto setup = scenes::referenceSetup(name.substr(prefix.size()), size);
  Frame f{.size = size, .clearColor = setup.clearColor, .clearDepth = setup.clearDepth, .clearStencil = setup.clearStencil};
  for (const auto& d : setup.draws) f.draws.push_back({d.what, d.state, d.vertices, {}});
  return f;
}

/// The mesh centred and scaled to radius 1, seen by an orbit camera whose near and far planes
/// hug the bounding sphere (so depth.png uses the whole range); per-vertex Lambert
/// shading (the "vertex shader" runs here) becomes varying 0.
Frame meshFrame(const Mesh& mesh, ivec2 size, vec3 camera, bool cull) {
  const Bounds b = mesh.bounds();
  const float radius = std::max(0.5f * b.diagonal(), 1e-20f);
  const mat4 model = glm::scale(mat4(1.0f), vec3(1.0f / radius)) * glm::translate(mat4(1.0f), -b.center());
  const auto cam = glint::Camera::orbit(vec3(0.0f), camera.z, glm::radians(camera.x), glm::radians(camera.y), 40.0f,
                                         float(size.x) / float(size.y), 0.9f * (camera.z - 1.0f), camera.z + 1.1f);
  const mat4 mvp = cam.viewProjection() * model;
  // Light from the upper left behind the viewer, fixed to the camera.
  const vec3 light = glm::normalize(glm::transpose(cam.rotation()) * glm::normalize(vec3(-0.4f, 0.6f, 0.7f)));
  const vec3 albedo{0.85f, 0.74f, 0.58f};
  Draw job{.what = fmt::format("{} triangles, Lambert-shaded per vertex", mesh.triangleCount()),
          .state = raster::State{.depthTest = true,
                                 .stencilTest = true,  // counts depth-test passes: how often each pixel was overwritten
                                 .stencilFront = {.dppass = raster::StencilOp::Incr},
                                 .stencilBack = {.dppass = raster::StencilOp::Incr},
                                 .cull = cull},
          .indices = mesh.indices};
  job.vertices.reserve(mesh.vertexCount());
  for (std::size_t i = 0; i < mesh.vertexCount(); ++i) {
    const vec3 n = mesh.hasNormals() ? glm::normalize(mesh.normals[i]) : vec3(0.0f, 0.0f, 1.0f);
    const float lambert = std::max(0.0f, glm::dot(n, light));
    job.vertices.push_back({mvp * vec4(mesh.positions[i], 1.0f), {vec4(albedo * (0.15f + 0.85f * lambert), 1.0f)}});
  }
  return Frame{.size = size, .clearColor = vec4(0.12f, 0.14f, 0.18f, 1.0f), .draws = {std::move(job)}};
}

// -- The chosen triangle ---------------------------------------------------------------

struct ChosenTriangle {
  std::size_t index = 0;
  std::array<glm::dvec3, 3> window{};  // x, y, z
};

std::size_t totalTriangles(const Frame& f) {
  std::size_t n = 0;
  for (const Draw& j : f.draws) n += j.triangleCount();
  return n;
}

/// Window coordinates of triangle t (counted across all jobs), or nullopt when a vertex is
/// on or behind the eye plane (w <= 0): its edge functions are not a window-space picture.
std::optional<std::array<glm::dvec3, 3>> windowTriangle(const Frame& f, std::size_t t) {
  for (const Draw& j : f.draws) {
    if (t >= j.triangleCount()) {
      t -= j.triangleCount();
      continue;
    }
    const raster::Viewport vp = raster::effectiveViewport(j.state, f.size.x, f.size.y);
    std::array<glm::dvec3, 3> out{};
    for (int c = 0; c < 3; ++c) {
      const vec4 p = j.vertex(t, c).position;
      if (!(p.w > 0.0f) || !std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return std::nullopt;
      out[std::size_t(c)] = raster::clipToWindow(glm::dvec4(p), vp, j.state.depthRange);
    }
    return out;
  }
  return std::nullopt;
}

/// --triangle N, or the largest (by window area, in front of the eye) when N < 0.
ChosenTriangle chooseTriangle(const Frame& f, int requested) {
  const std::size_t total = totalTriangles(f);
  if (requested >= 0) {
    if (std::size_t(requested) >= total)
      fail(ErrorKind::Usage, "--triangle {} is out of range: there are {} triangles (0..{})", requested, total, total - 1);
    const auto w = windowTriangle(f, std::size_t(requested));
    if (!w) fail(ErrorKind::Usage, "triangle {} has a vertex behind the eye (w <= 0); choose another with --triangle", requested);
    if (raster::signedArea2(glm::dvec2((*w)[0]), glm::dvec2((*w)[1]), glm::dvec2((*w)[2])) == 0.0)
      fail(ErrorKind::Usage, "triangle {} has zero area in window space: it has no edge functions to show", requested);
    return {std::size_t(requested), *w};
  }
  std::optional<ChosenTriangle> best;
  double bestArea = 0.0;
  const glm::dvec2 lo(0.0), hi(f.size);
  for (std::size_t t = 0; t < total; ++t) {
    const auto w = windowTriangle(f, t);
    if (!w) continue;
    // Area of the part near the window: clamp the vertices (a cheap stand-in for clipping).
    const auto c = [&](int i) { return glm::clamp(glm::dvec2((*w)[std::size_t(i)]), lo, hi); };
    const double area = std::abs(raster::signedArea2(c(0), c(1), c(2)));
    if (area > bestArea) bestArea = area, best = ChosenTriangle{t, *w};
  }
  if (!best) fail(ErrorKind::Input, "no triangle is in front of the eye and inside the window: nothing to show");
  return *best;
}

// -- Rendering and output --------------------------------------------------------------

struct Rendered {
  raster::Framebuffer fb;
  raster::DrawStats stats;
};

void accumulate(raster::DrawStats& total, const raster::DrawStats& s) {
  total.triangles += s.triangles, total.rejected += s.rejected, total.clippedAway += s.clippedAway;
  total.degenerate += s.degenerate, total.culled += s.culled, total.clipped += s.clipped;
  total.fragments += s.fragments, total.discarded += s.discarded, total.stencilFailed += s.stencilFailed;
  total.depthFailed += s.depthFailed, total.written += s.written;
}

Rendered renderFrame(const Frame& f) {
  Rendered r{raster::Framebuffer(f.size.x, f.size.y, {.depth = raster::DepthFormat::Unorm24}), {}};
  r.fb.clear(f.clearColor, f.clearDepth, f.clearStencil);
  Progress progress("rasterizing", totalTriangles(f));
  for (const Draw& j : f.draws) {
    const std::size_t n = j.triangleCount();
    for (std::size_t first = 0; first < n; first += kTrianglesPerStep) {
      const std::size_t count = std::min(kTrianglesPerStep, n - first);
      // Indexed draws go in slices (same order, same result) so the bar can move.
      const raster::DrawStats s =
          j.indices.empty() ? raster::drawTriangles(r.fb, j.state, std::span(j.vertices).subspan(3 * first, 3 * count))
                            : raster::drawTriangles(r.fb, j.state, j.vertices, std::span(j.indices).subspan(3 * first, 3 * count));
      accumulate(r.stats, s);
      progress.advance(count);
    }
  }
  progress.finish();
  return r;
}

std::uint32_t maxOf(std::span<const std::uint32_t> v) { return v.empty() ? 0 : *std::max_element(v.begin(), v.end()); }

void writeOutputs(const Rendered& r, const ChosenTriangle& chosen, const std::string& dir) {
  const fs::path out(dir);
  const std::array<glm::dvec2, 3> xy = {glm::dvec2(chosen.window[0]), glm::dvec2(chosen.window[1]), glm::dvec2(chosen.window[2])};
  saveImage(raster::colorImage(r.fb).converted(PixelType::U8), out / "color.png");
  saveImage(raster::depthImage(r.fb), out / "depth.png");  // 16-bit PNG: depth needs more than 256 levels
  saveImage(raster::edgeFunctionsImage(xy, r.fb.width(), r.fb.height()), out / "edges.png");
  saveImage(raster::overdrawImage(r.fb), out / "overdraw.png");
  saveImage(raster::stencilImage(r.fb), out / "stencil.png");
}

void appendStats(std::string& out, const raster::DrawStats& s) {
  fmt::format_to(std::back_inserter(out), "pipeline: {} triangles: {} clipped away, {} clipped, {} culled, {} degenerate, {} rejected (NaN/inf)\n",
             s.triangles, s.clippedAway, s.clipped, s.culled, s.degenerate, s.rejected);
  fmt::format_to(std::back_inserter(out), "          {} fragments: {} written, {} failed the depth test, {} failed the stencil test\n", s.fragments,
             s.written, s.depthFailed, s.stencilFailed);
}

void appendEdges(std::string& out, std::size_t index, const std::array<glm::dvec3, 3>& window) {
  const std::array<glm::dvec2, 3> xy = {glm::dvec2(window[0]), glm::dvec2(window[1]), glm::dvec2(window[2])};
  const double area2 = raster::signedArea2(xy[0], xy[1], xy[2]);
  fmt::format_to(std::back_inserter(out), "triangle {}: window (x, y, z) = ({:.4f}, {:.4f}, {:.6f}), ({:.4f}, {:.4f}, {:.6f}), ({:.4f}, {:.4f}, {:.6f})\n",
             index, window[0].x, window[0].y, window[0].z, window[1].x, window[1].y, window[1].z, window[2].x, window[2].y,
             window[2].z);
  fmt::format_to(std::back_inserter(out), "  2 x signed area = {:.6g}: {}\n", area2,
             area2 < 0 ? "clockwise, so every edge is negated (\"reverse the comparison sense\")"
                       : "counter-clockwise, edges used as they are");
  const auto edges = raster::orientedEdges(xy);
  static const char* const kNames[] = {"E0 (v1->v2)", "E1 (v2->v0)", "E2 (v0->v1)"};
  for (std::size_t i = 0; i < 3; ++i)
    fmt::format_to(std::back_inserter(out), "  {}: A = {:.6g}, B = {:.6g}, C = {:.6g}   (edges.png panel {})\n", kNames[i], edges[i].a, edges[i].b,
               edges[i].c, i + 1);
  if (const auto z = raster::planeEquation(window[0], window[1], window[2]))
    fmt::format_to(std::back_inserter(out), "  z plane: Z(x, y) = {:.7g} x + {:.7g} y + {:.7g}\n", z->a, z->b, z->c);
}

/// The lecture's own numbers (the OpenGL III lecture), recomputed with the functions the pipeline uses.
std::string lectureNumbers(const Frame& f) {
  std::string out;
  const Draw& job = f.draws.front();
  const raster::Viewport vp = raster::effectiveViewport(job.state, f.size.x, f.size.y);
  fmt::format_to(std::back_inserter(out), "The lecture's triangle (the OpenGL III lecture), glViewport({}, {}, {}, {}), glDepthRange(0, 1)\n\n", vp.x, vp.y,
             vp.width, vp.height);
  fmt::format_to(std::back_inserter(out), "NDC -> window: w_x = (w/2) x + v_x + w/2, w_y = (h/2) y + v_y + h/2, w_z = z/2 + 1/2\n");
  static const char* const kColors[] = {"red  ", "green", "blue "};
  std::array<glm::dvec3, 3> win{};
  for (int i = 0; i < 3; ++i) {
    const vec4 p = job.vertices[std::size_t(i)].position;
    win[std::size_t(i)] = raster::clipToWindow(glm::dvec4(p), vp);
    const raster::FixedPoint fp = raster::snapToSubpixel(glm::dvec2(win[std::size_t(i)]));
    fmt::format_to(std::back_inserter(out), "  {} NDC ({:5.2f}, {:5.2f}, {:5.2f}) -> window ({:g}, {:g}, {:g})  fixed point ({}, {}) / 256\n",
               kColors[i], p.x / p.w, p.y / p.w, p.z / p.w, win[std::size_t(i)].x, win[std::size_t(i)].y,
               win[std::size_t(i)].z, fp.x, fp.y);
  }
  const double cx = vp.x + vp.width / 2.0, cy = vp.y + vp.height / 2.0;
  const raster::EdgeEquation ln = raster::edgeEquation(glm::dvec2(win[1]), glm::dvec2(win[0]));
  fmt::format_to(std::back_inserter(out), "\nEdge equation setup (slide \"Look at the LN edge\", L = green, N = red):\n");
  fmt::format_to(std::back_inserter(out), "  A = Ly - Ny = {:g}, B = Nx - Lx = {:g}, C = Ny Lx - Nx Ly = {:g}\n", ln.a, ln.b, ln.c);
  fmt::format_to(std::back_inserter(out), "  E({:g}, {:g}) = {:g} {} 0, so ({:g}, {:g}) is {} the triangle\n", cx, cy, ln(cx, cy),
             ln(cx, cy) > 0 ? ">" : "<=", cx, cy, ln(cx, cy) > 0 ? "in" : "not in");
  if (const auto z = raster::planeEquation(win[0], win[2], win[1])) {
    fmt::format_to(std::back_inserter(out), "\nInterpolating window z (slide \"Setup Plane Equation\"):\n");
    fmt::format_to(std::back_inserter(out), "  [Lx Ly 1; Mx My 1; Nx Ny 1]^-1 [{:g} {:g} {:g}]^T with L = red, M = blue, N = green\n", win[0].z,
               win[2].z, win[1].z);
    fmt::format_to(std::back_inserter(out), "  A_z = {:.7g}, B_z = {:.7g}, C_z = {:.7g}\n", z->a, z->b, z->c);
    fmt::format_to(std::back_inserter(out), "  Z({:g}, {:g}) = {:.7g} (pixel ({}, {})'s centre)\n", cx + 0.5, cy + 0.5, (*z)(cx + 0.5, cy + 0.5),
               int(cx), int(cy));
  }
  if (const auto bary = raster::barycentric(glm::dvec2(win[0]), glm::dvec2(win[1]), glm::dvec2(win[2]),
                                            glm::dvec2(cx + 0.5, cy + 0.5))) {
    fmt::format_to(std::back_inserter(out), "\nBarycentric coordinates at ({:g}, {:g}): alpha = {:.5f} (red), beta = {:.5f} (green), gamma = {:.5f} "
               "(blue); sum = {:g}\n",
               cx + 0.5, cy + 0.5, bary->x, bary->y, bary->z, bary->x + bary->y + bary->z);
  }
  fmt::format_to(std::back_inserter(out), "\n");
  return out;
}

}  // namespace

vec3 parseOrbitCamera(std::string_view text) {
  const auto fields = splitFields(text, ',');
  if (fields.size() != 2 && fields.size() != 3)
    fail(ErrorKind::Usage, "--camera must be AZIMUTH,ELEVATION[,DISTANCE] (degrees, degrees, bounding radii), got '{}'",
         printable(text));
  // core/text's strict numbers: no spaces, no "nan", nothing after the last number.
  const float az = parseFloat(fields[0], "--camera azimuth"), el = parseFloat(fields[1], "--camera elevation");
  const float dist = fields.size() == 3 ? parseFloat(fields[2], "--camera distance") : 2.6f;
  if (std::abs(el) >= 90.0f) fail(ErrorKind::Usage, "--camera elevation must be within (-90, 90) degrees, got {}", el);
  if (!(dist > 1.0f) || dist > 1000.0f)
    fail(ErrorKind::Usage, "--camera distance must be above 1 (outside the mesh's bounding sphere) and at most 1000, got {}", dist);
  return {az, el, dist};
}

std::string RasterReport::text() const {
  std::string out = lecture;
  for (const std::string& d : draws) fmt::format_to(std::back_inserter(out), "draw: {}\n", d);
  appendStats(out, stats);
  appendEdges(out, triangle, window);
  fmt::format_to(std::back_inserter(out),
                 "wrote {}/{{color,depth,edges,overdraw,stencil}}.png ({}x{}; overdraw up to {}, stencil up to {})\n",
                 output, size.x, size.y, maxOverdraw, maxStencil);
  return out;
}

RasterReport runRasterJob(const RasterJob& job) {
  // Everything checked before anything is written.
  const ivec2 size = job.size.value_or(job.geometry == RasterGeometry::Mesh ? ivec2(640, 480) : ivec2(500, 500));
  if (size.x < 1 || size.y < 1 || size.x > kMaxImageSide || size.y > kMaxImageSide)
    fail(ErrorKind::Usage, "--size must be 1x1 to {0}x{0}, got {1}x{2}", kMaxImageSide, size.x, size.y);
  Frame frame;
  switch (job.geometry) {
    case RasterGeometry::Lecture: frame = lectureFrame(size); break;
    case RasterGeometry::Mesh: {
      const Mesh m = loadMesh(job.mesh);
      m.validate(job.mesh);
      frame = meshFrame(m, size, job.camera, job.cull);
      break;
    }
    case RasterGeometry::Scene: frame = sceneFrame(job.scene, size); break;
  }
  const ChosenTriangle chosen = chooseTriangle(frame, job.triangle);
  prepareOutputDir(job.output);

  RasterReport report{.output = job.output, .size = size, .triangle = chosen.index, .window = chosen.window};
  if (job.geometry == RasterGeometry::Lecture) report.lecture = lectureNumbers(frame);
  for (const Draw& d : frame.draws) report.draws.push_back(d.what);
  const Rendered r = renderFrame(frame);
  report.stats = r.stats;
  writeOutputs(r, chosen, job.output);
  const std::vector<std::uint32_t> stencils(r.fb.stencils().begin(), r.fb.stencils().end());
  report.maxOverdraw = maxOf(r.fb.overdraws());
  report.maxStencil = maxOf(stencils);
  return report;
}

}  // namespace glint::scenes

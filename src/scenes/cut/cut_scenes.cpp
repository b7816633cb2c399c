// cut/* — the shadow cutter's result (WWDC 2003 session 212, ATI's "Pipe Dream" static shadows). Each
// scene cuts its geometry with glint_cut when it is created, so what is drawn is exactly
// what `glint cut` writes for it:
//   cut/table       WWDC 2003 session 212's example: a table and a microphone under one light. pieces:
//                   lit pieces warm, shadowed ones blue, the cut wireframe on top; shaded:
//                   drawn as a renderer would use the cut (N·L where the light reaches,
//                   ambient where the mask says it does not), no shadow pass at all.
//   cut/cyclic      three cyclically overlapping triangles ("the root of all evil"): each
//                   shadows the next, no order sorts them, the cut gets them right.
//   cut/two-lights  two lights: pieces coloured by their light mask; and WWDC 2003 session 212's
//                   destination-alpha view, the dim factor as grey (white: no light reaches,
//                   darker: more lights to dim when a dynamic shadow falls there).
#include "glint/cut/cutter.h"
#include "glint/cut/output.h"
#include "glint/gl/shader.h"
#include "glint/core/camera.h"
#include "glint/render/gpu_mesh.h"
#include "glint/render/state.h"
#include "glint/scenes/scene.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace glint::scenes {
namespace {

const vec4 kBackground{0.11f, 0.12f, 0.14f, 1.0f};
const vec3 kLit{0.96f, 0.82f, 0.52f};
const vec3 kShadowed{0.22f, 0.29f, 0.46f};

Mesh box(vec3 lo, vec3 hi) {
  Mesh m = makeCube(1.0f);
  m.normals.clear();
  m.uvs.clear();
  m.transform(glm::scale(glm::translate(mat4(1.0f), 0.5f * (lo + hi)), hi - lo));  // the cube spans ±0.5
  return m;
}

/// A closed cylinder along y from `base`, capped (shared vertices: watertight).
Mesh cylinder(vec3 base, float height, float radius, int segments) {
  Mesh m;
  for (int k = 0; k <= 1; ++k)
    for (int s = 0; s < segments; ++s) {
      const float a = 2.0f * kPi * float(s) / float(segments);
      m.positions.push_back(base + vec3(radius * std::cos(a), height * float(k), radius * std::sin(a)));
    }
  const auto n = std::uint32_t(segments);
  m.positions.push_back(base);
  m.positions.push_back(base + vec3(0.0f, height, 0.0f));
  for (std::uint32_t s = 0; s < n; ++s) {
    const std::uint32_t a = s, b = (s + 1) % n, c = n + (s + 1) % n, d = n + s;
    m.indices.insert(m.indices.end(), {a, c, b, a, d, c, 2 * n, a, b, 2 * n + 1, c, d});
  }
  return m;
}

Mesh stripped(Mesh m) {
  m.normals.clear();
  m.uvs.clear();
  m.tangents.clear();
  return m;
}

/// WWDC 2003 session 212's example: a table on a floor, a microphone on a stand beside and above it.
Mesh tableAndMicrophone() {
  Mesh scene = box({-2.2f, -0.1f, -1.8f}, {2.6f, 0.0f, 1.8f});  // the floor, a closed slab
  scene.append(box({-1.0f, 0.9f, -0.6f}, {1.0f, 1.0f, 0.6f}));  // table top
  for (const vec2 leg : {vec2(-0.9f, -0.5f), vec2(0.9f, -0.5f), vec2(-0.9f, 0.5f), vec2(0.9f, 0.5f)})
    scene.append(box({leg.x - 0.05f, 0.0f, leg.y - 0.05f}, {leg.x + 0.05f, 0.9f, leg.y + 0.05f}));
  // The microphone: a stand (foot, pole) and a head held over the table.
  scene.append(cylinder({1.6f, 0.0f, 0.2f}, 0.04f, 0.3f, 24));
  scene.append(cylinder({1.6f, 0.04f, 0.2f}, 1.7f, 0.025f, 12));
  scene.append(box({0.45f, 1.70f, 0.17f}, {1.62f, 1.74f, 0.23f}));  // the boom
  Mesh head = stripped(makeIcosphere(0.14f, 2));
  head.transform(glm::translate(mat4(1.0f), vec3(0.4f, 1.62f, 0.2f)));
  scene.append(head);
  Mesh body = cylinder({0.4f, 1.3f, 0.2f}, 0.3f, 0.06f, 16);
  scene.append(body);
  return scene;
}

/// Three long triangles, each passing over the next and under the previous (no floor:
/// every shadow shown falls on one of them).
Mesh cyclicTriangles() {
  Mesh scene;
  for (int i = 0; i < 3; ++i) {
    const float angle = float(i) * 2.0f * kPi / 3.0f + 0.3f;
    const vec3 t(std::cos(angle), 0.0f, std::sin(angle)), n(-t.z, 0.0f, t.x);
    const vec3 c = 0.45f * n, start = c - 1.8f * t, end = c + 1.8f * t;
    Mesh tri;
    // Counter-clockwise seen from above: the top faces the light.
    tri.positions = {start + vec3(0, 1.9f, 0) + 0.4f * n, end + vec3(0, 0.5f, 0), start + vec3(0, 1.9f, 0) - 0.4f * n};
    tri.indices = {0, 1, 2};
    scene.append(tri);
  }
  return scene;
}

enum class View {
  Pieces,   ///< lit/shadowed colours (one light) or mask colours (two), with the wireframe
  Shaded,   ///< as a renderer uses the cut: N·L where lit, ambient where the mask says shadow
  DimAlpha  ///< the destination-alpha dim factor per piece, as grey
};

struct Setup {
  Mesh scene;
  std::vector<cut::Light> lights;
  vec3 eye, target;
  float fov = 40.0f;
  vec3 up{0.0f, 1.0f, 0.0f};
};

class CutScene final : public Scene {
public:
  CutScene(Setup setup, View view)
      : m_view(view), m_lights(setup.lights), m_eye(setup.eye), m_target(setup.target), m_up(setup.up), m_fov(setup.fov) {
    m_program = gl::Program::fromFiles({"cut/pieces.vert", "cut/pieces.frag"});
    cut::CutOptions options;
    options.lights = m_lights;
    const auto start = std::chrono::steady_clock::now();
    const cut::CutResult result = cut::cut(setup.scene, options);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const cut::CutMesh& m = result.mesh;
    m_notes = fmt::format("{} triangles in → {} pieces ({} before merging), {} light(s); cut in {:.0f} ms",
                          setup.scene.triangleCount(), m.polygonCount(), result.stats.facesBeforeMerge, m_lights.size(),
                          seconds * 1000.0);

    // Pieces: each its own vertices (flat colour), triangulated as glint writes them.
    const cut::Triangles tris = cut::triangulate(m);
    Mesh pieces;
    std::vector<vec4> colours;
    for (std::size_t t = 0; t < tris.trianglePolygon.size(); ++t) {
      const std::uint32_t p = tris.trianglePolygon[t];
      const vec3 a = tris.mesh.positions[tris.mesh.indices[3 * t]], b = tris.mesh.positions[tris.mesh.indices[3 * t + 1]],
                 c = tris.mesh.positions[tris.mesh.indices[3 * t + 2]];
      const vec3 normal = glm::normalize(glm::cross(b - a, c - a));
      const vec4 colour = pieceColour(m.polygonMask[p]);
      for (const vec3& v : {a, b, c}) {
        pieces.indices.push_back(std::uint32_t(pieces.positions.size()));
        pieces.positions.push_back(v);
        pieces.normals.push_back(normal);
        colours.push_back(colour);
      }
    }
    m_pieces = render::GpuMesh(pieces, colours, "cut-pieces");
    // The cut wireframe: every polygon side once (zero-length pairs pad the index count
    // to whole triangles, which GpuMesh wants; they draw nothing).
    Mesh lines;
    lines.positions = m.positions;
    std::map<std::pair<std::uint32_t, std::uint32_t>, bool> seen;
    for (std::size_t p = 0; p < m.polygonCount(); ++p) {
      const std::size_t n = m.cornerCount(p), s = m.polygonStart[p];
      for (std::size_t i = 0; i < n; ++i) {
        std::uint32_t u = m.corners[s + i], v = m.corners[s + (i + 1) % n];
        if (u > v) std::swap(u, v);
        if (seen.emplace(std::make_pair(u, v), true).second) lines.indices.insert(lines.indices.end(), {u, v});
      }
    }
    while (lines.indices.size() % 6 != 0) lines.indices.push_back(lines.indices.front());
    m_wire = render::GpuMesh(lines, {}, "cut-wireframe");
    Mesh marker = stripped(makeIcosphere(0.06f, 1));
    m_marker = render::GpuMesh(marker, {}, "light-marker");
  }

  std::string notes() const override { return m_notes; }

  void render(const FrameInput& frame) override {
    frame.target.bind();
    render::clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT, kBackground);
    const auto camera = frame.camera(glint::Camera::lookAt(m_eye, m_target, m_up, m_fov, frame.target.aspect(), 0.1f, 50.0f));
    m_program.use();
    m_program.set("uViewProjection", camera.viewProjection());
    m_program.set("uLight", m_lights.front().position);
    // Pieces pushed back a little so the wireframe on their sides wins the depth test.
    render::PipelineState fill{.depthTest = true};
    fill.polygonOffset = m_view == View::Pieces;
    fill.offsetFactor = 1.0f;
    fill.offsetUnits = 1.0f;
    fill.apply();
    m_program.set("uMode", m_view == View::Pieces ? 0 : m_view == View::DimAlpha ? 1 : 3);
    m_pieces.draw();
    if (m_view == View::Pieces) {
      render::PipelineState{.depthTest = true}.apply();
      m_program.set("uMode", 2);
      m_program.set("uColor", vec4(0.05f, 0.05f, 0.07f, 1.0f));
      m_wire.draw(GL_LINES);
    }
    if (m_view != View::DimAlpha) {
      render::PipelineState{.depthTest = true}.apply();
      m_program.set("uMode", 2);
      for (const cut::Light& l : m_lights) {
        m_program.set("uViewProjection", camera.viewProjection() * glm::translate(mat4(1.0f), l.position));
        m_program.set("uColor", vec4(1.0f, 0.95f, 0.6f, 1.0f));
        m_marker.draw();
      }
    }
    render::PipelineState{}.apply();
  }

private:
  vec4 pieceColour(cut::LightMask mask) const {
    const int lights = int(m_lights.size());
    const int reach = std::popcount(mask);
    switch (m_view) {
      case View::DimAlpha: {
        // WWDC 2003 session 212's dim factor: 1 (white) where no light reaches, darker the more
        // lights a dynamic shadow would have to take away.
        const float dim = 1.0f - 0.4f * float(reach);
        return vec4(vec3(dim), 1.0f);
      }
      case View::Shaded: return vec4(1.0f, 1.0f, 1.0f, (mask & 1u) ? 1.0f : 0.0f);
      case View::Pieces:
        if (lights == 1) return vec4((mask & 1u) ? kLit : kShadowed, 1.0f);
        // Two lights: both, the first only, the second only, neither.
        if (mask == 3u) return vec4(kLit, 1.0f);
        if (mask == 1u) return vec4(0.85f, 0.45f, 0.32f, 1.0f);
        if (mask == 2u) return vec4(0.35f, 0.7f, 0.5f, 1.0f);
        return vec4(kShadowed, 1.0f);
    }
    return vec4(1.0f);
  }

  View m_view;
  std::vector<cut::Light> m_lights;
  vec3 m_eye, m_target, m_up;
  float m_fov;
  gl::Program m_program;
  render::GpuMesh m_pieces, m_wire, m_marker;
  std::string m_notes;
};

Setup tableSetup() {
  return {tableAndMicrophone(), {{.position = {-0.6f, 3.4f, 0.9f}, .name = "key"}}, {0.9f, 2.9f, 3.6f}, {0.3f, 0.55f, 0.0f}, 42.0f};
}

Setup cyclicSetup() {
  // Seen from above, the light to one side: each triangle's shadow falls beside it, on
  // the next one.
  return {cyclicTriangles(), {{.position = {-0.9f, 3.0f, 0.6f}, .name = "key"}}, {0.0f, 7.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, 40.0f,
          {0.0f, 0.0f, -1.0f}};
}

Setup twoLightSetup() {
  return {tableAndMicrophone(),
          {{.position = {-0.6f, 3.4f, 0.9f}, .name = "key"}, {.position = {2.9f, 2.2f, 1.6f}, .name = "fill"}},
          {0.9f, 2.9f, 3.6f},
          {0.3f, 0.55f, 0.0f},
          42.0f};
}

}  // namespace

void registerCutScenes(Registry& registry) {
  registry.add({.name = "cut/table",
                .summary = "The shadow cutter (WWDC 2003 session 212, Pipe Dream): a microphone's and a table's shadows cut into "
                           "the table and the floor by far beams; pieces tagged lit or shadowed",
                .variants = {{"pieces", "lit pieces warm, shadowed pieces blue, the cut wireframe on top"},
                             {"shaded", "drawn as a renderer uses the cut: N·L where lit, ambient where shadowed, no "
                                        "shadow pass"}},
                .defaultSize = {800, 500},
                .create = [](int variant) -> std::unique_ptr<Scene> {
                  return std::make_unique<CutScene>(tableSetup(), variant == 0 ? View::Pieces : View::Shaded);
                }});
  registry.add({.name = "cut/cyclic",
                .summary = "Three cyclically overlapping triangles, \"the root of all evil\" for ordering methods: "
                           "each shadows the next, and the cut gets every one right",
                .variants = {{"pieces", "lit pieces warm, shadowed pieces blue, the cut wireframe on top"},
                             {"shaded", "drawn with the cut's tags: N·L where lit, ambient where shadowed"}},
                .defaultSize = {800, 500},
                .create = [](int variant) -> std::unique_ptr<Scene> {
                  return std::make_unique<CutScene>(cyclicSetup(), variant == 0 ? View::Pieces : View::Shaded);
                }});
  registry.add({.name = "cut/two-lights",
                .summary = "Two lights, a light mask per piece: which lights reach it, and WWDC 2003 session 212's "
                           "destination-alpha dim factor from it",
                .variants = {{"pieces", "both lights warm, key only red, fill only green, neither blue; the cut wireframe"},
                             {"dim-alpha", "the dim factor as grey: white where no light reaches, darker the more lights "
                                           "reach (what a dynamic shadow must take away)"}},
                .defaultSize = {800, 500},
                .create = [](int variant) -> std::unique_ptr<Scene> {
                  return std::make_unique<CutScene>(twoLightSetup(), variant == 0 ? View::Pieces : View::DimAlpha);
                }});
}

}  // namespace glint::scenes

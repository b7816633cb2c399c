// The Pipe Dream frame (render/pipedream/renderer.h): cut static shadows, GPU-extruded
// dynamic volumes, the destination-alpha dim factor and one quad per light, blurred balls.
// The debug views and measurements are debug_views.cpp's.
#include "glint/render/pipedream/renderer.h"

#include "renderer_parts.h"

#include "glint/core/error.h"
#include "glint/mesh/adjacency.h"
#include "glint/shadows/volume.h"
#include "glint/render/shadows/world_renderer.h"
#include "glint/render/state.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>

namespace glint::render::pipedream {

using detail::FramebufferSrgb;

namespace {

float maxOf(const vec3& v) { return std::max({v.x, v.y, v.z}); }

/// The weights buffer's format: one 8-bit channel per light.
GLenum weightsFormat(int lights) { return lights == 1 ? GL_R8 : lights == 2 ? GL_RG8 : GL_RGBA8; }

// Linear colours (shaders write linear light; the colour buffer encodes it, present()
// encodes the output by hand).
const vec4 kBackground{0.030f, 0.034f, 0.045f, 1.0f};  // alpha 1: nothing to dim
const vec3 kSkinAlbedo{0.86f, 0.82f, 0.70f};
const vec3 kCymbalAlbedo{0.85f, 0.66f, 0.26f};
const vec3 kMalletAlbedo{0.55f, 0.42f, 0.30f};
const vec3 kMarkerColor{1.6f, 1.45f, 1.0f};
constexpr float kMarkerRadius = 0.12f;

// Volumes are pushed away from the camera so that a caster's lit faces (its volume's near
// cap) never z-fight with themselves (render/shadows/stencil_shadows.h).
constexpr float kOffsetFactor = 1.0f, kOffsetUnits = 4.0f;

/// Z-fail volume counting in one draw (two-sided stencil): back faces increment where
/// depth fails, front faces decrement; colour and depth untouched, only `writeMask`'s
/// stencil bits written.
PipelineState zFailCounting(GLuint writeMask) {
  PipelineState state{.depthTest = true,
                      .depthWrite = false,
                      .colorMask = {false, false, false, false},
                      .polygonOffset = true,
                      .offsetFactor = kOffsetFactor,
                      .offsetUnits = kOffsetUnits};
  state.stencil.enabled = true;
  state.stencil.separate = true;
  state.stencil.front = {.writeMask = writeMask, .dpfail = GL_DECR_WRAP};
  state.stencil.back = {.writeMask = writeMask, .dpfail = GL_INCR_WRAP};
  return state;
}

mat3 normalMatrix(const mat4& model) { return glm::transpose(glm::inverse(mat3(model))); }

float maxScale(const mat4& model) {
  return std::max({glm::length(vec3(model[0])), glm::length(vec3(model[1])), glm::length(vec3(model[2]))});
}

/// The uncut static scene with one albedo per vertex (every vertex of the machine belongs
/// to one part, so to one material).
Mesh uncutMesh(const InstrumentMachine& machine, std::vector<vec4>& colors) {
  Mesh mesh;
  mesh.positions = machine.staticMesh.positions;
  mesh.normals = machine.staticMesh.normals;
  mesh.indices = machine.staticMesh.indices;
  colors.assign(mesh.positions.size(), vec4(1.0f));
  for (std::size_t t = 0; t < machine.triangleMaterial.size(); ++t)
    for (int c = 0; c < 3; ++c)
      colors[mesh.indices[3 * t + std::size_t(c)]] = vec4(machineMaterialColor(machine.triangleMaterial[t]), 1.0f);
  return mesh;
}

/// A bounding sphere: the box's centre and the furthest vertex from it.
std::pair<vec3, float> boundingSphere(const Mesh& mesh) {
  const vec3 centre = mesh.bounds().center();
  float radius = 0.0f;
  for (const vec3& p : mesh.positions) radius = std::max(radius, glm::length(p - centre));
  return {centre, radius};
}

/// The triangles [first, first + count) of `mesh`, positions kept whole.
Mesh subMesh(const Mesh& mesh, std::size_t first, std::size_t count) {
  Mesh out;
  out.positions = mesh.positions;
  out.indices.assign(mesh.indices.begin() + std::ptrdiff_t(3 * first), mesh.indices.begin() + std::ptrdiff_t(3 * (first + count)));
  return out;
}

}  // namespace

Renderer::Renderer(const InstrumentMachine& machine, const StaticGeometry& geometry, const RendererOptions& options)
    : m_machine(machine), m_options(options), m_lights(int(machine.lights.size())) {
  if (m_lights < 1 || m_lights > kMaxLights)
    fail(ErrorKind::Usage, "the pipedream renderer takes 1 to {} lights, the machine has {}", kMaxLights, m_lights);
  if (geometry.lights != m_lights || geometry.maskStart.size() != (std::size_t(1) << m_lights) + 1)
    fail(ErrorKind::Internal, "static geometry cut for {} lights, the machine has {}", geometry.lights, m_lights);

  m_maxAlbedo = std::max({maxOf(kSkinAlbedo), maxOf(kCymbalAlbedo), maxOf(kMalletAlbedo)});
  for (const vec4& c : geometry.colors) m_maxAlbedo = std::max(m_maxAlbedo, maxOf(vec3(c)));
  {
    Mesh mesh = geometry.mesh;
    std::vector<vec4> meshColors = geometry.colors;
    m_staticClusters = clusterTriangles(mesh, meshColors, geometry.maskStart, m_options.clusterSize);
    m_static = GpuMesh(mesh, meshColors, "pipedream-static-cut");
  }
  m_maskStart = geometry.maskStart;
  m_staticTriangles = geometry.mesh.triangleCount();
  m_staticVertices = geometry.mesh.positions.size();
  if (!geometry.edges.indices.empty()) {
    m_edges = GpuMesh(geometry.edges, {}, "pipedream-cut-edges");
    m_edgeCount = geometry.edges.indices.size() / 2;
  }
  std::vector<vec4> colors;
  Mesh uncut = uncutMesh(machine, colors);
  for (const vec4& c : colors) m_maxAlbedo = std::max(m_maxAlbedo, maxOf(vec3(c)));
  const std::uint32_t all[] = {0, std::uint32_t(uncut.triangleCount())};
  m_uncutClusters = clusterTriangles(uncut, colors, all, m_options.clusterSize);
  m_uncut = GpuMesh(uncut, colors, "pipedream-static-uncut");
  m_uncutTriangles = uncut.triangleCount();
  m_uncutVertices = uncut.positions.size();

  const Mesh* parts[3] = {&machine.skin, &machine.cymbal, &machine.mallet};
  // What casts each part's shadow: the part itself, or a proxy inside it (the mallet's).
  const Mesh* casters[3] = {&machine.skin, &machine.cymbal,
                            machine.malletShadow.indices.empty() ? &machine.mallet : &machine.malletShadow};
  const char* names[3] = {"skin", "cymbal", "mallet"};
  for (int i = 0; i < 3; ++i) {
    m_parts[i] = GpuMesh(*parts[i], {}, std::string("pipedream-") + names[i]);
    m_partCasters[i] = makeCaster(*casters[i], std::string("pipedream-") + names[i] + "-extrusion");
    m_partClosed[i] = EdgeMap::build(*parts[i]).isClosedManifold();
    std::tie(m_partCentre[i], m_partRadius[i]) = boundingSphere(*parts[i]);
  }
  m_staticBox = machine.staticMesh.bounds();
  m_ballCaster = makeCaster(makeIcosphere(1.0f, 2), "pipedream-ball-extrusion");
  m_marker = GpuMesh(makeIcosphere(kMarkerRadius, 2), {}, "pipedream-light-marker");

  // The blur ball: positions, then the rear flag, in one buffer.
  const glint::pipedream::BlurBallMesh ball = glint::pipedream::buildBlurBall(32, 16);
  std::vector<float> data;
  for (const vec3& p : ball.positions) data.insert(data.end(), {p.x, p.y, p.z});
  data.insert(data.end(), ball.rear.begin(), ball.rear.end());
  m_ballVertices = gl::Buffer(std::span<const float>(data), 0, "pipedream-ball-vertices");
  m_ballIndices = gl::Buffer(std::span<const std::uint32_t>(ball.indices), 0, "pipedream-ball-indices");
  m_ballVao = gl::VertexArray::create("pipedream-ball");
  m_ballVao.attribute(0, 0, 3, 0);
  m_ballVao.vertexBuffer(0, m_ballVertices, 0, sizeof(vec3));
  m_ballVao.attribute(1, 1, 1, 0);
  m_ballVao.vertexBuffer(1, m_ballVertices, GLintptr(ball.positions.size() * sizeof(vec3)), sizeof(float));
  m_ballVao.indexBuffer(m_ballIndices);
  m_ballIndexCount = GLsizei(ball.indices.size());

  m_lit = gl::Program::fromFiles({"pipedream/scene.vert", "pipedream/scene.frag"});
  m_shadowed = gl::Program::fromFiles({"pipedream/scene.vert", "pipedream/shadowed.frag"});
  m_extrude = gl::Program::fromFiles({"shadows/extrude.vert", "shadows/volume.frag"});
  m_ball = gl::Program::fromFiles({"pipedream/ball.vert", "pipedream/ball.frag"});
  m_alphaPass = FullscreenPass("pipedream/alpha.frag");
  m_quad = FullscreenPass("shadows/flat.frag");
  m_present = FullscreenPass("pipedream/present.frag");
  for (const gl::Program* p : {&m_lit, &m_shadowed}) setLights(*p);
  renderCube();
}

std::vector<Renderer::Cluster> Renderer::clusterTriangles(Mesh& mesh, std::vector<vec4>& colors,
                                                          std::span<const std::uint32_t> groupStart, float cell) {
  const Bounds box = mesh.bounds();
  const auto cellOf = [&](std::size_t t) -> std::uint64_t {
    if (!(cell > 0.0f)) return 0;
    const vec3 c = (mesh.positions[mesh.indices[3 * t]] + mesh.positions[mesh.indices[3 * t + 1]] +
                    mesh.positions[mesh.indices[3 * t + 2]]) / 3.0f;
    const glm::u64vec3 i(glm::clamp((c - box.min) / cell, vec3(0.0f), vec3(1048575.0f)));
    return (i.x << 40) | (i.y << 20) | i.z;
  };
  std::vector<Cluster> clusters;
  std::vector<std::uint32_t> indices(mesh.indices.size());
  for (std::size_t g = 0; g + 1 < groupStart.size(); ++g) {
    std::vector<std::pair<std::uint64_t, std::uint32_t>> order;  // (cell, triangle)
    for (std::uint32_t t = groupStart[g]; t < groupStart[g + 1]; ++t) order.emplace_back(cellOf(t), t);
    std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t i = 0; i < order.size(); ++i) {
      const std::uint32_t slot = groupStart[g] + std::uint32_t(i);
      if (i == 0 || order[i].first != order[i - 1].first)
        clusters.push_back({.mask = std::uint32_t(g), .first = slot, .count = 0,
                            .bounds = {vec3(std::numeric_limits<float>::max()), vec3(std::numeric_limits<float>::lowest())}});
      Cluster& c = clusters.back();
      ++c.count;
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = mesh.indices[3 * std::size_t(order[i].second) + std::size_t(k)];
        indices[3 * std::size_t(slot) + std::size_t(k)] = v;
        c.bounds.min = glm::min(c.bounds.min, mesh.positions[v]);
        c.bounds.max = glm::max(c.bounds.max, mesh.positions[v]);
      }
    }
  }
  // Vertices by first use in the new order: what the vertex fetch and cache like best.
  std::vector<std::uint32_t> id(mesh.positions.size(), ~0u);
  Mesh out;
  std::vector<vec4> outColors;
  for (std::uint32_t& v : indices) {
    if (id[v] == ~0u) {
      id[v] = std::uint32_t(out.positions.size());
      out.positions.push_back(mesh.positions[v]);
      if (!mesh.normals.empty()) out.normals.push_back(mesh.normals[v]);
      if (!colors.empty()) outColors.push_back(colors[v]);
    }
    v = id[v];
  }
  out.indices = std::move(indices);
  mesh = std::move(out);
  colors = std::move(outColors);
  return clusters;
}

std::size_t Renderer::drawClusters(const std::vector<Cluster>& clusters, std::uint32_t mask) {
  // The view's side and near planes (the far plane is at infinity): a cluster whose box lies
  // wholly behind one of them is not drawn.
  const mat4 m = glm::transpose(m_camera.viewProjection());
  const vec4 planes[5] = {m[3] + m[0], m[3] - m[0], m[3] + m[1], m[3] - m[1], m[3] + m[2]};
  m_drawOrder.clear();
  for (std::size_t i = 0; i < clusters.size(); ++i) {
    const Cluster& c = clusters[i];
    if (c.mask != mask || c.count == 0) continue;
    bool outside = false;
    for (const vec4& p : planes) {
      const vec3 far = glm::mix(c.bounds.min, c.bounds.max, glm::step(vec3(0.0f), vec3(p)));  // the corner furthest inside
      if (glm::dot(vec3(p), far) + p.w < 0.0f) {
        outside = true;
        break;
      }
    }
    if (outside) {
      m_stats.staticCulled += c.count;
      continue;
    }
    m_drawOrder.emplace_back(glm::length(c.bounds.center() - m_camera.position), i);
  }
  // Nearest first: what later clusters hide fails the depth test before it is shaded.
  std::sort(m_drawOrder.begin(), m_drawOrder.end());
  m_drawCounts.clear();
  m_drawOffsets.clear();
  std::size_t triangles = 0;
  for (const auto& [distance, i] : m_drawOrder) {
    m_drawCounts.push_back(GLsizei(3 * clusters[i].count));
    m_drawOffsets.push_back(reinterpret_cast<const void*>(std::uintptr_t(3 * clusters[i].first) * sizeof(std::uint32_t)));
    triangles += clusters[i].count;
  }
  if (!m_drawCounts.empty())
    glMultiDrawElements(GL_TRIANGLES, m_drawCounts.data(), GL_UNSIGNED_INT, m_drawOffsets.data(), GLsizei(m_drawCounts.size()));
  return triangles;
}

Renderer::Caster Renderer::makeCaster(const Mesh& mesh, const std::string& name) {
  const EdgeMap edges = EdgeMap::build(mesh);
  Caster c;
  // Closed parts cast the classic volume; anything else the thin two-sided shell.
  c.twoSided = !edges.isClosedManifold();
  const glint::shadows::ExtrusionMesh extrusion = glint::shadows::buildExtrusionMesh(edges, c.twoSided);
  std::vector<vec3> data(extrusion.positions);
  data.insert(data.end(), extrusion.faceNormals.begin(), extrusion.faceNormals.end());
  c.vertices = gl::Buffer(std::span<const vec3>(data), 0, name);
  c.indices = gl::Buffer(std::span<const std::uint32_t>(extrusion.indices), 0, name + "-indices");
  c.vao = gl::VertexArray::create(name);
  c.vao.attribute(0, 0, 3, 0);
  c.vao.vertexBuffer(0, c.vertices, 0, sizeof(vec3));
  c.vao.attribute(1, 1, 3, 0);
  c.vao.vertexBuffer(1, c.vertices, GLintptr(extrusion.positions.size() * sizeof(vec3)), sizeof(vec3));
  c.vao.indexBuffer(c.indices);
  c.indexCount = GLsizei(extrusion.indices.size());
  std::tie(c.centre, c.radius) = boundingSphere(mesh);
  return c;
}

void Renderer::setLights(const gl::Program& program) const {
  program.set("uLightCount", m_lights);
  program.set("uAmbient", m_options.ambient);
  for (int i = 0; i < m_lights; ++i) {
    const MachineLight& l = m_machine.lights[std::size_t(i)];
    program.set(fmt::format("uLightPos[{}]", i), l.position);
    program.set(fmt::format("uLightRange[{}]", i), l.range);
    program.set(fmt::format("uLightIntensity[{}]", i), l.intensity);
  }
}

void Renderer::renderCube() {
  // The balls reflect the room as seen from the middle of the stage: the uncut scene lit by
  // every light (reflections in small, blurred balls need no shadows), once.
  m_cube = env::DynamicCubeMap(m_options.cubeSize, "pipedream-room-cube");
  const vec3 centre = 0.5f * (m_machine.room.min + m_machine.room.max);
  m_cube.render(vec3(centre.x, 2.5f, centre.z),
                [&](const Camera& face) {
                  PipelineState{.depthTest = true}.apply();
                  m_lit.set("uViewProj", face.viewProjection());
                  m_lit.set("uModel", mat4(1.0f));
                  m_lit.set("uNormalMatrix", mat3(1.0f));
                  m_lit.set("uVertexAlbedo", true);
                  m_lit.set("uPass", 0);
                  m_lit.set("uMask", (1 << m_lights) - 1);
                  m_lit.set("uColorScale", 1.0f);  // the cube holds plain linear light
                  m_lit.use();
                  m_uncut.draw();
                },
                kBackground);
}

void Renderer::resize(ivec2 size) {
  if (size == m_size && m_options.floatBuffers == m_floatBuffers && m_color) return;
  if (size.x <= 0 || size.y <= 0) fail(ErrorKind::Usage, "pipedream: frame size {}x{} is empty", size.x, size.y);
  m_size = size;
  m_floatBuffers = m_options.floatBuffers;
  // Colour in 8-bit sRGB (issue 37: half the bytes of RGBA16F): blending, the quads' dim
  // factor and the balls decode, work in linear light and encode again (GL_FRAMEBUFFER_SRGB,
  // on while render() draws), so one rounding to the output's own 8-bit sRGB is all that
  // is added; alpha (the dim factor) is linear, in steps of 1/255. No pixel of the scene is
  // brighter than 1 before the quads (tests/pipedream: PipeDreamDimFactorNeverDarkensTwice
  // checks), so
  // nothing is clipped that a shadow would dim. The weights: one 8-bit unorm channel per
  // light that exists (R8, RG8, RGBA8); the channels beyond read as 0.
  m_color = gl::Texture(GL_TEXTURE_2D, "pipedream-color");
  m_color.storage(m_floatBuffers ? GL_RGBA16F : GL_SRGB8_ALPHA8, size.x, size.y);
  m_weights = gl::Texture(GL_TEXTURE_2D, "pipedream-weights");
  m_weights.storage(m_floatBuffers ? GL_RGBA16F : weightsFormat(m_lights), size.x, size.y);
  for (const GLenum channel : {GL_TEXTURE_SWIZZLE_G, GL_TEXTURE_SWIZZLE_B, GL_TEXTURE_SWIZZLE_A}) {
    const int index = channel == GL_TEXTURE_SWIZZLE_G ? 1 : channel == GL_TEXTURE_SWIZZLE_B ? 2 : 3;
    if (index >= m_lights && !m_floatBuffers) glTextureParameteri(m_weights.id(), channel, GL_ZERO);
  }
  for (const gl::Texture* t : {&m_color, &m_weights}) t->filtering(GL_NEAREST, GL_NEAREST, GL_CLAMP_TO_EDGE);
  m_depthStencil = gl::Texture(GL_TEXTURE_2D, "pipedream-depth-stencil");
  m_depthStencil.storage(GL_DEPTH24_STENCIL8, size.x, size.y);
  m_sceneFbo = gl::Framebuffer::create("pipedream-scene");
  m_sceneFbo.attach(GL_COLOR_ATTACHMENT0, m_color);
  m_sceneFbo.attach(GL_COLOR_ATTACHMENT1, m_weights);
  m_sceneFbo.attach(GL_DEPTH_STENCIL_ATTACHMENT, m_depthStencil);
  const GLenum both[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  m_sceneFbo.drawBuffers(both);
  m_sceneFbo.checkComplete();
  m_compositeFbo = gl::Framebuffer::create("pipedream-composite");
  m_compositeFbo.attach(GL_COLOR_ATTACHMENT0, m_color);
  m_compositeFbo.attach(GL_DEPTH_STENCIL_ATTACHMENT, m_depthStencil);
  m_compositeFbo.checkComplete();
}

void Renderer::prepare(const glint::pipedream::MachinePose& pose, const Camera& camera, ivec2 size, Mode mode) {
  resize(size);
  m_mode = mode;
  m_camera = camera;
  m_camera.projection = shadows::infiniteFarProjection(camera.projection);
  m_stats = {};
  float light = m_options.ambient;
  for (const MachineLight& l : m_machine.lights) light += l.intensity;
  m_colorScale = m_floatBuffers ? 1.0f : 1.0f / std::max({1.0f, maxOf(kMarkerColor), m_maxAlbedo * light});
  for (const gl::Program* p : {&m_lit, &m_shadowed, &m_ball}) p->set("uColorScale", m_colorScale);
  m_dynamic.clear();
  for (const mat4& m : pose.skins) m_dynamic.push_back({0, m, kSkinAlbedo});
  for (const mat4& m : pose.cymbals) m_dynamic.push_back({1, m, kCymbalAlbedo});
  for (const mat4& m : pose.mallets) m_dynamic.push_back({2, m, kMalletAlbedo});
  m_balls.clear();
  const vec3 forward = glm::normalize(camera.target - camera.position);
  for (const glint::pipedream::BallState& b : pose.balls) {
    BallDraw d{.state = b};
    if (mode != Mode::NoBlur)
      d.blur = glint::pipedream::blurOf(b.velocity, m_machine.ballRadius, m_options.shutter, m_options.minOpacity, m_options.lodScale);
    d.depth = glm::dot(b.position - camera.position, forward);
    m_balls.push_back(d);
  }
  // Back to front for blending.
  std::stable_sort(m_balls.begin(), m_balls.end(), [](const BallDraw& a, const BallDraw& b) { return a.depth > b.depth; });
  m_stats.casters = m_dynamic.size() + m_balls.size();
  m_stats.balls = m_balls.size();

  // The box of everything the depth buffer can hold this frame (a blurred ball's streak
  // included) and of the eye, for bounded volumes.
  m_frameBox = m_staticBox;
  const auto grow = [&](const vec3& centre, float radius) {
    m_frameBox.min = glm::min(m_frameBox.min, centre - radius);
    m_frameBox.max = glm::max(m_frameBox.max, centre + radius);
  };
  for (const DynamicDraw& d : m_dynamic)
    grow(vec3(d.model * vec4(m_partCentre[d.mesh], 1.0f)), m_partRadius[d.mesh] * maxScale(d.model));
  for (const BallDraw& b : m_balls)
    grow(b.state.position, m_machine.ballRadius + glm::length(b.state.velocity) * m_options.shutter);
  for (const MachineLight& l : m_machine.lights) grow(l.position, kMarkerRadius);
  // And the eye: every segment from it to a visible point then lies in the box.
  grow(camera.position, 0.0f);
}

void Renderer::drawStaticGroups() {
  // One draw per light mask: pieces no light reaches take the cheaper shader. Closed solids
  // and the room (seen from inside) show only their front faces.
  m_static.vertexArray().bind();
  glEnable(GL_CULL_FACE);
  for (std::size_t mask = 0; mask + 1 < m_maskStart.size(); ++mask) {
    if (m_maskStart[mask + 1] == m_maskStart[mask]) continue;
    const gl::Program& p = mask == 0 ? m_shadowed : m_lit;
    p.use();
    p.set("uMask", int(mask));
    m_stats.sceneTriangles += drawClusters(m_staticClusters, std::uint32_t(mask));
  }
  glDisable(GL_CULL_FACE);
  glBindVertexArray(0);
}

void Renderer::drawDynamic(const gl::Program& program) const {
  program.set("uVertexAlbedo", false);
  program.use();
  for (const DynamicDraw& d : m_dynamic) {
    program.set("uModel", d.model);
    program.set("uNormalMatrix", normalMatrix(d.model));
    program.set("uAlbedo", d.albedo);
    // Closed parts, not mirrored, show only their front faces.
    const bool closed = m_partClosed[d.mesh] && glm::determinant(mat3(d.model)) > 0.0f;
    if (closed) glEnable(GL_CULL_FACE);
    m_parts[d.mesh].draw();
    if (closed) glDisable(GL_CULL_FACE);
  }
}

void Renderer::drawMarkers() const {
  m_lit.set("uPass", 3);
  m_lit.set("uEmissive", kMarkerColor);
  m_lit.use();
  for (const MachineLight& l : m_machine.lights) {
    m_lit.set("uModel", glm::translate(mat4(1.0f), l.position));
    m_lit.set("uNormalMatrix", mat3(1.0f));
    m_marker.draw();
  }
}

void Renderer::drawScene() {
  const FramebufferSrgb srgb;
  m_sceneFbo.bind();
  glViewport(0, 0, m_size.x, m_size.y);
  PipelineState state{.depthTest = true};
  // The wireframe's lines must win the depth test on the surfaces they lie on.
  state.polygonOffset = m_mode == Mode::Wireframe;
  state.offsetFactor = 1.0f;
  state.offsetUnits = 1.0f;
  state.apply();
  render::clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT, scaled(kBackground));
  const vec4 noWeights(0.0f);
  m_sceneFbo.clearColor(1, &noWeights.x);

  for (const gl::Program* p : {&m_lit, &m_shadowed}) {
    p->set("uViewProj", m_camera.viewProjection());
    p->set("uModel", mat4(1.0f));
    p->set("uNormalMatrix", mat3(1.0f));
    p->set("uVertexAlbedo", true);
    p->set("uAmbient", m_options.ambient);
  }
  m_lit.set("uPass", 0);
  drawStaticGroups();
  // Dynamic parts: lit by every light (their shadows on themselves come from the volumes).
  m_lit.set("uMask", (1 << m_lights) - 1);
  drawDynamic(m_lit);
  drawMarkers();
  for (const DynamicDraw& d : m_dynamic) m_stats.sceneTriangles += m_parts[d.mesh].triangleCount();
  if (m_mode == Mode::NoBlur) drawBalls(false);
}

void Renderer::drawBalls(bool translucent) {
  m_ball.set("uViewProj", m_camera.viewProjection());
  m_ball.set("uEye", m_camera.position);
  m_ball.set("uRadius", m_machine.ballRadius);
  m_ball.set("uShutter", translucent ? m_options.shutter : 0.0f);
  m_ball.use();
  m_cube.texture().bind(0);
  m_ballVao.bind();
  for (const BallDraw& b : m_balls) {
    m_ball.set("uFrame", glint::pipedream::ballFrame(b.state.velocity));
    m_ball.set("uCentre", b.state.position);
    m_ball.set("uVelocity", b.state.velocity);
    m_ball.set("uLodBias", translucent ? b.blur.lodBias : 0.0f);
    m_ball.set("uOpacity", translucent ? b.blur.opacity : 1.0f);
    glDrawElements(GL_TRIANGLES, m_ballIndexCount, GL_UNSIGNED_INT, nullptr);
  }
  glBindVertexArray(0);
  m_stats.sceneTriangles += m_balls.size() * std::size_t(m_ballIndexCount / 3);
}

void Renderer::drawTranslucent() {
  if (m_mode == Mode::NoBlur || m_balls.empty()) return;
  const FramebufferSrgb srgb;
  m_compositeFbo.bind();
  glViewport(0, 0, m_size.x, m_size.y);
  // Over the scene, depth-tested but not written; alpha masked: destination alpha keeps
  // the dim factor of the surface behind. Back faces culled: one layer of a convex pill.
  PipelineState{.depthTest = true,
                .depthWrite = false,
                .colorMask = {true, true, true, false},
                .cull = true,
                .blend = {.enabled = true, .src = GL_SRC_ALPHA, .dst = GL_ONE_MINUS_SRC_ALPHA}}
      .apply();
  drawBalls(true);
}

bool Renderer::inRange(const Caster& caster, const mat4& model, int light) const {
  const MachineLight& l = m_machine.lights[std::size_t(light)];
  const vec3 centre = vec3(model * vec4(caster.centre, 1.0f));
  return glm::length(centre - l.position) - caster.radius * maxScale(model) < l.range;
}

float Renderer::extrusionDistance(const vec3& centre, float radius, const vec3& light) const {
  if (!m_options.boundVolumes) return 0.0f;
  const vec3 axis = centre - light;
  const float distance = glm::length(axis);
  // The light inside (or on) the caster's sphere: its volume spreads every way.
  if (!(distance > 1.001f * radius + 1e-3f)) return 0.0f;
  const vec3 u = axis / distance;
  const float sine = radius / distance;
  const float cosine = std::sqrt(1.0f - sine * sine);
  // The box's furthest corner along the cone's axis.
  float reach = 0.0f;
  for (int k = 0; k < 8; ++k) {
    const vec3 corner(k & 1 ? m_frameBox.max.x : m_frameBox.min.x, k & 2 ? m_frameBox.max.y : m_frameBox.min.y,
                      k & 4 ? m_frameBox.max.z : m_frameBox.min.z);
    reach = std::max(reach, glm::dot(corner - light, u));
  }
  // Past that corner by 1 % and 1 cm (far beyond float and depth rounding at room scale),
  // and never short of the caster's own far side (every vertex moves away from the light).
  const float t = std::max(reach / cosine, distance + radius) * 1.01f + 0.01f;
  return std::isfinite(t) ? t : 0.0f;
}

void Renderer::drawCaster(const Caster& caster, const mat4& model, float extrudeTo) const {
  m_extrude.set("uExtrudeTo", extrudeTo);
  m_extrude.set("uModel", model);
  m_extrude.set("uNormalMatrix", normalMatrix(model));
  caster.vao.bind();
  glDrawElements(GL_TRIANGLES, caster.indexCount, GL_UNSIGNED_INT, nullptr);
}

void Renderer::extendVolumeBounds(const vec3& centre, float radius, const vec3& light, float extrudeTo) {
  // Every point of the volume is p + t (p − L), t ≥ 0, p in the box: in homogeneous terms a
  // non-negative combination of the 8 corners (c, 1) and their directions (c − L, 0). A
  // bounded volume (extrudeTo > 0) reaches no further from L than extrudeTo, so t ≤
  // extrudeTo / d − 1 with d the box's distance from L: the corners pushed to L + s (c − L),
  // s = extrudeTo / d, stand in for the directions. When all 16 lie in front of the eye
  // (clip w > 0), the volume's projection is inside the bounds of theirs.
  if (m_volumeBounds.whole) return;
  const mat4 viewProj = m_camera.viewProjection();
  const vec3 gap = glm::max(glm::abs(light - centre) - radius, vec3(0.0f));
  const float nearest = glm::length(gap);  // from the light to the caster's box
  const bool bounded = extrudeTo > 0.0f && nearest > 1e-4f * extrudeTo;
  const float scale = bounded ? extrudeTo / nearest : 0.0f;
  for (int k = 0; k < 8; ++k) {
    const vec3 c = centre + radius * vec3(k & 1 ? 1.0f : -1.0f, k & 2 ? 1.0f : -1.0f, k & 4 ? 1.0f : -1.0f);
    const vec4 far = bounded ? vec4(light + scale * (c - light), 1.0f) : vec4(c - light, 0.0f);
    for (const vec4& clip : {viewProj * vec4(c, 1.0f), viewProj * far}) {
      if (!(clip.w > 1e-6f)) {
        m_volumeBounds.whole = true;
        return;
      }
      const vec2 ndc = vec2(clip) / clip.w;
      m_volumeBounds.lo = glm::min(m_volumeBounds.lo, ndc);
      m_volumeBounds.hi = glm::max(m_volumeBounds.hi, ndc);
    }
  }
}

bool Renderer::drawVolumesOf(int light, bool everything) {
  m_extrude.set("uViewProj", m_camera.viewProjection());
  m_extrude.set("uLightPos", m_machine.lights[std::size_t(light)].position);
  m_extrude.use();
  // The naive method knows no ranges: every caster, every light.
  const bool cull = m_options.cullVolumes && !everything;
  bool any = false;
  const auto cast = [&](const Caster& c, const mat4& model) {
    if (cull && !inRange(c, model, light)) {
      ++m_stats.castersCulled;
      return;
    }
    const vec3 centre = vec3(model * vec4(c.centre, 1.0f));
    const float radius = c.radius * maxScale(model);
    const vec3& position = m_machine.lights[std::size_t(light)].position;
    const float extrudeTo = extrusionDistance(centre, radius, position);
    m_stats.castersBounded += extrudeTo > 0.0f;
    drawCaster(c, model, extrudeTo);
    extendVolumeBounds(centre, radius, position, extrudeTo);
    ++m_stats.castersDrawn;
    m_stats.volumeTriangles += std::size_t(c.indexCount / 3);
    any = true;
  };
  for (const DynamicDraw& d : m_dynamic) cast(m_partCasters[d.mesh], d.model);
  for (const BallDraw& b : m_balls)
    cast(m_ballCaster, glm::scale(glm::translate(mat4(1.0f), b.state.position), vec3(m_machine.ballRadius)));
  if (everything) {
    cast(m_staticSolids, mat4(1.0f));
    cast(m_staticShell, mat4(1.0f));
  }
  glBindVertexArray(0);
  return any;
}

bool Renderer::countVolumes(int light) {
  m_compositeFbo.bind();
  glViewport(0, 0, m_size.x, m_size.y);
  const StencilLayout layout = stencilLayout();
  // Only the count bits are written, so earlier lights' markers stay.
  zFailCounting(layout.countMask()).apply();
  m_volumeBounds = {};
  const bool any = drawVolumesOf(light, false);
  if (any) ++m_stats.lightsWithShadows;
  return any;
}

void Renderer::compositeLight(int light, std::uint32_t earlier) {
  const FramebufferSrgb srgb;
  m_compositeFbo.bind();
  glViewport(0, 0, m_size.x, m_size.y);
  // The passes below change only pixels where this light's volumes left a count: the
  // rectangle of their projections (a pixel of margin), not the whole frame.
  if (!m_volumeBounds.whole) {
    const vec2 size(m_size);
    const ivec2 lo = glm::clamp(ivec2(glm::floor((0.5f * m_volumeBounds.lo + 0.5f) * size)) - 1, ivec2(0), m_size);
    const ivec2 hi = glm::clamp(ivec2(glm::ceil((0.5f * m_volumeBounds.hi + 0.5f) * size)) + 1, ivec2(0), m_size);
    glEnable(GL_SCISSOR_TEST);
    glScissor(lo.x, lo.y, std::max(0, hi.x - lo.x), std::max(0, hi.y - lo.y));
  }
  const StencilLayout layout = stencilLayout();
  if (light > 0) {
    // Destination alpha := this light's factor. It depends on which earlier lights are
    // already gone here: one pass per combination, picked by the markers in the stencil.
    GLuint markers = 0;
    for (int j = 0; j < light; ++j)
      if (earlier & (1u << j)) markers |= layout.marker(j);
    const gl::Program& p = m_alphaPass.program();
    p.set("uLight", light);
    m_weights.bind(0);
    for (std::uint32_t removed = 0; removed < (1u << light); ++removed) {
      if ((removed & ~earlier) != 0) continue;  // only subsets of the lights whose quads ran
      GLuint ref = 0;
      for (int j = 0; j < light; ++j)
        if (removed & (1u << j)) ref |= layout.marker(j);
      PipelineState{.colorMask = {false, false, false, true},
                    .stencil = {.enabled = true,
                                .front = {.func = GL_EQUAL, .ref = GLint(ref), .valueMask = markers, .writeMask = 0}}}
          .apply();
      p.set("uRemoved", int(removed));
      m_alphaPass.drawWithCurrentState();
    }
  }
  // WWDC 2003 session 212's shadow quad: colour × destination alpha where the count is not zero. The
  // same pass zeroes the count (for the next light) and sets this light's marker.
  PipelineState{.depthWrite = false,
                .stencil = {.enabled = true,
                            .front = {.func = GL_NOTEQUAL,
                                      .ref = GLint(layout.marker(light)),
                                      .valueMask = layout.countMask(),
                                      .writeMask = layout.countMask() | layout.marker(light),
                                      .dppass = GL_REPLACE}},
                .blend = {.enabled = true, .src = GL_ZERO, .dst = GL_DST_ALPHA}}
      .apply();
  m_quad.drawWithCurrentState();
  glDisable(GL_SCISSOR_TEST);
}

void Renderer::present(const gl::Target& target) const {
  target.bind();
  const gl::Program& p = m_present.program();
  p.set("uOrigin", target.origin);
  p.set("uView", m_mode == Mode::DestAlpha ? 1 : 0);
  p.set("uColorScale", m_colorScale);
  m_color.bind(0);
  m_weights.bind(1);
  m_present.draw();
}

void Renderer::ensureNaiveCasters() {
  if (m_staticSolids.indexCount) return;
  // Built on first use: only the baseline needs volumes of the static scene.
  const Mesh& s = m_machine.staticMesh;
  m_staticShell = makeCaster(subMesh(s, 0, m_machine.shellTriangles), "pipedream-naive-shell");
  m_staticSolids = makeCaster(subMesh(s, m_machine.shellTriangles, s.triangleCount() - m_machine.shellTriangles),
                              "pipedream-naive-solids");
}

void Renderer::renderNaive() {
  const FramebufferSrgb srgb;
  ensureNaiveCasters();
  m_compositeFbo.bind();
  glViewport(0, 0, m_size.x, m_size.y);
  PipelineState{.depthTest = true}.apply();
  render::clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT, scaled(kBackground));
  const auto drawAll = [&](int pass) {
    m_lit.set("uPass", pass);
    m_lit.set("uViewProj", m_camera.viewProjection());
    m_lit.set("uModel", mat4(1.0f));
    m_lit.set("uNormalMatrix", mat3(1.0f));
    m_lit.set("uVertexAlbedo", true);
    m_lit.use();
    // The uncut scene as the cut one is drawn: front faces, clusters in view, nearest first.
    m_uncut.vertexArray().bind();
    glEnable(GL_CULL_FACE);
    m_stats.sceneTriangles += drawClusters(m_uncutClusters, 0);
    glDisable(GL_CULL_FACE);
    glBindVertexArray(0);
    drawDynamic(m_lit);
    for (const DynamicDraw& d : m_dynamic) m_stats.sceneTriangles += m_parts[d.mesh].triangleCount();
  };
  // Ambient everywhere.
  setLights(m_lit);
  drawAll(1);
  drawMarkers();
  for (int light = 0; light < m_lights; ++light) {
    render::clear(GL_STENCIL_BUFFER_BIT);
    zFailCounting(0xFF).apply();
    drawVolumesOf(light, true);
    ++m_stats.lightsWithShadows;
    // This light added where the stencil says nothing is in between: same vertices, GL_EQUAL.
    PipelineState{.depthTest = true,
                  .depthFunc = GL_EQUAL,
                  .depthWrite = false,
                  .stencil = {.enabled = true, .front = {.func = GL_EQUAL, .ref = 0, .writeMask = 0}},
                  .blend = {.enabled = true, .src = GL_ONE, .dst = GL_ONE}}
        .apply();
    m_lit.set("uLight", light);
    drawAll(2);
  }
  drawTranslucent();  // the balls as in Full
}

void Renderer::render(const glint::pipedream::MachinePose& pose, const Camera& camera, const gl::Target& target, Mode mode) {
  prepare(pose, camera, target.size, mode);
  if (mode == Mode::Naive) {
    renderNaive();
  } else {
    drawScene();
    drawTranslucent();
    if (mode != Mode::StaticOnly && mode != Mode::DestAlpha) {
      std::uint32_t done = 0;
      for (int light = 0; light < m_lights; ++light)
        if (countVolumes(light)) {
          compositeLight(light, done);
          done |= 1u << light;
        }
    }
    if (mode == Mode::Wireframe) drawEdges();
    if (mode == Mode::Volumes) drawVolumeWireframe();
  }
  present(target);
  PipelineState{}.apply();
}

}  // namespace glint::render::pipedream

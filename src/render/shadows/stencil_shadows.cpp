// Stencil shadow volumes: the passes of every counting method and composite.
#include "glint/render/shadows/stencil_shadows.h"

#include "glint/render/state.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <span>
#include <vector>

namespace glint::render::shadows {

namespace {
bool isZFail(StencilCounting c) { return c == StencilCounting::ZFail || c == StencilCounting::TwoSidedZFail; }

const char* countingName(StencilCounting c) {
  switch (c) {
    case StencilCounting::InvertZPass: return "z-pass INVERT (parity)";
    case StencilCounting::ZPass: return "z-pass INCR/DECR_WRAP";
    case StencilCounting::ZFail: return "z-fail (Carmack's reverse)";
    case StencilCounting::TwoSidedZPass: return "two-sided z-pass";
    case StencilCounting::TwoSidedZFail: return "two-sided z-fail";
  }
  return "?";
}

const char* casterName(glint::shadows::CasterMode m) {
  switch (m) {
    case glint::shadows::CasterMode::Auto: return "auto";
    case glint::shadows::CasterMode::Closed: return "closed";
    case glint::shadows::CasterMode::TwoSided: return "two-sided";
    case glint::shadows::CasterMode::Naive: return "naive";
  }
  return "?";
}
}  // namespace

StencilShadows::StencilShadows(const glint::shadows::World& world, const StencilShadowOptions& options)
    : m_options(options),
      m_scene(world),
      m_volumeProgram(gl::Program::fromFiles({"shadows/volume.vert", "shadows/volume.frag"})),
      m_extrudeProgram(gl::Program::fromFiles({"shadows/extrude.vert", "shadows/volume.frag"})),
      m_flat("shadows/flat.frag") {
  for (std::size_t i = 0; i < world.objects.size(); ++i) {
    if (!world.objects[i].castsShadow) continue;
    Caster c;
    c.object = i;
    c.edges = EdgeMap::build(world.objects[i].mesh);
    // Parity counting cancels the doubled silhouettes of two-sided casters.
    c.mode = options.counting == StencilCounting::InvertZPass && options.casters != glint::shadows::CasterMode::Naive
                 ? glint::shadows::CasterMode::Closed
                 : glint::shadows::resolveCasterMode(options.casters, c.edges);
    c.vao = gl::VertexArray::create(world.objects[i].name + "-volume");
    if (options.construction == VolumeConstruction::Gpu) {
      // Naive and Closed need a closed mesh on the GPU; anything else gets the thin shell.
      const bool twoSided = c.mode == glint::shadows::CasterMode::TwoSided || !c.edges.isClosedManifold();
      const glint::shadows::ExtrusionMesh mesh = glint::shadows::buildExtrusionMesh(c.edges, twoSided);
      const std::size_t n = mesh.positions.size() * sizeof(vec3);
      std::vector<vec3> data(mesh.positions);
      data.insert(data.end(), mesh.faceNormals.begin(), mesh.faceNormals.end());
      c.buffer = gl::Buffer(std::span<const vec3>(data), 0, world.objects[i].name + "-extrusion");
      c.indices = gl::Buffer(std::span<const std::uint32_t>(mesh.indices), 0, world.objects[i].name + "-extrusion-indices");
      c.vao.attribute(0, 0, 3, 0);
      c.vao.vertexBuffer(0, c.buffer, 0, sizeof(vec3));
      c.vao.attribute(1, 1, 3, 0);
      c.vao.vertexBuffer(1, c.buffer, GLintptr(n), sizeof(vec3));
      c.vao.indexBuffer(c.indices);
      c.indexCount = GLsizei(mesh.indices.size());
      m_stats.volumeTriangles += mesh.indices.size() / 3;
      m_stats.bytes += c.buffer.size() + c.indices.size();
    }
    m_casters.push_back(std::move(c));
  }
  m_stats.casters = m_casters.size();
}

bool StencilShadows::needsInfiniteFar(const StencilShadowOptions& options) {
  return isZFail(options.counting) && !options.depthClamp;
}

bool StencilShadows::usesCaps() const { return isZFail(m_options.counting); }

void StencilShadows::update(const glint::shadows::World& world) {
  if (m_options.construction == VolumeConstruction::Gpu) return;
  const auto start = std::chrono::steady_clock::now();
  bool rebuilt = false;
  for (Caster& c : m_casters) {
    const auto& object = world.objects.at(c.object);
    const vec3 light = vec3(glm::inverse(object.transform) * vec4(world.lightPosition, 1.0f));
    if (c.built && glm::all(glm::equal(light, c.builtForLight))) continue;
    const glint::shadows::ShadowVolume volume = glint::shadows::buildShadowVolume(c.edges, light, c.mode, usesCaps());
    const std::size_t bytes = volume.vertices.size() * sizeof(vec4);
    // Grow the buffer geometrically; otherwise overwrite in place.
    if (bytes > c.buffer.size() || !c.buffer) {
      c.buffer = gl::Buffer(std::max<std::size_t>(bytes + bytes / 2, 1024), nullptr, GL_DYNAMIC_STORAGE_BIT,
                            object.name + "-volume");
      c.vao.attribute(0, 0, 4, 0);
      c.vao.vertexBuffer(0, c.buffer, 0, sizeof(vec4));
    }
    if (bytes) c.buffer.update(0, bytes, volume.vertices.data());
    c.sideVertices = 3 * volume.sideTriangles;
    c.capVertices = 3 * volume.capTriangles;
    c.silhouetteEdges = volume.silhouetteEdges;
    c.builtForLight = light;
    c.built = true;
    rebuilt = true;
  }
  if (!rebuilt) return;
  m_stats.buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  m_stats.silhouetteEdges = m_stats.volumeTriangles = m_stats.bytes = 0;
  for (const Caster& c : m_casters) {
    m_stats.volumeTriangles += (c.sideVertices + c.capVertices) / 3;
    m_stats.silhouetteEdges += c.silhouetteEdges;
    m_stats.bytes += c.buffer.size();
  }
}

void StencilShadows::drawScene(const glint::shadows::World& world, const Camera& camera, LightTerms terms) const {
  PipelineState{.depthTest = true}.apply();
  render::clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT, vec4(0.52f, 0.6f, 0.7f, 1.0f));
  m_scene.draw(world, camera, terms);
}

void StencilShadows::drawVolumes(const glint::shadows::World& world, const Camera& camera, bool caps) const {
  const bool gpu = m_options.construction == VolumeConstruction::Gpu;
  const gl::Program& program = gpu ? m_extrudeProgram : m_volumeProgram;
  program.set("uViewProj", camera.viewProjection());
  program.set("uLightPos", world.lightPosition);
  program.use();
  for (const Caster& c : m_casters) {
    const mat4& model = world.objects.at(c.object).transform;
    program.set("uModel", model);
    c.vao.bind();
    if (gpu) {
      program.set("uNormalMatrix", glm::transpose(glm::inverse(mat3(model))));
      glDrawElements(GL_TRIANGLES, c.indexCount, GL_UNSIGNED_INT, nullptr);
    } else {
      const std::size_t count = c.sideVertices + (caps ? c.capVertices : 0);
      if (count) glDrawArrays(GL_TRIANGLES, 0, GLsizei(count));
    }
  }
  glBindVertexArray(0);
}

void StencilShadows::countVolumes(const glint::shadows::World& world, const Camera& camera) const {
  PipelineState state{.depthTest = true, .depthWrite = false,
                      .depthClamp = isZFail(m_options.counting) && m_options.depthClamp,
                      .colorMask = {false, false, false, false},
                      .polygonOffset = true,
                      .offsetFactor = m_options.offsetFactor,
                      .offsetUnits = m_options.offsetUnits};
  state.stencil.enabled = true;
  const bool caps = usesCaps();
  const auto twoDraws = [&](GLenum firstCull, StencilFace first, StencilFace second) {
    state.cull = true;
    state.cullFace = firstCull;
    state.stencil.front = first;
    state.apply();
    drawVolumes(world, camera, caps);
    state.cullFace = firstCull == GL_FRONT ? GL_BACK : GL_FRONT;
    state.stencil.front = second;
    state.apply();
    drawVolumes(world, camera, caps);
  };
  switch (m_options.counting) {
    case StencilCounting::InvertZPass:
      // The WWDC 2001 talk's order: back faces (cull front), then front faces.
      twoDraws(GL_FRONT, {.dppass = GL_INVERT}, {.dppass = GL_INVERT});
      break;
    case StencilCounting::ZPass:
      twoDraws(GL_BACK, {.dppass = GL_INCR_WRAP}, {.dppass = GL_DECR_WRAP});
      break;
    case StencilCounting::ZFail:
      twoDraws(GL_FRONT, {.dpfail = GL_INCR_WRAP}, {.dpfail = GL_DECR_WRAP});
      break;
    case StencilCounting::TwoSidedZPass:
    case StencilCounting::TwoSidedZFail: {
      const bool zfail = m_options.counting == StencilCounting::TwoSidedZFail;
      state.cull = false;
      state.stencil.separate = true;
      state.stencil.front = zfail ? StencilFace{.dpfail = GL_DECR_WRAP} : StencilFace{.dppass = GL_INCR_WRAP};
      state.stencil.back = zfail ? StencilFace{.dpfail = GL_INCR_WRAP} : StencilFace{.dppass = GL_DECR_WRAP};
      state.apply();
      drawVolumes(world, camera, caps);
      break;
    }
  }
}

void StencilShadows::composite(const glint::shadows::World& world, const Camera& camera) const {
  // Overlays touch each shadowed pixel once: the stencil is zeroed where they draw.
  const StencilState once{.enabled = true, .front = {.func = GL_NOTEQUAL, .ref = 0, .dppass = GL_ZERO}};
  const BlendState alpha{.enabled = true, .src = GL_SRC_ALPHA, .dst = GL_ONE_MINUS_SRC_ALPHA};
  switch (m_options.composite) {
    case ShadowComposite::MultiPass:
      // Same program, same vertices as the ambient pass: GL_EQUAL finds exactly the visible surfaces.
      PipelineState{.depthTest = true, .depthFunc = GL_EQUAL,
                    .depthWrite = false,
                    .stencil = {.enabled = true, .front = {.func = GL_EQUAL, .ref = 0, .writeMask = 0}},
                    .blend = {.enabled = true, .src = GL_ONE, .dst = GL_ONE}}
          .apply();
      m_scene.draw(world, camera, LightTerms::Direct);
      break;
    case ShadowComposite::ShadowQuad:
      PipelineState{.depthTest = false, .depthWrite = false, .stencil = once, .blend = alpha}.apply();
      m_flat.program().set("uColor", vec4(0.0f, 0.0f, 0.0f, m_options.quadAlpha));
      m_flat.drawWithCurrentState();
      break;
    case ShadowComposite::VolumeAlpha: {
      PipelineState{.depthTest = false,
                    .depthWrite = false,
                    .depthClamp = isZFail(m_options.counting) && m_options.depthClamp,
                    .stencil = once,
                    .blend = alpha}
          .apply();
      const gl::Program& p = m_options.construction == VolumeConstruction::Gpu ? m_extrudeProgram : m_volumeProgram;
      p.set("uColor", vec4(0.0f, 0.0f, 0.0f, m_options.volumeOpacity));
      drawVolumes(world, camera, true);
      break;
    }
    case ShadowComposite::DimAlpha:
      // result = dst · dst.alpha: the scene wrote "how much a shadow keeps" into alpha.
      PipelineState{.depthTest = false, .depthWrite = false, .stencil = once,
                    .blend = {.enabled = true, .src = GL_ZERO, .dst = GL_DST_ALPHA}}
          .apply();
      m_flat.drawWithCurrentState();
      break;
    case ShadowComposite::CountColors: {
      struct Band {
        GLenum func;
        GLint ref;
        vec4 color;
      };
      // func(ref, stencil): EQUAL k, or LEQUAL k for "stencil ≥ k"; later bands overwrite.
      const Band bands[] = {{GL_EQUAL, 1, {1.0f, 0.9f, 0.2f, 0.6f}},   {GL_EQUAL, 2, {1.0f, 0.55f, 0.1f, 0.6f}},
                            {GL_EQUAL, 3, {0.9f, 0.15f, 0.1f, 0.6f}},  {GL_LEQUAL, 4, {0.9f, 0.1f, 0.8f, 0.6f}},
                            {GL_LEQUAL, 128, {0.45f, 0.2f, 0.95f, 0.6f}}};
      for (const Band& b : bands) {
        PipelineState{.depthTest = false,
                      .depthWrite = false,
                      .stencil = {.enabled = true, .front = {.func = b.func, .ref = b.ref, .writeMask = 0}},
                      .blend = alpha}
            .apply();
        m_flat.program().set("uColor", b.color);
        m_flat.drawWithCurrentState();
      }
      break;
    }
    case ShadowComposite::None:
      break;
  }
}

void StencilShadows::drawView(const glint::shadows::World& world, const Camera& camera) const {
  if (m_options.view == VolumeView::None) return;
  PipelineState state{.depthTest = true, .depthWrite = false,
                      .depthClamp = isZFail(m_options.counting) && m_options.depthClamp,
                      .polygonOffset = true,
                      .offsetFactor = m_options.offsetFactor,
                      .offsetUnits = m_options.offsetUnits,
                      .blend = {.enabled = true, .src = GL_ONE, .dst = GL_ONE}};
  const gl::Program& p = m_options.construction == VolumeConstruction::Gpu ? m_extrudeProgram : m_volumeProgram;
  const auto faces = [&](GLenum cull, vec4 color) {
    state.cull = true;
    state.cullFace = cull;
    state.apply();
    p.set("uColor", color);
    drawVolumes(world, camera, usesCaps());
  };
  // The WWDC 2001 talk's colours: back faces green, front faces blue; added, both make cyan.
  const vec4 green{0.0f, 0.55f, 0.0f, 1.0f}, blue{0.0f, 0.0f, 0.75f, 1.0f};
  switch (m_options.view) {
    case VolumeView::BackFaces: faces(GL_FRONT, green); break;
    case VolumeView::FrontFaces: faces(GL_BACK, blue); break;
    case VolumeView::BothFaces:
      faces(GL_FRONT, green);
      faces(GL_BACK, blue);
      break;
    case VolumeView::Wireframe:
      state.blend = {};
      state.polygonMode = GL_LINE;
      state.polygonOffset = false;
      state.apply();
      p.set("uColor", vec4(1.0f, 0.85f, 0.2f, 1.0f));
      drawVolumes(world, camera, true);
      PipelineState{.depthTest = true}.apply();  // back to GL_FILL
      break;
    case VolumeView::None: break;
  }
}

std::uint64_t StencilShadows::measureFill(const glint::shadows::World& world, const Camera& camera) const {
  PipelineState{.depthTest = false,
                .depthWrite = false,
                .depthClamp = isZFail(m_options.counting) && m_options.depthClamp,
                .colorMask = {false, false, false, false}}
      .apply();
  gl::Query query(GL_SAMPLES_PASSED, "stencil-fill");
  query.begin();
  drawVolumes(world, camera, usesCaps());
  query.end();
  PipelineState{.depthTest = true}.apply();
  return query.result();
}

void StencilShadows::render(const glint::shadows::World& world, const Camera& camera, const gl::Target& target) {
  update(world);
  target.bind();
  const LightTerms terms = m_options.composite == ShadowComposite::MultiPass ? LightTerms::Ambient
                           : m_options.composite == ShadowComposite::DimAlpha ? LightTerms::DimAlpha
                                                                              : LightTerms::Full;
  drawScene(world, camera, terms);
  countVolumes(world, camera);
  composite(world, camera);
  drawView(world, camera);
  PipelineState{.depthTest = true}.apply();
}

std::string StencilShadows::describe() const {
  std::string modes;
  for (const Caster& c : m_casters)
    if (modes.find(casterName(c.mode)) == std::string::npos) modes += (modes.empty() ? "" : "+") + std::string(casterName(c.mode));
  const bool gpu = m_options.construction == VolumeConstruction::Gpu;
  return fmt::format("{}, {}, {} casters ({}): {} volume triangles, {:.1f} KiB{}", countingName(m_options.counting),
                     gpu ? "GPU extrusion (degenerate quads)" : "CPU silhouettes", m_stats.casters, modes,
                     m_stats.volumeTriangles, double(m_stats.bytes) / 1024.0,
                     gpu ? std::string() : fmt::format(", {} silhouette edges, built in {:.2f} ms",
                                                       m_stats.silhouetteEdges, m_stats.buildMs));
}

}  // namespace glint::render::shadows

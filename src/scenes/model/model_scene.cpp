// Any model file as a scene (scenes/model.h): `glint view FILE`, `glint render FILE`.
#include "glint/core/error.h"
#include "glint/core/text.h"
#include "glint/gl/shader.h"
#include "glint/render/bump/textures.h"
#include "glint/render/env/environment.h"
#include "glint/render/gpu_mesh.h"
#include "glint/render/state.h"
#include "glint/scenes/model.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

namespace glint::scenes {

namespace fs = std::filesystem;

namespace {

// The page `glint bake --preview` writes has the same background, field of view, framing
// and light rig, so a picture here and a screenshot there can be put side by side.
const vec4 kBackground{0x2b / 255.0f, 0x2d / 255.0f, 0x31 / 255.0f, 1.0f};
constexpr float kFovY = 35.0f;
struct RigLight {
  vec3 direction;  ///< in view space: x right, y up, z towards the viewer
  vec3 color;
};
const RigLight kRig[3] = {{glm::normalize(vec3(1.0f, 1.2f, 1.4f)), vec3(0.9f)},        // key
                          {glm::normalize(vec3(-1.5f, 0.4f, 0.8f)), vec3(0.81f, 0.88f, 1.0f) * 0.3f},  // fill
                          {glm::normalize(vec3(0.2f, 1.0f, -1.6f)), vec3(0.5f)}};       // rim

/// Edges of a model as lines: every triangle edge; edges whose faces disagree on UVs or
/// have one face (UV seams); edges whose faces disagree on normals (hard edges).
struct Lines {
  std::vector<vec3> wire, seams, hardEdges;  ///< pairs of points
};

Lines modelLines(const ModelFile& model) {
  Lines lines;
  const float cell = std::max(model.bounds().diagonal(), 1e-6f) * 1e-6f;
  using Point = std::tuple<long, long, long>;
  const auto point = [cell](vec3 p) { return Point{std::lround(p.x / cell), std::lround(p.y / cell), std::lround(p.z / cell)}; };
  struct Side {
    vec3 a, b;            // the edge's ends, in the order of its key
    vec2 uvA, uvB;
    vec3 normalA, normalB;
  };
  std::map<std::pair<Point, Point>, std::vector<Side>> edges;
  for (const ModelPart& part : model.parts) {
    const Mesh& m = part.mesh;
    for (std::size_t t = 0; t < m.triangleCount(); ++t)
      for (int k = 0; k < 3; ++k) {
        std::uint32_t i = m.indices[3 * t + std::size_t(k)], j = m.indices[3 * t + std::size_t(k + 1) % 3];
        Point pi = point(m.positions[i]), pj = point(m.positions[j]);
        if (pj < pi) std::swap(i, j), std::swap(pi, pj);
        if (pi == pj) continue;
        const vec2 uvI = m.hasUvs() ? m.uvs[i] : vec2(0.0f), uvJ = m.hasUvs() ? m.uvs[j] : vec2(0.0f);
        edges[{pi, pj}].push_back({m.positions[i], m.positions[j], uvI, uvJ, m.normals[i], m.normals[j]});
      }
  }
  const auto add = [](std::vector<vec3>& points, vec3 a, vec3 b) {
    points.push_back(a);
    points.push_back(b);
  };
  const float uvTolerance = 1e-5f, normalTolerance = std::cos(glm::radians(0.5f));
  for (const auto& [key, sides] : edges) {
    const Side& s = sides.front();
    add(lines.wire, s.a, s.b);
    bool seam = sides.size() != 2, hard = false;
    for (std::size_t k = 1; k < sides.size(); ++k) {
      seam = seam || glm::length(sides[k].uvA - s.uvA) > uvTolerance || glm::length(sides[k].uvB - s.uvB) > uvTolerance;
      hard = hard || glm::dot(glm::normalize(sides[k].normalA), glm::normalize(s.normalA)) < normalTolerance ||
             glm::dot(glm::normalize(sides[k].normalB), glm::normalize(s.normalB)) < normalTolerance;
    }
    if (seam) add(lines.seams, s.a, s.b);
    if (hard) add(lines.hardEdges, s.a, s.b);
  }
  return lines;
}

/// Line segments (pairs of positions) on the GPU, drawn with glDrawArrays(GL_LINES).
class LineSet {
public:
  LineSet() = default;
  LineSet(const std::vector<vec3>& points, std::string_view name) : m_count(GLsizei(points.size())) {
    if (points.empty()) return;
    m_vao = gl::VertexArray::create(name);
    m_buffer = gl::Buffer(points.size() * sizeof(vec3), points.data(), 0, std::string(name));
    m_vao.attribute(render::attrib::kPosition, 0, 3, 0);
    m_vao.vertexBuffer(0, m_buffer, 0, GLsizei(sizeof(vec3)));
  }
  void draw() const {
    if (m_count == 0) return;
    m_vao.bind();
    glDrawArrays(GL_LINES, 0, m_count);
    glBindVertexArray(0);
  }

private:
  gl::Buffer m_buffer;
  gl::VertexArray m_vao;
  GLsizei m_count = 0;
};

/// The sphere the camera frames: the bounding box's centre and the farthest vertex from it
/// (as the preview page computes it).
std::pair<vec3, float> boundingSphere(const ModelFile& model) {
  const vec3 center = model.bounds().center();
  float radius = 1e-6f;
  for (const ModelPart& p : model.parts)
    for (const vec3& v : p.mesh.positions) radius = std::max(radius, glm::length(v - center));
  return {center, radius};
}

gl::Texture upload(const Image& image, std::string_view label) {
  if (image.empty()) {  // a 1×1 stand-in: the shader reads "no such map" from its size
    Image none(1, 1, 4);
    return render::bump::uploadImage(none, {.mipmaps = false, .label = label});
  }
  return render::bump::uploadImage(image, {.label = label});
}

class ModelScene final : public Scene {
public:
  explicit ModelScene(std::shared_ptr<const ModelFile> model)
      : m_model(std::move(model)),
        m_program(gl::Program::fromFiles({"model/model.vert", "model/model.frag"})),
        m_lineProgram(gl::Program::fromFiles({"model/lines.vert", "model/lines.frag"})) {
    std::tie(m_center, m_radius) = boundingSphere(*m_model);
    m_frame = {m_center, m_radius};
    m_names = m_model->mapNames();
    for (const ModelPart& part : m_model->parts) {
      std::vector<vec4> colors = part.colors;
      m_parts.push_back({render::GpuMesh(part.mesh, colors, "model-part"), part.material, !part.colors.empty()});
    }
    for (const ModelMaterial& mat : m_model->materials) {
      GpuMaterial g{.source = &mat, .normal = upload(mat.normalMap, "normal-map"),
                    .occlusion = upload(mat.occlusionMap, "occlusion-map"), .base = upload(mat.baseColorMap, "base-color")};
      for (const std::string& name : m_names) {
        const auto it = std::find_if(mat.maps.begin(), mat.maps.end(), [&](const auto& m) { return m.first == name; });
        g.maps.push_back(upload(it == mat.maps.end() ? Image() : it->second, name));
      }
      m_materials.push_back(std::move(g));
    }
    m_none = upload(Image(), "none");
    const Image equirect = render::env::loadEquirect(render::env::findEnvironment("courtyard"));
    m_environment = render::env::cubeFromEquirect(equirect, {.faceSize = 128, .label = "studio-environment"});
    m_hasMisses = std::find(m_names.begin(), m_names.end(), "miss_mask") != m_names.end();
  }

  std::vector<Option> options() override {
    std::string shows = "0 shaded";
    for (std::size_t i = 0; i < m_names.size(); ++i) shows += fmt::format(", {} {}", i + 1, m_names[i]);
    std::vector<Option> o = {
        {"normal-map", "the material's normal map", &m_normalMap, 0, 1, 'N'},
        {"ao", "the occlusion (AO) map", &m_occlusion, 0, 1, 'O'},
        {"show", "a map as a colour: " + shows, &m_show, 0, float(m_names.size()), 'M'},
        {"wireframe", "every triangle edge", &m_wireframe, 0, 1, 'W'},
        {"uv-seams", "edges whose faces disagree on UVs, or open edges", &m_uvSeams, 0, 1, 'U'},
        {"hard-edges", "edges whose faces disagree on normals: a bake's rays fan apart there", &m_hardEdges, 0, 1, 'H'},
        {"misses", "texels whose bake rays missed, in red (the asset's miss mask)", &m_misses, 0, 1, 'X'},
        {"yaw", "the camera around the model, degrees (from +Z towards +X)", &m_yaw, -180, 180},
        {"pitch", "the camera above the model, degrees", &m_pitch, -85, 85},
        {"zoom", "the camera's distance, as a factor of the framing distance", &m_zoom, 0.2f, 4},
        {"frame", "another model file whose bounding sphere the camera frames (a high poly at its low poly's "
                  "camera); empty: this one", &m_frameFile}};
    return o;
  }

  std::string notes() const override {
    std::size_t triangles = 0;
    for (const ModelPart& p : m_model->parts) triangles += p.mesh.triangleCount();
    std::string text = fmt::format("{}: {} triangles, {} part{}, {} material{}", m_model->name, triangles,
                                   m_model->parts.size(), m_model->parts.size() == 1 ? "" : "s",
                                   m_model->materials.size(), m_model->materials.size() == 1 ? "" : "s");
    if (!m_names.empty()) {
      text += "; maps:";
      for (const std::string& n : m_names) text += " " + n;
    }
    if (m_model->bake.is_object()) {
      // The file's JSON: "high" may be anything, so its type is asked first.
      const auto high = m_model->bake.find("high");
      text += fmt::format("; baked by glint from {}", high != m_model->bake.end() && high->is_string()
                                                          ? printable(high->get<std::string>()) : std::string("?"));
    }
    return text;
  }

  void render(const FrameInput& frame) override {
    frame.target.bind();
    render::clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT, kBackground);
    if (m_frameFile != m_framedBy) {  // --set frame=OTHER: that model's sphere
      m_framedBy = m_frameFile;
      m_frame = m_frameFile.empty() ? std::pair{m_center, m_radius} : boundingSphere(loadModelFile(m_frameFile));
    }
    const auto [center, radius] = m_frame;
    const float distance = radius / std::sin(glm::radians(kFovY / 2.0f)) * 1.05f;
    const glint::Camera camera = frame.camera(glint::Camera::orbit(
        center, distance * m_zoom, glm::radians(m_yaw), glm::radians(m_pitch), kFovY, frame.target.aspect(),
        distance * m_zoom / 100.0f, distance * m_zoom * 10.0f));
    const mat3 toWorld = glm::transpose(camera.rotation());
    m_program.set("uViewProj", camera.viewProjection());
    m_program.set("uEye", camera.position);
    for (int i = 0; i < 3; ++i) {
      m_program.set(fmt::format("uLightDirection[{}]", i), glm::normalize(toWorld * kRig[i].direction));
      m_program.set(fmt::format("uLightColor[{}]", i), kRig[i].color);
    }
    m_program.set("uEnvironmentLevels", float(m_environment.levels()));
    render::PipelineState{.depthTest = true, .polygonOffset = true, .offsetFactor = 1.0f, .offsetUnits = 1.0f,
                          .seamlessCubeMap = true}.apply();
    m_environment.bind(5);
    m_program.use();
    for (const GpuPart& part : m_parts) {
      const GpuMaterial* mat = part.material >= 0 && std::size_t(part.material) < m_materials.size()
                                   ? &m_materials[std::size_t(part.material)] : nullptr;
      const bool mapped = mat && !mat->source->normalMap.empty();
      m_program.set("uUseNormalMap", m_normalMap && mapped);
      m_program.set("uUseOcclusion", m_occlusion && mat && !mat->source->occlusionMap.empty());
      m_program.set("uUseBaseColorMap", mat && !mat->source->baseColorMap.empty());
      m_program.set("uUseVertexColor", part.colored);
      m_program.set("uBaseColor", mat ? mat->source->baseColor : vec4(0.8f, 0.8f, 0.8f, 1.0f));
      m_program.set("uRoughness", mat ? mat->source->roughness : 0.55f);
      m_program.set("uShow", m_show > 0 && std::size_t(m_show) <= m_names.size());
      m_program.set("uMisses", m_misses && m_hasMisses && mat != nullptr);
      (mat ? mat->normal : m_none).bind(0);
      (mat ? mat->occlusion : m_none).bind(1);
      (mat ? mat->base : m_none).bind(2);
      const bool showing = mat && m_show > 0 && std::size_t(m_show) <= m_names.size();
      (showing ? mat->maps[std::size_t(m_show - 1)] : m_none).bind(3);
      const auto miss = std::find(m_names.begin(), m_names.end(), "miss_mask");
      (mat && miss != m_names.end() ? mat->maps[std::size_t(miss - m_names.begin())] : m_none).bind(4);
      part.mesh.draw();
    }
    // Lines over the surface (the triangles were pushed back by the polygon offset), made
    // when an overlay is first asked for: a large model's edge map costs seconds.
    if ((m_wireframe || m_uvSeams || m_hardEdges) && !m_linesMade) {
      const Lines lines = modelLines(*m_model);
      m_wire = LineSet(lines.wire, "wireframe");
      m_seams = LineSet(lines.seams, "uv-seams");
      m_hard = LineSet(lines.hardEdges, "hard-edges");
      m_linesMade = true;
    }
    render::PipelineState{.depthTest = true, .depthFunc = GL_LEQUAL}.apply();
    m_lineProgram.set("uViewProj", camera.viewProjection());
    m_lineProgram.use();
    const std::array<std::tuple<bool, const LineSet*, vec4>, 3> overlays = {
        std::tuple{m_wireframe, &m_wire, vec4(0.05f, 0.05f, 0.05f, 1.0f)},
        std::tuple{m_uvSeams, &m_seams, vec4(1.0f, 0.63f, 0.13f, 1.0f)},
        std::tuple{m_hardEdges, &m_hard, vec4(0.1f, 0.85f, 1.0f, 1.0f)}};
    for (const auto& [on, lines, color] : overlays) {
      if (!on) continue;
      m_lineProgram.set("uColor", color);
      lines->draw();
    }
  }

private:
  struct GpuPart {
    render::GpuMesh mesh;
    int material = -1;
    bool colored = false;
  };
  struct GpuMaterial {
    const ModelMaterial* source = nullptr;
    gl::Texture normal, occlusion, base;
    std::vector<gl::Texture> maps;  ///< by m_names
  };

  std::shared_ptr<const ModelFile> m_model;
  gl::Program m_program, m_lineProgram;
  std::vector<GpuPart> m_parts;
  std::vector<GpuMaterial> m_materials;
  std::vector<std::string> m_names;
  gl::Texture m_none, m_environment;
  LineSet m_wire, m_seams, m_hard;
  bool m_linesMade = false;
  vec3 m_center{0.0f};
  float m_radius = 0.0f;
  std::string m_frameFile, m_framedBy;
  std::pair<vec3, float> m_frame;
  bool m_hasMisses = false;
  bool m_normalMap = true, m_occlusion = true, m_wireframe = false, m_uvSeams = false, m_hardEdges = false, m_misses = false;
  int m_show = 0;
  float m_yaw = 25.0f, m_pitch = 15.0f, m_zoom = 1.0f;
};

}  // namespace

Registry modelRegistry(const fs::path& path) {
  auto model = std::make_shared<const ModelFile>(loadModelFile(path));
  Registry registry;
  const std::string summary = fmt::format("{} under a studio light rig; a toggle per map it carries", model->name);
  registry.add({.name = "model/" + model->name,
                .summary = summary,
                .variants = {{"view", "The model framed by its bounding sphere, lit by key, fill and rim lights and the "
                                      "courtyard environment."}},
                .defaultSize = {960, 720},
                .create = [model](int) -> std::unique_ptr<Scene> { return std::make_unique<ModelScene>(model); }});
  return registry;
}

const Registry& registryFor(std::string& name, Registry& storage) {
  std::error_code ec;
  if (!isModelFile(name)) return Registry::builtin();
  if (!fs::exists(name, ec)) fail(ErrorKind::Input, "cannot read '{}': no such file", name);
  storage = modelRegistry(name);
  name = storage.scenes().front().name;
  return storage;
}

}  // namespace glint::scenes

#pragma once
// glint/render/bump/normal_mapping.h — per-pixel lighting with normal maps: the renderer side
// of the normal mapper (`glint bake`), and the technique bump mapping builds on.
//
// Contents
//   ShadingNormal           where the shading normal comes from: vertices, a tangent-space
//                           map (MikkTSpace) or an object-space map
//   NormalMappingOutput     lit colour, or the world-space normal itself (tests, debugging)
//   DirectionalLight        a light at infinity
//   PointLight              a light at a position, with distance falloff
//   NormalMappingMaterial   albedo, ambient, Blinn-Phong highlight
//   NormalMapping           the program and its draw call
//   NormalMapView           a normal map itself, as an image filling the viewport
//
// One tangent space. Tangent-space maps are decoded with MikkTSpace's per-pixel rule,
// exactly the inverse of what the baker stores (glint/mesh/tangents.h):
//   vertex:   n = normalize(normalMatrix · normal), t = normalize(model₃ₓ₃ · tangent.xyz)
//   pixel:    b = tangent.w · sign(det model) · cross(n, t)        (n, t interpolated, NOT normalized)
//             N = normalize(m.x · t + m.y · b + m.z · n),   m = 2·texel − 1 (green negated if DirectX)
// The mesh's tangents must be the ones the map was baked with: bake::BakeResult::low, or
// any mesh run through generateTangents(). Render the low poly with them, and the map
// decodes to the high poly's normals (tests/bake/bake_roundtrip_test.cpp measures it).
// Rotations, uniform scales and mirrors in `model` are handled; non-uniform scale bends
// the frame, as in every engine.
//
/// ```cpp
/// #include <glint/image/normalmap.h>
/// #include <glint/mesh/tangents.h>
/// #include <glint/render/bump/textures.h>
/// namespace bump = glint::render::bump;
/// glint::Mesh low = glint::loadMesh("low.obj");
/// glint::generateTangents(low);  // the frame the map was baked in
/// const glint::render::GpuMesh lowMesh(low);
/// const glint::Image normals = glint::prepareNormalMap(glint::loadImage("baked.png"), "baked.png");  // checked
/// const glint::gl::Texture map = bump::uploadImage(normals, {.label = "baked-normals"});
/// const glint::mat4 model(1.0f);
/// const auto camera = glint::Camera::orbit({0, 0, 0}, 3.0f, 0.5f, 0.3f, 45.0f, 16.0f / 9.0f);
/// const bump::NormalMapping shader({.normal = bump::ShadingNormal::TangentMap});
/// const bump::DirectionalLight sun{.direction = glm::normalize(glint::vec3(1, 2, 1))};
/// shader.draw(lowMesh, model, camera, {&sun, 1}, {}, &map);
/// ```
//
// State: depth test on, back faces culled, texture units 0 (normal map) and 1 (albedo map)
// with no sampler objects; the program is left bound, the texture units cleared.

#include "glint/gl/objects.h"
#include "glint/gl/shader.h"
#include "glint/core/camera.h"
#include "glint/render/gpu_mesh.h"

#include <span>

namespace glint::render::bump {

enum class ShadingNormal {
  Vertex,      ///< the interpolated vertex normal (a mesh as it is: the low poly unmapped, the high poly)
  TangentMap,  ///< a tangent-space normal map, MikkTSpace frame from the mesh's normals and tangents
  ObjectMap    ///< an object-space normal map (transformed by the model's normal matrix)
};

enum class NormalMappingOutput {
  Lit,         ///< ambient + Σ lights (Lambert diffuse + optional Blinn-Phong), linear RGB
  WorldNormal  ///< the shading normal n as (n + 1) / 2 in RGB — read back as float for tests
};

struct NormalMappingOptions {
  ShadingNormal normal = ShadingNormal::TangentMap;
  bool directX = false;  ///< the map stores green down (DirectX/Unreal convention)
  NormalMappingOutput output = NormalMappingOutput::Lit;
};

struct DirectionalLight {
  vec3 direction{0.0f, 1.0f, 0.0f};  ///< towards the light, world space (normalized by draw)
  vec3 color{1.0f};
};

/// A point light: the direction to it is computed per pixel (the WWDC 2001 talk's "positional light").
struct PointLight {
  vec3 position{0.0f, 2.0f, 0.0f};  ///< world space
  vec3 color{1.0f};
  float range = 0.0f;  ///< intensity × 1 / (1 + (d / range)²); 0: no falloff
};

struct NormalMappingMaterial {
  vec3 albedo{0.8f};
  const gl::Texture* albedoMap = nullptr;  ///< optional colour texture (unit 1), multiplies albedo
  vec3 ambient{0.06f};     ///< added regardless of the normal
  float specular = 0.0f;   ///< Blinn-Phong highlight strength (0: diffuse only)
  float shininess = 48.0f;
};

class NormalMapping {
public:
  static constexpr int kMaxLights = 4;

  NormalMapping() : NormalMapping(NormalMappingOptions{}) {}
  explicit NormalMapping(const NormalMappingOptions& options);

  /// Draws `mesh` (positions, normals; UVs and tangents for the map paths) placed by `model`.
  /// `normalMap` is required for the map paths (Error(Internal) when missing) and ignored
  /// for ShadingNormal::Vertex. At most kMaxLights lights (Error(Internal) beyond).
  void draw(const GpuMesh& mesh, const mat4& model, const Camera& camera, std::span<const DirectionalLight> lights,
            const NormalMappingMaterial& material = {}, const gl::Texture* normalMap = nullptr) const;
  /// The same with point lights as well (at most kMaxLights of each kind).
  void draw(const GpuMesh& mesh, const mat4& model, const Camera& camera, std::span<const DirectionalLight> lights,
            std::span<const PointLight> pointLights, const NormalMappingMaterial& material = {},
            const gl::Texture* normalMap = nullptr) const;

  const NormalMappingOptions& options() const { return m_options; }

private:
  NormalMappingOptions m_options;
  gl::Program m_program;
};

/// Shows a 2D texture (a normal map, an AO map) filling the current viewport, v = 0 at
/// the bottom like the mesh's UVs. Depth test and writes off.
class NormalMapView {
public:
  NormalMapView();
  void draw(const gl::Texture& map) const;

private:
  FullscreenPass m_pass;
};

}  // namespace glint::render::bump

#include "glint/render/shadows/world_renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <string>

namespace glint::render::shadows {

WorldRenderer::WorldRenderer(const glint::shadows::World& world, const std::vector<std::string>& defines)
    : m_program(gl::Program::fromFiles({"shadows/scene.vert", "shadows/scene.frag"}, defines)) {
  m_program.label("shadows-scene");
  m_meshes.reserve(world.objects.size());
  for (const auto& o : world.objects) m_meshes.emplace_back(o.mesh, std::span<const vec4>{}, o.name);
}

void WorldRenderer::draw(const glint::shadows::World& world, const Camera& camera, LightTerms terms) const {
  draw(world, camera, terms, m_program);
}

void WorldRenderer::draw(const glint::shadows::World& world, const Camera& camera, LightTerms terms, const gl::Program& program) const {
  program.set("uViewProj", camera.viewProjection());
  program.set("uEye", camera.position);
  program.set("uLightPos", world.lightPosition);
  program.set("uAmbient", world.ambient);
  program.set("uTerms", int(terms));
  program.use();
  for (std::size_t i = 0; i < world.objects.size() && i < m_meshes.size(); ++i) {
    const auto& o = world.objects[i];
    program.set("uModel", o.transform);
    program.set("uNormalMatrix", glm::transpose(glm::inverse(mat3(o.transform))));
    program.set("uColor", o.color);
    program.set("uGround", o.ground);
    m_meshes[i].draw();
  }
}

void WorldRenderer::drawGeometry(const glint::shadows::World& world, const mat4& viewProj, const gl::Program& program,
                                 const std::function<bool(const glint::shadows::WorldObject&)>& filter) const {
  program.set("uViewProj", viewProj);
  program.use();
  for (std::size_t i = 0; i < world.objects.size() && i < m_meshes.size(); ++i) {
    if (filter && !filter(world.objects[i])) continue;
    program.set("uModel", world.objects[i].transform);
    m_meshes[i].draw();
  }
}

Bounds shadowFocus(const glint::shadows::World& world) {
  Bounds out{vec3(std::numeric_limits<float>::max()), vec3(std::numeric_limits<float>::lowest())};
  const vec3 l = world.lightPosition;
  for (std::size_t i = 0; i < world.objects.size(); ++i) {
    if (!world.objects[i].castsShadow) continue;
    // The corners of the object's box (conservative, and cheap enough for every frame).
    const Bounds b = world.objects[i].mesh.bounds();
    for (int k = 0; k < 8; ++k) {
      const vec3 corner{(k & 1) ? b.max.x : b.min.x, (k & 2) ? b.max.y : b.min.y, (k & 4) ? b.max.z : b.min.z};
      const vec3 p = vec3(world.objects[i].transform * vec4(corner, 1.0f));
      out.min = glm::min(out.min, p);
      out.max = glm::max(out.max, p);
      // Along the ray from the light through p, down to the ground (if it gets there).
      if (p.y < l.y - 1e-4f) {
        const vec3 g = l + (p - l) * ((l.y - world.groundHeight) / (l.y - p.y));
        out.min = glm::min(out.min, g);
        out.max = glm::max(out.max, g);
      }
    }
  }
  if (out.min.x > out.max.x) return world.bounds();  // no casters
  return out;
}

Camera lightCamera(const glint::shadows::World& world, const Bounds& focus, float aspect) {
  const vec3 centre = focus.center();
  const float radius = 0.5f * focus.diagonal();
  const float distance = std::max(glm::length(world.lightPosition - centre), 1e-3f);
  // Half-angle that just encloses the sphere; the light must be outside it.
  const float half = distance > radius ? std::asin(radius / distance) : glm::radians(75.0f);
  const float nearPlane = std::max(0.05f, distance - radius);
  const float farPlane = distance + radius;
  const vec3 dir = (centre - world.lightPosition) / distance;
  const vec3 up = std::abs(dir.y) > 0.99f ? vec3(0.0f, 0.0f, -1.0f) : vec3(0.0f, 1.0f, 0.0f);
  return Camera::lookAt(world.lightPosition, centre, up, glm::degrees(2.0f * half), aspect, nearPlane, farPlane);
}

mat4 infiniteFarProjection(const mat4& projection, float epsilon) {
  // glm::perspective: P[2][2] = −(f + n)/(f − n), P[3][2] = −2fn/(f − n), so
  // n = P[3][2] / (P[2][2] − 1). Letting f → ∞: P[2][2] → −1, P[3][2] → −2n; the
  // tweak keeps w = 0 points at NDC z = 1 − ε instead of exactly on the far plane.
  mat4 p = projection;
  const float nearPlane = p[3][2] / (p[2][2] - 1.0f);
  p[2][2] = epsilon - 1.0f;
  p[3][2] = (epsilon - 2.0f) * nearPlane;
  return p;
}

}  // namespace glint::render::shadows

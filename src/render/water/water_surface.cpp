#include "glint/render/water/water_surface.h"

#include "glint/core/error.h"
#include "glint/core/log.h"
#include "glint/image/envmap.h"
#include "glint/render/env/environment.h"
#include "glint/render/state.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace glint::render::water {

WaterSurface::WaterSurface(int cells)
    : m_grid(makeGrid(cells, cells, 2.0f), {}, "water-grid"),
      m_program(gl::Program::fromFiles({"water/surface.vert", "water/surface.frag"})) {}

void WaterSurface::draw(const Camera& camera, const gl::Texture& waveState, const gl::Texture& normalMap,
                        const gl::Texture& environment, const gl::Texture& poolFloor,
                        const WaterSurfaceOptions& o) const {
  m_program.set("uViewProjection", camera.viewProjection());
  m_program.set("uEye", camera.position);
  m_program.set("uHalfSize", o.halfSize);
  m_program.set("uDisplacement", o.displacement);
  m_program.set("uDepth", o.depth);
  m_program.set("uF0", o.fresnelF0);
  m_program.set("uAbsorption", o.absorption);
  m_program.set("uSunDirection", o.sunDirection);
  m_program.set("uSunColor", o.sunColor);
  m_program.set("uSunShininess", o.sunShininess);
  waveState.bind(0);
  normalMap.bind(1);
  environment.bind(2);
  poolFloor.bind(3);
  for (GLuint unit = 0; unit < 4; ++unit) gl::Sampler::unbind(unit);
  PipelineState{.depthTest = true, .seamlessCubeMap = true}.apply();
  m_program.use();
  m_grid.draw();
}

namespace {
// A clear-day sky: a horizon-to-zenith gradient, a sun with a glow, a dark ground below.
vec3 proceduralSky(vec3 d, vec3 sun) {
  d = glm::normalize(d);
  const float up = d.y;
  vec3 c;
  if (up >= 0.0f) {
    const float t = std::pow(up, 0.45f);
    c = glm::mix(vec3(0.78f, 0.85f, 0.92f), vec3(0.22f, 0.45f, 0.80f), t);
  } else {
    c = glm::mix(vec3(0.42f, 0.40f, 0.36f), vec3(0.18f, 0.17f, 0.15f), std::min(1.0f, -up * 4.0f));
  }
  const float s = std::max(0.0f, glm::dot(d, glm::normalize(sun)));
  c += vec3(1.0f, 0.9f, 0.7f) * (std::pow(s, 800.0f) * 3.0f + std::pow(s, 12.0f) * 0.25f);
  return glm::clamp(c, 0.0f, 1.0f);
}
}  // namespace

SkyEnvironment skyEnvironment(const char* name, int faceSize) {
  try {
    const auto path = env::findEnvironment(name);
    return {env::cubeFromEquirect(env::loadEquirect(path), {.faceSize = faceSize, .label = "water-environment"}),
            path.filename().string() + " (glint's data directory)"};
  } catch (const Error& e) {
    if (e.kind() != ErrorKind::Input) throw;
    log::warn("water: {}; reflecting a procedural sky instead", e.what());
  }
  // Each face texel's direction from the cube-map convention of image/envmap.h, so the sky
  // lands where a lookup by direction finds it.
  const vec3 sun = WaterSurfaceOptions{}.sunDirection;
  std::vector<Image> faces;
  for (int face = 0; face < glint::kCubeFaces; ++face) {
    Image img(faceSize, faceSize, 4);
    for (int y = 0; y < faceSize; ++y)
      for (int x = 0; x < faceSize; ++x) {
        const vec3 c = proceduralSky(glint::cubeTexelDirection(face, x, y, faceSize), sun);
        for (int k = 0; k < 3; ++k) img.set(x, y, k, c[k]);
        img.set(x, y, 3, 1.0f);
      }
    faces.push_back(std::move(img));
  }
  return {env::cubeFromFaces(faces), "procedural sky (glint's environment data is not installed: scripts/setup)"};
}

}  // namespace glint::render::water

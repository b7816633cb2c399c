#pragma once
// glint/core/math.h — GLM aliases used across glint.
//
// GLM is the math library; glint only names its types in the glint namespace so
// headers read `vec3` rather than `glm::vec3`. Depth is [0, 1] for GL clip
// control defaults, right-handed like OpenGL.

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

namespace glint {

using glm::dvec2;
using glm::dvec3;
using glm::ivec2;
using glm::ivec3;
using glm::ivec4;
using glm::mat3;
using glm::mat4;
using glm::uvec2;
using glm::uvec3;
using glm::uvec4;
using glm::vec2;
using glm::vec3;
using glm::vec4;

constexpr float kPi = 3.14159265358979323846f;

}  // namespace glint

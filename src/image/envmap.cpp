#include "glint/image/envmap.h"

#include "glint/core/error.h"
#include "glint/image/srgb.h"

#include <algorithm>
#include <cmath>

namespace glint {

const char* cubeFaceName(int face) {
  static constexpr const char* kNames[] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
  return face >= 0 && face < kCubeFaces ? kNames[face] : "?";
}

vec3 cubeFaceDirection(int face, vec2 st) {
  // Inverse of the OpenGL spec's table: sc = 2s − 1, tc = 2t − 1 on the face whose
  // major axis is ±1.
  const float sc = 2.0f * st.x - 1.0f;
  const float tc = 2.0f * st.y - 1.0f;
  switch (face) {
    case 0: return {1.0f, -tc, -sc};
    case 1: return {-1.0f, -tc, sc};
    case 2: return {sc, 1.0f, tc};
    case 3: return {sc, -1.0f, -tc};
    case 4: return {sc, -tc, 1.0f};
    case 5: return {-sc, -tc, -1.0f};
    default: fail(ErrorKind::Internal, "cube face {} out of range", face);
  }
}

vec3 cubeTexelDirection(int face, int x, int y, int size) {
  return cubeFaceDirection(face, {(float(x) + 0.5f) / float(size), (float(y) + 0.5f) / float(size)});
}

CubeCoord cubeLookup(vec3 d) {
  const vec3 a = glm::abs(d);
  CubeCoord c;
  float sc = 0, tc = 0, ma = 0;
  if (a.x >= a.y && a.x >= a.z) {
    ma = a.x;
    c.face = d.x >= 0 ? 0 : 1;
    sc = d.x >= 0 ? -d.z : d.z;
    tc = -d.y;
  } else if (a.y >= a.z) {
    ma = a.y;
    c.face = d.y >= 0 ? 2 : 3;
    sc = d.x;
    tc = d.y >= 0 ? d.z : -d.z;
  } else {
    ma = a.z;
    c.face = d.z >= 0 ? 4 : 5;
    sc = d.z >= 0 ? d.x : -d.x;
    tc = -d.y;
  }
  c.st = {0.5f * (sc / ma + 1.0f), 0.5f * (tc / ma + 1.0f)};
  return c;
}

vec2 equirectUv(vec3 d) {
  const vec3 n = glm::normalize(d);
  // atan2(x, −z): 0 along −Z, +π/2 along +X; u = 0.5 there and 0.75 respectively.
  const float u = 0.5f + std::atan2(n.x, -n.z) / (2.0f * kPi);
  const float v = std::acos(std::clamp(n.y, -1.0f, 1.0f)) / kPi;
  return {u - std::floor(u), v};
}

vec3 equirectDirection(vec2 uv) {
  const float phi = (uv.x - 0.5f) * 2.0f * kPi;
  const float theta = uv.y * kPi;
  return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

vec3 sampleEquirect(const Image& img, vec3 direction) {
  const vec2 uv = equirectUv(direction);
  const int w = img.width(), h = img.height();
  // Texel centres sit at half-integers, as in GL's bilinear filter.
  const float fx = uv.x * float(w) - 0.5f;
  const float fy = uv.y * float(h) - 0.5f;
  const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
  const float ax = fx - float(x0), ay = fy - float(y0);
  auto texel = [&](int x, int y) {
    x = ((x % w) + w) % w;           // GL_REPEAT around the horizon
    y = std::clamp(y, 0, h - 1);     // GL_CLAMP_TO_EDGE at the poles
    return vec3(img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2));
  };
  const vec3 top = glm::mix(texel(x0, y0), texel(x0 + 1, y0), ax);
  const vec3 bottom = glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), ax);
  return glm::mix(top, bottom, ay);
}

vec3 displayEncode(vec3 radiance, float exposure) {
  // Keep in step with displayEncode() in shaders/env/envmap.glsl.
  const vec3 x = glm::max(radiance * exposure, vec3(0.0f));
  const vec3 mapped = glm::clamp((x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
  return {srgbEncode(mapped.r), srgbEncode(mapped.g), srgbEncode(mapped.b)};
}

Image perspectiveView(const Image& equirect, ivec2 size, float yaw, float pitch, float fovY, float exposure) {
  Image out(size.x, size.y, 4, PixelType::U8);
  // Camera basis: forward along yaw/pitch, right-handed, +Y up.
  const vec3 forward(-std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch));
  const vec3 right = glm::normalize(glm::cross(forward, vec3(0.0f, 1.0f, 0.0f)));
  const vec3 up = glm::cross(right, forward);
  const float tanHalf = std::tan(glm::radians(fovY) * 0.5f);
  const float aspect = float(size.x) / float(size.y);
  for (int y = 0; y < size.y; ++y) {
    for (int x = 0; x < size.x; ++x) {
      vec3 sum(0.0f);
      for (int sy = 0; sy < 2; ++sy) {
        for (int sx = 0; sx < 2; ++sx) {
          const float px = (2.0f * (float(x) + 0.25f + 0.5f * float(sx)) / float(size.x) - 1.0f) * tanHalf * aspect;
          const float py = (1.0f - 2.0f * (float(y) + 0.25f + 0.5f * float(sy)) / float(size.y)) * tanHalf;
          sum += sampleEquirect(equirect, forward + px * right + py * up);
        }
      }
      const vec3 c = displayEncode(sum * 0.25f, exposure);
      for (int k = 0; k < 3; ++k) out.set(x, y, k, c[k]);
      out.set(x, y, 3, 1.0f);
    }
  }
  return out;
}

vec2 sphereMapUv(vec3 r) {
  r = glm::normalize(r);
  const float m = 2.0f * std::sqrt(r.x * r.x + r.y * r.y + (r.z + 1.0f) * (r.z + 1.0f));
  if (m < 1e-6f) return {1.0f, 0.5f};
  return {r.x / m + 0.5f, r.y / m + 0.5f};
}

vec3 sphereMapDirection(vec2 st, bool* inside) {
  const float x = 2.0f * st.x - 1.0f;
  const float y = 2.0f * st.y - 1.0f;
  const float rr = x * x + y * y;
  if (inside) *inside = rr <= 1.0f;
  if (rr > 1.0f) return {0.0f, 0.0f, -1.0f};
  // The ball's normal there, and the viewing ray (0, 0, −1) reflected off it.
  const vec3 n{x, y, std::sqrt(1.0f - rr)};
  return glm::reflect(vec3(0.0f, 0.0f, -1.0f), n);
}

SphereMapCoverage sphereMapCoverage(int size) {
  if (size <= 0) fail(ErrorKind::Usage, "sphere map size must be positive, got {}", size);
  SphereMapCoverage c;
  c.size = size;
  std::size_t wasted = 0, front = 0, back = 0;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      bool inside = false;
      const vec3 r = sphereMapDirection({(float(x) + 0.5f) / float(size), (float(y) + 0.5f) / float(size)}, &inside);
      if (!inside) ++wasted;
      else if (r.z >= 0.0f) ++front;
      else ++back;
    }
  }
  const double n = double(size) * double(size);
  c.wastedFraction = double(wasted) / n;
  c.frontFraction = double(front) / n;
  c.backFraction = double(back) / n;
  return c;
}

AngularResolution sphereMapResolution(int size, double theta) {
  // Radius in the disk ρ = sin(θ/2) (disk radius = size/2 texels).
  //   radial:     d(ρ·size/2)/dθ            = size·cos(θ/2)/4
  //   tangential: (ρ·size/2) / sin θ        = size/(4·cos(θ/2))  (circle of radius sin θ)
  const double c = std::cos(theta / 2.0);
  return {double(size) * c / 4.0, c > 1e-12 ? double(size) / (4.0 * c) : INFINITY};
}

double cubeMapResolution(int faceSize) {
  // At a face centre s moves by 1/2 per unit of tan(angle) and d tan/dθ = 1 there.
  return double(faceSize) / 2.0;
}

double equivalentCubeFaceSize(int sphereMapSize, double maxTheta) {
  // Radial resolution is the smaller one and falls with θ: the worst is at maxTheta.
  return 2.0 * sphereMapResolution(sphereMapSize, maxTheta).minimum();
}

void validateEquirect(const Image& image, const std::string& name) {
  if (image.channels() < 3) {
    fail(ErrorKind::Input, "environment '{}' has {} channel(s); an RGB(A) image is needed", name, image.channels());
  }
  if (image.width() != 2 * image.height()) {
    fail(ErrorKind::Input, "environment '{}' is {}x{}; an equirectangular image is twice as wide as high", name,
         image.width(), image.height());
  }
  if (image.type() == PixelType::F32) {
    for (float v : image.pixels<float>()) {
      if (!std::isfinite(v)) fail(ErrorKind::Input, "environment '{}' contains NaN or infinite values", name);
    }
  }
}

void validateCubeFaces(std::span<const Image> faces, std::span<const std::string> names) {
  auto nameOf = [&](std::size_t i) {
    return i < names.size() ? names[i] : std::string("face ") + cubeFaceName(int(i));
  };
  if (faces.size() != std::size_t(kCubeFaces)) {
    fail(ErrorKind::Input, "a cube map needs 6 face images (+X -X +Y -Y +Z -Z), got {}", faces.size());
  }
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const Image& f = faces[i];
    if (f.width() != f.height()) {
      fail(ErrorKind::Input, "cube face {} '{}' is {}x{}; cube map faces must be square", cubeFaceName(int(i)),
           nameOf(i), f.width(), f.height());
    }
    if (f.width() != faces[0].width()) {
      fail(ErrorKind::Input, "cube face {} '{}' is {}x{} but face +X '{}' is {}x{}; all six faces must be equal",
           cubeFaceName(int(i)), nameOf(i), f.width(), f.height(), nameOf(0), faces[0].width(), faces[0].height());
    }
    if (f.channels() < 3) {
      fail(ErrorKind::Input, "cube face {} '{}' has {} channel(s); RGB(A) faces are needed", cubeFaceName(int(i)),
           nameOf(i), f.channels());
    }
  }
}

}  // namespace glint

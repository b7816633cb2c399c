#include "glint/render/filtering/filtering.h"

#include "glint/core/error.h"
#include "glint/core/hash.h"
#include "glint/gl/context.h"
#include "glint/gl/render_target.h"
#include "glint/image/metrics.h"
#include "glint/render/state.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

namespace glint::render::filtering {
namespace {

constexpr float kEyeHeight = 1.0f;
constexpr float kPitchDegrees = 10.0f;  // looking down: the horizon sits a third from the top
constexpr float kFovY = 60.0f;
// The textured plane reaches 40 units ahead; beyond, a flat band in the texture's mean
// colour continues to the horizon. Textured geometry must stop a couple of pixels short
// of the vanishing line: there the 2×2 quads' helper pixels see texture coordinates and
// derivatives without bound, and llvmpipe's anisotropic filter, which sizes its sample
// loop from them, runs for minutes at some image heights (e.g. 180).
constexpr float kPlaneExtent = 80.0f;   // ±40 units around the camera
constexpr float kBandStart = 39.5f;     // overlaps the plane by half a unit, under it
constexpr float kBandEnd = 2000.0f;
const vec3 kSky{0.62f, 0.72f, 0.86f};

const FilterMode kModes[] = {
    {"nearest", GL_NEAREST, GL_NEAREST, 1.0f, 0.0f, "GL_NEAREST, no mipmaps: one texel per pixel, blocky up close, noise far away"},
    {"bilinear", GL_LINEAR, GL_LINEAR, 1.0f, 0.0f, "GL_LINEAR without mipmaps: smooth up close, sparkles far away as the camera moves"},
    {"bilinear-mip-nearest", GL_LINEAR_MIPMAP_NEAREST, GL_LINEAR, 1.0f, 0.0f, "GL_LINEAR_MIPMAP_NEAREST: mipmaps stop the sparkle; visible bands where the level switches"},
    {"trilinear", GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, 1.0f, 0.0f, "GL_LINEAR_MIPMAP_LINEAR: smooth, but blurred where the plane is oblique (the WWDC 2001 talk: \"the texture becomes blurred\")"},
    {"aniso2", GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, 2.0f, 0.0f, "trilinear + GL_TEXTURE_MAX_ANISOTROPY 2"},
    {"aniso4", GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, 4.0f, 0.0f, "trilinear + anisotropy 4"},
    {"aniso8", GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, 8.0f, 0.0f, "trilinear + anisotropy 8"},
    {"aniso16", GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, 16.0f, 0.0f, "trilinear + anisotropy 16: sharp even at oblique angles, closest to the truth"},
    {"lod-bias", GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR, 1.0f, -1.0f, "trilinear with GL_TEXTURE_LOD_BIAS −1: sharper than trilinear, but the sparkle comes back"},
};

// Truth frames are expensive (size × 256 samples each): kept per content and options.
std::map<std::string, std::vector<Image>>& truthCache() {
  static std::map<std::string, std::vector<Image>> cache;
  return cache;
}

Image renderFrame(const GroundPlane& ground, const FilterMode& mode, ivec2 size, float forward) {
  gl::RenderTarget target(size, GL_RGBA8, "filtering-measure");
  target.target().bind();
  ground.draw(GroundPlane::camera(size, forward), mode);
  return gl::readColor(target.framebuffer(), size);
}
}  // namespace

std::span<const FilterMode> standardModes() { return kModes; }

float maxAnisotropy() { return gl::queryContextInfo().maxAnisotropy; }

void applyFilterMode(const gl::Sampler& sampler, const FilterMode& mode) {
  const float maximum = maxAnisotropy();
  if (!(mode.anisotropy >= 1.0f) || mode.anisotropy > maximum) {
    fail(ErrorKind::Usage, "anisotropy {} is not supported: GL_MAX_TEXTURE_MAX_ANISOTROPY is {} here (use 1 to {})",
         mode.anisotropy, maximum, maximum);
  }
  sampler.parameter(GL_TEXTURE_MIN_FILTER, GLint(mode.minFilter));
  sampler.parameter(GL_TEXTURE_MAG_FILTER, GLint(mode.magFilter));
  sampler.parameter(GL_TEXTURE_WRAP_S, GLint(GL_REPEAT));
  sampler.parameter(GL_TEXTURE_WRAP_T, GLint(GL_REPEAT));
  sampler.parameter(GL_TEXTURE_LOD_BIAS, mode.lodBias);
  if (maximum > 1.0f) sampler.parameter(GL_TEXTURE_MAX_ANISOTROPY, mode.anisotropy);
}

FilterMode clampedToDevice(FilterMode mode) {
  mode.anisotropy = std::min(mode.anisotropy, maxAnisotropy());
  return mode;
}

GroundPlane::GroundPlane(const Image& texture, float tileSize, std::string_view label)
    : m_sampler(gl::Sampler::create(std::string(label) + "-sampler")),
      m_program(gl::Program::fromFiles({"filtering/ground.vert", "filtering/ground.frag"})),
      m_plane(makePlane(kPlaneExtent, kPlaneExtent / tileSize), {}, std::string(label) + "-plane"),
      m_tileSize(tileSize) {
  Mesh band = makePlane(1.0f);
  band.transform(glm::translate(mat4(1.0f), {0.0f, -0.001f, -0.5f * (kBandStart + kBandEnd)}) *
                 glm::scale(mat4(1.0f), {4.0f * kBandEnd, 1.0f, kBandEnd - kBandStart}));
  m_band = GpuMesh(band, {}, std::string(label) + "-distant-band");
  // Image row 0 is the top; GL's t = 0 is the bottom row (mesh UVs have v up).
  Image rgba = texture.converted(PixelType::U8).withChannels(4);
  rgba.flipVertical();
  m_texture = gl::Texture(GL_TEXTURE_2D, label);
  m_texture.storage(GL_RGBA8, rgba.width(), rgba.height(), 1, 0);
  m_texture.upload(0, rgba.width(), rgba.height(), GL_RGBA, GL_UNSIGNED_BYTE, rgba.bytes().data());
  m_texture.generateMipmap();
  m_key = fmt::format("{:016x}-{}", fnv1a(rgba.bytes()), tileSize);
  vec3 sum(0.0f);
  for (int y = 0; y < rgba.height(); ++y)
    for (int x = 0; x < rgba.width(); ++x) sum += vec3(rgba.at(x, y, 0), rgba.at(x, y, 1), rgba.at(x, y, 2));
  m_meanColor = sum / float(rgba.pixelCount());
}

Camera GroundPlane::camera(ivec2 size, float forward) {
  const float pitch = glm::radians(kPitchDegrees);
  const vec3 eye{0.0f, kEyeHeight, -forward};
  return Camera::lookAt(eye, eye + vec3(0.0f, -std::sin(pitch), -std::cos(pitch)), {0.0f, 1.0f, 0.0f}, kFovY,
                        float(size.x) / float(size.y), 0.05f, 500.0f);
}

float GroundPlane::horizonRow(ivec2 size) {
  // A horizontal direction sits kPitch above the view axis: NDC y = tan(pitch)/tan(fov/2).
  const float ndcY = std::tan(glm::radians(kPitchDegrees)) / std::tan(glm::radians(kFovY / 2.0f));
  return 0.5f * (1.0f - ndcY) * float(size.y);
}

void GroundPlane::draw(const Camera& camera, const FilterMode& mode) const {
  applyFilterMode(m_sampler, mode);
  PipelineState{.depthTest = true}.apply();
  render::clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT, vec4(kSky.r, kSky.g, kSky.b, 1.0f));
  m_program.set("uViewProj", camera.viewProjection());
  m_program.set("uMeanColor", m_meanColor);
  // Whole tiles behind the camera's position: the plane moves with it, the texture does not.
  m_program.set("uOffsetZ", m_tileSize * std::round(camera.position.z / m_tileSize));
  m_texture.bind(0);
  m_sampler.bind(0);
  m_program.use();
  m_program.set("uFlat", true);
  m_band.draw();
  m_program.set("uFlat", false);
  m_plane.draw();
  gl::Sampler::unbind(0);
  glBindTextureUnit(0, 0);
}

FilterQuality measureFiltering(const GroundPlane& ground, const FilterMode& mode, const MeasureOptions& o) {
  if (o.frames < 2 || o.supersample < 1) fail(ErrorKind::Usage, "filter measurement needs 2+ frames and supersample ≥ 1");
  const SavedTarget saved;
  const std::string key = fmt::format("{}-{}x{}-{}-{}-{}", ground.contentKey(), o.size.x, o.size.y, o.supersample, o.frames, o.step);
  std::vector<Image>& truth = truthCache()[key];
  if (truth.empty()) {
    // The truth: the continuous (bilinearly reconstructed) texture from level 0, point
    // sampled supersample² times per pixel and box filtered.
    const FilterMode reference{"truth", GL_LINEAR, GL_LINEAR};
    for (int f = 0; f < o.frames; ++f) {
      truth.push_back(boxDownsample(renderFrame(ground, reference, o.size * o.supersample, o.step * float(f)), o.supersample));
    }
  }
  std::vector<Image> frames;
  for (int f = 0; f < o.frames; ++f) frames.push_back(renderFrame(ground, mode, o.size, o.step * float(f)));

  // The ground starts a few rows below the horizon (where even the truth is converged);
  // the oblique band is its far half.
  const int top = int(std::ceil(GroundPlane::horizonRow(o.size))) + 3;
  const Region groundRegion{0, top, o.size.x, o.size.y};
  const Region oblique{0, top, o.size.x, top + (o.size.y - top) / 2};
  FilterQuality q;
  q.rmsError = rmsError(frames[0], truth[0], groundRegion);
  q.sharpness = sharpness(frames[0], oblique);
  q.truthSharpness = sharpness(truth[0], oblique);
  q.flicker = temporalFlicker(frames, truth, groundRegion);
  return q;
}

}  // namespace glint::render::filtering

// The pipedream frame on a headless context, checked against its own buffers and against
// independent computations:
//   - the dim factor: after the quads every pixel is its scene-pass colour times
//     1 − Σ (weights of the lights whose volumes cover it); pixels no light reaches are
//     left exactly as they were (no double darkening), and a pixel in one light's dynamic
//     shadow is WWDC 2003 session 212's "dest colour × dest alpha";
//   - translucent balls leave destination alpha alone;
//   - culling by light range changes no pixel (the shadows it skips fall where the light
//     is already zero);
//   - WWDC 2003 session 212's method against the naive method (full-scene volumes, no cut): the same
//     picture away from shadow edges;
//   - the oracle: Embree rays from each visible pixel's surface point to each light,
//     against static and dynamic occluders, decide lit or shadowed; the frame's own
//     classification (the cut's mask through the light weights, the light's stencil count)
//     agrees for ≥ 99.5% of (pixel, light) pairs outside a 2-pixel band at shadow edges
//     (the method of tests/shadows/oracle_test.cpp);
//   - the ball's vertex shader against stretchVertex (transform feedback).
// A small stage (detail 1: ~11k input triangles, ~80k cut) keeps it quick on llvmpipe; the
// cut is cached in the build tree like the scene's.
#include "support/classified.h"
#include "support/depth_rays.h"
#include "support/gl_test.h"

#include "glint/gl/render_target.h"
#include "glint/image/srgb.h"
#include "glint/raytrace/raytracer.h"
#include "glint/render/state.h"
#include "glint/scenes/pipedream.h"
#include "glint/scenes/scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

using namespace glint;
using glint::testing::GlTest;
namespace rp = glint::render::pipedream;
namespace pd = glint::scenes::pipedream;

namespace {

constexpr ivec2 kSize{320, 180};
constexpr int kBand = 2;
constexpr int kDetail = 1;

const pd::Stage& stage() {
  static const auto s = pd::loadStage({.detail = kDetail, .progress = false});
  return *s;
}

rp::Renderer& renderer() {
  static rp::Renderer r(stage().machine, stage().geometry);
  return r;
}

glint::Camera camera(int index) { return pd::namedCamera(index, float(kSize.x) / float(kSize.y)); }

glint::pipedream::MachinePose poseAt(double time) { return glint::pipedream::poseAt(stage().machine, stage().score, time); }

Image readFloat(const gl::Texture& texture) { return gl::readTexture(texture, 0, 0, 4, PixelType::F32); }

/// The colour buffer in linear light: its texels as stored (sRGB-encoded RGB, read back
/// without decoding), decoded; alpha (the dim factor) is linear already.
Image readLinear(const gl::Texture& color) {
  Image image = readFloat(color);
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x)
      for (int c = 0; c < 3; ++c) image.set(x, y, c, srgbDecode(image.at(x, y, c)));
  return image;
}

/// How far apart two linear values are in 8-bit sRGB steps (the colour buffer's and the
/// output's own unit).
float srgbSteps(float a, float b) { return 255.0f * std::abs(srgbEncode(a) - srgbEncode(b)); }

/// One Full frame step by step: the scene pass's colour and weights, which lights' volumes
/// cover each pixel (bit k: light k's stencil count was not zero), the final colour, depth.
struct Steps {
  Image opaque, scene, weights, final, depth;
  std::vector<std::uint8_t> covered;
};

Steps renderSteps(const glint::pipedream::MachinePose& pose, const glint::Camera& cam) {
  rp::Renderer& r = renderer();
  r.prepare(pose, cam, kSize, rp::Mode::Full);
  r.drawScene();
  Steps s;
  s.opaque = readLinear(r.colorTexture());
  r.drawTranslucent();
  s.scene = readLinear(r.colorTexture());
  s.weights = readFloat(r.weightsTexture());
  s.depth = gl::readDepth(r.sceneFramebuffer(), kSize);
  s.covered.assign(std::size_t(kSize.x * kSize.y), 0);
  const GLuint countMask = r.stencilLayout().countMask();
  std::uint32_t done = 0;
  for (int light = 0; light < r.lights(); ++light) {
    if (!r.countVolumes(light)) continue;
    const Image stencil = gl::readStencil(r.compositeFramebuffer(), kSize);
    const auto px = stencil.pixels<std::uint8_t>();
    for (std::size_t i = 0; i < px.size(); ++i)
      if (px[i] & countMask) s.covered[i] |= std::uint8_t(1u << light);
    r.compositeLight(light, done);
    done |= 1u << light;
  }
  s.final = readLinear(r.colorTexture());
  return s;
}

// ------------------------------------------------------------------ the oracle

enum class Truth : std::uint8_t {
  Excluded,  ///< no verdict: a silhouette, a grazing or terminator surface, the end of the range
  Dark,      ///< the light gives nothing here in any method: beyond its range, or the shading normal faces away
  Lit,
  Shadowed
};

/// Per light, per pixel (row 0 = top): lit or shadowed by the ray tracer, or excluded.
class Oracle {
public:
  explicit Oracle(const glint::pipedream::MachinePose& pose) {
    const InstrumentMachine& m = stage().machine;
    m_meshes.push_back(m.staticMesh);
    const auto place = [&](const Mesh& part, const mat4& model) {
      Mesh w = part;
      w.uvs.clear();
      w.tangents.clear();
      w.transform(model);
      m_meshes.push_back(std::move(w));
    };
    for (const mat4& t : pose.skins) place(m.skin, t);
    for (const mat4& t : pose.cymbals) place(m.cymbal, t);
    for (const mat4& t : pose.mallets) place(m.mallet, t);
    // The balls cast what the renderer's volumes cast: an icosphere of the ball's radius.
    Mesh ball = makeIcosphere(1.0f, 2);
    for (const glint::pipedream::BallState& b : pose.balls)
      place(ball, glm::scale(glm::translate(mat4(1.0f), b.position), vec3(m.ballRadius)));
    for (Mesh& mesh : m_meshes)
      if (mesh.normals.empty()) computeNormals(mesh);
    m_all.emplace(std::span<const Mesh>(m_meshes), raytrace::SceneOptions{.robust = true});
    m_static.emplace(m.staticMesh, raytrace::SceneOptions{.robust = true});
    m_size = m.staticMesh.bounds().diagonal();
  }

  /// `truth[light][pixel]`; `dynamicOnly` counts pairs shadowed only because of a dynamic
  /// occluder (the static scene alone would leave them lit).
  /// `surface` (when given): pixels whose depth is the surface the pixel-centre ray hits
  /// (not a silhouette, not behind a translucent ball).
  std::vector<std::vector<Truth>> classify(const Image& depth, const glint::Camera& cam, std::size_t& dynamicOnly,
                                           std::vector<bool>* surface = nullptr) const {
    const InstrumentMachine& m = stage().machine;
    const int w = depth.width(), h = depth.height();
    const glint::testing::DepthSamples samples = glint::testing::depthSamples(depth, cam.viewProjection(), cam.position);
    const std::vector<vec3>& positions = samples.positions;
    const std::vector<std::size_t>& where = samples.pixels;
    const std::vector<raytrace::Ray>& primary = samples.primary;
    const auto hits = m_all->intersectBatch(primary);
    std::vector<std::vector<Truth>> truth(m.lights.size(), std::vector<Truth>(std::size_t(w * h), Truth::Excluded));
    if (surface) {
      surface->assign(std::size_t(w * h), false);
      for (std::size_t i = 0; i < hits.size(); ++i)
        (*surface)[where[i]] = hits[i] && std::abs(hits[i]->t - 1.0f) <= 0.01f;
    }
    for (std::size_t light = 0; light < m.lights.size(); ++light) {
      const MachineLight& l = m.lights[light];
      std::vector<raytrace::Ray> shadow;
      std::vector<std::size_t> of;
      for (std::size_t i = 0; i < hits.size(); ++i) {
        const auto& hit = hits[i];
        if (!hit || std::abs(hit->t - 1.0f) > 0.01f) continue;  // silhouette, or a translucent ball in front
        const Mesh& mesh = m_meshes[hit->mesh];
        vec3 n = hit->geometricNormal;
        if (glm::dot(n, primary[i].direction) > 0.0f) n = -n;  // the side the camera sees
        const vec3 p = positions[i], toLight = l.position - p;
        const vec3 dir = glm::normalize(toLight);
        // Light that reaches no surface is no test: facing away (the geometric or the
        // shading normal), or beyond the light's range (its term is zero there).
        const vec3 shading = glm::normalize(raytrace::interpolate(*hit, std::span<const vec3>(mesh.normals),
                                                                  std::span<const std::uint32_t>(mesh.indices)));
        const float distance = glm::length(toLight), facing = glm::dot(shading, dir);
        if (distance >= l.range || facing <= -0.02f) {
          truth[light][where[i]] = Truth::Dark;
          continue;
        }
        if (glm::dot(n, dir) <= 0.02f || facing <= 0.02f || distance > 0.95f * l.range) continue;
        const vec3 origin = p + n * (1e-4f * m_size);
        shadow.push_back({.origin = origin, .direction = l.position - origin, .tnear = 0.0f, .tfar = 1.0f});
        of.push_back(where[i]);
      }
      const auto blocked = m_all->occludedBatch(shadow);
      const auto blockedStatic = m_static->occludedBatch(shadow);
      for (std::size_t i = 0; i < blocked.size(); ++i) {
        truth[light][of[i]] = blocked[i] ? Truth::Shadowed : Truth::Lit;
        dynamicOnly += blocked[i] && !blockedStatic[i];
      }
    }
    return truth;
  }

private:
  std::vector<Mesh> m_meshes;
  std::optional<raytrace::Scene> m_all, m_static;
  float m_size = 1.0f;
};

/// Classified and not within kBand pixels of a pixel classified the other way.
std::vector<bool> awayFromEdges(const std::vector<Truth>& truth, int w, int h) {
  return glint::testing::awayFromEdges(truth, w, h, kBand, [](Truth t) { return t == Truth::Lit || t == Truth::Shadowed; });
}

struct View {
  double time;
  int camera;
};
// Several times and WWDC 2003 session 212's camera moves: the whole stage, the drum machine from above,
// across the machine from the side.
const View kViews[] = {{2.1, 0}, {6.35, 1}, {9.8, 3}};

}  // namespace

TEST_F(GlTest, PipeDreamShadowsAgreeWithTheRayTracer) {
  std::size_t compared = 0, agree = 0, shadowed = 0, dynamicOnly = 0;
  for (const View& v : kViews) {
    const glint::pipedream::MachinePose pose = poseAt(v.time);
    const glint::Camera cam = camera(v.camera);
    const Steps s = renderSteps(pose, cam);
    std::size_t dyn = 0;
    // The renderer's camera has the infinite far plane its depth buffer was drawn with.
    const auto truth = Oracle(pose).classify(s.depth, renderer().camera(), dyn);
    std::size_t c = 0, a = 0;
    for (std::size_t light = 0; light < truth.size(); ++light) {
      const std::vector<bool> use = awayFromEdges(truth[light], kSize.x, kSize.y);
      for (int y = 0; y < kSize.y; ++y)
        for (int x = 0; x < kSize.x; ++x) {
          const std::size_t i = std::size_t(y * kSize.x + x);
          if (!use[i]) continue;
          // The frame's verdict: the cut says the light reaches the piece (its weight is
          // not zero) and no dynamic volume of this light covers the pixel.
          const bool lit = s.weights.at(x, y, int(light)) > 0.0f && !(s.covered[i] & (1u << light));
          const bool truthShadowed = truth[light][i] == Truth::Shadowed;
          ++c;
          a += lit != truthShadowed;
          shadowed += truthShadowed;
        }
    }
    compared += c;
    agree += a;
    dynamicOnly += dyn;
    const double agreement = c ? double(a) / double(c) : 0.0;
    std::printf("[ oracle   ] t = %.2f, camera %s: %zu of %zu (pixel, light) pairs agree (%.3f%%)\n", v.time,
                pd::namedCameras()[std::size_t(v.camera)].name, a, c, 100.0 * agreement);
    EXPECT_GE(agreement, 0.995) << "t = " << v.time;
    EXPECT_GT(c, std::size_t(kSize.x * kSize.y / 3)) << "too few pairs compared";
  }
  std::printf("[ oracle   ] all: %zu of %zu agree (%.3f%%), %zu shadowed, %zu shadowed by a dynamic occluder only\n",
              agree, compared, 100.0 * double(agree) / double(compared), shadowed, dynamicOnly);
  EXPECT_GT(shadowed, compared / 10) << "too little static shadow to test anything";
  EXPECT_GT(dynamicOnly, 300u) << "too little dynamic shadow to test anything";
}

TEST_F(GlTest, PipeDreamDimFactorNeverDarkensTwice) {
  std::size_t untouched = 0, singles = 0, multiples = 0, clipped = 0;
  float brightest = 0.0f;
  for (const View& v : kViews) {
    const Steps s = renderSteps(poseAt(v.time), camera(v.camera));
    for (int y = 0; y < kSize.y; ++y)
      for (int x = 0; x < kSize.x; ++x) {
        const std::uint8_t covered = s.covered[std::size_t(y * kSize.x + x)];
        float removed = 0.0f, any = 0.0f;
        for (int k = 0; k < renderer().lights(); ++k) {  // one channel per light (RG8 for two)
          any += s.weights.at(x, y, k);
          if (covered & (1u << k)) removed += s.weights.at(x, y, k);
        }
        for (int c = 0; c < 3; ++c) {
          const float before = s.scene.at(x, y, c), after = s.final.at(x, y, c);
          // The 8-bit colour buffer holds 0..1: a lit pixel at 1 may have been clipped, and a
          // shadow would dim the clipped value. None is.
          if (any > 0.0f) {
            brightest = std::max(brightest, before);
            clipped += before >= 1.0f;
          }
          if (any == 0.0f) {
            // No light reaches (every light's baked shadow, or facing away): exactly as drawn.
            ASSERT_EQ(after, before) << x << "," << y << " t = " << v.time;
          } else {
            // Colour × the factors of the lights that left: 1 − Σ of their weights. Within
            // 1.5 steps of 8-bit sRGB: the product is rounded once into the buffer (half a
            // step), and the factor and weights are 8-bit (half of 1/255 each).
            ASSERT_LE(srgbSteps(after, before * (1.0f - removed)), 1.5f)
                << x << "," << y << " t = " << v.time << ": " << after << " against " << before * (1.0f - removed);
          }
        }
        if (covered && any == 0.0f) ++untouched;
        // One light's shadow: WWDC 2003 session 212's quad, dest colour × dest alpha.
        if (covered == 1u && s.weights.at(x, y, 0) > 0.05f) {
          ++singles;
          // One rounding into the buffer (half a step) by the GL's own sRGB encoding, which
          // need not be exact (llvmpipe's: up to 0.6 of a step): within one step.
          for (int c = 0; c < 3; ++c)
            ASSERT_LE(srgbSteps(s.final.at(x, y, c), s.scene.at(x, y, c) * s.scene.at(x, y, 3)), 1.0f);
        }
        if (std::popcount(unsigned(covered)) > 1 && removed > 0.05f) ++multiples;
      }
  }
  std::printf("[ dim      ] %zu pixels in a dynamic shadow that no light reached (left alone), %zu in one light's "
              "shadow, %zu in both\n",
              untouched, singles, multiples);
  std::printf("[ dim      ] brightest lit pixel before the quads: %.3f of the colour buffer's top (linear light %.3f; "
              "colour scale 1/%.3f)\n",
              brightest, brightest / renderer().colorScale(), 1.0f / renderer().colorScale());
  EXPECT_EQ(clipped, 0u) << "lit pixels at the colour buffer's top: a shadow would dim a clipped value";
  EXPECT_GT(untouched, 200u) << "no dynamic shadow fell on baked shadow: the test shows nothing";
  EXPECT_GT(singles, 200u);
}

TEST_F(GlTest, PipeDreamTranslucentBallsLeaveDestinationAlpha) {
  rp::Renderer& r = renderer();
  std::size_t changed = 0;
  for (const double t : {3.0, 6.35, 10.4}) {
    r.prepare(poseAt(t), camera(4), kSize, rp::Mode::Full);
    r.drawScene();
    const Image before = readFloat(r.colorTexture());
    r.drawTranslucent();
    const Image after = readFloat(r.colorTexture());
    for (int y = 0; y < kSize.y; ++y)
      for (int x = 0; x < kSize.x; ++x) {
        ASSERT_EQ(after.at(x, y, 3), before.at(x, y, 3)) << x << "," << y;
        changed += after.at(x, y, 0) != before.at(x, y, 0);
      }
  }
  EXPECT_GT(changed, 100u) << "no ball was drawn";
}

TEST_F(GlTest, PipeDreamRangeCullingChangesNoPixel) {
  rp::Renderer& r = renderer();
  gl::RenderTarget target(kSize);
  std::size_t culled = 0;
  for (const View& v : kViews) {
    const glint::pipedream::MachinePose pose = poseAt(v.time);
    r.options().cullVolumes = true;
    r.render(pose, camera(v.camera), target.target(), rp::Mode::Full);
    culled += r.stats().castersCulled;
    const Image with = readFloat(r.colorTexture());
    r.options().cullVolumes = false;
    r.render(pose, camera(v.camera), target.target(), rp::Mode::Full);
    EXPECT_EQ(r.stats().castersCulled, 0u);
    const Image without = readFloat(r.colorTexture());
    r.options().cullVolumes = true;
    std::size_t differ = 0;
    for (int y = 0; y < kSize.y; ++y)
      for (int x = 0; x < kSize.x; ++x)
        for (int c = 0; c < 3; ++c) differ += std::abs(with.at(x, y, c) - without.at(x, y, c)) > 1e-6f;
    EXPECT_EQ(differ, 0u) << "t = " << v.time;
  }
  EXPECT_GT(culled, 0u) << "nothing was out of range: the test shows nothing";
}

TEST_F(GlTest, PipeDreamBoundedVolumesMatchVolumesToInfinity) {
  // Volumes that end just past the box of the room and the eye count what volumes to
  // infinity count at every visible surface: the same picture, both methods, from the
  // named cameras and from far outside the room, with less fill. Tolerance: isolated
  // single pixels, at most 8 a frame (0.014 %) — rounding at the infinite volumes' far
  // ends, whose vertices sit at w = 0 (from the stage camera, outside the room's box, two
  // pixels of Full and four of Naive differ at this size; there the ray tracer sides with
  // the bounded volumes: PipeDreamShadowsAgreeWithTheRayTracer counts one more agreeing
  // pair with them than without). A shadow moved or lost would differ in runs of pixels.
  rp::Renderer& r = renderer();
  gl::RenderTarget target(kSize);
  std::size_t bounded = 0, differing = 0;
  std::uint64_t fillBounded = 0, fillInfinite = 0;
  const glint::Camera outside = glint::Camera::lookAt({-30.0f, 40.0f, 60.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f},
                                                        30.0f, float(kSize.x) / float(kSize.y));
  std::vector<std::pair<double, glint::Camera>> views;
  for (const View& v : kViews) views.emplace_back(v.time, camera(v.camera));
  views.emplace_back(kViews[0].time, outside);
  for (const auto& [time, cam] : views)
    for (const rp::Mode mode : {rp::Mode::Full, rp::Mode::Naive}) {
      const glint::pipedream::MachinePose pose = poseAt(time);
      r.options().boundVolumes = true;
      r.render(pose, cam, target.target(), mode);
      bounded += r.stats().castersBounded;
      if (mode == rp::Mode::Full) fillBounded += r.measureVolumeFill();
      const Image with = readFloat(r.colorTexture());
      r.options().boundVolumes = false;
      r.render(pose, cam, target.target(), mode);
      EXPECT_EQ(r.stats().castersBounded, 0u);
      if (mode == rp::Mode::Full) fillInfinite += r.measureVolumeFill();
      const Image without = readFloat(r.colorTexture());
      r.options().boundVolumes = true;
      // Colour only: after the composite, alpha is scratch (a later light's dim factor where
      // its passes ran, inside the rectangle of its volumes, which bounded volumes shrink).
      const auto differs = [&](int x, int y) {
        if (x < 0 || y < 0 || x >= kSize.x || y >= kSize.y) return false;
        for (int c = 0; c < 3; ++c)
          if (with.at(x, y, c) != without.at(x, y, c)) return true;
        return false;
      };
      std::size_t differ = 0, clustered = 0;
      for (int y = 0; y < kSize.y; ++y)
        for (int x = 0; x < kSize.x; ++x) {
          if (!differs(x, y)) continue;
          ++differ;
          clustered += differs(x + 1, y) || differs(x - 1, y) || differs(x, y + 1) || differs(x, y - 1);
        }
      const std::string where = fmt::format("t = {}, eye ({}, {}, {}), mode {}", time, cam.position.x, cam.position.y,
                                            cam.position.z, int(mode));
      EXPECT_LE(differ, 8u) << where;
      EXPECT_EQ(clustered, 0u) << where;
      differing += differ;
    }
  EXPECT_GT(bounded, 0u) << "no volume was bounded: the test shows nothing";
  EXPECT_LT(fillBounded, fillInfinite);
  std::printf("[ bounded  ] %zu volumes bounded; stencil fragments %llu against %llu to infinity; %zu isolated pixels "
              "differ in %zu frames\n",
              bounded, static_cast<unsigned long long>(fillBounded), static_cast<unsigned long long>(fillInfinite),
              differing, 2 * views.size());
}

TEST_F(GlTest, PipeDreamClustersChangeNoPixel) {
  // The static scene drawn in clusters (outside the view culled, the rest nearest first)
  // against one draw per light mask in the cut's order: the same picture, every mode that
  // draws the static scene, the naive method's uncut scene included.
  rp::Renderer& clustered = renderer();
  rp::Renderer whole(stage().machine, stage().geometry, {.clusterSize = 0.0f});
  gl::RenderTarget target(kSize);
  std::size_t culled = 0, drawn = 0;
  for (const View& v : kViews)
    for (const rp::Mode mode : {rp::Mode::Full, rp::Mode::Naive}) {
      const glint::pipedream::MachinePose pose = poseAt(v.time);
      clustered.render(pose, camera(v.camera), target.target(), mode);
      culled += clustered.stats().staticCulled;
      drawn += clustered.stats().sceneTriangles;
      const Image a = readFloat(clustered.colorTexture());
      whole.render(pose, camera(v.camera), target.target(), mode);
      EXPECT_EQ(whole.stats().staticCulled, 0u);
      const Image b = readFloat(whole.colorTexture());
      std::size_t differ = 0;
      for (int y = 0; y < kSize.y; ++y)
        for (int x = 0; x < kSize.x; ++x)
          for (int c = 0; c < 4; ++c) differ += a.at(x, y, c) != b.at(x, y, c);
      EXPECT_EQ(differ, 0u) << "t = " << v.time << ", camera " << v.camera << ", mode " << int(mode);
    }
  EXPECT_GT(culled, 0u) << "no cluster was outside a view: the test shows nothing";
  std::printf("[ clusters ] %zu static triangles culled of %zu drawn in %zu frames\n", culled, culled + drawn,
              2 * std::size(kViews));
}

TEST_F(GlTest, PipeDreamMatchesFullSceneVolumes) {
  // The naive method knows nothing of the cut or the dim factor: ambient, then each light
  // added where its stencil (every caster's volume) is zero. The two pictures are the same
  // but at shadow edges (rasterised differently: the naive volumes are pushed back by a
  // polygon offset), silhouettes and terminators (a facet turned just away from a light,
  // whose smooth normal still faces it: the cut leaves it dark, the naive stencil, pushed
  // back, lets it be lit): compared are the pixels where, for every light, the oracle
  // compares (not within 2 pixels of a shadow edge) or the light gives nothing anyway
  // (beyond its range, or turned away from it).
  rp::Renderer& r = renderer();
  gl::RenderTarget target(kSize);
  for (const View& v : kViews) {
    const glint::pipedream::MachinePose pose = poseAt(v.time);
    r.render(pose, camera(v.camera), target.target(), rp::Mode::Full);
    const Image full = readLinear(r.colorTexture());
    std::size_t dyn = 0;
    std::vector<bool> surface;
    const auto truth = Oracle(pose).classify(gl::readDepth(r.sceneFramebuffer(), kSize), r.camera(), dyn, &surface);
    std::vector<bool> compared = surface;
    for (const auto& t : truth) {
      const std::vector<bool> use = awayFromEdges(t, kSize.x, kSize.y);
      for (std::size_t i = 0; i < t.size(); ++i) compared[i] = compared[i] && (use[i] || t[i] == Truth::Dark);
    }
    r.render(pose, camera(v.camera), target.target(), rp::Mode::Naive);
    const Image naive = readLinear(r.colorTexture());
    std::size_t count = 0, same = 0;
    for (int y = 0; y < kSize.y; ++y)
      for (int x = 0; x < kSize.x; ++x) {
        if (!compared[std::size_t(y * kSize.x + x)]) continue;
        bool close = true;
        // Within 2 steps of 8-bit sRGB: each method rounds into the 8-bit buffer (the naive
        // one once a pass), WWDC 2003 session 212's dim factor and weights are 8-bit.
        for (int c = 0; c < 3; ++c) close &= srgbSteps(full.at(x, y, c), naive.at(x, y, c)) <= 2.0f;
        ++count;
        same += close;
      }
    const double fraction = double(same) / double(count);
    std::printf("[ naive    ] t = %.2f: %zu of %zu pixels within 2 steps of the naive method's (%.3f%%)\n", v.time, same,
                count, 100.0 * fraction);
    EXPECT_GE(fraction, 0.995) << "t = " << v.time;
    EXPECT_GT(count, std::size_t(kSize.x * kSize.y / 3));
  }
}

TEST_F(GlTest, PipeDreamEightBitBuffersHalveTheFillAndKeepThePicture) {
  // Issue 37: 8-bit sRGB colour and a byte a light against RGBA16F colour and weights (the
  // layout before). The same fragments, half the renderer's framebuffer bytes; the same
  // picture to the 8-bit output's precision: each pixel within 3 steps (the colour
  // buffer's rounding, scaled by 1/colorScale(), and the 8-bit dim factor and weights:
  // 1.9 steps at most where a bright pixel is dimmed), 0.7 steps on average.
  rp::Renderer& narrow = renderer();
  rp::Renderer wide(stage().machine, stage().geometry, {.floatBuffers = true});
  gl::RenderTarget target(kSize);
  double sum = 0.0;
  int worst = 0;
  std::size_t values = 0;
  for (const View& v : kViews) {
    const glint::pipedream::MachinePose pose = poseAt(v.time);
    narrow.render(pose, camera(v.camera), target.target(), rp::Mode::Full);
    const Image a = gl::readColor(target.framebuffer(), kSize);
    wide.render(pose, camera(v.camera), target.target(), rp::Mode::Full);
    const Image b = gl::readColor(target.framebuffer(), kSize);
    for (int y = 0; y < kSize.y; ++y)
      for (int x = 0; x < kSize.x; ++x)
        for (int c = 0; c < 3; ++c) {
          const int d = int(std::lround(255.0f * std::abs(a.at(x, y, c) - b.at(x, y, c))));
          worst = std::max(worst, d);
          sum += d;
          ++values;
        }
    narrow.render(pose, camera(v.camera), target.target(), rp::Mode::StaticOnly);
    const std::vector<rp::PassFill> fill = narrow.measureStaticFill(target.target());
    wide.render(pose, camera(v.camera), target.target(), rp::Mode::StaticOnly);
    const std::vector<rp::PassFill> fillWide = wide.measureStaticFill(target.target());
    ASSERT_EQ(fill.size(), fillWide.size());
    std::uint64_t bytes = 0, bytesWide = 0;
    for (std::size_t i = 0; i < fill.size(); ++i) {
      EXPECT_EQ(fill[i].pass, fillWide[i].pass);
      EXPECT_EQ(fill[i].fragments, fillWide[i].fragments) << fill[i].pass;
      if (fill[i].pass == "present") continue;
      bytes += fill[i].bytes();
      bytesWide += fillWide[i].bytes();
    }
    EXPECT_GT(fill[1].fragments, std::uint64_t(kSize.x * kSize.y / 2)) << "the scene pass drew little";
    EXPECT_LE(2 * bytes, bytesWide) << "t = " << v.time;
  }
  const double mean = sum / double(values);
  std::printf("[ buffers  ] 8-bit against RGBA16F buffers: max %d step(s), mean %.3f steps\n", worst, mean);
  EXPECT_LE(worst, 3);
  EXPECT_LE(mean, 0.7);
}

TEST_F(GlTest, PipeDreamBallShaderStretchesAsTheReference) {
  // The vertex shader's world positions, captured by transform feedback, against
  // stretchVertex() — the arithmetic the unit tests check for length and closedness.
  const glint::pipedream::BlurBallMesh ball = glint::pipedream::buildBlurBall(16, 8);
  std::vector<float> data;
  for (const vec3& p : ball.positions) data.insert(data.end(), {p.x, p.y, p.z});
  data.insert(data.end(), ball.rear.begin(), ball.rear.end());
  const gl::Buffer vertices(std::span<const float>(data), 0, "test-ball");
  gl::VertexArray vao = gl::VertexArray::create("test-ball");
  vao.attribute(0, 0, 3, 0);
  vao.vertexBuffer(0, vertices, 0, sizeof(vec3));
  vao.attribute(1, 1, 1, 0);
  vao.vertexBuffer(1, vertices, GLintptr(ball.positions.size() * sizeof(vec3)), sizeof(float));
  const gl::Buffer captured(ball.positions.size() * sizeof(vec3), nullptr, 0, "test-ball-capture");
  const gl::Program program = gl::Program::fromFiles({"pipedream/ball.vert"}, {"CAPTURE"});
  const vec3 centre(0.5f, 2.0f, -1.0f), velocity(6.0f, 9.0f, -3.0f);
  const float radius = 0.12f, shutter = 1.0f / 30.0f;
  program.set("uFrame", glint::pipedream::ballFrame(velocity));
  program.set("uCentre", centre);
  program.set("uVelocity", velocity);
  program.set("uRadius", radius);
  program.set("uShutter", shutter);
  program.set("uViewProj", mat4(1.0f));
  program.use();
  vao.bind();
  const gl::RenderTarget target(ivec2(4));  // a complete framebuffer (a surfaceless context has none)
  target.target().bind();
  glEnable(GL_RASTERIZER_DISCARD);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, captured.id());
  glBeginTransformFeedback(GL_POINTS);
  glDrawArrays(GL_POINTS, 0, GLsizei(ball.positions.size()));
  glEndTransformFeedback();
  glDisable(GL_RASTERIZER_DISCARD);
  glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
  glBindVertexArray(0);
  std::vector<vec3> out(ball.positions.size());
  glGetNamedBufferSubData(captured.id(), 0, GLsizeiptr(out.size() * sizeof(vec3)), out.data());
  for (std::size_t i = 0; i < out.size(); ++i) {
    const vec3 expected = glint::pipedream::stretchVertex(ball.positions[i], ball.rear[i], centre, velocity, radius, shutter);
    ASSERT_LT(glm::length(out[i] - expected), 1e-5f) << i;
  }
}

TEST_F(GlTest, PipeDreamViewerKeysSwitchViewsWithoutAReload) {
  // The scene as the viewer holds it: keys toggle WWDC 2003 session 212's views and pick cameras.
  const auto ref = scenes::Registry::builtin().resolve("pipedream/full");
  std::unique_ptr<scenes::Scene> scene = ref.scene->create(ref.variant);
  scenes::setOption(*scene, fmt::format("detail={}", kDetail));
  gl::RenderTarget target(kSize);
  const auto frame = [&] {
    scene->render({.target = target.target(), .time = 6.35});
    return gl::readColor(target.framebuffer(), kSize);
  };
  const Image full = frame();
  EXPECT_TRUE(scene->keyPressed('A'));
  const Image alpha = frame();
  EXPECT_NE(alpha, full);
  EXPECT_NE(scene->notes().find("(dest-alpha)"), std::string::npos) << scene->notes();
  EXPECT_TRUE(scene->keyPressed('A'));  // again: back to the full frame
  EXPECT_EQ(frame(), full);
  EXPECT_TRUE(scene->keyPressed('3'));
  EXPECT_NE(frame(), full);
  EXPECT_NE(scene->notes().find("camera 'wall'"), std::string::npos) << scene->notes();
  EXPECT_FALSE(scene->keyPressed('X'));
}

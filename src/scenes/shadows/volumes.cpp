// shadows/zpass-invert, zpass, zfail, two-sided, gpu-extrude, volumes-debug, inside-volume —
// stencil shadow volumes as the WWDC 2001 talk and WWDC 2003 session 212 (ATI)
// describe them, and the counting methods that made them robust.
//
// Every variant is one StencilShadowOptions over the WWDC 2001 talk's demo world: a slab
// under a positional light casts a volume onto the ground, and a sphere rolls in
// and out of it with --time.
#include "common.h"

#include "glint/render/shadows/stencil_shadows.h"
#include "glint/render/shadows/world_renderer.h"

#include <memory>
#include <string>
#include <vector>

namespace glint::scenes {
namespace shadows {
namespace {

using glint::shadows::CasterMode;
using sh::ShadowComposite;
using sh::StencilCounting;
using sh::StencilShadowOptions;
using sh::VolumeConstruction;
using sh::VolumeView;

struct Variant {
  const char* name;
  const char* description;
  StencilShadowOptions options;
  SceneView view = SceneView::Demo;
  bool sphereCasts = true;
  double time = 0.0;  // added to --time: variants that need the sphere elsewhere
};

class VolumeScene final : public Scene {
public:
  explicit VolumeScene(const Variant& v)
      : m_variant(v), m_world(glint::shadows::makeDemoWorld(0.0, v.sphereCasts)), m_shadows(m_world, v.options) {
    m_light.position = m_world.lightPosition;
  }

  void render(const FrameInput& frame) override {
    glint::shadows::animateDemoWorld(m_world, frame.time + m_variant.time);
    m_world.lightPosition = m_light.position;
    glint::Camera camera = frame.camera(glint::shadows::sceneCamera(m_variant.view, aspectOf(frame)));
    if (sh::StencilShadows::needsInfiniteFar(m_shadows.options()))
      camera.projection = sh::infiniteFarProjection(camera.projection);
    m_shadows.render(m_world, camera, frame.target);
  }

  std::vector<Option> options() override {
    std::vector<Option> out;
    m_light.add(out);
    auto& o = m_shadows.options();
    out.push_back({"quad-alpha", "opacity of the shadow quad (composite quad)", &o.quadAlpha, 0.0f, 1.0f});
    out.push_back({"volume-opacity", "opacity of the black re-drawn volume (composite volume; the WWDC 2001 talk: 0.85, 0.5)",
                   &o.volumeOpacity, 0.0f, 1.0f});
    out.push_back({"offset-factor", "polygon offset slope factor of the volume passes", &o.offsetFactor, 0.0f, 8.0f});
    out.push_back({"offset-units", "polygon offset units of the volume passes", &o.offsetUnits, 0.0f, 64.0f});
    return out;
  }

  std::string notes() const override { return m_shadows.describe(); }

private:
  Variant m_variant;
  glint::shadows::World m_world;
  sh::StencilShadows m_shadows;
  LightOptions m_light;
};

void add(Registry& registry, const char* name, const char* summary, std::vector<Variant> variants) {
  SceneDesc desc{.name = name, .summary = summary};
  for (const auto& v : variants) desc.variants.push_back({v.name, v.description});
  desc.create = [variants](int i) -> std::unique_ptr<Scene> { return std::make_unique<VolumeScene>(variants[std::size_t(i)]); };
  registry.add(std::move(desc));
}

constexpr StencilShadowOptions invert(ShadowComposite composite, float opacity = 0.85f) {
  return {.counting = StencilCounting::InvertZPass, .casters = CasterMode::Closed, .composite = composite,
          .volumeOpacity = opacity};
}

}  // namespace
}  // namespace shadows

namespace shadows {
namespace {

/// The WWDC 2001 talk's method: GL_INVERT parity, with its three composites.
void registerInvert(Registry& registry) {
  add(registry, "shadows/zpass-invert",
      "Stencil shadow volumes the WWDC 2001 talk's way: scene, then the volume's back faces and front faces "
      "with colour and depth writes off and GL_INVERT where depth passes; the sphere moves in and out of the "
      "slab's volume with --time.",
      {
          {"multipass", "(iii) the correct composite: ambient everywhere, then diffuse + specular added only where "
                        "the stencil is 0 (GL_EQUAL depth, additive blending).",
           invert(ShadowComposite::MultiPass), SceneView::Demo, false},
          {"quad", "(i) a full-screen black quad, 55% opaque, alpha-blended where the stencil is set: simple, but "
                   "shadowed surfaces keep their diffuse and specular highlights under the tint.",
           invert(ShadowComposite::ShadowQuad), SceneView::Demo, false},
          {"volume-85", "(ii) the volume drawn again into colour under the stencil test, black and 85% opaque: "
                        "shadows keep 15% of the lit colour, a trace of diffuse and specular still shows (the "
                        "talk's choice, \"not too bad\").",
           invert(ShadowComposite::VolumeAlpha, 0.85f), SceneView::Demo, false},
          {"volume-50", "(ii) the same at 50% opacity: shadows keep half the lit colour, and the diffuse and "
                        "specular light through them is much more noticeable.",
           invert(ShadowComposite::VolumeAlpha, 0.5f), SceneView::Demo, false},
          {"overlap", "INVERT counts parity: with the sphere inside the slab's volume and casting too, its shadow "
                      "inside the slab's shadow is crossed twice and comes out lit — why counting replaced it.",
           invert(ShadowComposite::MultiPass), SceneView::Demo, true, 6.0},
      });
}

/// Counting instead of parity: z-pass, z-fail, and both in one two-sided draw.
void registerCounting(Registry& registry) {
  add(registry, "shadows/zpass",
      "Z-pass counting: front faces INCR_WRAP, back faces DECR_WRAP where the depth test passes, so "
      "overlapping volumes add up (the sphere now casts too).",
      {
          {"multipass", "Counted shadows with the multi-pass composite; the sphere's and the slab's shadows overlap "
                        "correctly when the sphere is inside.",
           {.counting = StencilCounting::ZPass}, SceneView::Demo, true, 6.0},
          {"count", "The stencil counts as colours: 1 yellow, 2 orange, 3 red; the sphere inside the slab's volume "
                    "shows 2 where both shadows fall.",
           {.counting = StencilCounting::ZPass, .composite = ShadowComposite::CountColors}, SceneView::Demo, true, 6.0},
          {"dim-alpha", "WWDC 2003 session 212's composite: the scene writes a dim factor (ambient/full) into destination alpha "
                        "and one quad blended (ZERO, DST_ALPHA) under the stencil test multiplies it in.",
           {.counting = StencilCounting::ZPass, .composite = ShadowComposite::DimAlpha}},
      });
  add(registry, "shadows/zfail",
      "Z-fail (Carmack's reverse): count the volume faces *behind* the visible surface (back INCR_WRAP, front "
      "DECR_WRAP on depth fail); needs near and far caps and a far plane that never clips them.",
      {
          {"infinite", "Far caps at infinity (w = 0) and a camera with an infinite far plane.",
           {.counting = StencilCounting::ZFail}},
          {"depth-clamp", "The camera keeps its far plane; GL_DEPTH_CLAMP stops the far caps being clipped.",
           {.counting = StencilCounting::ZFail, .depthClamp = true}},
          {"count", "The z-fail stencil counts as colours (same values as z-pass from outside the volumes).",
           {.counting = StencilCounting::ZFail, .composite = ShadowComposite::CountColors}, SceneView::Demo, true, 6.0},
      });
  add(registry, "shadows/two-sided",
      "Two-sided stencil: one draw with culling off, glStencilOpSeparate giving front and back faces their own "
      "ops — half the geometry passes of the two-draw methods.",
      {
          {"zpass", "One-pass z-pass (front INCR_WRAP, back DECR_WRAP).", {.counting = StencilCounting::TwoSidedZPass}},
          {"zfail", "One-pass z-fail (back INCR_WRAP, front DECR_WRAP on depth fail).",
           {.counting = StencilCounting::TwoSidedZFail}},
      });
}

/// GPU extrusion, the debug views, and the camera inside a volume.
void registerExtrusionAndViews(Registry& registry) {
  add(registry, "shadows/gpu-extrude",
      "GPU extrusion (WWDC 2003 session 212, ATI): a degenerate quad on every edge, the face normal in each vertex; the "
      "vertex shader sends faces turned from the light to infinity (w = 0), stretching the quads into sides.",
      {
          {"zfail", "GPU-extruded volumes counted with z-fail: the same shadows as CPU silhouettes, no CPU work.",
           {.counting = StencilCounting::TwoSidedZFail, .construction = VolumeConstruction::Gpu}},
          {"wireframe", "The GPU-extruded volumes as wireframe: every face and quad, stretched ones forming the "
                        "pill-shaped volume of WWDC 2003 session 212.",
           {.counting = StencilCounting::TwoSidedZFail, .construction = VolumeConstruction::Gpu,
            .view = VolumeView::Wireframe}},
          {"cpu-wireframe", "For comparison, CPU silhouette volumes as wireframe: only silhouette quads and caps.",
           {.counting = StencilCounting::TwoSidedZFail, .view = VolumeView::Wireframe}},
      });
  add(registry, "shadows/volumes-debug",
      "The WWDC 2001 talk's debug view of the two-pass method: volume faces drawn depth-tested and added "
      "over the scene, no stencil.",
      {
          {"back", "Back faces of the volume in green: they pass the depth test only in front of the ground.",
           {.counting = StencilCounting::InvertZPass, .casters = CasterMode::Closed,
            .composite = ShadowComposite::None, .view = VolumeView::BackFaces}, SceneView::Demo, false},
          {"front", "Front faces in blue.",
           {.counting = StencilCounting::InvertZPass, .casters = CasterMode::Closed,
            .composite = ShadowComposite::None, .view = VolumeView::FrontFaces}, SceneView::Demo, false},
          {"both", "Both: cyan where back and front faces pass, blue where only the front face does — the blue "
                   "region is the shadow.",
           {.counting = StencilCounting::InvertZPass, .casters = CasterMode::Closed,
            .composite = ShadowComposite::None, .view = VolumeView::BothFaces}, SceneView::Demo, false},
          {"wireframe", "The volumes as wireframe over the shadowed scene.",
           {.counting = StencilCounting::ZFail, .view = VolumeView::Wireframe}},
      });
  add(registry, "shadows/inside-volume",
      "The camera inside the slab's shadow volume, looking out: z-pass starts counting at 0 where the true "
      "count is 1 and inverts the shadows; z-fail counts behind the surface and stays right.",
      {
          {"zpass", "Z-pass from inside the volume: lit and shadowed swap wherever the volume is seen.",
           {.counting = StencilCounting::TwoSidedZPass}, SceneView::Inside},
          {"zfail", "Z-fail from the same place: correct.", {.counting = StencilCounting::TwoSidedZFail},
           SceneView::Inside},
      });
}

}  // namespace
}  // namespace shadows

void registerShadowVolumes(Registry& registry) {
  shadows::registerInvert(registry);
  shadows::registerCounting(registry);
  shadows::registerExtrusionAndViews(registry);
}

}  // namespace glint::scenes

// pipedream — WWDC 2003 session 212's Animusic "Pipe Dream" demo as a glint scene: an instrument machine
// (pipedream/machine_room.h) playing its score (pipedream/score.h), static shadows cut in
// by glint::cut, dynamic ones from GPU-extruded volumes, joined through the destination-
// alpha dim factor, motion-blurred balls (render/pipedream/renderer.h). Variants are WWDC
// 2003 session 212's demo toggles; `camera` picks one of its camera moves, `detail` the polygon count.
#include "glint/scenes/pipedream.h"
#include "glint/scenes/scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

namespace glint::scenes {
namespace {

namespace rp = render::pipedream;
namespace pd = glint::pipedream;

struct VariantSetup {
  rp::Mode mode;
  int camera;  // the variant's own camera (the `camera` option changes it)
};

// In the order of registerPipeDream's variants.
const VariantSetup kVariants[] = {
    {rp::Mode::Full, 0},      {rp::Mode::Wireframe, 2}, {rp::Mode::DestAlpha, 0}, {rp::Mode::Volumes, 1},
    {rp::Mode::StaticOnly, 0}, {rp::Mode::NoBlur, 4},   {rp::Mode::Naive, 0},
};

const char* modeName(rp::Mode mode) {
  switch (mode) {
    case rp::Mode::Full: return "full";
    case rp::Mode::Wireframe: return "wireframe";
    case rp::Mode::DestAlpha: return "dest-alpha";
    case rp::Mode::Volumes: return "volumes";
    case rp::Mode::StaticOnly: return "static-only";
    case rp::Mode::NoBlur: return "no-blur";
    case rp::Mode::Naive: return "naive";
  }
  return "?";
}

class PipeDreamScene final : public Scene {
public:
  // The stage is loaded by the first frame, after --set has given the options (a detail
  // other than the default is then the only one cut).
  explicit PipeDreamScene(int variant) : m_mode(kVariants[variant].mode), m_camera(kVariants[variant].camera) {}

  std::vector<Option> options() override {
    return {{"camera", "WWDC 2003 session 212's camera moves: 0 stage, 1 drums, 2 wall, 3 side, 4 balls", &m_camera, 0.0f,
             float(pipedream::namedCameras().size() - 1)},
            {"detail", "tessellation 1..16: polygons per frame (5: ~440k triangles, WWDC 2003 session 212's range); a new value "
                       "is cut once and cached",
             &m_detail, 1.0f, 8.0f},
            {"shutter", "seconds the shutter is open: streak length = speed × shutter", &m_options.shutter, 0.0f, 0.1f},
            {"ambient", "the light every pixel keeps", &m_options.ambient, 0.0f, 0.5f},
            {"cull", "skip dynamic casters beyond a light's range (their shadows would be black on black)",
             &m_options.cullVolumes, 0.0f, 1.0f}};
  }

  std::string notes() const override { return m_notes; }

  // WWDC 2003 session 212's demo toggles, without a reload: F full, W wireframe, A destination alpha,
  // V volumes, S static only, B blur on/off, N naive; 1–5 the named cameras.
  bool keyPressed(int key) override {
    const auto toggle = [&](rp::Mode mode) { m_mode = m_mode == mode ? rp::Mode::Full : mode; };
    switch (key) {
      case 'F': m_mode = rp::Mode::Full; return true;
      case 'W': toggle(rp::Mode::Wireframe); return true;
      case 'A': toggle(rp::Mode::DestAlpha); return true;
      case 'V': toggle(rp::Mode::Volumes); return true;
      case 'S': toggle(rp::Mode::StaticOnly); return true;
      case 'B': toggle(rp::Mode::NoBlur); return true;
      case 'N': toggle(rp::Mode::Naive); return true;
      default: break;
    }
    if (key >= '1' && key < '1' + int(pipedream::namedCameras().size())) {
      m_camera = key - '1';
      return true;
    }
    return Scene::keyPressed(key);
  }

  void render(const FrameInput& frame) override {
    if (!m_stage || m_detail != m_stage->detail) load();
    m_renderer->options() = m_options;
    const pd::MachinePose pose = pd::poseAt(m_stage->machine, m_stage->score, frame.time);
    const glint::Camera camera = frame.camera(pipedream::namedCamera(m_camera, frame.target.aspect()));
    m_renderer->render(pose, camera, frame.target, m_mode);
    const rp::FrameStats& s = m_renderer->stats();
    m_notes = fmt::format("{}. This frame ({}): {} triangles drawn ({} balls); {} volume triangles from {} of {} "
                          "(caster, light) pairs, {} culled by range; camera '{}'. Keys: F full, W wireframe, A dest "
                          "alpha, V volumes, S static only, B blur, N naive, 1-5 cameras.",
                          m_stage->describe(), modeName(m_mode), s.sceneTriangles, s.balls, s.volumeTriangles, s.castersDrawn,
                          s.castersDrawn + s.castersCulled, s.castersCulled,
                          pipedream::namedCameras()[std::size_t(std::clamp(m_camera, 0, int(pipedream::namedCameras().size()) - 1))].name);
  }

private:
  void load() {
    m_renderer.reset();
    m_stage = pipedream::loadStage({.detail = m_detail});
    m_detail = m_stage->detail;
    m_renderer = std::make_unique<rp::Renderer>(m_stage->machine, m_stage->geometry, m_options);
    m_notes = m_stage->describe();
  }

  rp::Mode m_mode;
  int m_camera;
  int m_detail = pipedream::kDefaultDetail;
  rp::RendererOptions m_options;
  std::shared_ptr<const pipedream::Stage> m_stage;
  std::unique_ptr<rp::Renderer> m_renderer;
  std::string m_notes;
};

}  // namespace

void registerPipeDream(Registry& registry) {
  registry.add(
      {.name = "pipedream",
       .summary = "WWDC 2003 session 212's Animusic \"Pipe Dream\": an instrument machine whose static shadows are cut into the "
                  "geometry (glint cut), dynamic ones GPU-extruded stencil volumes culled per light, joined by the "
                  "destination-alpha dim factor and one quad per light; motion-blurred balls",
       .variants = {{"full", "WWDC 2003 session 212's method: cut static shadows, dynamic volumes, the dim-factor quad, blurred balls"},
                    {"wireframe", "the cut polygons' sides over the frame (the back wall: shadow boundaries are edges)"},
                    {"dest-alpha", "the dim factor as grey (WWDC 2003 session 212's debug view): white where no light reaches, "
                                   "darker the more light a dynamic shadow would take away"},
                    {"volumes", "the dynamic shadow volumes in blue wireframe, culled per light"},
                    {"static-only", "the cut static shadows alone: no volumes, no quad"},
                    {"no-blur", "balls still, opaque and sharp: without motion blur they read as hard balls"},
                    {"naive", "full-scene stencil volumes for every caster, static included, per light (WWDC 2003 session 212's "
                              "2 fps baseline)"}},
       .defaultSize = {800, 450},
       .defaultTime = 6.35,
       .create = [](int variant) -> std::unique_ptr<Scene> { return std::make_unique<PipeDreamScene>(variant); }});
}

}  // namespace glint::scenes

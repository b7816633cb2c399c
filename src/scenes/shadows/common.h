#pragma once
// Pieces the shadow scenes share: their cameras and the light options.
#include "glint/render/camera.h"
#include "glint/render/shadows/world.h"
#include "glint/scenes/scene.h"

namespace glint::scenes::shadows {

namespace sh = glint::render::shadows;

/// Where a shadow scene looks from.
enum class View {
  Demo,    ///< seeds/000's demo seen from the front and above
  Inside,  ///< from inside the slab's shadow volume, looking out at the sphere
  Bunny    ///< the bunny and the pinwheel
};

inline render::Camera makeCamera(View view, float aspect) {
  switch (view) {
    case View::Demo: return render::Camera::lookAt({2.2f, 3.4f, 5.6f}, {0.9f, 0.8f, -0.4f}, {0, 1, 0}, 45.0f, aspect, 0.5f, 60.0f);
    case View::Inside:
      return render::Camera::lookAt({-0.1f, 0.9f, -0.2f}, {2.6f, 0.2f, 1.6f}, {0, 1, 0}, 70.0f, aspect, 0.05f, 60.0f);
    case View::Bunny:
      return render::Camera::lookAt({0.9f, 1.5f, 2.7f}, {-0.35f, 0.25f, 0.1f}, {0, 1, 0}, 45.0f, aspect, 0.3f, 40.0f);
  }
  return {};
}

/// The light position as three options (light-x/-y/-z), so the viewer can move it.
struct LightOptions {
  vec3 position{0.0f};
  void add(std::vector<Option>& out, const char* what = "light") {
    out.push_back({"light-x", std::string(what) + " position x (world units)", &position.x, -8.0f, 8.0f});
    out.push_back({"light-y", std::string(what) + " position y (height)", &position.y, 0.5f, 12.0f});
    out.push_back({"light-z", std::string(what) + " position z", &position.z, -8.0f, 8.0f});
  }
};

inline float aspectOf(const FrameInput& frame) { return float(frame.target.size.x) / float(frame.target.size.y); }

}  // namespace glint::scenes::shadows

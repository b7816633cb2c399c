#pragma once
// Pieces the shadow scenes share: the light options (their cameras are
// glint::shadows::sceneCamera, which the oracle tests use too).
#include "glint/shadows/world.h"
#include "glint/scenes/scene.h"

#include <string>
#include <vector>

namespace glint::render::shadows {}  // the GL techniques (render/shadows/*.h), which each scene includes

namespace glint::scenes::shadows {

namespace sh = glint::render::shadows;

using glint::shadows::SceneView;

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

#include "glint/core/error.h"
#include "glint/core/text.h"
#include "glint/scenes/scene.h"

#include <algorithm>
#include <limits>
#include <charconv>
#include <string>
#include <vector>

namespace glint::scenes {

// One register function per scene file; listed here so static libraries never
// drop a scene (no static-initialiser tricks).
void registerBasicsTriangle(Registry& registry);
void registerBasicsDepth(Registry& registry);
void registerBasicsReference(Registry& registry);
void registerEnvScenes(Registry& registry);
void registerEnvBubble(Registry& registry);
void registerEnvClassic(Registry& registry);
void registerFilteringScenes(Registry& registry);
void registerRttScenes(Registry& registry);
void registerShadowVolumes(Registry& registry);
void registerShadowMaps(Registry& registry);
void registerShadowBunny(Registry& registry);
void registerBumpDot3(Registry& registry);
void registerBumpNormalMap(Registry& registry);
void registerBakeResult(Registry& registry);
#if GLINT_HAS_CUT
void registerCutScenes(Registry& registry);
void registerPipeDream(Registry& registry);
#endif
void registerWaterScenes(Registry& registry);
void registerPostScenes(Registry& registry);
#if GLINT_HAS_VIDEO
void registerPostCamera(Registry& registry);
#endif

const Registry& Registry::builtin() {
  static const Registry registry = [] {
    Registry r;
    registerBasicsTriangle(r);
    registerBasicsDepth(r);
    registerBasicsReference(r);
    registerEnvScenes(r);
    registerEnvBubble(r);
    registerEnvClassic(r);
    registerFilteringScenes(r);
    registerRttScenes(r);
    registerShadowVolumes(r);
    registerShadowMaps(r);
    registerShadowBunny(r);
    registerBumpDot3(r);
    registerBumpNormalMap(r);
    registerBakeResult(r);
#if GLINT_HAS_CUT  // GLINT_BUILD_CUT
    registerCutScenes(r);
    registerPipeDream(r);
#endif
    registerWaterScenes(r);
    registerPostScenes(r);
#if GLINT_HAS_VIDEO  // GLINT_BUILD_VIDEO
    registerPostCamera(r);
#endif
    return r;
  }();
  return registry;
}

void Registry::add(SceneDesc desc) {
  if (desc.variants.empty()) fail(ErrorKind::Internal, "scene '{}' has no variants", desc.name);
  m_scenes.push_back(std::move(desc));
}

std::vector<VariantRef> Registry::allVariants() const {
  std::vector<VariantRef> out;
  for (const auto& s : m_scenes)
    for (int v = 0; v < int(s.variants.size()); ++v) out.push_back({&s, v});
  return out;
}

std::vector<VariantRef> Registry::match(const std::string& filter) const {
  std::vector<VariantRef> out;
  for (const auto& ref : allVariants())
    if (filter.empty() || ref.fullName().find(filter) != std::string::npos) out.push_back(ref);
  return out;
}

VariantRef Registry::resolve(const std::string& name) const {
  for (const auto& s : m_scenes) {
    if (name == s.name) return {&s, 0};
    if (name.size() > s.name.size() && name.compare(0, s.name.size(), s.name) == 0 && name[s.name.size()] == '/') {
      const std::string variant = name.substr(s.name.size() + 1);
      for (int v = 0; v < int(s.variants.size()); ++v)
        if (s.variants[std::size_t(v)].name == variant) return {&s, v};
      std::string names;
      for (const auto& v : s.variants) names += (names.empty() ? "" : ", ") + v.name;
      fail(ErrorKind::Usage, "scene '{}' has no variant '{}' (variants: {})", s.name, variant, names);
    }
  }
  // Suggest scenes sharing the group or a substring, so typos are quick to fix.
  std::string group = name.substr(0, name.find('/'));
  std::string suggestions;
  for (const auto& s : m_scenes) {
    if (s.name.rfind(group + "/", 0) == 0 || s.name.find(name) != std::string::npos)
      suggestions += (suggestions.empty() ? "" : ", ") + s.name;
  }
  if (suggestions.empty()) fail(ErrorKind::Usage, "unknown scene '{}' (`glint list` shows them all)", name);
  fail(ErrorKind::Usage, "unknown scene '{}' (did you mean: {}?)", name, suggestions);
}

bool Scene::keyPressed(int key) {
  bool used = false;
  for (auto& o : options()) {
    if (!o.key || int(o.key) != key) continue;
    if (auto* b = std::get_if<bool*>(&o.value)) **b = !**b, used = true;
    if (auto* i = std::get_if<int*>(&o.value)) **i = **i >= int(o.max) ? int(o.min) : **i + 1, used = true;
  }
  return used;
}

void setOption(Scene& scene, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos) fail(ErrorKind::Usage, "--set expects name=value, got '{}'", printable(assignment));
  const std::string name = assignment.substr(0, eq);
  const std::string value = assignment.substr(eq + 1);
  auto options = scene.options();
  auto it = std::find_if(options.begin(), options.end(), [&](const Option& o) { return o.name == name; });
  if (it == options.end()) {
    std::string names;
    for (const auto& o : options) names += (names.empty() ? "" : ", ") + o.name;
    fail(ErrorKind::Usage, "this scene has no option '{}' (options: {})", printable(name), names.empty() ? "none" : names);
  }
  const auto bad = [&] { fail(ErrorKind::Usage, "option '{}': cannot use '{}'", name, printable(value)); };
  if (auto* f = std::get_if<float*>(&it->value)) {
    try {
      **f = parseFloat(value, name);  // the whole text, finite, no locale
    } catch (const Error&) {
      bad();
    }
  } else if (auto* i = std::get_if<int*>(&it->value)) {
    try {
      **i = parseInt(value, name, std::numeric_limits<int>::min(), std::numeric_limits<int>::max());  // core/text's
    } catch (const Error&) {
      bad();
    }
  } else if (auto* b = std::get_if<bool*>(&it->value)) {
    if (value == "1" || value == "true" || value == "on") **b = true;
    else if (value == "0" || value == "false" || value == "off") **b = false;
    else bad();
  } else if (auto* text = std::get_if<std::string*>(&it->value)) {
    **text = value;
  }
}

}  // namespace glint::scenes

// Lights: `--light`'s text, names, and the checks before a cut or a merge.
#include "lights.h"

#include "glint/core/error.h"
#include "glint/core/text.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace glint::cut {

Light parseLight(std::string_view text) {
  const auto fields = splitFields(text, ',');
  if (fields.size() != 3 && fields.size() != 4) {
    fail(ErrorKind::Usage, "--light must be x,y,z or x,y,z,name, got '{}'", printable(text));
  }
  Light light;
  for (int i = 0; i < 3; ++i) light.position[i] = parseFloat(fields[std::size_t(i)], "--light");
  if (fields.size() == 4) light.name = std::string(fields[3]);
  return light;
}

std::string lightName(const Light& light, std::size_t index) {
  return light.name.empty() ? fmt::format("light{}", index) : light.name;
}

void checkLights(const std::vector<Light>& lights) {
  if (lights.empty()) fail(ErrorKind::Usage, "cut needs at least one light (--light x,y,z)");
  if (lights.size() > std::size_t(kMaxLights))
    fail(ErrorKind::Usage, "cut handles at most {} lights, got {}", kMaxLights, lights.size());
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const vec3& p = lights[i].position;
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      fail(ErrorKind::Usage, "light '{}' has a non-finite position", lightName(lights[i], i));
    // A name is written into a PLY header line and JSON: one line of text.
    if (std::any_of(lights[i].name.begin(), lights[i].name.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }))
      fail(ErrorKind::Usage, "light {}'s name '{}' holds a control character", i, escapedLine(lights[i].name));
  }
}

void checkShardLights(const std::vector<Light>& given, const std::vector<Light>& theirs) {
  if (given.empty()) return;
  bool same = theirs.size() == given.size();
  for (std::size_t i = 0; same && i < theirs.size(); ++i) same = theirs[i].position == given[i].position;
  if (!same) fail(ErrorKind::Usage, "--light differs from the lights the shards were cut with (leave it out to use theirs)");
}

}  // namespace glint::cut

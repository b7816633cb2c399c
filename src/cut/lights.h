#pragma once
// The lights as every step of the cutter sees them: their names in reports and files, and
// the checks a list of lights must pass before anything is cut or merged.
#include "glint/cut/cutter.h"

#include <string>
#include <vector>

namespace glint::cut {

/// The light's name, or "light<index>" when it has none.
std::string lightName(const Light& light, std::size_t index);

/// Error(Usage) for no lights, more than kMaxLights, or a non-finite position.
void checkLights(const std::vector<Light>& lights);

/// Error(Usage) unless `given` is empty or has the positions of `theirs` (the lights the
/// shards were cut with), in order.
void checkShardLights(const std::vector<Light>& given, const std::vector<Light>& theirs);

}  // namespace glint::cut

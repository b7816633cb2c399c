// Fuzz harness: the values users type on command lines — sizes (--size), numbers, vectors
// integers and memory sizes (core/text.h), lights (`glint cut --light`, cut/cutter.h), and effect chains
// with their settings (`glint post -e NAME:p=v --set p=v`, post/effects.h). The first
// byte chooses the parser; the rest is the text. What parses must be in range and finite.
#include "support.h"

#include "glint/core/text.h"
#include "glint/cut/cutter.h"
#include "glint/post/effects.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace glint;
  if (size < 1) return 0;
  const std::string_view text(reinterpret_cast<const char*>(data + 1), size - 1);
  fuzz::parse([&] {
    switch (data[0] % 7) {
      case 0: {
        const ivec2 s = parseSize(text);
        fuzz::check(s.x >= 1 && s.y >= 1 && s.x <= kMaxImageSide && s.y <= kMaxImageSide, "size in range");
        break;
      }
      case 1: fuzz::check(std::isfinite(parseFloat(text, "--value")), "finite number"); break;
      case 2: {
        const int v = parseInt(text, "--count", -7, 1000);
        fuzz::check(v >= -7 && v <= 1000, "integer in range");
        break;
      }
      case 3: {
        const vec3 v = parseVec3(text, "--position");
        fuzz::check(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z), "finite vector");
        break;
      }
      case 5: {
        // "-e" specs separated by blanks, then a newline and "--set" assignments.
        std::vector<std::string> specs, settings;
        const std::size_t nl = text.find('\n');
        for (auto* list : {&specs, &settings}) {
          const std::string_view part = list == &specs ? text.substr(0, nl) : nl == text.npos ? "" : text.substr(nl + 1);
          for (std::string_view field : splitFields(part, ' ')) {
            if (!field.empty()) list->emplace_back(field);
          }
        }
        (void)post::parseEffects(specs, settings);
        break;
      }
      case 6: {
        const double mib = parseMemorySize(text, "--max-memory");
        fuzz::check(std::isfinite(mib) && mib > 0.0, "memory sizes are positive");
        break;
      }
      default: {
        const cut::Light light = cut::parseLight(text);
        fuzz::check(std::isfinite(light.position.x) && std::isfinite(light.position.y) && std::isfinite(light.position.z),
                    "finite light");
        break;
      }
    }
  });
  return 0;
}

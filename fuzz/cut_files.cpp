// Fuzz harness: the files `glint cut` reads besides meshes — glTF lights
// (KHR_lights_punctual, through tinygltf), its own shard files (--merge) and the light
// masks of a cut PLY. The first byte chooses the reader.
#include "support.h"

#include "glint/core/log.h"
#include "glint/cut/cutter.h"
#include "glint/cut/output.h"

#include <cmath>
#include <cstdint>
#include <span>

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glint::log::setLevel(glint::log::Level::Error);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace glint;
  if (size < 1) return 0;
  const std::span<const std::uint8_t> bytes(data + 1, size - 1);
  fuzz::parse([&] {
    switch (data[0] % 4) {
      case 0:
      case 1: {
        const auto lights = cut::loadGltfLights(fuzz::inputFile(bytes, data[0] % 4 == 0 ? "gltf" : "glb"));
        for (const cut::Light& l : lights) {
          fuzz::check(std::isfinite(l.position.x) && std::isfinite(l.position.y) && std::isfinite(l.position.z), "finite lights");
        }
        break;
      }
      case 2: {
        const cut::Shard shard = cut::loadShard(fuzz::inputFile(bytes, "shard"));
        fuzz::check(shard.shardIndex >= 0 && shard.shardIndex < shard.shardCount, "shard index in range");
        break;
      }
      default: (void)cut::loadPlyMasks(fuzz::inputFile(bytes, "ply")); break;
    }
  });
  return 0;
}

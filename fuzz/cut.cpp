// Fuzz harness: the shadow cutter (cut/cutter.h cut) on the geometry exact predicates
// exist for. The bytes become up to 24 triangles whose corners lie on a coarse grid
// (coordinates −2 … 1.75 in steps of 0.25), so coplanar, touching, edge-sharing,
// degenerate and cyclically overlapping triangles are the common case, not the rare one,
// and 1–3 lights on the same grid. The cut must end (no loop), and what it returns must be
// a cut: every piece comes from an input triangle, masks name only given lights, and the
// pieces of each triangle (or of each patch of coplanar triangles merged) cover its area.
#include "support.h"

#include "glint/core/log.h"
#include "glint/cut/cutter.h"

#include <tbb/global_control.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace {

float gridValue(std::uint8_t b) { return float(int(b % 16) - 8) * 0.25f; }

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glint::log::setLevel(glint::log::Level::Off);  // the cutter warns about degenerate input
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace glint;
  static tbb::global_control oneThread(tbb::global_control::max_allowed_parallelism, 1);
  if (size < 4) return 0;
  const int lightCount = 1 + data[0] % 3;
  std::size_t at = 1;
  cut::CutOptions options;
  for (int l = 0; l < lightCount && at + 3 <= size; ++l, at += 3) {
    options.lights.push_back({vec3(gridValue(data[at]), gridValue(data[at + 1]) + 2.0f, gridValue(data[at + 2])), {}});
  }
  Mesh mesh;
  for (; at + 9 <= size && mesh.positions.size() < 72; at += 9) {
    for (int c = 0; c < 3; ++c) {
      mesh.positions.push_back(vec3(gridValue(data[at + 3 * c]), gridValue(data[at + 3 * c + 1]), gridValue(data[at + 3 * c + 2])));
      mesh.indices.push_back(std::uint32_t(mesh.positions.size() - 1));
    }
  }
  if (options.lights.empty()) return 0;
  fuzz::parse([&] {
    const cut::CutResult result = cut::cut(mesh, options);
    const cut::CutMesh& out = result.mesh;
    const std::size_t triangles = mesh.indices.size() / 3;
    std::vector<double> area(triangles, 0.0);
    fuzz::check(out.polygonStart.size() == out.polygonCount() + 1 && out.polygonSource.size() == out.polygonCount(),
                "one start, source and mask per polygon");
    for (std::size_t p = 0; p < out.polygonCount(); ++p) {
      fuzz::check(out.polygonSource[p] < triangles, "pieces come from input triangles");
      fuzz::check(out.polygonMask[p] < (cut::LightMask(1) << lightCount), "masks name given lights only");
      fuzz::check(out.cornerCount(p) >= 3, "pieces are polygons");
      for (std::uint32_t k = out.polygonStart[p]; k < out.polygonStart[p + 1]; ++k) {
        fuzz::check(out.corners[k] < out.positions.size(), "corners in range");
      }
      area[out.polygonSource[p]] += cut::polygonArea(out, p);
    }
    // Pieces of a patch of coplanar triangles merged count for the patch (its lowest triangle).
    fuzz::check(out.trianglePatch.size() == triangles, "a patch per triangle");
    std::vector<double> inputArea(triangles, 0.0);
    for (std::size_t t = 0; t < triangles; ++t) {
      fuzz::check(out.trianglePatch[t] <= t && out.trianglePatch[out.trianglePatch[t]] == out.trianglePatch[t],
                  "a patch is named by its lowest triangle");
      const glm::dvec3 a(mesh.positions[3 * t]), b(mesh.positions[3 * t + 1]), c(mesh.positions[3 * t + 2]);
      inputArea[out.trianglePatch[t]] += 0.5 * glm::length(glm::cross(b - a, c - a));
    }
    for (std::size_t t = 0; t < triangles; ++t) {
      const double input = inputArea[t];
      // Degenerate triangles are carried through or dropped (counted in the stats); the
      // others keep their area, up to slivers that rounding to float flattened.
      if (input > 1e-6) fuzz::check(std::abs(area[t] - input) <= 1e-6 * input + 1e-9 * double(result.stats.droppedSlivers + 1) , "area kept");
    }
  });
  return 0;
}

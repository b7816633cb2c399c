// The shadow cutter against independent computations: Embree shadow rays, areas per
// input triangle, the edge topology of the result; the seed's hard cases.
#include "glint/cut/cutter.h"

#include "cut_test_util.h"

#include <gtest/gtest.h>

using namespace glint;
using namespace glint::cut;
using namespace glint::cut::testing;

namespace {

/// A closed slab as the floor, a closed box floating above it.
Mesh boxOverFloor() {
  Mesh scene = makeBox({-4, -1, -4}, {4, 0, 4});
  scene.append(makeBox({-0.5f, 1, -0.5f}, {0.5f, 2, 0.5f}));
  return scene;
}

void expectClosed(const CutMesh& mesh) {
  const EdgeMap map = EdgeMap::build(triangulate(mesh).mesh);
  EXPECT_TRUE(map.isClosedManifold()) << map.count(EdgeKind::Open) << " open, " << map.count(EdgeKind::NonManifold)
                                      << " non-manifold, " << map.count(EdgeKind::Inconsistent) << " inconsistent, "
                                      << map.degenerateFaces() << " degenerate";
}

}  // namespace

TEST(Cut, BoxOverFloorAgreesWithShadowRays) {
  const Mesh scene = boxOverFloor();
  CutOptions options;
  options.lights = {{.position = {0.7f, 6.0f, 0.4f}, .name = "key"}};
  const CutResult result = cut::cut(scene, options);
  EXPECT_GT(result.mesh.polygonCount(), scene.triangleCount());
  const OracleResult o = shadowOracle(scene, result.mesh, options.lights, 64);
  EXPECT_GE(o.agreement(), 0.9999) << o.agree << " of " << o.samples;
  EXPECT_LT(worstAreaError(scene, result.mesh), 1e-6);
  expectClosed(result.mesh);
  // The floor under the box is shadowed, its far corners lit.
  EXPECT_GT(result.stats.lights[0].shadowedArea, 1.0);
  EXPECT_GT(result.stats.lights[0].litArea, 60.0);
}

TEST(Cut, DebugPrint) {
  const Mesh scene = boxOverFloor();
  CutOptions options;
  options.lights = {{.position = {0.7f, 6.0f, 0.4f}, .name = "key"}, {.position = {-3.0f, 4.0f, 2.0f}, .name = "fill"}};
  const CutResult result = cut::cut(scene, options);
  const auto& s = result.stats;
  printf("tris %zu polys %zu outTris %zu verts %zu cand %zu occ %zu pairs %zu cuts %zu before %zu sym %zu filt %zu exact %zu\n",
         (size_t)s.inputTriangles, (size_t)s.outputPolygons, (size_t)s.outputTriangles, (size_t)s.outputVertices,
         (size_t)s.candidates, (size_t)s.occluders, (size_t)s.clippedPairs, (size_t)s.cuts, (size_t)s.facesBeforeMerge,
         (size_t)s.symbolicPredicates, (size_t)s.filteredPredicates, (size_t)s.exactPredicates);
  for (auto& l : s.lights) printf("%s lit %zu shad %zu litA %g shA %g\n", l.name.c_str(), (size_t)l.litPolygons, (size_t)l.shadowedPolygons, l.litArea, l.shadowedArea);
  const OracleResult o = shadowOracle(scene, result.mesh, options.lights, 64);
  printf("oracle %zu/%zu skipped %zu\n", o.agree, o.samples, o.skipped);
  expectClosed(result.mesh);
  EXPECT_LT(worstAreaError(scene, result.mesh), 1e-6);
}

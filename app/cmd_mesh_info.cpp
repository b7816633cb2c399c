// glint mesh-info FILE — size, bounds and topology of a mesh: open (hole) edges,
// non-manifold edges and flipped windings, which stencil shadow volumes care about.
#include "common.h"

#include "glint/mesh/adjacency.h"
#include "glint/mesh/mesh.h"

#include <fmt/format.h>

#include <memory>
#include <string>

namespace glint::app {

namespace {
struct MeshInfoArgs {
  std::string file;
  int limit = 20;
};

const char* kindName(EdgeKind kind) {
  switch (kind) {
    case EdgeKind::Manifold: return "manifold";
    case EdgeKind::Open: return "open";
    case EdgeKind::NonManifold: return "non-manifold";
    case EdgeKind::Inconsistent: return "inconsistent";
  }
  return "?";
}
}  // namespace

Command meshInfoCommand(CLI::App& app, const GlobalOptions&) {
  auto args = std::make_shared<MeshInfoArgs>();
  auto* cmd = app.add_subcommand("mesh-info", "Show a mesh's size, bounds and edge topology (open and non-manifold edges)");
  cmd->add_option("file", args->file, "Mesh file (any format Assimp reads: OBJ, PLY, glTF, STL, ...)")->required();
  cmd->add_option("--limit", args->limit, "Problem edges listed per kind (0: none, -1: all)")->capture_default_str();
  return Command{.run = [args] {
    const Mesh mesh = loadMesh(args->file);
    const EdgeMap map = EdgeMap::build(mesh);
    const Bounds b = mesh.bounds();
    fmt::print("file:               {}\n", args->file);
    fmt::print("vertices:           {} ({} distinct positions)\n", mesh.vertexCount(), map.positions().size());
    fmt::print("triangles:          {} ({} degenerate)\n", mesh.triangleCount(), map.degenerateFaces());
    fmt::print("bounds:             ({:.4g}, {:.4g}, {:.4g}) .. ({:.4g}, {:.4g}, {:.4g})\n", b.min.x, b.min.y, b.min.z,
               b.max.x, b.max.y, b.max.z);
    fmt::print("edges:              {}\n", map.edges().size());
    for (EdgeKind k : {EdgeKind::Manifold, EdgeKind::Open, EdgeKind::NonManifold, EdgeKind::Inconsistent})
      fmt::print("  {:<17} {}\n", std::string(kindName(k)) + ":", map.count(k));
    fmt::print("holes (border loops): {}\n", map.borderLoops());
    fmt::print("closed 2-manifold:  {}\n",
               map.isClosedManifold() ? "yes (shadow volumes may use its silhouette alone)"
                                      : "no (shadow volumes need the robust two-sided method)");
    for (EdgeKind k : {EdgeKind::Open, EdgeKind::NonManifold, EdgeKind::Inconsistent}) {
      if (map.count(k) == 0 || args->limit == 0) continue;
      fmt::print("{} edges:\n", kindName(k));
      int shown = 0;
      for (const Edge& e : map.edges()) {
        if (map.kind(e) != k) continue;
        if (args->limit > 0 && shown == args->limit) {
          fmt::print("  ... {} more (--limit -1 lists all)\n", map.count(k) - std::size_t(shown));
          break;
        }
        const vec3 pa = map.positions()[e.a], pb = map.positions()[e.b];
        std::string faces;
        for (const EdgeFace& f : map.faces(e)) faces += fmt::format("{}{}", faces.empty() ? "" : ",", f.face);
        fmt::print("  v{}-v{}  ({:.4g}, {:.4g}, {:.4g}) - ({:.4g}, {:.4g}, {:.4g})  faces {}\n", e.a, e.b, pa.x, pa.y,
                   pa.z, pb.x, pb.y, pb.z, faces);
        ++shown;
      }
    }
    return 0;
  }, .readsImages = false};
}

}  // namespace glint::app

// Bake groups matched by name, and the material ID and vertex colour maps (bake/groups.h).
#include "glint/bake/groups.h"
#include "glint/core/hash.h"

#include "glint/core/error.h"
#include "glint/core/log.h"
#include "parts_internal.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace glint::bake {

std::string groupName(std::string_view part, std::string_view suffix, bool high) {
  if (suffix.empty() || part.size() <= suffix.size()) return {};
  if (part.ends_with(suffix)) return std::string(part.substr(0, part.size() - suffix.size()));
  if (!high) return {};
  // `<group><suffix>_<anything>`: the last such occurrence, so `a_high_b_high_2` is group `a_high_b`.
  const std::string marker = std::string(suffix) + "_";
  const std::size_t at = part.rfind(marker);
  if (at == std::string_view::npos || at == 0 || at + marker.size() >= part.size()) return {};
  return std::string(part.substr(0, at));
}

GroupMatch matchGroups(const MeshParts& low, const MeshParts& high, const GroupNaming& naming) {
  if (naming.lowSuffix.empty() || naming.highSuffix.empty())
    fail(ErrorKind::Usage, "bake groups: --low-suffix and --high-suffix must not be empty");
  if (naming.lowSuffix == naming.highSuffix)
    fail(ErrorKind::Usage, "bake groups: --low-suffix and --high-suffix must differ (both '{}')", naming.lowSuffix);
  GroupMatch match;
  std::vector<std::string> lowGroup(low.partNames.size()), highGroup(high.partNames.size());
  bool anyNamed = false;
  for (std::size_t i = 0; i < low.partNames.size(); ++i) {
    lowGroup[i] = groupName(low.partNames[i], naming.lowSuffix, false);
    anyNamed = anyNamed || !lowGroup[i].empty();
  }
  for (std::size_t i = 0; i < high.partNames.size(); ++i) highGroup[i] = groupName(high.partNames[i], naming.highSuffix, true);
  if (!anyNamed) return match;  // no low part follows the convention: today's bake, one group

  // Groups in the low file's order; a low part's group needs at least one high part.
  std::map<std::string, std::uint32_t> index;
  for (std::size_t i = 0; i < low.partNames.size(); ++i) {
    const std::string& g = lowGroup[i];
    const bool hasHigh = !g.empty() && std::find(highGroup.begin(), highGroup.end(), g) != highGroup.end();
    if (!hasHigh) {
      match.unmatchedLow.push_back(low.partNames[i]);
      continue;
    }
    auto [it, inserted] = index.try_emplace(g, std::uint32_t(match.groups.size()));
    if (inserted) match.groups.push_back({.name = g});
    match.groups[it->second].lowParts.push_back(low.partNames[i]);
  }
  for (std::size_t i = 0; i < high.partNames.size(); ++i) {
    const auto it = highGroup[i].empty() ? index.end() : index.find(highGroup[i]);
    if (it == index.end()) match.unmatchedHigh.push_back(high.partNames[i]);
    else match.groups[it->second].highParts.push_back(high.partNames[i]);
  }
  if (match.groups.empty()) {
    fail(ErrorKind::Input, "bake groups: no low part matches a high part by name (low parts end in '{}', high parts "
         "in '{}' or '{}_*'): low parts {}, high parts {}", naming.lowSuffix, naming.highSuffix, naming.highSuffix,
         fmt::join(low.partNames, ", "), fmt::join(high.partNames, ", "));
  }
  const auto perTriangle = [&](const MeshParts& parts, const std::vector<std::string>& groupOf,
                               std::vector<std::uint32_t>& out, std::size_t BakeGroup::*count) {
    std::vector<std::uint32_t> partGroup(parts.partNames.size(), GroupMatch::kNone);
    for (std::size_t i = 0; i < partGroup.size(); ++i) {
      const auto it = groupOf[i].empty() ? index.end() : index.find(groupOf[i]);
      if (it != index.end()) partGroup[i] = it->second;
    }
    out.resize(parts.mesh.triangleCount());
    for (std::size_t t = 0; t < out.size(); ++t) {
      out[t] = t < parts.trianglePart.size() ? partGroup[parts.trianglePart[t]] : GroupMatch::kNone;
      if (out[t] != GroupMatch::kNone) ++(match.groups[out[t]].*count);
    }
  };
  perTriangle(low, lowGroup, match.lowTriangleGroup, &BakeGroup::lowTriangles);
  perTriangle(high, highGroup, match.highTriangleGroup, &BakeGroup::highTriangles);
  return match;
}

vec3 materialColor(std::string_view name) {
  const std::uint64_t hash = Fnv1a().addBytes(name.data(), name.size()).value();
  // The golden ratio spreads even neighbouring hashes around the hue circle. (32 bits of the
  // hash: a double keeps the fraction of their product to 1e-6.)
  const double hue = std::fmod(double(std::uint32_t(hash >> 32)) * 0.6180339887498949, 1.0);
  const double s = 0.7, v = 0.95;
  const double h6 = hue * 6.0;
  const int sector = int(h6) % 6;
  const double f = h6 - std::floor(h6);
  const double p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  double r = v, g = t, b = p;
  switch (sector) {
    case 0: r = v, g = t, b = p; break;
    case 1: r = q, g = v, b = p; break;
    case 2: r = p, g = v, b = t; break;
    case 3: r = p, g = q, b = v; break;
    case 4: r = t, g = p, b = v; break;
    default: r = v, g = p, b = q; break;
  }
  const auto byte = [](double x) { return float(std::lround(x * 255.0)) / 255.0f; };
  return {byte(r), byte(g), byte(b)};
}

BakeResult bake(const MeshParts& low, const MeshParts& high, const GroupMatch& match, const BakeOptions& options) {
  if (match.grouped() && (match.lowTriangleGroup.size() != low.mesh.triangleCount() ||
                          match.highTriangleGroup.size() != high.mesh.triangleCount()))
    fail(ErrorKind::Internal, "bake groups: the match is not of these meshes");
  for (const std::string& name : match.unmatchedLow)
    log::warn("bake groups: low part '{}' has no high part: its texels are not baked", name);
  for (const std::string& name : match.unmatchedHigh)
    log::warn("bake groups: high part '{}' matches no low part: ignored", name);
  const detail::PartsInput parts{.match = &match, .high = &high};
  BakeResult result = detail::bakeWith(low.mesh, high.mesh, options, &parts);
  for (const std::string& name : match.unmatchedLow)
    result.warnings.push_back(fmt::format("bake groups: low part '{}' has no high part: its texels are not baked", name));
  for (const std::string& name : match.unmatchedHigh)
    result.warnings.push_back(fmt::format("bake groups: high part '{}' matches no low part: ignored", name));
  return result;
}

nlohmann::ordered_json toJson(const GroupMatch& match) {
  nlohmann::ordered_json report = nlohmann::ordered_json::object();
  nlohmann::ordered_json groups = nlohmann::ordered_json::array();
  for (const BakeGroup& g : match.groups) {
    groups.push_back({{"name", g.name}, {"low_parts", g.lowParts}, {"high_parts", g.highParts},
                      {"low_triangles", g.lowTriangles}, {"high_triangles", g.highTriangles}});
  }
  report["groups"] = std::move(groups);
  report["unmatched_low"] = match.unmatchedLow;
  report["unmatched_high"] = match.unmatchedHigh;
  return report;
}

}  // namespace glint::bake

namespace glint::bake::detail {

PartsTables makePartsTables(const BakeOptions& options, const Mesh& high, const MeshParts* parts,
                            std::vector<std::string>& warnings) {
  PartsTables tables;
  tables.highIndices = &high.indices;
  if (options.maps.has(Map::VertexColor)) {
    if (!parts || !parts->hasColors())
      fail(ErrorKind::Input, "--vertex-color: the high poly has no vertex colours (OBJ 'v x y z r g b', PLY "
           "red/green/blue, glTF COLOR_0)");
    tables.colors = &parts->colors;
  }
  if (options.maps.has(Map::MaterialId)) {
    if (parts && parts->hasMaterials()) {
      tables.triangleMaterial = &parts->triangleMaterial;
      for (const std::string& name : parts->materialNames) tables.materialColors.push_back(materialColor(name));
    } else {
      const std::string message = "--material-id: the high poly has no materials: the map is one colour";
      log::warn("{}", message);
      warnings.push_back(message);
    }
    tables.materialColors.push_back(materialColor(""));
  }
  return tables;
}

Mesh groupHighMesh(const Mesh& high, const std::vector<std::uint32_t>& highTriangleGroup, std::uint32_t group,
                   std::vector<std::uint32_t>& ids) {
  Mesh m;
  ids.clear();
  for (std::size_t t = 0; t < highTriangleGroup.size(); ++t) {
    if (highTriangleGroup[t] != group) continue;
    ids.push_back(std::uint32_t(t));
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = high.indices[3 * t + std::size_t(k)];
      m.indices.push_back(std::uint32_t(m.positions.size()));
      m.positions.push_back(high.positions[v]);
      m.normals.push_back(high.normals[v]);
    }
  }
  return m;
}

void storePartsMaps(Context& ctx, std::size_t texel, std::span<const SampleResult> results, float* out) {
  const PartsTables& tables = *ctx.parts;
  const auto original = [&](const SampleResult& r) {
    return ctx.highTriangleIds ? ctx.highTriangleIds[r.triangle] : std::uint32_t(r.triangle);
  };
  if (!ctx.texelMaterial.empty()) {
    // The majority of the hits' materials, ties to the earliest sample: one exact colour.
    const std::uint32_t none = std::uint32_t(tables.materialColors.size() - 1);
    const auto materialOf = [&](const SampleResult& r) {
      if (!tables.triangleMaterial) return none;
      const std::uint32_t m = (*tables.triangleMaterial)[original(r)];
      return m == MeshParts::kNoMaterial ? none : m;
    };
    std::uint32_t best = 0;  // index + 1
    std::size_t bestCount = 0;
    for (std::size_t i = 0; i < results.size() && bestCount * 2 <= results.size(); ++i) {
      if (!results[i].hit) continue;
      const std::uint32_t m = materialOf(results[i]);
      std::size_t n = 0;
      for (std::size_t j = i; j < results.size(); ++j) n += results[j].hit && materialOf(results[j]) == m;
      if (n > bestCount) bestCount = n, best = m + 1;
    }
    ctx.texelMaterial[texel] = best ? best : kMaterialMissed;  // no hit: black, kept out of dilation
  }
  if (ctx.baking(Map::VertexColor)) {
    vec3 sum(0.0f);
    std::size_t hits = 0;
    for (const SampleResult& r : results) {
      if (!r.hit) continue;
      const std::uint32_t* corner = &(*tables.highIndices)[3 * std::size_t(original(r))];
      const std::vector<vec4>& c = *tables.colors;
      sum += vec3((1.0f - r.hitUv.x - r.hitUv.y) * c[corner[0]] + r.hitUv.x * c[corner[1]] + r.hitUv.y * c[corner[2]]);
      ++hits;
    }
    const vec3 colour = hits ? sum / float(hits) : vec3(0.0f);
    for (int k = 0; k < 3; ++k) out[ctx.channelOf(Map::VertexColor) + k] = colour[k];
  }
}

void dilateMaterials(std::vector<std::uint32_t>& ids, int width, int height, int passes) {
  const ivec2 order[8] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}, {-1, -1}, {1, -1}, {-1, 1}, {1, 1}};
  std::vector<std::uint32_t> previous;
  for (int pass = 0; passes < 0 || pass < passes; ++pass) {
    previous = ids;
    bool changed = false;
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x < width; ++x) {
        std::uint32_t& id = ids[std::size_t(y) * std::size_t(width) + std::size_t(x)];
        if (id != 0) continue;
        for (const ivec2& d : order) {
          const int nx = x + d.x, ny = y + d.y;
          if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
          const std::uint32_t n = previous[std::size_t(ny) * std::size_t(width) + std::size_t(nx)];
          if (n != 0) {
            id = n;
            changed = true;
            break;
          }
        }
      }
    }
    if (!changed) break;
  }
}

Image materialImage(const Context& ctx) {
  const int W = ctx.options.width, H = ctx.options.height;
  Image image(W, H, 3, PixelType::F32);
  const std::span<float> px = image.pixels<float>();
  const std::vector<vec3>& colors = ctx.parts->materialColors;
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      const std::uint32_t id = ctx.texelMaterial[std::size_t(y) * std::size_t(W) + std::size_t(x)];
      const vec3 c = id != 0 && id != kMaterialMissed ? colors[id - 1] : vec3(0.0f);
      float* out = &px[(std::size_t(H - 1 - y) * std::size_t(W) + std::size_t(x)) * 3];
      out[0] = c.r, out[1] = c.g, out[2] = c.b;
    }
  }
  return image;
}

}  // namespace glint::bake::detail

#pragma once
// glint/bake/maps.h — the maps `glint bake` writes, as one table: one row per map with its
// option name (also its batch-file key), the channels it holds, whether dilation pads it,
// the rays its measurement costs, its share of the memory estimate, its help line and
// --help's summary, its report key, and how its baked values become a file's pixels at 8,
// 16 or 32 bits. The options (bake/job.h's addOptions), --help's map list, batch keys, the
// writes, the report's "maps" and the memory estimate all come from the table.
//
// Adding a map: one row in src/bake/maps.cpp, and its measurement: what one sample yields
// (trace.cpp's SampleResult) and how a texel's samples combine (baker.cpp's storeTexel).
//
/// ```cpp
/// for (const glint::bake::MapInfo& m : glint::bake::mapTable())
///   if (m.work & glint::bake::kHemisphereRays) { /* AO and bent normals share their rays */ }
/// glint::bake::MapSet maps;
/// maps.add(glint::bake::Map::Ao).add(glint::bake::Map::Curvature);
/// const bool ao = maps.has(glint::bake::Map::Ao);  // true
/// ```
#include "glint/image/image.h"

#include <bitset>
#include <cstddef>
#include <cstdint>
#include <span>

namespace glint::bake {

struct BakeStats;

/// Every map, in the table's order (the normal map first: it is always baked).
enum class Map : std::uint8_t {
  Normal,
  Ao,
  Height,
  MissMask,
  BentNormal,
  Thickness,
  Curvature,
  Position,
  Opacity,
  MaterialId,
  VertexColor,
};
inline constexpr std::size_t kMapCount = 11;

/// What a map's measurement costs beyond the normal pass (MapInfo::work, a bit set).
enum MapWork : unsigned {
  kNoExtraWork = 0,
  kHemisphereRays = 1,  ///< cosine-weighted rays around the low poly's normal (AO, bent normals share them)
  kInwardRays = 2,      ///< rays from the hit into the high poly (thickness)
  kCurvatureRays = 4,   ///< rays dropping points onto the high poly around the hit (curvature)
  kHitTriangle = 8,     ///< reads the hit's triangle: the high poly read as parts (material, colour)
};

/// One row of the table.
struct MapInfo {
  Map map;
  const char* name;       ///< the option's long name and batch key: "ao", "bent-normal" ("output": the normal map's -o)
  const char* reportKey;  ///< its key in the report's "maps": "ao", "bent_normal", "normal"
  int channels;           ///< of the baked image: 1 or 3
  int texelChannels;      ///< floats per texel while baking (material ID: 0, it keeps one index per texel)
  double memoryChannels;  ///< float channels the memory estimate counts per texel (material ID: 2)
  bool dilated;           ///< padding grows it past the islands (the miss mask and opacity stay as measured)
  unsigned work;          ///< MapWork bits
  const char* help;       ///< the option's help line
  const char* summary;    ///< --help's map list: what a texel holds
  /// The baked image (F32; the normal map may come quantized already) as a file of `type`
  /// holds it: height, curvature and position scaled to 0..1 by the bake's distances
  /// (bake/output.h), the others converted.
  Image (*forOutput)(const Image& baked, PixelType type, const BakeStats& stats);
};

/// Every map, in Map's order.
std::span<const MapInfo> mapTable();
const MapInfo& mapInfo(Map map);

/// Whether a map's 8-bit pixels are colours to look at (sRGB: vertex colour, material ID)
/// rather than data (linear: normals, occlusion, distances).
inline bool isColourMap(Map map) { return map == Map::VertexColor || map == Map::MaterialId; }

/// A set of maps (BakeOptions::maps: the extra maps a bake makes besides the normal map).
class MapSet {
public:
  bool has(Map m) const { return m_bits.test(std::size_t(m)); }
  MapSet& add(Map m) {
    m_bits.set(std::size_t(m));
    return *this;
  }
  MapSet& remove(Map m) {
    m_bits.reset(std::size_t(m));
    return *this;
  }
  /// Whether a map of the set (the normal map aside) needs any of `work`'s MapWork bits.
  bool needs(unsigned work) const;
  bool empty() const { return m_bits.none(); }

private:
  std::bitset<kMapCount> m_bits;
};

}  // namespace glint::bake

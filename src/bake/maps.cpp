// The table of maps (bake/maps.h). Adding a map: a row here, and its measurement (trace.cpp,
// baker.cpp's storeTexel).
#include "glint/bake/maps.h"

#include "glint/bake/baker.h"
#include "glint/bake/output.h"

#include <algorithm>
#include <array>

namespace glint::bake {

namespace {

Image converted(const Image& baked, PixelType type, const BakeStats&) { return forOutput(baked, type); }
Image heightFile(const Image& baked, PixelType type, const BakeStats& s) {
  return heightForOutput(baked, type, std::max(s.frontDistance, s.rearDistance));
}
Image curvatureFile(const Image& baked, PixelType type, const BakeStats& s) {
  return curvatureForOutput(baked, type, s.curvatureRadius);
}
Image positionFile(const Image& baked, PixelType type, const BakeStats& s) {
  return positionForOutput(baked, type, s.positionBounds.value_or(Bounds{}));
}

const std::array<MapInfo, kMapCount> kTable = {{
    {.map = Map::Normal, .name = "output", .reportKey = "normal", .channels = 3, .texelChannels = 3,
     .memoryChannels = 0.0, .dilated = true, .work = kNoExtraWork,
     .help = "Normal map to write; format from the extension: .png .tga .tif .exr; name it with <UDIM> "
             "(normal.<UDIM>.png) for one map per UDIM tile",
     .summary = "high-poly normal in --space, encoded (n + 1) / 2", .forOutput = converted},
    {.map = Map::Ao, .name = "ao", .reportKey = "ao", .channels = 1, .texelChannels = 1, .memoryChannels = 1.0,
     .dilated = true, .work = kHemisphereRays,
     .help = "Also bake ambient occlusion (hemisphere rays against the high poly) to this file",
     .summary = "open fraction of --ao-samples hemisphere rays (1 = unoccluded)", .forOutput = converted},
    {.map = Map::Height, .name = "height", .reportKey = "height", .channels = 1, .texelChannels = 1,
     .memoryChannels = 1.0, .dilated = true, .work = kNoExtraWork,
     .help = "Also bake height/displacement (signed ray distance) to this file; 8/16-bit files map ±max(--max-front, "
             "--max-rear) to 0..1, EXR keeps distances",
     .summary = "signed distance along the low poly's normal (+ in front)", .forOutput = heightFile},
    {.map = Map::MissMask, .name = "miss-mask", .reportKey = "miss_mask", .channels = 1, .texelChannels = 1,
     .memoryChannels = 1.0, .dilated = false, .work = kNoExtraWork,
     .help = "Also write the fraction of each texel's rays that found nothing (debug)",
     .summary = "fraction of samples whose rays found nothing (debug)", .forOutput = converted},
    {.map = Map::BentNormal, .name = "bent-normal", .reportKey = "bent_normal", .channels = 3, .texelChannels = 3,
     .memoryChannels = 3.0, .dilated = true, .work = kHemisphereRays,
     .help = "Also bake bent normals (the mean unoccluded direction of the AO rays; casts them without --ao too), in "
             "--space, encoded like the normal map",
     .summary = "mean unoccluded direction of the AO rays, encoded like -o", .forOutput = converted},
    {.map = Map::Thickness, .name = "thickness", .reportKey = "thickness", .channels = 1, .texelChannels = 1,
     .memoryChannels = 1.0, .dilated = true, .work = kInwardRays,
     .help = "Also bake thickness for subsurface/translucency: --ao-samples rays into the surface, mean distance to "
             "where they leave it / --thickness-distance (1 = thick)",
     .summary = "mean distance through the surface / --thickness-distance (1 = thick)", .forOutput = converted},
    {.map = Map::Curvature, .name = "curvature", .reportKey = "curvature", .channels = 1, .texelChannels = 1,
     .memoryChannels = 1.0, .dilated = true, .work = kCurvatureRays,
     .help = "Also bake curvature (convex bright, concave dark, mid-grey flat; EXR: signed mean curvature in 1/scene "
             "units), from the high poly's normals at --curvature-radius",
     .summary = "mean curvature at --curvature-radius: mid-grey flat, bright convex (ridges), dark concave "
                "(creases); EXR: signed, 1 / scene units",
     .forOutput = curvatureFile},
    {.map = Map::Position, .name = "position", .reportKey = "position", .channels = 3, .texelChannels = 3,
     .memoryChannels = 3.0, .dilated = true, .work = kNoExtraWork,
     .help = "Also bake the high-poly hit point (object space): EXR keeps coordinates, 8/16-bit maps the high poly's "
             "bounding box to 0..1 (position_min/max in the report)",
     .summary = "hit point, object space: EXR raw, 8/16-bit over the high poly's box", .forOutput = positionFile},
    {.map = Map::Opacity, .name = "opacity", .reportKey = "opacity", .channels = 1, .texelChannels = 1,
     .memoryChannels = 1.0, .dilated = false, .work = kNoExtraWork,
     .help = "Also bake coverage/opacity: the fraction of each texel's samples that hit the high poly, 0 outside UV "
             "islands (not dilated)",
     .summary = "fraction of a texel's samples that hit, 0 outside islands", .forOutput = converted},
    {.map = Map::MaterialId, .name = "material-id", .reportKey = "material_id", .channels = 3, .texelChannels = 0,
     .memoryChannels = 2.0, .dilated = true, .work = kHitTriangle,
     .help = "Also bake a material ID map: a flat colour per high-poly material (majority of the texel's hits, never "
             "blended), stable from the material's name",
     .summary = "flat colour per high-poly material (a stable colour of its name)", .forOutput = converted},
    {.map = Map::VertexColor, .name = "vertex-color", .reportKey = "vertex_color", .channels = 3, .texelChannels = 3,
     .memoryChannels = 3.0, .dilated = true, .work = kHitTriangle,
     .help = "Also bake the high poly's vertex colours (OBJ 'v x y z r g b', PLY red/green/blue, glTF COLOR_0), "
             "averaged over each texel's hits",
     .summary = "the high poly's vertex colours, interpolated at the hits", .forOutput = converted},
}};

}  // namespace

std::span<const MapInfo> mapTable() { return kTable; }
const MapInfo& mapInfo(Map map) { return kTable[std::size_t(map)]; }

bool MapSet::needs(unsigned work) const {
  for (const MapInfo& m : kTable)
    if (m.map != Map::Normal && has(m.map) && (m.work & work)) return true;
  return false;
}

}  // namespace glint::bake

#pragma once
// glint/bake/output.h — turning baked maps into files: pixel depth per format, and the
// height, curvature and position maps' scaling into integer formats.
//
/// ```cpp
/// const glint::Image normal(64, 64, 3, glint::PixelType::F32);  // e.g. bake::BakeResult::normal
/// const glint::PixelType type = glint::bake::outputType("normal.png", 16);   // U16
/// glint::saveImage(glint::bake::forOutput(normal, type), "normal.png");
/// ```
//
// Formats and depths (the extension decides the format):
//   .png   8 (default) or 16 bits          .tga   8 bits
//   .tif   8 or 16 (default) bits          .exr   32-bit float (default) — 16 is not offered
// Normal maps are stored encoded, (n + 1) / 2, in every format, float included, so one
// decoder reads them all.

#include "glint/image/image.h"
#include "glint/mesh/mesh.h"

#include <filesystem>

namespace glint::bake {

/// Pixel type for `path` given the requested bits: `bits` when the format holds that depth,
/// else the format's default (8 PNG/TGA, 16 TIFF, 32 float EXR), as `--bits` applies to the
/// maps whose format has it. Error(Usage) for an unknown extension.
PixelType outputType(const std::filesystem::path& path, int bits = 0);
/// Whether the format of `path` holds `bits`-bit channels (PNG 8/16, TGA 8, TIFF 8/16, EXR 32).
bool holdsBits(const std::filesystem::path& path, int bits);

/// `image` (F32) converted to `type`, values clamped to 0..1 for integer types.
Image forOutput(const Image& image, PixelType type);

/// A signed-distance height map for an integer file: 0.5 is the low-poly surface, 0 and 1
/// are `range` behind and in front of it. Float files keep the distances as they are.
Image heightForOutput(const Image& height, PixelType type, float range);

/// A curvature map (BakeResult::curvature, signed mean curvature) for a file: float files
/// keep the curvature (1 / scene units, convex positive); integer files hold
/// 0.5 + 0.5 · clamp(H · radius, −1, 1): 0.5 flat, 1 a convex bend of `radius` or tighter,
/// 0 a concave one (`radius`: BakeStats::curvatureRadius, the scale it was measured at).
Image curvatureForOutput(const Image& curvature, PixelType type, float radius);

/// A position map (BakeResult::position, object-space coordinates) for a file: float files
/// keep the coordinates; integer files hold (p − bounds.min) / (bounds.max − bounds.min)
/// per axis, clamped to 0..1 (an axis without extent reads 0). Decode with
/// p = min + value · (max − min), the bounds from the report (position_min, position_max).
Image positionForOutput(const Image& position, PixelType type, const Bounds& bounds);

}  // namespace glint::bake

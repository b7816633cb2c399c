#include "glint/bake/output.h"

#include "glint/core/error.h"
#include "glint/core/file.h"

#include <algorithm>
#include <cctype>
#include <span>
#include <string>

namespace glint::bake {

namespace {
struct Format {
  const char* ext;
  int defaultBits;
  bool allows8, allows16, allows32;
};
constexpr Format kFormats[] = {
    {".png", 8, true, true, false},  {".tga", 8, true, false, false},  {".tif", 16, true, true, false},
    {".tiff", 16, true, true, false}, {".exr", 32, false, false, true},
};
const Format& formatOf(const std::filesystem::path& path) {
  const std::string ext = lowerExtension(path);
  for (const Format& f : kFormats)
    if (ext == f.ext) return f;
  fail(ErrorKind::Usage, "'{}': unknown map format '{}' (use .png, .tga, .tif or .exr)", path.string(), ext);
}
bool allows(const Format& f, int bits) {
  return (bits == 8 && f.allows8) || (bits == 16 && f.allows16) || (bits == 32 && f.allows32);
}
}  // namespace

bool holdsBits(const std::filesystem::path& path, int bits) { return allows(formatOf(path), bits); }

PixelType outputType(const std::filesystem::path& path, int bits) {
  const Format& f = formatOf(path);
  const int b = bits != 0 && allows(f, bits) ? bits : f.defaultBits;
  return b == 8 ? PixelType::U8 : b == 16 ? PixelType::U16 : PixelType::F32;
}

Image forOutput(const Image& image, PixelType type) { return image.converted(type); }

Image heightForOutput(const Image& height, PixelType type, float range) {
  if (type == PixelType::F32) return height;
  Image scaled = height;
  const float r = range > 0.0f ? range : 1.0f;
  for (float& v : scaled.pixels<float>()) v = std::clamp(0.5f + 0.5f * v / r, 0.0f, 1.0f);
  return scaled.converted(type);
}

Image curvatureForOutput(const Image& curvature, PixelType type, float radius) {
  if (type == PixelType::F32) return curvature;
  Image scaled = curvature;
  const float r = radius > 0.0f ? radius : 1.0f;
  for (float& v : scaled.pixels<float>()) v = 0.5f + 0.5f * std::clamp(v * r, -1.0f, 1.0f);
  return scaled.converted(type);
}

Image positionForOutput(const Image& position, PixelType type, const Bounds& bounds) {
  if (type == PixelType::F32) return position;
  Image scaled = position;
  const std::span<float> values = scaled.pixels<float>();
  const int channels = scaled.channels();
  for (std::size_t i = 0; i < values.size(); ++i) {
    const int axis = int(i % std::size_t(channels));
    if (axis > 2) continue;
    const float extent = bounds.max[axis] - bounds.min[axis];
    values[i] = extent > 0.0f ? std::clamp((values[i] - bounds.min[axis]) / extent, 0.0f, 1.0f) : 0.0f;
  }
  return scaled.converted(type);
}

}  // namespace glint::bake

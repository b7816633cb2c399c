#include "glint/image/pattern.h"

#include "glint/core/error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace glint {
namespace {

// A 5×7 font: one byte per row, bit 4 = leftmost pixel.
struct Glyph {
  char c;
  std::array<std::uint8_t, 7> rows;
};

constexpr Glyph kFont[] = {
    {'A', {0x0E, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}}, {'B', {0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E}},
    {'C', {0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E}}, {'D', {0x1C, 0x12, 0x11, 0x11, 0x11, 0x12, 0x1C}},
    {'E', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F}}, {'F', {0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10}},
    {'G', {0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F}}, {'H', {0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11}},
    {'I', {0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E}}, {'J', {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C}},
    {'K', {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}}, {'L', {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F}},
    {'M', {0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11}}, {'N', {0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11}},
    {'O', {0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}}, {'P', {0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10}},
    {'Q', {0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D}}, {'R', {0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11}},
    {'S', {0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E}}, {'T', {0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}},
    {'U', {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E}}, {'V', {0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04}},
    {'W', {0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A}}, {'X', {0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11}},
    {'Y', {0x11, 0x11, 0x11, 0x0A, 0x04, 0x04, 0x04}}, {'Z', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F}},
    {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}}, {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
    {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}}, {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
    {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}}, {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
    {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}}, {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}}, {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
    {' ', {0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00}}, {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C}},
    {'-', {0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00}}, {':', {0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00}},
    {'/', {0x01, 0x02, 0x02, 0x04, 0x08, 0x08, 0x10}}, {'x', {0x00, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x00}},
};
constexpr std::array<std::uint8_t, 7> kBox = {0x1F, 0x11, 0x11, 0x11, 0x11, 0x11, 0x1F};

const std::array<std::uint8_t, 7>& glyphRows(char c) {
  if (c >= 'a' && c <= 'z' && c != 'x') c = char(c - 'a' + 'A');
  for (const auto& g : kFont)
    if (g.c == c) return g.rows;
  return kBox;
}

void fill(Image& img, int x0, int y0, int w, int h, vec3 color) {
  for (int y = std::max(0, y0); y < std::min(img.height(), y0 + h); ++y)
    for (int x = std::max(0, x0); x < std::min(img.width(), x0 + w); ++x)
      for (int c = 0; c < 3; ++c) img.set(x, y, c, color[c]);
}

Image opaque(int size) {
  Image img(size, size, 4);
  auto px = img.pixels<std::uint8_t>();
  for (std::size_t i = 3; i < px.size(); i += 4) px[i] = 255;
  return img;
}
}  // namespace

Image makeCheckerboard(int size, int checks, vec3 a, vec3 b) {
  if (checks <= 0 || size % checks) fail(ErrorKind::Usage, "checkerboard: {} checks do not divide {} texels", checks, size);
  Image img = opaque(size);
  const int cell = size / checks;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const vec3 c = ((x / cell + y / cell) % 2 == 0) ? a : b;
      for (int k = 0; k < 3; ++k) img.set(x, y, k, c[k]);
    }
  return img;
}

void drawText(Image& image, int x, int y, std::string_view text, int scale, vec3 color) {
  for (std::size_t i = 0; i < text.size(); ++i) {
    const auto& rows = glyphRows(text[i]);
    const int gx = x + int(i) * 6 * scale;
    for (int r = 0; r < 7; ++r)
      for (int col = 0; col < 5; ++col)
        if (rows[std::size_t(r)] & (0x10 >> col)) fill(image, gx + col * scale, y + r * scale, scale, scale, color);
  }
}

Image makeTestChart(int size) {
  if (size < 256) fail(ErrorKind::Usage, "test chart needs at least 256 texels, got {}", size);
  Image img = opaque(size);
  fill(img, 0, 0, size, size, vec3(0.96f));
  const vec3 ink(0.05f), blue(0.1f, 0.25f, 0.7f), red(0.7f, 0.12f, 0.1f);
  // Text from large to small: each line shows where a filter stops resolving letters.
  const int unit = size / 256;
  int y = 6 * unit;
  const struct {
    const char* text;
    int scale;
    vec3 color;
  } lines[] = {{"GLINT", 6, ink},      {"FILTERING", 4, blue},  {"ANISOTROPIC 16x", 3, red},
               {"TRILINEAR MIPMAP", 2, ink}, {"THE QUICK BROWN FOX", 2, blue}, {"JUMPS OVER THE LAZY DOG", 1, ink},
               {"0123456789 ABCDEFGHIJKLM", 1, red}, {"NOPQRSTUVWXYZ .-:/", 1, ink}};
  for (const auto& l : lines) {
    drawText(img, 6 * unit, y, l.text, l.scale * unit, l.color);
    y += (7 * l.scale + 3) * unit;
  }
  // Gratings: 1-, 2- and 4-texel lines, vertical and horizontal, in the lower part.
  const int gy = std::max(y + 4 * unit, size * 5 / 8);
  const int gh = size - gy - 8 * unit;
  for (int k = 0; k < 3; ++k) {
    const int period = 2 << k;  // line width period/2 texels
    const int x0 = 6 * unit + k * (size / 6);
    for (int x = 0; x < size / 8; ++x)
      if ((x % period) < period / 2) fill(img, x0 + x, gy, 1, gh / 2, ink);
    for (int yy = 0; yy < gh / 2; ++yy)
      if ((yy % period) < period / 2) fill(img, x0, gy + gh / 2 + yy, size / 8, 1, ink);
  }
  // Tile border: a 2-texel grid line on the left and top edges, so tiles read as a grid.
  fill(img, 0, 0, size, 2 * unit, blue);
  fill(img, 0, 0, 2 * unit, size, blue);
  return img;
}

Image makeZonePlate(int size) {
  Image image(size, size, 4);
  const float c = 0.5f * float(size);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const float dx = float(x) + 0.5f - c, dy = float(y) + 0.5f - c;
      // Local frequency k·r with k = 1/(√2·size): 0.5 cycles/pixel at the corners.
      const float v = 0.5f + 0.5f * std::cos(kPi * (dx * dx + dy * dy) / (std::sqrt(2.0f) * float(size)));
      for (int k = 0; k < 3; ++k) image.set(x, y, k, v);
      image.set(x, y, 3, 1.0f);
    }
  }
  return image;
}

Image makeRectangle(int size, int w, int h) {
  Image image(size, size, 4);
  const int x0 = (size - w) / 2, y0 = (size - h) / 2;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      const float v = x >= x0 && x < x0 + w && y >= y0 && y < y0 + h ? 1.0f : 0.0f;
      for (int k = 0; k < 3; ++k) image.set(x, y, k, v);
      image.set(x, y, 3, 1.0f);
    }
  }
  return image;
}

}  // namespace glint

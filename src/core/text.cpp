#include "glint/core/text.h"
#include "glint/core/json.h"

#include "glint/core/error.h"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>

namespace glint {

std::string escapeHtml(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

namespace {

/// Whole-text integer (optional '-'), false when anything is left over or it overflows.
bool wholeInt(std::string_view text, int& value) {
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && end == text.data() + text.size() && !text.empty();
}

}  // namespace

std::string printable(std::string_view text) {
  std::string out(text.substr(0, 200));
  for (char& c : out) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  return text.size() > 200 ? out + "..." : out;
}

namespace {
/// The length of the UTF-8 character at text[i], or 0 when the byte there does not start one.
std::size_t utf8Length(std::string_view text, std::size_t i) {
  const auto b = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char c = b(i);
  if (c < 0x80) return 1;
  std::size_t n = 0;
  unsigned min = 0;
  unsigned cp = 0;
  if ((c & 0xE0) == 0xC0) n = 2, min = 0x80, cp = c & 0x1F;
  else if ((c & 0xF0) == 0xE0) n = 3, min = 0x800, cp = c & 0x0F;
  else if ((c & 0xF8) == 0xF0) n = 4, min = 0x10000, cp = c & 0x07;
  else return 0;
  if (i + n > text.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    if ((b(i + k) & 0xC0) != 0x80) return 0;
    cp = cp << 6 | (b(i + k) & 0x3F);
  }
  if (cp < min || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;
  return n;
}
}  // namespace

std::size_t jsonDepth(std::string_view text) {
  std::size_t depth = 0, deepest = 0;
  bool inString = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      if (c == '\\') ++i;
      else if (c == '"') inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '{' || c == '[') {
      deepest = std::max(deepest, ++depth);
    } else if ((c == '}' || c == ']') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

bool isUtf8(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = utf8Length(text, i);
    if (n == 0) return false;
    i += n;
  }
  return true;
}

std::string escapedLine(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    const std::size_t n = utf8Length(text, i);
    if (n > 1) {
      out.append(text.substr(i, n));
      i += n;
      continue;
    }
    if (c == '\n') out += "\\n";
    else if (c == '\r') out += "\\r";
    else if (c == '\t') out += "\\t";
    else if (c < 0x20 || c == 0x7F || n == 0) out += fmt::format("\\x{:02x}", c);
    else out += char(c);
    ++i;
  }
  return out;
}

std::string utf8Escaped(std::string_view text) {
  if (isUtf8(text)) return std::string(text);
  std::string out;
  out.reserve(text.size() + 16);
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = utf8Length(text, i);
    const auto c = static_cast<unsigned char>(text[i]);
    if (n == 0 || c == '\\') {
      out += fmt::format("\\x{:02x}", c);
      ++i;
    } else {
      out.append(text.substr(i, n));
      i += n;
    }
  }
  return out;
}

std::vector<std::string_view> splitFields(std::string_view text, char separator) {
  std::vector<std::string_view> fields;
  for (std::size_t start = 0;;) {
    const std::size_t at = text.find(separator, start);
    fields.push_back(text.substr(start, at == std::string_view::npos ? std::string_view::npos : at - start));
    if (at == std::string_view::npos) return fields;
    start = at + 1;
  }
}

ivec2 parseSize(std::string_view text) {
  const std::size_t x = text.find_first_of("xX");
  int w = 0, h = 0;
  if (x == std::string_view::npos || !wholeInt(text.substr(0, x), w) || !wholeInt(text.substr(x + 1), h)) {
    fail(ErrorKind::Usage, "size must be WIDTHxHEIGHT (e.g. 640x360), got '{}'", printable(text));
  }
  return checkSize({w, h});
}

ivec2 checkSize(ivec2 size) {
  if (size.x < 1 || size.y < 1 || size.x > kMaxImageSide || size.y > kMaxImageSide) {
    fail(ErrorKind::Usage, "size {}x{} is out of range (1..{} per side)", size.x, size.y, kMaxImageSide);
  }
  return size;
}

float parseFloat(std::string_view text, std::string_view what) {
  std::string_view digits = text;
  if (digits.size() > 1 && digits.front() == '+' && digits[1] != '-') digits.remove_prefix(1);
  float value = 0.0f;
  // from_chars: the "C" locale always, no leading blanks, and "nan"/"inf" come out non-finite.
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  const bool whole = !digits.empty() && end == digits.data() + digits.size();
  if (whole && ec == std::errc::result_out_of_range) {  // "1e40": a number, too large (or small) for a float
    fail(ErrorKind::Usage, "{}: '{}' is out of range (beyond a float's ±3.4e38 or 1e-38)", what, printable(text));
  }
  if (!whole || ec != std::errc() || !std::isfinite(value)) {
    fail(ErrorKind::Usage, "{}: '{}' is not a finite number", what, printable(text));
  }
  return value;
}

int parseInt(std::string_view text, std::string_view what, int lo, int hi) {
  int value = 0;
  if (!wholeInt(text, value)) fail(ErrorKind::Usage, "{}: '{}' is not an integer", what, printable(text));
  if (value < lo || value > hi) fail(ErrorKind::Usage, "{}: {} is out of range ({}..{})", what, value, lo, hi);
  return value;
}

FrameRange parseFrameRange(std::string_view text, std::string_view what) {
  const auto colon = text.find(':');
  if (colon == std::string_view::npos) {
    fail(ErrorKind::Usage, "{} must be FIRST:END (e.g. 0:250 or 250:), got '{}'", what, printable(text));
  }
  const std::string numbers = fmt::format("{} (FIRST:END, frame numbers, END excluded)", what);
  const auto number = [&](std::string_view s, std::int64_t empty) -> std::int64_t {
    return s.empty() ? empty : parseInt(s, numbers, 0, INT_MAX);
  };
  return {number(text.substr(0, colon), 0), number(text.substr(colon + 1), -1)};
}

ShardSpec parseShard(std::string_view text, std::string_view what) {
  const std::size_t slash = text.find('/');
  ShardSpec part;
  if (slash == std::string_view::npos || !wholeInt(text.substr(0, slash), part.index) ||
      !wholeInt(text.substr(slash + 1), part.count) || part.index < 1 || part.index > part.count) {
    fail(ErrorKind::Usage, "{} must be i/n with 1 ≤ i ≤ n, got '{}'", what, printable(text));
  }
  return part;
}

double parseMemorySize(std::string_view text, std::string_view what) {
  std::string_view number = text;
  for (std::string_view suffix : {"iB", "B"}) {
    if (number.size() > suffix.size() && number.ends_with(suffix)) {
      number.remove_suffix(suffix.size());
      break;
    }
  }
  double scale = 1.0;  // MiB
  if (!number.empty()) {
    switch (number.back()) {
      case 'K': case 'k': scale = 1.0 / 1024.0; break;
      case 'M': case 'm': scale = 1.0; break;
      case 'G': case 'g': scale = 1024.0; break;
      case 'T': case 't': scale = 1024.0 * 1024.0; break;
      default: scale = 0.0;
    }
    if (scale != 0.0) number.remove_suffix(1);
    else scale = 1.0;
  }
  double value = 0.0;
  const auto [end, ec] = std::from_chars(number.data(), number.data() + number.size(), value);
  if (number.empty() || ec != std::errc() || end != number.data() + number.size() || !std::isfinite(value) || value <= 0.0) {
    fail(ErrorKind::Usage, "{}: '{}' is not a memory size (e.g. 4096 for MiB, 512M, 4G)", what, printable(text));
  }
  return value * scale;
}

vec3 parseVec3(std::string_view text, std::string_view what) {
  const auto fields = splitFields(text, ',');
  if (fields.size() != 3) fail(ErrorKind::Usage, "{} must be x,y,z, got '{}'", what, printable(text));
  return {parseFloat(fields[0], what), parseFloat(fields[1], what), parseFloat(fields[2], what)};
}

std::string shellWord(std::string_view word) {
  const bool safe = !word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                            "0123456789@%+=:,./_-") == std::string_view::npos;
  if (safe) return std::string(word);
  std::string quoted = "'";
  for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace glint

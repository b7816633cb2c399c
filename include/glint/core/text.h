#pragma once
// glint/core/text.h — escaping for the HTML pages glint writes (JSON goes through
// nlohmann-json), and strict parsers for the values users type on command lines.
//
// The parsers accept exactly the documented form and nothing around it (no spaces, no
// trailing text, no "nan" or "inf"), independent of the C locale, and fail with
// Error(Usage) whose one line quotes the text. They are fuzzed (fuzz/options.cpp).
//
//   const ivec2 size = parseSize("1920x1080");          // {1920, 1080}
//   const float f = parseFloat("0.25", "--exposure");    // 0.25
//   const vec3 p = parseVec3("1,2.5,-3", "--light");     // {1, 2.5, -3}
//   const double mib = parseMemorySize("4G", "--max-memory");  // 4096

#include "glint/core/math.h"

#include <string>
#include <string_view>
#include <vector>

namespace glint {

/// Escapes &, <, >, " for HTML text and attribute values.
std::string escapeHtml(std::string_view text);

/// `text` for a one-line message: control characters shown as '?', cut after 200 characters.
std::string printable(std::string_view text);

/// Largest width or height parseSize accepts (also GL's usual texture limit).
constexpr int kMaxImageSide = 16384;

/// "WIDTHxHEIGHT" (or "WIDTHXHEIGHT"), each side 1..kMaxImageSide.
ivec2 parseSize(std::string_view text);

/// A finite decimal number ("1", "-0.5", "2e-3"; a leading '+' allowed). `what` names the
/// option in the error ("--light", "option 'i'"); a number a float cannot hold ("1e40") is
/// refused as out of range.
float parseFloat(std::string_view text, std::string_view what);

/// An integer in [lo, hi].
int parseInt(std::string_view text, std::string_view what, int lo, int hi);

/// A memory size in MiB: "4096" (MiB), "512M", "1.5G", "2T" (binary units; a trailing
/// "iB" or "B" is allowed: "4GiB"). Positive and finite.
double parseMemorySize(std::string_view text, std::string_view what);

/// "x,y,z": three finite numbers.
vec3 parseVec3(std::string_view text, std::string_view what);

/// The fields between separators ("a,,b" → {"a", "", "b"}; "" → {""}).
std::vector<std::string_view> splitFields(std::string_view text, char separator);

}  // namespace glint

#pragma once
// glint/core/text.h — escaping for the HTML pages glint writes (JSON goes through
// nlohmann-json), and strict parsers for the values users type on command lines.
//
// The parsers accept exactly the documented form and nothing around it (no spaces, no
// trailing text, no "nan" or "inf"), independent of the C locale, and fail with
// Error(Usage) whose one line quotes the text. They are fuzzed (fuzz/options.cpp).
//
/// ```cpp run
/// const glint::ivec2 size = glint::parseSize("1920x1080");                // {1920, 1080}
/// const float f = glint::parseFloat("0.25", "--exposure");                 // 0.25
/// const int n = glint::parseInt("8", "--threads", 1, 256);                 // 8
/// const glint::vec3 p = glint::parseVec3("1,2.5,-3", "--light");           // {1, 2.5, -3}
/// const double mib = glint::parseMemorySize("4G", "--max-memory");         // 4096
/// const auto fields = glint::splitFields("a,,b", ',');                     // {"a", "", "b"}
/// const glint::FrameRange part = glint::parseFrameRange("150:300", "--frames");  // {150, 300}
/// ```

#include "glint/core/math.h"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace glint {

/// Escapes &, <, >, " for HTML text and attribute values.
std::string escapeHtml(std::string_view text);

/// `text` for a one-line message: control characters shown as '?', cut after 200 characters.
std::string printable(std::string_view text);

/// `text` on one line, nothing lost: control characters as escapes ("\n", "\t", "\x1b"),
/// and bytes that are not part of a UTF-8 character as "\xNN"; valid UTF-8 is kept.
/// Every message glint prints goes through it (errors, warnings, Python's exceptions), so
/// a file name with a line break in it still makes one line.
std::string escapedLine(std::string_view text);

/// `text` as valid UTF-8, nothing lost: unchanged when it is UTF-8; otherwise each byte that
/// is not part of a UTF-8 character is written "\xNN", and each backslash "\x5c", so
/// the original bytes can be recovered. For file names in JSON reports (a name on Linux is
/// any bytes; JSON text is UTF-8).
std::string utf8Escaped(std::string_view text);

/// Whether `text` is valid UTF-8 (no overlong forms, no surrogates, at most U+10FFFF).
bool isUtf8(std::string_view text);

/// Largest width or height parseSize accepts (also GL's usual texture limit).
constexpr int kMaxImageSide = 16384;

/// "WIDTHxHEIGHT" (or "WIDTHXHEIGHT"), each side 1..kMaxImageSide (checkSize).
ivec2 parseSize(std::string_view text);

/// Error(Usage) "size WxH is out of range (1..16384 per side)" unless each side is in
/// 1..kMaxImageSide: the rule every front end applies to a size (--size, glint.render).
ivec2 checkSize(ivec2 size);

/// A finite decimal number ("1", "-0.5", "2e-3"; a leading '+' allowed). `what` names the
/// option in the error ("--light", "option 'i'"); a number a float cannot hold ("1e40") is
/// refused as out of range.
float parseFloat(std::string_view text, std::string_view what);

/// An integer in [lo, hi].
int parseInt(std::string_view text, std::string_view what, int lo, int hi);

/// A memory size in MiB: "4096" (MiB), "512M", "1.5G", "2T" (binary units; a trailing
/// "iB" or "B" is allowed: "4GiB"). Positive and finite.
double parseMemorySize(std::string_view text, std::string_view what);

/// One part of a job split `count` ways: `--shard index/count`, 1 ≤ index ≤ count.
struct ShardSpec {
  int index = 1;
  int count = 1;
};

/// "i/n": two integers (parseInt's form: no spaces, no '+') with 1 ≤ i ≤ n. Error(Usage)
/// "<what> must be i/n with 1 ≤ i ≤ n, got '<text>'" for anything else.
ShardSpec parseShard(std::string_view text, std::string_view what);

/// Frames [first, end) of a video, `--frames FIRST:END` (`glint post`, `glint render`):
/// END is excluded; `end` −1 means "to the end" (the text "250:").
struct FrameRange {
  std::int64_t first = 0;
  std::int64_t end = -1;
};

/// "a:b", "a:" (to the end) or ":b" (from frame 0): whole numbers 0..INT_MAX, no signs or
/// spaces. Error(Usage) naming `what` otherwise. Whether the range may be open or empty is
/// the caller's to check (glint render needs an END after FIRST).
FrameRange parseFrameRange(std::string_view text, std::string_view what);

/// `word` as one POSIX shell word: unchanged when it is made of safe characters (letters,
/// digits, @%+=:,./_-), else in single quotes ("it's" → 'it'\''s'). For printed command
/// lines (`glint bake --batch --list`) and generated scripts (`glint farm`).
std::string shellWord(std::string_view word);

/// "x,y,z": three finite numbers.
vec3 parseVec3(std::string_view text, std::string_view what);

/// The fields between separators ("a,,b" → {"a", "", "b"}; "" → {""}).
std::vector<std::string_view> splitFields(std::string_view text, char separator);

}  // namespace glint

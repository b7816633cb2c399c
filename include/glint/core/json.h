#pragma once
// glint/core/json.h — the JSON text glint writes (reports, farm records, the gallery's index):
// a file name on Linux is any bytes, JSON text is UTF-8, and nlohmann-json refuses to write a
// string that is not (type_error.316). jsonText writes every string and key through
// utf8Escaped (core/text.h): unchanged when UTF-8, else each stray byte as "\xNN" (and each
// backslash as "\x5c"), so a report about a file named in Latin-1 is written, and the name
// can be recovered from it.
//
/// ```cpp run
/// nlohmann::json report = {{"output", "caf\xe9.png"}, {"size", 64}};  // Latin-1 é
/// const std::string text = glint::jsonText(report);                   // "caf\\xe9.png"
/// ```
#include "glint/core/error.h"
#include "glint/core/text.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <string>
#include <string_view>

namespace glint {

/// The deepest nesting of arrays and objects glint parses from a file: a glTF needs about
/// 10 levels, a batch file 3. Deeper JSON is refused before it is parsed, because writing it
/// out again (an error message quoting a value) or walking it recurses once per level.
inline constexpr std::size_t kMaxJsonDepth = 64;

/// The deepest nesting of arrays and objects in JSON text (strings skipped), in one pass.
std::size_t jsonDepth(std::string_view text);

/// JSON text from a file (`what`: "bake: jobs.json"), checked: Error(`kind`), one line, for
/// nesting deeper than kMaxJsonDepth or text that does not parse (with the parser's reason).
template <class Json = nlohmann::json>
Json parseJson(std::string_view text, const std::string& what, ErrorKind kind = ErrorKind::Input) {
  if (jsonDepth(text) > kMaxJsonDepth) fail(kind, "{}: JSON nested deeper than {} levels", what, kMaxJsonDepth);
  try {
    return Json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // parse_error, or out_of_range for a number past a double (1e999)
    // "[json.exception.parse_error.101] parse error at line 3, column 5: syntax error ..."
    std::string why = e.what();
    if (const auto end = why.find("] "); why.starts_with("[json.exception") && end != std::string::npos) why.erase(0, end + 2);
    fail(kind, "{}: not valid JSON: {}", what, printable(why));
  }
}

namespace detail {
template <class Json>
Json utf8Strings(const Json& value) {
  if (value.is_string()) return Json(utf8Escaped(value.template get_ref<const std::string&>()));
  if (value.is_array()) {
    Json out = Json::array();
    for (const auto& item : value) out.push_back(utf8Strings(item));
    return out;
  }
  if (value.is_object()) {
    Json out = Json::object();
    for (auto it = value.begin(); it != value.end(); ++it) out[utf8Escaped(it.key())] = utf8Strings(it.value());
    return out;
  }
  return value;
}
}  // namespace detail

/// `value` as JSON text (`indent` < 0: one line), every string valid UTF-8 as above, ending
/// with a newline when indented.
template <class Json>
std::string jsonText(const Json& value, int indent = 2) {
  const std::string text = detail::utf8Strings(value).dump(indent);
  return indent >= 0 ? text + "\n" : text;
}

}  // namespace glint

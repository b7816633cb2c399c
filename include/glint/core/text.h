#pragma once
// glint/core/text.h — escaping for the HTML pages glint writes (JSON goes through nlohmann-json).

#include <string>
#include <string_view>

namespace glint {

/// Escapes &, <, >, " for HTML text and attribute values.
std::string escapeHtml(std::string_view text);

}  // namespace glint

#pragma once
// glint/core/text.h — escaping for the small JSON and HTML reports glint writes.

#include <string>
#include <string_view>

namespace glint {

/// Escapes a string for a JSON string literal (quotes, backslashes, control characters).
std::string escapeJson(std::string_view text);
/// Escapes &, <, >, " for HTML text and attribute values.
std::string escapeHtml(std::string_view text);

}  // namespace glint

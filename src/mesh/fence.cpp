// What a model file may reference (mesh/fence.h).
#include "glint/mesh/fence.h"

#include "glint/core/error.h"
#include "glint/core/text.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <fstream>

namespace glint {
namespace fs = std::filesystem;

namespace {

int hexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

/// RFC 3986's scheme: a letter, then letters, digits, '+', '-' or '.', then ':'.
bool hasScheme(std::string_view uri) {
  const std::size_t colon = uri.find(':');
  if (colon == std::string_view::npos || colon == 0) return false;
  const auto letter = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); };
  if (!letter(uri[0])) return false;
  for (std::size_t i = 1; i < colon; ++i) {
    const char c = uri[i];
    if (!letter(c) && !(c >= '0' && c <= '9') && c != '+' && c != '-' && c != '.') return false;
  }
  return true;
}

/// Whether `path` (canonical) is `folder` (canonical) or lies under it.
bool inside(const fs::path& path, const fs::path& folder) {
  auto p = path.begin();
  for (auto f = folder.begin(); f != folder.end(); ++f, ++p) {
    if (f->empty()) continue;  // a trailing separator
    if (p == path.end() || *p != *f) return false;
  }
  return true;
}

}  // namespace

std::string percentDecode(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '%') {
      out += text[i];
      continue;
    }
    const int hi = i + 2 < text.size() ? hexDigit(text[i + 1]) : -1;
    const int lo = i + 2 < text.size() ? hexDigit(text[i + 2]) : -1;
    if (hi < 0 || lo < 0) fail(ErrorKind::Input, "'{}' has a '%' that is not followed by two hex digits", printable(text));
    out += char(hi * 16 + lo);
    i += 2;
  }
  return out;
}

bool isDataUri(std::string_view uri) {
  return uri.size() >= 5 && (uri.substr(0, 5) == "data:" || uri.substr(0, 5) == "DATA:" || uri.substr(0, 5) == "Data:");
}

std::vector<unsigned char> decodeDataUri(std::string_view uri, std::string& mediaType, std::uint64_t maxBytes) {
  if (!isDataUri(uri)) fail(ErrorKind::Input, "'{}...' is not a data: URI", printable(uri.substr(0, 40)));
  const std::size_t comma = uri.find(',');
  if (comma == std::string_view::npos) fail(ErrorKind::Input, "a data: URI without a ',' before its data");
  std::string_view header = uri.substr(5, comma - 5);
  const std::string_view data = uri.substr(comma + 1);
  bool base64 = false;
  if (header.size() >= 7 && header.substr(header.size() - 7) == ";base64") {
    base64 = true;
    header.remove_suffix(7);
  }
  mediaType = std::string(header.substr(0, header.find(';')));
  if (mediaType.empty()) mediaType = "text/plain";
  std::vector<unsigned char> out;
  if (!base64) {
    if (data.size() > maxBytes * 3) fail(ErrorKind::Input, "a data: URI larger than glint reads ({} MiB)", maxBytes >> 20);
    const std::string decoded = percentDecode(data);
    if (decoded.size() > maxBytes) fail(ErrorKind::Input, "a data: URI larger than glint reads ({} MiB)", maxBytes >> 20);
    return {decoded.begin(), decoded.end()};
  }
  if (data.size() / 4 * 3 > maxBytes) fail(ErrorKind::Input, "a data: URI larger than glint reads ({} MiB)", maxBytes >> 20);
  out.reserve(data.size() / 4 * 3);
  std::uint32_t bits = 0;
  int count = 0;
  std::size_t padding = 0;
  for (std::size_t i = 0; i < data.size(); ++i) {
    const char c = data[i];
    int v;
    if (c >= 'A' && c <= 'Z') v = c - 'A';
    else if (c >= 'a' && c <= 'z') v = c - 'a' + 26;
    else if (c >= '0' && c <= '9') v = c - '0' + 52;
    else if (c == '+' || c == '-') v = 62;  // base64 and base64url
    else if (c == '/' || c == '_') v = 63;
    else if (c == '=') {
      ++padding;
      continue;
    } else {
      fail(ErrorKind::Input, "a data: URI's base64 has a character that is not base64 ('{}' at {})", printable(std::string(1, c)), i);
    }
    if (padding) fail(ErrorKind::Input, "a data: URI's base64 has data after its '=' padding");
    bits = bits << 6 | std::uint32_t(v);
    if (++count == 4) {
      out.push_back((unsigned char)(bits >> 16));
      out.push_back((unsigned char)(bits >> 8));
      out.push_back((unsigned char)bits);
      bits = 0;
      count = 0;
    }
  }
  if (count == 1 || padding > 2) fail(ErrorKind::Input, "a data: URI's base64 is cut short");
  if (count == 2) out.push_back((unsigned char)(bits >> 4));
  if (count == 3) {
    out.push_back((unsigned char)(bits >> 10));
    out.push_back((unsigned char)(bits >> 2));
  }
  return out;
}

ModelFence::ModelFence(const fs::path& modelFile) : m_model(modelFile) {
  std::error_code ec;
  const fs::path folder = modelFile.has_parent_path() ? modelFile.parent_path() : fs::path(".");
  m_folder = fs::canonical(folder, ec);
  if (ec) fail(ErrorKind::Input, "cannot read '{}': its folder: {}", printable(modelFile.string()), ec.message());
}

fs::path ModelFence::resolve(std::string_view reference, std::string_view what) const {
  const auto refuse = [&](std::string_view why) {
    fail(ErrorKind::Input, "'{}': {}'s uri '{}' {}; a model may only reference files in its own folder", printable(m_model.string()),
         what, printable(reference), why);
  };
  if (reference.empty()) refuse("is empty");
  if (hasScheme(reference)) refuse("has a scheme (only data: URIs are read)");
  const std::string decoded = percentDecode(reference);
  if (decoded.find('\0') != std::string::npos) refuse("holds a NUL");
  const fs::path relative(decoded);
  if (relative.is_absolute() || decoded.front() == '/') refuse("is an absolute path");
  const fs::path normal = relative.lexically_normal();
  if (!normal.empty() && *normal.begin() == "..") refuse("leaves the folder");
  if (normal.empty() || normal == ".") refuse("names the folder, not a file");
  std::error_code ec;
  const fs::path joined = m_folder / normal;
  const fs::path real = fs::canonical(joined, ec);
  if (ec) refuse(fmt::format("cannot be read ({})", ec == std::errc::no_such_file_or_directory ? "no such file" : ec.message()));
  if (!inside(real, m_folder)) refuse("leaves the folder through a symbolic link");
  if (!fs::is_regular_file(real, ec)) refuse("is not a regular file");
  return real;
}

bool ModelFence::allows(const fs::path& path) const {
  // Links in the part that exists are resolved; a missing file inside the folder is
  // allowed (opening it then fails as for any missing file).
  std::error_code ec;
  const fs::path real = fs::weakly_canonical(fs::absolute(path, ec), ec);
  if (ec) return false;
  return inside(real, m_folder);
}

std::vector<unsigned char> ModelFence::read(const fs::path& resolved, std::string_view what) const {
  const std::string name = printable(m_model.string());
  std::error_code ec;
  if (!allows(resolved) || !fs::is_regular_file(resolved, ec))
    fail(ErrorKind::Input, "'{}': {} '{}' is not a file in the model's folder", name, what, printable(resolved.string()));
  std::ifstream in(resolved, std::ios::binary);
  struct stat st{};
  if (!in || ::stat(resolved.c_str(), &st) != 0)
    fail(ErrorKind::Input, "'{}': cannot read {} '{}': {}", name, what, printable(resolved.filename().string()), std::strerror(errno));
  if (std::uint64_t(st.st_size) > kMaxReferencedBytes)
    fail(ErrorKind::Input, "'{}': {} '{}' is larger than glint reads ({} GiB)", name, what, printable(resolved.filename().string()),
         kMaxReferencedBytes >> 30);
  std::vector<unsigned char> bytes(std::size_t(st.st_size));
  in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(bytes.size()));
  if (std::size_t(in.gcount()) != bytes.size())
    fail(ErrorKind::Input, "'{}': cannot read {} '{}': it changed while being read", name, what, printable(resolved.filename().string()));
  return bytes;
}

}  // namespace glint

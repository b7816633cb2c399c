#pragma once
// The cutter's two binary files, shard files (shard.cpp) and cached cuts (cache.cpp):
// plain values in the machine's (little-endian) order, arrays and strings after their
// uint64 length. The reader checks every length against what is left of the file before
// it allocates, so a damaged file is one Error(Input), never a huge allocation or a read
// past the end (fuzz/cut_files.cpp feeds it damaged shards).
#include "glint/core/error.h"

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace glint::cut::detail {

class BinaryWriter {
public:
  template <typename T>
  void pod(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    m_data.append(reinterpret_cast<const char*>(&v), sizeof(T));
  }
  template <typename T>
  void array(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    pod(std::uint64_t(v.size()));
    m_data.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void string(std::string_view s) {
    pod(std::uint64_t(s.size()));
    m_data.append(s);
  }
  const std::string& data() const { return m_data; }

private:
  std::string m_data;
};

class BinaryReader {
public:
  /// `file` names the file in errors: "{file}: {why}", e.g. "'a.shard' is not a usable cut shard".
  BinaryReader(std::string data, std::string file) : m_data(std::move(data)), m_file(std::move(file)) {}

  template <typename T>
  T pod() {
    static_assert(std::is_trivially_copyable_v<T>);
    need(sizeof(T));
    T v;
    std::memcpy(&v, m_data.data() + m_pos, sizeof(T));
    m_pos += sizeof(T);
    return v;
  }
  template <typename T>
  std::vector<T> array() {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto n = pod<std::uint64_t>();
    if (n > (m_data.size() - m_pos) / sizeof(T)) bad("truncated or corrupt");
    std::vector<T> v(n);
    if (n > 0) std::memcpy(v.data(), m_data.data() + m_pos, n * sizeof(T));  // an empty vector's data() may be null
    m_pos += n * sizeof(T);
    return v;
  }
  std::string string() {
    const auto n = pod<std::uint64_t>();
    need(n);
    std::string s(m_data.data() + m_pos, n);
    m_pos += n;
    return s;
  }
  bool atEnd() const { return m_pos == m_data.size(); }
  /// Error(Input): "{file}: {why}".
  [[noreturn]] void bad(std::string_view why) const { fail(ErrorKind::Input, "{}: {}", m_file, why); }

private:
  void need(std::uint64_t n) const {
    if (n > m_data.size() - m_pos) bad("truncated or corrupt");
  }
  std::string m_data;
  std::string m_file;
  std::size_t m_pos = 0;
};

}  // namespace glint::cut::detail

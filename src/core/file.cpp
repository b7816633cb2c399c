#include "glint/core/file.h"

#include "glint/core/error.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <utility>

namespace glint {
namespace fs = std::filesystem;

namespace {
fs::path temporarySibling(const fs::path& destination) {
  static std::atomic<unsigned> counter{0};
  const auto name = fmt::format(".{}.tmp{}-{}{}", destination.stem().string(), getpid(),
                                counter.fetch_add(1), destination.extension().string());
  return destination.parent_path() / name;
}
}  // namespace

void checkWritable(const fs::path& destination) {
  const fs::path dir = destination.parent_path().empty() ? fs::path(".") : destination.parent_path();
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    fail(ErrorKind::Output, "cannot write '{}': directory '{}' does not exist", destination.string(),
         dir.string());
  }
  if (access(dir.c_str(), W_OK) != 0) {
    fail(ErrorKind::Output, "cannot write '{}': directory '{}' is not writable", destination.string(),
         dir.string());
  }
  if (fs::is_directory(destination, ec)) {
    fail(ErrorKind::Output, "cannot write '{}': it is a directory", destination.string());
  }
}

void writeAtomically(const fs::path& destination, const std::function<void(const fs::path&)>& write) {
  checkWritable(destination);
  const fs::path tmp = temporarySibling(destination);
  try {
    write(tmp);
    std::error_code ec;
    fs::rename(tmp, destination, ec);
    if (ec) fail(ErrorKind::Output, "cannot write '{}': {}", destination.string(), ec.message());
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw;
  }
}

AtomicFile::AtomicFile(const fs::path& destination)
    : m_destination(destination), m_temporary(temporarySibling(destination)) {
  checkWritable(destination);
}

AtomicFile::~AtomicFile() {
  if (m_committed || m_temporary.empty()) return;
  std::error_code ignored;
  fs::remove(m_temporary, ignored);
}

AtomicFile::AtomicFile(AtomicFile&& other) noexcept
    : m_destination(std::move(other.m_destination)), m_temporary(std::exchange(other.m_temporary, {})),
      m_committed(other.m_committed) {}

void AtomicFile::commit() {
  std::error_code ec;
  fs::rename(m_temporary, m_destination, ec);
  if (ec) fail(ErrorKind::Output, "cannot write '{}': {}", m_destination.string(), ec.message());
  m_committed = true;
}

void writeTextAtomically(const fs::path& destination, std::string_view contents) {
  writeAtomically(destination, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    out.close();
    if (!out) fail(ErrorKind::Output, "cannot write '{}': {}", destination.string(), std::strerror(errno));
  });
}

std::string readTextFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(ErrorKind::Input, "cannot read '{}': {}", path.string(), std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace glint

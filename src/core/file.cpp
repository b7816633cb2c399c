#include "glint/core/file.h"

#include "glint/core/error.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <charconv>
#include <mutex>
#include <set>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <utility>

namespace glint {
namespace fs = std::filesystem;

namespace {
// Temporary files are named ".<stem>.tmp<pid>-<n><extension>": hidden, saying what they
// are, and naming the process that writes them.
fs::path temporarySibling(const fs::path& destination) {
  static std::atomic<unsigned> counter{0};
  const auto name = fmt::format(".{}.tmp{}-{}{}", destination.stem().string(), getpid(),
                                counter.fetch_add(1), destination.extension().string());
  return destination.parent_path() / name;
}

/// The writer's process id in a temporary file's name, or 0 when it is not one of ours.
pid_t temporaryOwner(const std::string& name) {
  if (name.size() < 2 || name[0] != '.') return 0;
  const std::size_t tmp = name.rfind(".tmp");
  if (tmp == std::string::npos || tmp == 0) return 0;
  const char* first = name.data() + tmp + 4;
  const char* last = name.data() + name.size();
  long pid = 0;
  const auto [end, ec] = std::from_chars(first, last, pid);
  if (ec != std::errc() || end == first || end == last || *end != '-' || pid <= 0) return 0;
  return pid_t(pid);
}

/// Removes temporaries that a killed glint left in `dir` (kill -9, a crash, a power cut
/// mid-write): files named as temporarySibling names them whose process no longer
/// exists. Once per directory per process; a file it cannot remove stays, clearly named.
void removeStaleTemporaries(const fs::path& dir) {
  static std::mutex mutex;
  static std::set<fs::path> cleaned;
  {
    const std::lock_guard lock(mutex);
    if (!cleaned.insert(dir).second) return;
  }
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const pid_t owner = temporaryOwner(it->path().filename().string());
    if (owner == 0 || owner == getpid()) continue;
    if (::kill(owner, 0) == 0 || errno != ESRCH) continue;  // alive (or not ours to ask)
    std::error_code ignored;
    if (it->is_regular_file(ignored)) fs::remove(it->path(), ignored);
  }
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
  removeStaleTemporaries(destination.parent_path().empty() ? fs::path(".") : destination.parent_path());
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
  removeStaleTemporaries(destination.parent_path().empty() ? fs::path(".") : destination.parent_path());
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

// Cached files (core/cache.h): flock() serialises builders across processes; the atomic
// rename of core/file.h makes a present file a complete one.
#include "glint/core/cache.h"

#include "glint/core/error.h"
#include "glint/core/file.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <utility>

namespace glint {
namespace fs = std::filesystem;

namespace {
fs::path fromEnvironment(const char* variable) {
  const char* value = std::getenv(variable);
  return value && *value ? fs::path(value) : fs::path();
}

/// An exclusive flock() held for the object's lifetime. The kernel drops it when the
/// process dies, so a killed builder never leaves the others waiting.
class FileLock {
public:
  explicit FileLock(const fs::path& path) {
    m_fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (m_fd < 0) fail(ErrorKind::Output, "cannot lock '{}': {}", path.string(), std::strerror(errno));
    while (::flock(m_fd, LOCK_EX) != 0) {
      if (errno == EINTR) continue;
      const int error = errno;
      ::close(m_fd);
      fail(ErrorKind::Output, "cannot lock '{}': {}", path.string(), std::strerror(error));
    }
  }
  ~FileLock() {
    ::flock(m_fd, LOCK_UN);
    ::close(m_fd);
  }
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;

private:
  int m_fd = -1;
};
}  // namespace

fs::path cacheDirectory() {
  if (fs::path dir = fromEnvironment("GLINT_CACHE_DIR"); !dir.empty()) return dir;
  if (fs::path dir = fromEnvironment("XDG_CACHE_HOME"); !dir.empty()) return dir / "glint";
  if (fs::path home = fromEnvironment("HOME"); !home.empty()) return home / ".cache" / "glint";
  std::error_code ec;
  return fs::temp_directory_path(ec) / "glint-cache";
}

/// The identity of a file (inode and change time); {0, 0} when there is none. An atomic
/// rename over it gives a new inode, so two identities differ when the file was replaced.
static std::pair<ino_t, long long> identity(const fs::path& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return {0, 0};
  return {st.st_ino, (long long)st.st_ctim.tv_sec * 1000000000LL + st.st_ctim.tv_nsec};
}

CacheEntry cachedFile(const fs::path& directory, const std::string& name, const std::function<void(const fs::path&)>& build,
                      bool rebuild) {
  const fs::path path = directory / name;
  std::error_code ec;
  if (!rebuild && fs::is_regular_file(path, ec)) return {path, false};
  const auto seen = identity(path);  // the file the caller found bad, when rebuilding
  fs::create_directories(directory, ec);
  if (ec && !fs::is_directory(directory)) {
    fail(ErrorKind::Output, "cannot create the cache directory '{}': {}", directory.string(), ec.message());
  }
  const FileLock lock(directory / (name + ".lock"));
  // Another process may have built it while this one waited for the lock: a file is there
  // and (when rebuilding) it is not the one the caller found bad.
  if (fs::is_regular_file(path, ec) && (!rebuild || identity(path) != seen)) return {path, false};
  writeAtomically(path, build, Commit::Now);  // read back by the caller at once
  return {path, true};
}

}  // namespace glint

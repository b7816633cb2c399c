#include "glint/core/file.h"

#include "glint/core/error.h"

#include <signal.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
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

std::string lowerExtension(const fs::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

// ---------------------------------------------------------------------------- output sets

std::string fitFileName(const fs::path& dir, std::string stem, std::string_view tail, std::size_t reserved) {
  const long limit = ::pathconf(dir.empty() ? "." : dir.c_str(), _PC_NAME_MAX);
  const std::size_t nameMax = limit > 0 ? std::size_t(limit) : 255;
  std::string end(tail);
  if (reserved + end.size() > nameMax) end.resize(nameMax > reserved ? nameMax - reserved : 0);
  const std::size_t room = nameMax - reserved - end.size();
  if (stem.size() > room) {
    std::size_t cut = room;
    while (cut > 0 && (static_cast<unsigned char>(stem[cut]) & 0xC0) == 0x80) --cut;  // not inside a UTF-8 character
    stem.resize(cut);
  }
  return stem + end;
}

namespace {
// Temporary files are named ".<stem>.tmp<pid>-<n><extension>": hidden, saying what they
// are, and naming the process that writes them; the stem shortened as fitFileName says.
fs::path temporarySibling(const fs::path& destination) {
  static std::atomic<unsigned> counter{0};
  const fs::path dir = destination.parent_path();
  return dir / ("." + fitFileName(dir, destination.stem().string(),
                                  fmt::format(".tmp{}-{}{}", getpid(), counter.fetch_add(1), destination.extension().string()), 1));
}

}  // namespace

struct OutputSet::Impl {
  struct Staged {
    fs::path destination;  ///< as written
    fs::path key;          ///< absolute, normalized
    fs::path temporary;
  };
  std::mutex mutex;
  std::vector<Staged> staged;
  std::vector<fs::path> createdDirectories;  ///< by createOutputDirectories, outermost first
  Impl* previous = nullptr;  ///< the set that was open before this one

  /// Removes the folders this run made, innermost first, where they are empty again.
  void removeCreatedDirectories() {
    for (auto it = createdDirectories.rbegin(); it != createdDirectories.rend(); ++it) {
      std::error_code ignored;
      fs::remove(*it, ignored);  // only an empty directory goes
    }
    createdDirectories.clear();
  }
};

namespace {
std::mutex g_setsMutex;
OutputSet::Impl* g_openSet = nullptr;  ///< the innermost open set

fs::path keyOf(const fs::path& p) {
  std::error_code ec;
  const fs::path a = fs::absolute(p, ec);
  return (ec ? p : a).lexically_normal();
}

/// Stages `temporary` (complete) for `destination` in the open set; false when none is open.
bool stageInOpenSet(const fs::path& destination, const fs::path& temporary) {
  const std::lock_guard lock(g_setsMutex);
  if (!g_openSet) return false;
  const std::lock_guard setLock(g_openSet->mutex);
  const fs::path key = keyOf(destination);
  for (auto& s : g_openSet->staged) {
    if (s.key != key) continue;
    std::error_code ignored;  // written twice in one run: the later file wins
    fs::remove(s.temporary, ignored);
    s.temporary = temporary;
    return true;
  }
  g_openSet->staged.push_back({destination, key, temporary});
  return true;
}

/// Whether the filesystem holding `path`'s folder is (nearly) full: under 64 KiB for us.
bool filesystemFull(const fs::path& path) {
  const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  struct statvfs st {};
  if (::statvfs(dir.c_str(), &st) != 0) return false;
  return double(st.f_bavail) * double(st.f_frsize) < 64.0 * 1024.0;
}
}  // namespace

std::string writeFailure(const fs::path& destination, int error) {
  const fs::path dir = destination.parent_path().empty() ? fs::path(".") : destination.parent_path();
  if (error == ENOSPC || error == EDQUOT || filesystemFull(destination)) {
    struct statvfs st {};
    const bool known = ::statvfs(dir.c_str(), &st) == 0;
    const double freeKiB = known ? double(st.f_bavail) * double(st.f_frsize) / 1024.0 : 0.0;
    return fmt::format("no space left on device{}", known ? fmt::format(" ({:.0f} KiB free on its filesystem)", freeKiB) : "");
  }
  return error ? std::string(std::strerror(error)) : std::string("write error");
}

OutputSet::OutputSet() : m_impl(std::make_unique<Impl>()) {
  const std::lock_guard lock(g_setsMutex);
  m_impl->previous = g_openSet;
  g_openSet = m_impl.get();
}

OutputSet::~OutputSet() {
  {
    const std::lock_guard lock(g_setsMutex);
    // Unlink this set from the chain (sets close in the reverse order of opening, but be safe).
    if (g_openSet == m_impl.get()) {
      g_openSet = m_impl->previous;
    } else {
      for (Impl* s = g_openSet; s; s = s->previous)
        if (s->previous == m_impl.get()) s->previous = m_impl->previous;
    }
  }
  discard();
}

void OutputSet::discard() {
  const std::lock_guard lock(m_impl->mutex);
  for (const auto& s : m_impl->staged) {
    std::error_code ignored;
    fs::remove(s.temporary, ignored);
  }
  m_impl->staged.clear();
  m_impl->removeCreatedDirectories();
}

void createOutputDirectories(const fs::path& dir) {
  // The folders that do not exist yet, outermost first.
  std::vector<fs::path> missing;
  std::error_code ec;
  for (fs::path p = fs::absolute(dir, ec).lexically_normal(); !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
    missing.insert(missing.begin(), p);
    if (p == p.parent_path()) break;
  }
  for (const fs::path& p : missing) {
    if (!fs::create_directory(p, ec) && ec)
      fail(ErrorKind::Output, "cannot make the folder '{}': {}", p.string(), writeFailure(p / "x", ec.value()));
    const std::lock_guard lock(g_setsMutex);
    if (g_openSet) {
      const std::lock_guard setLock(g_openSet->mutex);
      g_openSet->createdDirectories.push_back(p);
    }
  }
}

bool OutputSet::staged(const fs::path& destination) const {
  const std::lock_guard lock(m_impl->mutex);
  const fs::path key = keyOf(destination);
  for (const auto& s : m_impl->staged)
    if (s.key == key) return true;
  return false;
}

void OutputSet::redirect(const fs::path& destination, const fs::path& other) {
  const std::lock_guard lock(m_impl->mutex);
  const fs::path key = keyOf(destination);
  for (auto& s : m_impl->staged) {
    if (s.key != key) continue;
    // The temporary sits beside `destination`; `other` is a name in the same folder.
    s.destination = other;
    s.key = keyOf(other);
    return;
  }
  fail(ErrorKind::Internal, "OutputSet::redirect: nothing staged for '{}'", destination.string());
}

void OutputSet::commit() {
  const std::lock_guard lock(m_impl->mutex);
  auto& staged = m_impl->staged;
  // Keep each file about to be replaced as a hard link, so a failed rename can put it back.
  std::vector<fs::path> backups(staged.size());
  for (std::size_t i = 0; i < staged.size(); ++i) {
    struct stat st {};
    if (::lstat(staged[i].destination.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) continue;
    const fs::path backup = temporarySibling(staged[i].destination);
    if (::link(staged[i].destination.c_str(), backup.c_str()) == 0) backups[i] = backup;
  }
  const auto removeAll = [](const std::vector<fs::path>& paths) {
    for (const auto& p : paths) {
      std::error_code ignored;
      if (!p.empty()) fs::remove(p, ignored);
    }
  };
  for (std::size_t i = 0; i < staged.size(); ++i) {
    if (::rename(staged[i].temporary.c_str(), staged[i].destination.c_str()) == 0) continue;
    const int error = errno;
    // Put back what was renamed, newest first: the previous file, or none where there was none.
    for (std::size_t j = i; j-- > 0;) {
      std::error_code ignored;
      if (!backups[j].empty()) fs::rename(backups[j], staged[j].destination, ignored);
      else fs::remove(staged[j].destination, ignored);
      backups[j].clear();
    }
    for (std::size_t j = i; j < staged.size(); ++j) {
      std::error_code ignored;
      fs::remove(staged[j].temporary, ignored);
    }
    removeAll(backups);
    const fs::path failed = staged[i].destination;
    staged.clear();
    m_impl->removeCreatedDirectories();
    fail(ErrorKind::Output, "cannot write '{}': {}; no output of this run was written", failed.string(),
         writeFailure(failed, error));
  }
  removeAll(backups);
  staged.clear();
  m_impl->createdDirectories.clear();  // kept: they hold the run's outputs
}

namespace {
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

namespace {
/// What makes two paths one file: device and inode when it exists, else the absolute,
/// normalized path (symbolic links in the existing part resolved).
struct FileIdentity {
  bool exists = false;
  dev_t device = 0;
  ino_t inode = 0;
  fs::path path;

  static FileIdentity of(const fs::path& p) {
    FileIdentity id;
    struct stat st {};
    if (::stat(p.c_str(), &st) == 0) {
      id.exists = true;
      id.device = st.st_dev;
      id.inode = st.st_ino;
    }
    std::error_code ec;
    id.path = fs::weakly_canonical(fs::absolute(p, ec), ec);
    if (ec) id.path = fs::absolute(p, ec).lexically_normal();
    return id;
  }
  bool operator==(const FileIdentity& o) const {
    if (exists || o.exists) return exists && o.exists && device == o.device && inode == o.inode;
    return path == o.path;
  }
};

bool skipped(const fs::path& p) { return p.empty() || p == "-"; }
}  // namespace

void checkDistinctFiles(const std::vector<FileUse>& inputs, const std::vector<FileUse>& outputs) {
  std::vector<FileIdentity> in, out;
  for (const FileUse& f : inputs) in.push_back(skipped(f.path) ? FileIdentity{} : FileIdentity::of(f.path));
  for (std::size_t o = 0; o < outputs.size(); ++o) {
    const FileUse& output = outputs[o];
    if (output.path == "-") {
      for (std::size_t p = 0; p < o; ++p)
        if (outputs[p].path == "-") fail(ErrorKind::Usage, "{} and {} both write to stdout ('-'): give one of them a file", outputs[p].role, output.role);
    }
    if (skipped(output.path)) {
      out.emplace_back();
      continue;
    }
    const FileIdentity id = FileIdentity::of(output.path);
    for (std::size_t i = 0; i < inputs.size(); ++i) {
      if (skipped(inputs[i].path) || !(in[i] == id)) continue;
      fail(ErrorKind::Usage, "{} '{}' is {} '{}': writing it would destroy the input; choose another name", output.role,
           output.path.string(), inputs[i].role, inputs[i].path.string());
    }
    for (std::size_t p = 0; p < o; ++p) {
      if (skipped(outputs[p].path) || !(out[p] == id)) continue;
      fail(ErrorKind::Usage, "{} '{}' and {} '{}' are the same file: one output would replace the other; choose "
           "another name", outputs[p].role, outputs[p].path.string(), output.role, output.path.string());
    }
    out.push_back(id);
  }
}

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

void writeAtomically(const fs::path& destination, const std::function<void(const fs::path&)>& write, Commit when) {
  checkWritable(destination);
  removeStaleTemporaries(destination.parent_path().empty() ? fs::path(".") : destination.parent_path());
  const fs::path tmp = temporarySibling(destination);
  try {
    write(tmp);
  } catch (const std::exception& e) {
    const int error = errno;
    // A writer that failed for want of space says so, whatever its own words were.
    const bool full = error == ENOSPC || filesystemFull(tmp);
    std::error_code ignored;
    fs::remove(tmp, ignored);
    if (full) fail(ErrorKind::Output, "cannot write '{}': {}", destination.string(), writeFailure(destination, ENOSPC));
    throw;
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw;
  }
  if (when == Commit::WithRun && stageInOpenSet(destination, tmp)) return;  // renamed with the run's other outputs
  std::error_code ec;
  fs::rename(tmp, destination, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    fail(ErrorKind::Output, "cannot write '{}': {}", destination.string(), ec.message());
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
  if (stageInOpenSet(m_destination, m_temporary)) {  // the open OutputSet renames it with the rest
    m_committed = true;
    return;
  }
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
    if (!out) fail(ErrorKind::Output, "cannot write '{}': {}", destination.string(), writeFailure(destination, errno));
  });
}

std::string readTextFile(const fs::path& path) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) fail(ErrorKind::Input, "cannot read '{}': it is a directory", path.string());
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(ErrorKind::Input, "cannot read '{}': {}", path.string(), std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace glint

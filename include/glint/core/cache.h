#pragma once
// glint/core/cache.h — files glint computes once and keeps: where they live, and building
// one safely when several processes want it at the same time.
//
// Contents
//   cacheDirectory   where cached files go ($GLINT_CACHE_DIR, $XDG_CACHE_HOME/glint, ~/.cache/glint)
//   cachedFile       a file of the cache, built under a lock when it is missing
//
// A cached file is named by its inputs (callers put a hash of everything that decides its
// contents in the name), so a changed input is a new name and an old file is never wrong,
// only unused. Everything in the cache directory can be deleted at any time; the next
// use rebuilds what it needs:
//
//   rm -rf "${GLINT_CACHE_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/glint}"
//
// Several processes (ctest -j, a farm sharing a directory on one machine) asking for one
// missing file: the first takes an exclusive lock (flock on NAME.lock beside it) and builds;
// the others wait on the lock and then find the file. The file is written atomically
// (core/file.h): under its final name it is always complete, so a reader that finds it
// needs no lock at all.
//
/// ```cpp
/// #include <glint/core/file.h>
/// #include <glint/core/log.h>
/// #include <fstream>
/// const auto entry = glint::cachedFile(glint::cacheDirectory(), "stage-3f2a.txt",
///                                      [&](const std::filesystem::path& tmp) { std::ofstream(tmp) << "the stage\n"; });
/// if (entry.built) glint::log::info("built {}", entry.path.string());
/// const std::string stage = glint::readTextFile(entry.path);
/// ```

#include <filesystem>
#include <functional>
#include <string>

namespace glint {

/// The directory cached files go into (not created here): $GLINT_CACHE_DIR when set,
/// else $XDG_CACHE_HOME/glint, else $HOME/.cache/glint, else a glint directory in the
/// system's temporary directory.
std::filesystem::path cacheDirectory();

struct CacheEntry {
  std::filesystem::path path;  ///< the complete file
  bool built = false;          ///< this call built it (false: it was there, or another process built it)
};

/// `directory`/`name`, built by `build(tmp)` when it does not exist: `directory` is created,
/// an exclusive lock is taken on `name`.lock, and if the file is still missing `build` writes
/// a temporary file that is renamed to the final name (core/file.h). Other processes and
/// threads asking for the same name wait for the lock meanwhile. `rebuild`: replace an
/// existing file (one a reader found corrupt or stale) — unless another process replaced it
/// while this call waited for the lock: two readers that both found it bad build it once. Error(Output) when the directory cannot be created or
/// written; whatever `build` throws passes through (and no file is left).
CacheEntry cachedFile(const std::filesystem::path& directory, const std::string& name,
                      const std::function<void(const std::filesystem::path& tmp)>& build, bool rebuild = false);

}  // namespace glint

// Finding the glint_oiio module: see oiio_locate.h for the order and why.
#include "oiio_locate.h"

#include "glint/core/locations.h"

#include <dlfcn.h>
#include <fmt/format.h>
#include <link.h>

#include <algorithm>
#include <cstdlib>
#include <memory>

#if !defined(GLINT_OIIO_MODULE) || !defined(GLINT_OIIO_MODULE_INSTALLED)
#error "GLINT_OIIO_MODULE and GLINT_OIIO_MODULE_INSTALLED (the module's build and install paths) must be defined"
#endif

namespace glint::oiio {
namespace fs = std::filesystem;

namespace {
const char* overridePath() {
  const char* path = std::getenv("GLINT_OIIO_MODULE");
  return path && *path ? path : nullptr;
}

// The directories dlopen() would search for a bare file name from the executable:
// LD_LIBRARY_PATH, its RUNPATH ($ORIGIN expanded) and the system's. Resolving them
// here, instead of dlopen()ing the bare name, keeps every candidate a path that can be
// checked without loading it (requireImageIo) and named in messages.
std::vector<fs::path> librarySearchPath() {
  std::vector<fs::path> dirs;
  void* self = dlopen(nullptr, RTLD_LAZY | RTLD_NOLOAD);
  if (!self) return dirs;
  Dl_serinfo size{};
  if (dlinfo(self, RTLD_DI_SERINFOSIZE, &size) == 0 && size.dls_size >= sizeof(Dl_serinfo)) {
    auto storage = std::make_unique<std::max_align_t[]>(size.dls_size / sizeof(std::max_align_t) + 1);
    auto* info = reinterpret_cast<Dl_serinfo*>(storage.get());
    *info = size;  // RTLD_DI_SERINFO wants dls_size and dls_cnt filled in
    if (dlinfo(self, RTLD_DI_SERINFO, info) == 0) {
      for (unsigned i = 0; i < info->dls_cnt; ++i) {
        // Only absolute directories: an empty or relative entry (CMake pads build-tree
        // RUNPATHs with empty ones) would make the working directory a candidate.
        const fs::path dir = info->dls_serpath[i].dls_name ? info->dls_serpath[i].dls_name : "";
        if (dir.is_absolute()) dirs.push_back(dir);
      }
    }
  }
  dlclose(self);
  return dirs;
}
}  // namespace

std::string moduleFileName() { return fs::path(GLINT_OIIO_MODULE).filename().string(); }

std::vector<fs::path> moduleCandidates() {
  std::error_code ec;
  if (const char* path = overridePath()) return fs::exists(path, ec) ? std::vector<fs::path>{path} : std::vector<fs::path>{};
  const std::string name = moduleFileName();
  std::vector<fs::path> candidates;
  auto add = [&](const fs::path& path) {
    if (path.empty() || !fs::exists(path, ec)) return;
    const fs::path normal = path.lexically_normal();
    if (std::find(candidates.begin(), candidates.end(), normal) == candidates.end()) candidates.push_back(normal);
  };
  if (const fs::path exe = executablePath(); !exe.empty()) add(exe.parent_path() / name);
  for (const fs::path& dir : librarySearchPath()) add(dir / name);
  add(GLINT_OIIO_MODULE);
  add(GLINT_OIIO_MODULE_INSTALLED);
  return candidates;
}

std::string moduleSearchDescription() {
  if (const char* path = overridePath()) return fmt::format("GLINT_OIIO_MODULE={}", path);
  return fmt::format("glint looks beside its executable, in the executable's library path (RUNPATH, "
                     "LD_LIBRARY_PATH), in {} and in {}; GLINT_OIIO_MODULE overrides",
                     fs::path(GLINT_OIIO_MODULE).parent_path().string(),
                     fs::path(GLINT_OIIO_MODULE_INSTALLED).parent_path().string());
}

}  // namespace glint::oiio

#include "glint/core/locations.h"

#include "glint/core/error.h"

#include <dlfcn.h>
#include <fmt/format.h>
#include <link.h>

#include <algorithm>
#include <cstring>
#include <cstdlib>
#include <memory>
#include <string>

// Compiled in by src/core/CMakeLists.txt.
#if !defined(GLINT_DATA_DIR) || !defined(GLINT_INSTALL_DATA_DIR) || !defined(GLINT_BIN_TO_DATA_DIR)
#error "GLINT_DATA_DIR, GLINT_INSTALL_DATA_DIR and GLINT_BIN_TO_DATA_DIR must be defined"
#endif

namespace glint {
namespace fs = std::filesystem;

fs::path executablePath() {
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : exe;
}

std::vector<fs::path> dataDirectories() {
  if (const char* dir = std::getenv("GLINT_DATA_DIR"); dir && *dir) return {dir};
  std::vector<fs::path> dirs;
  auto add = [&](const fs::path& dir) {
    if (!dir.empty() && std::find(dirs.begin(), dirs.end(), dir) == dirs.end()) dirs.push_back(dir);
  };
  // Relative to the executable first: a moved install must not pick up data from the
  // prefix it was configured for (or a source tree) when it carries its own.
  if (const fs::path exe = executablePath(); !exe.empty())
    add((exe.parent_path() / GLINT_BIN_TO_DATA_DIR).lexically_normal());
  add(GLINT_DATA_DIR);
  add(GLINT_INSTALL_DATA_DIR);
  return dirs;
}

fs::path findDataFile(const fs::path& relative, std::string_view what) {
  const std::vector<fs::path> dirs = dataDirectories();
  std::error_code ec;
  for (const fs::path& dir : dirs) {
    const fs::path path = dir / relative;
    if (fs::is_regular_file(path, ec)) return path;
  }
  std::string searched;
  for (const fs::path& dir : dirs) searched += (searched.empty() ? "" : ", ") + dir.string();
  if (const char* dir = std::getenv("GLINT_DATA_DIR"); dir && *dir) {
    fail(ErrorKind::Input, "{} not found: no {} in GLINT_DATA_DIR={} (unset it, or point it at glint's data: "
         "<source>/data from scripts/setup, <prefix>/share/glint when installed)", what, relative.string(), dir);
  }
  fail(ErrorKind::Input, "{} not found: no {} in {} (run scripts/setup in glint's source tree, and install again "
       "for an installed glint; or set GLINT_DATA_DIR)", what, relative.string(), searched);
}

namespace {
const char* overridePath(const ModuleLocation& module) {
  const char* path = *module.overrideVariable ? std::getenv(module.overrideVariable) : nullptr;
  return path && *path ? path : nullptr;
}

// The directories dlopen() would search for a bare file name from the executable:
// LD_LIBRARY_PATH, its RUNPATH ($ORIGIN expanded) and the system's. Resolving them
// here, instead of dlopen()ing the bare name, keeps every candidate a path that can be
// checked without loading it and named in messages.
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

std::vector<fs::path> moduleCandidates(const ModuleLocation& module) {
  std::error_code ec;
  if (const char* path = overridePath(module)) {
    return fs::exists(path, ec) ? std::vector<fs::path>{path} : std::vector<fs::path>{};
  }
  const fs::path name = module.built.filename();
  std::vector<fs::path> candidates;
  auto add = [&](const fs::path& path) {
    if (path.empty() || !fs::exists(path, ec)) return;
    const fs::path normal = path.lexically_normal();
    if (std::find(candidates.begin(), candidates.end(), normal) == candidates.end()) candidates.push_back(normal);
  };
  if (const fs::path exe = executablePath(); !exe.empty()) add(exe.parent_path() / name);
  for (const fs::path& dir : librarySearchPath()) add(dir / name);
  add(module.built);
  add(module.installed);
  return candidates;
}

const void* loadModuleTable(const ModuleLocation& module, std::string_view what, const char* entry, int abiVersion,
                            const void* (*call)(void* entryPoint)) {
  const auto candidates = moduleCandidates(module);
  if (candidates.empty()) {
    fail(ErrorKind::Internal, "cannot load the {} module '{}': not found ({})", what,
         module.built.filename().string(), moduleSearchDescription(module));
  }
  std::string error;  // the first candidate's reason
  for (const fs::path& path : candidates) {
    std::string reason;
    if (void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL)) {
      dlerror();
      void* fn = dlsym(handle, entry);
      const void* table = fn ? call(fn) : nullptr;
      int version = 0;
      if (table) std::memcpy(&version, table, sizeof version);  // the table's first member
      if (table && version == abiVersion) return table;
      reason = !fn ? fmt::format("no entry point {}: not a glint {} module", entry, what)
                   : fmt::format("ABI version {}, expected {} (a stale build?)", version, abiVersion);
    } else {
      const char* message = dlerror();
      reason = message ? message : "dlopen failed";
      // dlerror()'s message starts with the path, which this message names already.
      if (const std::string prefix = path.string() + ": "; reason.starts_with(prefix)) reason.erase(0, prefix.size());
    }
    if (error.empty()) error = fmt::format("cannot load the {} module '{}': {}", what, path.string(), reason);
  }
  throw Error(ErrorKind::Internal, error);
}

std::string moduleSearchDescription(const ModuleLocation& module) {
  if (const char* path = overridePath(module)) return fmt::format("{}={}", module.overrideVariable, path);
  return fmt::format("glint looks beside its executable, in the executable's library path (RUNPATH, "
                     "LD_LIBRARY_PATH), in {} and in {}; {} overrides",
                     module.built.parent_path().string(), module.installed.parent_path().string(),
                     module.overrideVariable);
}

}  // namespace glint

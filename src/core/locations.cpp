#include "glint/core/locations.h"

#include "glint/core/error.h"

#include <algorithm>
#include <cstdlib>
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

}  // namespace glint

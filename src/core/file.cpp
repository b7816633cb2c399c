#include "glint/core/file.h"

#include "glint/core/error.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

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

#include "support.h"

#include <cstdio>
#include <fstream>
#include <string>
#include <system_error>
#include <unistd.h>

namespace glint::fuzz {

namespace {

struct Scratch {
  std::filesystem::path dir;
  Scratch() {
    std::error_code ec;
    const std::filesystem::path base = std::filesystem::is_directory("/dev/shm", ec)
                                           ? std::filesystem::path("/dev/shm")
                                           : std::filesystem::temp_directory_path();
    dir = base / ("glint-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
  }
  ~Scratch() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
};

}  // namespace

const std::filesystem::path& scratchDirectory() {
  static const Scratch scratch;
  return scratch.dir;
}

std::filesystem::path inputFile(std::span<const std::uint8_t> bytes, std::string_view extension) {
  std::filesystem::path path = scratchDirectory() / "input";
  path += ".";
  path += extension;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  out.close();
  if (!out) {
    std::fprintf(stderr, "fuzz: cannot write %s\n", path.c_str());
    std::abort();
  }
  return path;
}

std::optional<std::filesystem::path> inputFile(const std::uint8_t* data, std::size_t size,
                                               std::span<const char* const> extensions, int selectorShift) {
  if (size < 1 || extensions.empty()) return std::nullopt;
  return inputFile({data + 1, size - 1}, extensions[(data[0] >> selectorShift) % extensions.size()]);
}

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "fuzz: invariant broken: %s\n", what);
    std::abort();
  }
}

}  // namespace glint::fuzz

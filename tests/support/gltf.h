#pragma once
// glTF files in tests: the Khronos glTF-Validator's verdict (tests/support/gltf-validate.js,
// node and npm gltf-validator from scripts/setup --test) and a .glb read back.
#include "glint/image/image.h"

#include "support/cli.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace glint::testing {

/// The Khronos validator's verdict on a file (tests/support/gltf-validate.js).
inline nlohmann::json validateGltf(const std::filesystem::path& file) {
  const auto r = runShell("node " + shellQuote(std::filesystem::path(GLINT_SOURCE_DIR) / "tests/support/gltf-validate.js") +
                          " " + shellQuote(file));
  if (r.status != 0) {
    ADD_FAILURE() << "the validator did not run (scripts/setup --test installs it: node, npm gltf-validator): "
                  << r.output;
    return nlohmann::json::object();
  }
  return nlohmann::json::parse(r.output);
}

/// A .glb read back: its JSON and its binary chunk.
struct Glb {
  nlohmann::json json;
  std::string bin;

  explicit Glb(const std::filesystem::path& path) {
    const std::string bytes = readBytes(path);
    std::uint32_t header[5] = {};
    if (bytes.size() < sizeof header) return;
    std::memcpy(header, bytes.data(), sizeof header);
    EXPECT_EQ(header[0], 0x46546C67u) << "glTF magic";
    EXPECT_EQ(header[2], bytes.size()) << "the header's length is the file's";
    json = nlohmann::json::parse(bytes.substr(20, header[3]));
    const std::size_t binAt = 20 + header[3];
    std::uint32_t chunk[2] = {};
    std::memcpy(chunk, bytes.data() + binAt, sizeof chunk);
    bin = bytes.substr(binAt + 8, chunk[0]);
  }
  /// An accessor's floats (or unsigned ints, as floats would lose them: T).
  template <class T> std::vector<T> read(int accessor) const {
    const auto& a = json["accessors"][accessor];
    const auto& v = json["bufferViews"][a["bufferView"].get<int>()];
    std::vector<T> out(v["byteLength"].get<std::size_t>() / sizeof(T));
    std::memcpy(out.data(), bin.data() + v.value("byteOffset", 0), out.size() * sizeof(T));
    return out;
  }
  /// A texture's image, decoded.
  Image image(int texture, const std::filesystem::path& scratch) const {
    const int source = json["textures"][texture]["source"];
    const auto& v = json["bufferViews"][json["images"][source]["bufferView"].get<int>()];
    std::ofstream(scratch, std::ios::binary)
        << bin.substr(v.value("byteOffset", std::size_t(0)), v["byteLength"].get<std::size_t>());
    return loadImage(scratch);
  }
};

}  // namespace glint::testing

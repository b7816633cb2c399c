#pragma once
// fuzz/model_kind.h — the extension a model file's bytes call for, from the bytes
// themselves, so that real model files (fuzz/regressions/models/, a glint asset, a Blender
// export, the bunny) are a harness's corpus as they are, with no selector byte in front.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string_view>

namespace glint::fuzz {

/// "glb", "gltf", "ply", "fbx" or "obj": what a loader would take the bytes for.
inline const char* modelExtension(const std::uint8_t* data, std::size_t size) {
  const auto starts = [&](std::string_view magic) { return size >= magic.size() && std::memcmp(data, magic.data(), magic.size()) == 0; };
  if (starts("glTF")) return "glb";
  if (starts("ply")) return "ply";
  if (starts("Kaydara FBX Binary") || starts("; FBX")) return "fbx";
  for (std::size_t i = 0; i < size; ++i) {  // JSON: the first character that is not a blank
    if (data[i] == ' ' || data[i] == '\n' || data[i] == '\r' || data[i] == '\t') continue;
    return data[i] == '{' || data[i] == '[' ? "gltf" : "obj";
  }
  return "obj";
}

}  // namespace glint::fuzz

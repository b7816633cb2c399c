// Fuzz harness: glint's one glTF reader (mesh/gltf.h, gltf::read) as every command meets it,
// then what the viewer does with the result: each image a material uses decoded
// (image/image.h decodeImage) and a bake asset's extras read. The bytes are a .glb or a
// .gltf (fuzz/model_kind.h); a .gltf's relative uris resolve inside the scratch folder, and
// anything that leaves it must be refused, never read.
#include "model_kind.h"
#include "support.h"

#include "glint/core/log.h"
#include "glint/image/image.h"
#include "glint/mesh/gltf.h"

#include <cmath>
#include <fstream>

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glint::log::setLevel(glint::log::Level::Error);
  // A file outside the scratch folder that a model might try to reach: a finding if read.
  std::ofstream(glint::fuzz::scratchDirectory().parent_path() / "glint-fuzz-secret.bin") << "outside the fence";
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace glint;
  const char* ext = fuzz::modelExtension(data, size);
  if (std::string_view(ext) != "glb") ext = "gltf";
  const auto path = fuzz::inputFile({data, size}, ext);
  fuzz::parse([&] {
    const gltf::Model model = gltf::read(path);
    for (const gltf::Primitive& p : model.primitives) {
      const std::size_t n = p.positions.size();
      fuzz::check(!p.indices.empty() && p.indices.size() % 3 == 0, "whole triangles");
      for (std::uint32_t i : p.indices) fuzz::check(i < n, "indices in range");
      for (const vec3& v : p.positions) fuzz::check(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z), "finite positions");
      fuzz::check(p.normals.empty() || p.normals.size() == n, "one normal per vertex");
      fuzz::check(p.uvs.empty() || p.uvs.size() == n, "one uv per vertex");
      fuzz::check(p.colors.empty() || p.colors.size() == n, "one colour per vertex");
      fuzz::check(p.tangents.empty() || p.tangents.size() == n, "one tangent per vertex");
      fuzz::check(p.material < int(model.materials.size()), "material in range");
    }
    for (const gltf::Material& m : model.materials)
      for (int image : {m.baseColorImage, m.normalImage, m.occlusionImage})
        fuzz::check(image < int(model.images.size()), "image in range");
    for (const gltf::ImageBytes& image : model.images) {
      if (image.bytes.empty()) continue;
      fuzz::parse([&] { (void)decodeImage(image.bytes, "fuzz"); });
    }
    if (model.extras.is_object() && model.extras.contains("glint_bake")) (void)model.extras.dump();
  });
  return 0;
}

// Fuzz harness: scenes::loadModelFile (scenes/model.h), what `glint view FILE`, `glint
// render FILE` and `--export-web` read: any model format (fuzz/model_kind.h), textures
// decoded, a bake asset's extras kept, tangents made for normal maps; then the model written
// again as the .glb an exported page holds (scenes::modelGlb) and read back.
#include "model_kind.h"
#include "support.h"

#include "glint/core/log.h"
#include "glint/scenes/model.h"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <vector>

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glint::log::setLevel(glint::log::Level::Error);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace glint;
  const auto path = fuzz::inputFile({data, size}, fuzz::modelExtension(data, size));
  fuzz::parse([&] {
    const scenes::ModelFile model = scenes::loadModelFile(path);
    fuzz::check(!model.parts.empty(), "a model has parts");
    for (const scenes::ModelPart& part : model.parts)
      fuzz::check(part.material < int(model.materials.size()), "material in range");
    fuzz::check(model.bake.is_null() || model.bake.is_object(), "a bake record is an object");
    // The page's .glb: what glint writes, glint reads back.
    const std::vector<unsigned char> glb = scenes::modelGlb(model);
    const std::filesystem::path again = fuzz::scratchDirectory() / "again.glb";
    std::ofstream(again, std::ios::binary).write(reinterpret_cast<const char*>(glb.data()), std::streamsize(glb.size()));
    const scenes::ModelFile reread = scenes::loadModelFile(again);
    fuzz::check(reread.parts.size() == model.parts.size(), "the page's .glb holds every part");
  });
  return 0;
}

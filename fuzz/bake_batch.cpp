// Fuzz harness: a `glint bake --batch` file (bake/job.h loadBatch): JSON of defaults and jobs,
// each job's keys parsed by the command's own option definitions and checked together.
#include "support.h"

#include "glint/bake/job.h"
#include "glint/core/log.h"

#include <cstdint>
#include <vector>

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glint::log::setLevel(glint::log::Level::Error);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace glint;
  const auto path = fuzz::inputFile({data, size}, "json");
  fuzz::parse([&] {
    const std::vector<bake::BatchJob> jobs = bake::loadBatch(path.string());
    fuzz::check(!jobs.empty(), "a batch has jobs");
  });
  return 0;
}

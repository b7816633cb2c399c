// Where a bake's rays are traced (bake/gpu_backend.h, BakeOptions::device): the choice and
// its reason, the GPU's memory checked before anything is uploaded.
#include "glint/bake/gpu_backend.h"
#include "glint/core/error.h"
#include "internal.h"

#include <fmt/format.h>

#include <cstdint>
#include <string>

namespace glint::bake {

std::uint64_t estimateGpuBytes(std::size_t triangles) {
  // Per triangle: at most 2 nodes of 32 bytes (a binary tree of single-triangle leaves),
  // the triangle (48) and its id (4), three corner normals (36). The batch buffers: 2^18
  // items of at most 80 bytes up and 16 down. The turns table: 32 KiB.
  return std::uint64_t(triangles) * (64 + 52 + 36) + (std::uint64_t(1) << 18) * (80 + 16) + (32u << 10);
}

namespace detail {

namespace {
std::string mib(std::uint64_t bytes) { return fmt::format("{:.0f} MiB", double(bytes) / double(1 << 20)); }
}  // namespace

DeviceChoice chooseDevice(const BakeOptions& options, std::size_t triangles) {
  DeviceChoice choice;
  const bool must = options.device == Device::Gpu;
  if (options.device == Device::Cpu) {
    choice.reason = "--device cpu";
    return choice;
  }
  const auto cpu = [&](std::string why) {
    if (must) fail(ErrorKind::NoGpu, "--device gpu: {}", why);
    choice.reason = "--device auto: " + why;
    return choice;
  };
  if (!options.gpu) return cpu("this program has no GPU backend");
  if (!must && options.gpu->onlySoftwareDevices())
    return cpu("the only GL devices are software renderers (llvmpipe), slower than the CPU path");
  try {
    choice.info = options.gpu->start(options.gpuDebug);
  } catch (const Error& e) {
    if (must) throw;
    return cpu(fmt::format("no OpenGL 4.5 context ({})", e.what()));
  }
  if (!must && choice.info.software)
    return cpu(fmt::format("the GL renderer is software ({}), slower than the CPU path", choice.info.renderer));
  // A software renderer's "GPU memory" is the host's, which the job's memory estimate checks
  // (llvmpipe in Debian 13's Mesa reports 21-32 MiB free, nothing like the host's memory).
  if (choice.info.software) choice.info.freeBytes.reset();
  const std::uint64_t need = estimateGpuBytes(triangles);
  if (choice.info.freeBytes && need > *choice.info.freeBytes) {
    return cpu(fmt::format("the high poly's {} triangles need about {} of GPU memory; the driver reports {} free",
                           triangles, mib(need), mib(*choice.info.freeBytes)));
  }
  choice.gpu = true;
  choice.reason = must ? "--device gpu" : fmt::format("--device auto: a hardware renderer ({})", choice.info.renderer);
  if (choice.info.freeBytes)
    choice.reason += fmt::format("; about {} needed, {} free", mib(need), mib(*choice.info.freeBytes));
  return choice;
}

}  // namespace detail
}  // namespace glint::bake

// glint bake's GPU backend (scenes/bake_gpu.h): the baker's GL side.
#include "glint/scenes/bake_gpu.h"

#include "glint/core/error.h"
#include "glint/gl/context.h"
#include "glint/raytrace/bvh.h"
#include "glint/scenes/bake_tracer.h"

#include <algorithm>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace glint::scenes {

namespace {

// GL_NVX_gpu_memory_info and GL_ATI_meminfo's enums (not in every GL header).
constexpr GLenum kNvxAvailableKiB = 0x9049;  // GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX
constexpr GLenum kAtiVboFree = 0x87FB;       // GL_VBO_FREE_MEMORY_ATI: 4 ints, [0] total free KiB

bool hasExtension(const char* name) {
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i) {
    const auto* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)));
    if (e && std::string_view(e) == name) return true;
  }
  return false;
}

std::optional<std::uint64_t> driverFreeBytes() {
  GLint kib[4] = {0, 0, 0, 0};
  if (hasExtension("GL_NVX_gpu_memory_info")) {
    glGetIntegerv(kNvxAvailableKiB, kib);
  } else if (hasExtension("GL_ATI_meminfo")) {
    glGetIntegerv(kAtiVboFree, kib);
  } else {
    return std::nullopt;
  }
  if (glGetError() != GL_NO_ERROR || kib[0] <= 0) return std::nullopt;
  return std::uint64_t(kib[0]) * 1024u;
}

class Scene final : public glint::bake::GpuScene {
public:
  Scene(const raytrace::Bvh& bvh, std::span<const vec3> cornerNormals) : m_tracer(bvh, cornerNormals) {}
  void closest(std::span<const raytrace::Ray> rays, std::span<std::optional<raytrace::Hit>> hits) override {
    m_tracer.intersect(rays, hits);
  }
  void hemisphere(std::span<const raytrace::HemisphereJob> jobs, std::span<raytrace::HemisphereSum> sums) override {
    m_tracer.hemisphere(jobs, sums);
  }
  void curvature(std::span<const raytrace::CurvatureJob> jobs, float epsilon, std::span<raytrace::CurvatureSum> sums) override {
    m_tracer.curvature(jobs, epsilon, sums);
  }
  std::uint64_t bytes() const override { return m_tracer.gpuBytes(); }
  std::size_t dispatches() const override { return m_tracer.dispatches(); }
  double longestDispatchMs() const override { return m_tracer.longestDispatchMs(); }

private:
  scenes::BakeTracer m_tracer;
};

class Backend final : public glint::bake::GpuBackend {
public:
  bool onlySoftwareDevices() override { return gl::onlySoftwareDevices(); }

  glint::bake::GpuInfo start(bool debug) override {
    if (!m_context) m_context = gl::HeadlessContext::create({.profile = gl::Profile::Core, .debug = debug});
    const gl::ContextInfo info = gl::queryContextInfo();
    return {.renderer = info.renderer, .software = info.software, .freeBytes = driverFreeBytes()};
  }

  std::unique_ptr<glint::bake::GpuScene> upload(const Mesh& mesh, const vec3* cornerNormals) override {
    if (!m_context) fail(ErrorKind::Internal, "bake's GPU backend used before start()");
    const raytrace::Bvh bvh = raytrace::buildBvh(mesh);
    return std::make_unique<Scene>(bvh, std::span<const vec3>(cornerNormals, 3 * mesh.triangleCount()));
  }

private:
  std::unique_ptr<gl::HeadlessContext> m_context;
};

}  // namespace

std::unique_ptr<glint::bake::GpuBackend> bakeGpuBackend() { return std::make_unique<Backend>(); }

}  // namespace glint::scenes

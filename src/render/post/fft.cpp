#include "glint/render/post/fft.h"

#include "glint/core/error.h"
#include "glint/gl/context.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string_view>
#include <numbers>

namespace glint::render::post {

namespace {
// Radices for one axis, in pass order: 4s first (fewest passes), then a 2, then 3s, 5s
// and any remaining primes.
std::vector<int> factor(int n) {
  std::vector<int> radices;
  while (n % 4 == 0) {
    radices.push_back(4);
    n /= 4;
  }
  if (n % 2 == 0) {
    radices.push_back(2);
    n /= 2;
  }
  for (int p = 3; n > 1; p += 2) {
    while (n % p == 0) {
      radices.push_back(p);
      n /= p;
    }
    if (p * p > n && n > 1) {
      radices.push_back(n);
      break;
    }
  }
  return radices;
}

GLuint groups(int count, int size) { return GLuint((count + size - 1) / size); }

void storageBarrier() { glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT); }
// After imageStore, before the texture is sampled, drawn into, read back or copied.
void imageBarrier() {
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                  GL_FRAMEBUFFER_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT);
}

void bindInput(const gl::Texture& texture, GLuint unit) {
  texture.bind(unit);
  gl::Sampler::unbind(unit);
}

void checkOutput(const char* pass, const gl::Texture& input, const gl::Texture& output) {
  if (input.width() != output.width() || input.height() != output.height()) {
    fail(ErrorKind::Usage, "{}: input {}x{} and output {}x{} must have the same size", pass, input.width(),
         input.height(), output.width(), output.height());
  }
  if (output.internalFormat() != GL_RGBA8 && output.internalFormat() != GL_RGBA32F)
    fail(ErrorKind::Usage, "{}: the output must be an RGBA8 or RGBA32F texture", pass);
}
/// The forward transform's first step, shared by the spectrum and the filters: `load`
/// (post/fft_load.comp) reads the input image into `fft`'s buffer 0.
void loadFftInput(const gl::Program& load, const Fft2d& fft, const gl::Texture& input, ivec2 size) {
  bindInput(input, 0);
  load.use();
  load.set("uInput", 0);
  fft.buffer(0).bindBase(GL_SHADER_STORAGE_BUFFER, 1);
  glDispatchCompute(groups(size.x, 8), groups(size.y, 8), 1);
  storageBarrier();
}
}  // namespace

// ---------------------------------------------------------------------------
namespace {
// One dispatch an axis where it fits (fft_axis.comp), except on a software rasterizer:
// llvmpipe runs a workgroup's barriers as coroutines, and there the shared-memory axes
// took twice the time of the passes (PostOracle.FftMatchesFftwAtLargeSizes: 16.4 s against
// 7.7 s). GLINT_FFT_AXES=shared or =passes decides instead (benches, tests).
bool sharedAxesByDefault() {
  if (const char* v = std::getenv("GLINT_FFT_AXES"); v && *v) {
    if (std::string_view(v) == "shared") return true;
    if (std::string_view(v) == "passes") return false;
    fail(ErrorKind::Usage, "GLINT_FFT_AXES must be 'shared' or 'passes', not '{}'", v);
  }
  return !gl::queryContextInfo().software;
}
}  // namespace

Fft2d::Fft2d(ivec2 size, int lanes) : m_size(size), m_lanes(lanes), m_sharedAxes(sharedAxesByDefault()) {
  if (size.x < 1 || size.y < 1) fail(ErrorKind::Usage, "FFT size must be positive, got {}x{}", size.x, size.y);
  if (lanes != 1 && lanes != 2) fail(ErrorKind::Usage, "FFT lanes must be 1 or 2, got {}", lanes);
  for (int axis = 0; axis < 2; ++axis) {
    Axis& a = m_axes[axis];
    a.length = axis == 0 ? size.x : size.y;
    a.radices = factor(a.length);
    std::vector<float> table(std::size_t(a.length) * 2);
    for (int m = 0; m < a.length; ++m) {
      // In double, reduced exactly (m < N): float twiddles within half an ulp.
      const double angle = -2.0 * std::numbers::pi * double(m) / double(a.length);
      table[std::size_t(m) * 2] = float(std::cos(angle));
      table[std::size_t(m) * 2 + 1] = float(std::sin(angle));
    }
    a.twiddles = gl::Buffer(table.size() * sizeof(float), table.data(), 0, axis == 0 ? "fft-twiddles-x" : "fft-twiddles-y");
    // fft_axis.comp: the line in 32 KB of shared memory, radices it has butterflies for.
    a.fitsShared = a.length <= 4096 && a.radices.size() <= 16 && !a.radices.empty() &&
                   std::all_of(a.radices.begin(), a.radices.end(), [](int r) { return r >= 2 && r <= 5; });
  }
  const std::size_t bytes = std::size_t(size.x) * std::size_t(size.y) * sizeof(float) * 2 * std::size_t(lanes);
  m_data[0] = gl::Buffer(bytes, nullptr, GL_DYNAMIC_STORAGE_BIT, "fft-data-0");
  m_data[1] = gl::Buffer(bytes, nullptr, GL_DYNAMIC_STORAGE_BIT, "fft-data-1");
}

const gl::Program& Fft2d::program(int radix) {
  auto it = m_programs.find(radix);
  if (it == m_programs.end()) {
    it = m_programs
             .emplace(radix, gl::Program::fromFiles({"post/fft.comp"}, {fmt::format("RADIX {}", radix),
                                                                       fmt::format("LANES {}", m_lanes)}))
             .first;
  }
  return it->second;
}

const gl::Program& Fft2d::axisProgram() {
  if (!m_axisProgram) m_axisProgram = gl::Program::fromFiles({"post/fft_axis.comp"}, {fmt::format("LANES {}", m_lanes)});
  return m_axisProgram;
}

int Fft2d::dispatches() const {
  int count = 0;
  for (int axis = 0; axis < 2; ++axis)
    count += inSharedMemory(axis) ? 1 : int(m_axes[axis].radices.size());
  return count;
}

int Fft2d::run(int from, FftDirection direction) {
  int current = from;
  const float sign = direction == FftDirection::Forward ? -1.0f : 1.0f;
  const int lastAxis = m_axes[1].radices.empty() ? 0 : 1;
  const float inverseScale = float(1.0 / (double(m_size.x) * m_size.y));
  // What fft.comp and fft_axis.comp share: the axis, the direction, the scale (1/(w·h) on
  // the inverse's last write, else 1) and the buffers, from `current` into the other.
  const auto begin = [&](const gl::Program& p, int axis, bool lastWrite) {
    p.use();
    p.set("uAxis", axis);
    p.set("uLength", m_axes[axis].length);
    p.set("uSize", m_size);
    p.set("uSign", sign);
    p.set("uScale", direction == FftDirection::Inverse && lastWrite ? inverseScale : 1.0f);
    m_data[current].bindBase(GL_SHADER_STORAGE_BUFFER, 0);
    m_data[1 - current].bindBase(GL_SHADER_STORAGE_BUFFER, 1);
  };
  for (int axis = 0; axis < 2; ++axis) {
    const Axis& a = m_axes[axis];
    a.twiddles.bindBase(GL_SHADER_STORAGE_BUFFER, 2);
    if (inSharedMemory(axis)) {  // every pass of the axis in one dispatch
      const gl::Program& p = axisProgram();
      begin(p, axis, axis == lastAxis);
      p.set("uPasses", int(a.radices.size()));
      glProgramUniform1iv(p.id(), p.uniformLocation("uRadices[0]"), GLsizei(a.radices.size()), a.radices.data());
      glDispatchCompute(GLuint(axis == 0 ? m_size.y : m_size.x), 1, 1);
      storageBarrier();
      current = 1 - current;
      continue;
    }
    int stride = 1;
    for (std::size_t pass = 0; pass < a.radices.size(); ++pass) {
      const int radix = a.radices[pass];
      const gl::Program& p = program(radix);
      begin(p, axis, axis == lastAxis && pass + 1 == a.radices.size());
      p.set("uStride", stride);
      const int butterflies = a.length / radix;
      if (axis == 0) glDispatchCompute(groups(butterflies, 64), GLuint(m_size.y), 1);
      else glDispatchCompute(groups(m_size.x, 64), GLuint(butterflies), 1);
      storageBarrier();
      current = 1 - current;
      stride *= radix;
    }
  }
  // A 1×1 transform has no passes: the inverse's 1/(w·h) is 1, nothing to do.
  return current;
}

std::vector<std::complex<float>> Fft2d::transform(std::span<const std::complex<float>> data, FftDirection direction) {
  if (m_lanes != 1) fail(ErrorKind::Usage, "Fft2d::transform needs a one-lane transform");
  const std::size_t n = std::size_t(m_size.x) * std::size_t(m_size.y);
  if (data.size() != n) fail(ErrorKind::Usage, "FFT of {}x{} needs {} values, got {}", m_size.x, m_size.y, n, data.size());
  m_data[0].update(0, n * sizeof(std::complex<float>), data.data());
  const int result = run(0, direction);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<std::complex<float>> out(n);
  m_data[result].read(0, n * sizeof(std::complex<float>), out.data());
  return out;
}

// ---------------------------------------------------------------------------
void SpectrumPass::prepare(ivec2 size) {
  if (m_fft && m_fft->size() == size) return;
  m_fft = std::make_unique<Fft2d>(size, 1);
  if (!m_load) {
    m_load = gl::Program::fromFiles({"post/fft_load.comp"}, {"LANES 1"});
  }
}

void SpectrumPass::run(const gl::Texture& input, const gl::Texture& output) {
  checkOutput("spectrum", input, output);
  const ivec2 size(input.width(), input.height());
  prepare(size);
  loadFftInput(m_load, *m_fft, input, size);
  const int result = m_fft->run(0, FftDirection::Forward);
  const bool wide = output.internalFormat() == GL_RGBA32F;
  gl::Program& show = wide ? m_showFloat : m_show;
  if (!show) show = gl::Program::fromFiles({"post/fft_spectrum.comp"}, wide ? std::vector<std::string>{"FLOAT_OUTPUT 1"}
                                                                            : std::vector<std::string>{});
  show.use();
  m_fft->buffer(result).bindBase(GL_SHADER_STORAGE_BUFFER, 0);
  output.bindImage(0, GL_WRITE_ONLY, output.internalFormat());
  glDispatchCompute(groups(size.x, 8), groups(size.y, 8), 1);
  imageBarrier();
}

// ---------------------------------------------------------------------------
void FrequencyFilterPass::prepare(ivec2 size, const FrequencyFilter& filter) {
  validateFilter(filter, size.x, size.y);
  if (!m_fft || m_fft->size() != size) {
    m_fft = std::make_unique<Fft2d>(size, 2);
    m_kernelFft.reset();
    m_hasTransfer = false;
  }
  if (!m_load) {
    m_load = gl::Program::fromFiles({"post/fft_load.comp"}, {"LANES 2"});
    m_multiply = gl::Program::fromFiles({"post/fft_multiply.comp"});
  }
  const auto& p = m_prepared;
  const bool same = m_hasTransfer && p.kind == filter.kind && p.cutoff == filter.cutoff && p.low == filter.low &&
                    p.order == filter.order && p.kernel == filter.kernel && p.size == filter.size;
  if (same) return;
  const std::size_t n = std::size_t(size.x) * std::size_t(size.y);
  if (filter.kind == FilterKind::Kernel) {
    // H = DFT(kernel), on the GPU: the kernel (image/fourier.h's, the reference's) goes in as
    // real values and its transform stays on the GPU as the transfer function.
    const auto kernel = filterKernel(filter, size.x, size.y);
    std::vector<std::complex<float>> values(n);
    for (std::size_t i = 0; i < n; ++i) values[i] = float(kernel[i]);
    if (!m_kernelFft) m_kernelFft = std::make_unique<Fft2d>(size, 1);
    const auto transfer = m_kernelFft->forward(values);
    m_transfer = gl::Buffer(std::span<const std::complex<float>>(transfer), 0, "fft-transfer");
  } else {
    std::vector<std::complex<float>> transfer(n);
    for (int v = 0; v < size.y; ++v)
      for (int u = 0; u < size.x; ++u)
        transfer[std::size_t(v) * std::size_t(size.x) + std::size_t(u)] = float(filterGain(filter, u, v, size.x, size.y));
    m_transfer = gl::Buffer(std::span<const std::complex<float>>(transfer), 0, "fft-transfer");
  }
  m_prepared = filter;
  m_hasTransfer = true;
}

void FrequencyFilterPass::run(const gl::Texture& input, const gl::Texture& output, const FrequencyFilter& filter) {
  checkOutput("frequency filter", input, output);
  const ivec2 size(input.width(), input.height());
  prepare(size, filter);
  loadFftInput(m_load, *m_fft, input, size);
  int result = m_fft->run(0, FftDirection::Forward);
  m_multiply.use();
  m_multiply.set("uCount", size.x * size.y);
  m_fft->buffer(result).bindBase(GL_SHADER_STORAGE_BUFFER, 0);
  m_transfer.bindBase(GL_SHADER_STORAGE_BUFFER, 2);
  glDispatchCompute(groups(size.x * size.y, 64), 1, 1);
  storageBarrier();
  result = m_fft->run(result, FftDirection::Inverse);
  const bool wide = output.internalFormat() == GL_RGBA32F;
  gl::Program& store = wide ? m_storeFloat : m_store;
  if (!store) store = gl::Program::fromFiles({"post/fft_store.comp"}, wide ? std::vector<std::string>{"FLOAT_OUTPUT 1"}
                                                                           : std::vector<std::string>{});
  store.use();
  store.set("uInput", 0);
  store.set("uOffset", filter.offset);
  bindInput(input, 0);
  m_fft->buffer(result).bindBase(GL_SHADER_STORAGE_BUFFER, 0);
  output.bindImage(0, GL_WRITE_ONLY, output.internalFormat());
  glDispatchCompute(groups(size.x, 8), groups(size.y, 8), 1);
  imageBarrier();
}

}  // namespace glint::render::post

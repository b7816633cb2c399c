#include "glint/render/post/fft.h"

#include "glint/core/error.h"
#include "glint/gl/context.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
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

// e^(−2πi·m/n), m = 0..n−1, as vec2: computed in double and reduced exactly (m < n), so
// every entry is within half an ulp of float.
gl::Buffer twiddleTable(int n, const char* label) {
  std::vector<float> table(std::size_t(n) * 2);
  for (int m = 0; m < n; ++m) {
    const double angle = -2.0 * std::numbers::pi * double(m) / double(n);
    table[std::size_t(m) * 2] = float(std::cos(angle));
    table[std::size_t(m) * 2 + 1] = float(std::sin(angle));
  }
  return gl::Buffer(table.size() * sizeof(float), table.data(), 0, label);
}

// Whether post/fft_line.glsl takes a line of n with these radices: 32 KB of shared memory,
// the butterflies it has.
bool lineFitsShared(int n, const std::vector<int>& radices) {
  return n <= 4096 && radices.size() <= 16 && !radices.empty() &&
         std::all_of(radices.begin(), radices.end(), [](int r) { return r >= 2 && r <= 5; });
}
// The line's radices for post/fft_line.glsl.
void setLineUniforms(const gl::Program& p, const std::vector<int>& radices) {
  p.set("uPasses", int(radices.size()));
  glProgramUniform1iv(p.id(), p.uniformLocation("uRadices[0]"), GLsizei(radices.size()), radices.data());
}

void storageBarrier() { glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT); }
// After imageStore, before the texture is sampled, drawn into, read back or copied.
void imageBarrier() {
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                  GL_FRAMEBUFFER_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT);
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
  input.bindUnsampled(0);
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
    a.twiddles = twiddleTable(a.length, axis == 0 ? "fft-twiddles-x" : "fft-twiddles-y");
    a.fitsShared = lineFitsShared(a.length, a.radices);  // fft_axis.comp
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
      setLineUniforms(p, a.radices);
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
bool RealFft2d::fits(ivec2 size) {
  if (size.x < 2 || size.y < 1 || size.x % 2 != 0 || size.x / 2 > 2048) return false;
  return lineFitsShared(size.x / 2, factor(size.x / 2)) && lineFitsShared(size.y, factor(size.y));
}

RealFft2d::RealFft2d(ivec2 size, int channels) : m_size(size), m_channels(channels) {
  if (!fits(size)) {
    fail(ErrorKind::Usage, "the real-input FFT takes an even width up to 4096 and a height up to 4096 with factors "
                           "2, 3 and 5 only, not {}x{}", size.x, size.y);
  }
  if (channels != 1 && channels != 3) fail(ErrorKind::Usage, "the real-input FFT takes 1 or 3 channels, got {}", channels);
  m_rowRadices = factor(size.x / 2);
  m_columnRadices = factor(size.y);
  m_rowTwiddles = twiddleTable(size.x, "fft-real-twiddles-x");  // the rows' n = w/2 point FFT takes every second
  m_columnTwiddles = twiddleTable(size.y, "fft-real-twiddles-y");
  const std::size_t values = std::size_t(halfWidth()) * std::size_t(size.y) * std::size_t(channels);
  m_data = gl::Buffer(values * sizeof(std::complex<float>), nullptr, 0, "fft-real-planes");
}

const gl::Program& RealFft2d::program(gl::Program& slot, const char* file, std::vector<std::string> defines) {
  if (!slot) slot = gl::Program::fromFiles({file}, defines);
  return slot;
}

// Error(Usage) unless `texture` is the transform's size.
void RealFft2d::checkSize(const gl::Texture& texture, const char* what) const {
  if (texture.width() != m_size.x || texture.height() != m_size.y)
    fail(ErrorKind::Usage, "real FFT of {}x{}: the {} is {}x{}", m_size.x, m_size.y, what, texture.width(), texture.height());
}

void RealFft2d::forwardRows(const gl::Texture& input) {
  checkSize(input, "input");
  const gl::Program& p = program(m_rows, "post/fft_real_rows.comp", {"FORWARD 1", fmt::format("CHANNELS {}", m_channels)});
  p.use();
  p.set("uInput", 0);
  p.set("uSize", m_size);
  setLineUniforms(p, m_rowRadices);
  input.bindUnsampled(0);
  m_rowTwiddles.bindBase(GL_SHADER_STORAGE_BUFFER, 2);
  m_data.bindBase(GL_SHADER_STORAGE_BUFFER, 1);
  glDispatchCompute(GLuint(m_size.y), 1, 1);
  storageBarrier();
}

// The columns' dispatch: `p` is fft_real_columns.comp in one of its modes.
void RealFft2d::columns(const gl::Program& p, int channels) {
  p.use();
  p.set("uSize", m_size);
  setLineUniforms(p, m_columnRadices);
  m_columnTwiddles.bindBase(GL_SHADER_STORAGE_BUFFER, 2);
  m_data.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
  glDispatchCompute(GLuint(halfWidth()), GLuint(channels), 1);
}

std::vector<std::complex<float>> RealFft2d::halfSpectrum(const gl::Texture& input, int channel) {
  if (channel < 0 || channel >= m_channels) fail(ErrorKind::Usage, "real FFT: no channel {}", channel);
  forwardRows(input);
  // COLUMNS_ONLY: each column's forward FFT written back, so the planes hold the 2D DFT.
  columns(program(m_columnsOnly, "post/fft_real_columns.comp", {"COLUMNS_ONLY 1"}), m_channels);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  const std::size_t plane = std::size_t(halfWidth()) * std::size_t(m_size.y);
  std::vector<std::complex<float>> out(plane);
  m_data.read(plane * std::size_t(channel) * sizeof(std::complex<float>), plane * sizeof(std::complex<float>), out.data());
  return out;
}

void RealFft2d::spectrum(const gl::Texture& output) {
  if (m_channels != 1) fail(ErrorKind::Usage, "the spectrum is of the luma: a 1-channel real FFT");
  checkSize(output, "output");
  const bool wide = output.internalFormat() == GL_RGBA32F;
  const gl::Program& p = wide ? program(m_spectrumFloat, "post/fft_real_columns.comp", {"SPECTRUM 1", "FLOAT_OUTPUT 1"})
                              : program(m_spectrum, "post/fft_real_columns.comp", {"SPECTRUM 1"});
  output.bindImage(0, GL_WRITE_ONLY, output.internalFormat());
  columns(p, 1);
  imageBarrier();
}

void RealFft2d::filterColumns(const gl::Buffer& transfer) {
  transfer.bindBase(GL_SHADER_STORAGE_BUFFER, 3);
  columns(program(m_columns, "post/fft_real_columns.comp", {"FILTER 1"}), m_channels);
  storageBarrier();
}

void RealFft2d::inverseRows(const gl::Texture& input, const gl::Texture& output, float offset) {
  if (m_channels != 3) fail(ErrorKind::Usage, "the inverse rows write R, G and B: a 3-channel real FFT");
  checkSize(input, "input");
  checkSize(output, "output");
  const bool wide = output.internalFormat() == GL_RGBA32F;
  const gl::Program& p = wide ? program(m_inverseRowsFloat, "post/fft_real_rows.comp", {"INVERSE 1", "FLOAT_OUTPUT 1"})
                              : program(m_inverseRows, "post/fft_real_rows.comp", {"INVERSE 1"});
  p.use();
  p.set("uInput", 0);
  p.set("uSize", m_size);
  p.set("uScale", float(1.0 / (double(m_size.x / 2) * double(m_size.y))));
  p.set("uOffset", offset);
  setLineUniforms(p, m_rowRadices);
  input.bindUnsampled(0);
  m_rowTwiddles.bindBase(GL_SHADER_STORAGE_BUFFER, 2);
  m_data.bindBase(GL_SHADER_STORAGE_BUFFER, 0);
  output.bindImage(0, GL_WRITE_ONLY, output.internalFormat());
  glDispatchCompute(GLuint(m_size.y), 1, 1);
  imageBarrier();
}

// ---------------------------------------------------------------------------
namespace {
// Whether a pass set to `path` runs RealFft2d at `size`. Asked once per size and path (it
// queries the context: not a question for every frame).
bool takesRealInput(FftPath path, ivec2 size) {
  if (path == FftPath::Complex || !RealFft2d::fits(size)) return false;
  return path == FftPath::RealInput || sharedAxesByDefault();
}

// The size the pass's transform was made for; 0 × 0 before the first run.
ivec2 preparedSize(const std::unique_ptr<RealFft2d>& real, const std::unique_ptr<Fft2d>& fft) {
  return real ? real->size() : fft ? fft->size() : ivec2(0);
}
}  // namespace

void SpectrumPass::prepare(ivec2 size) {
  if (preparedSize(m_real, m_fft) == size && m_preparedPath == m_path) return;
  m_preparedPath = m_path;
  m_real.reset();
  m_fft.reset();
  if (takesRealInput(m_path, size)) {
    m_real = std::make_unique<RealFft2d>(size, 1);
    return;
  }
  m_fft = std::make_unique<Fft2d>(size, 1);
  if (!m_load) m_load = gl::Program::fromFiles({"post/fft_load.comp"}, {"LANES 1"});
}

void SpectrumPass::run(const gl::Texture& input, const gl::Texture& output) {
  checkOutput("spectrum", input, output);
  const ivec2 size(input.width(), input.height());
  prepare(size);
  if (m_real) {  // 2 dispatches: the luma's rows, the columns drawn
    m_real->forwardRows(input);
    m_real->spectrum(output);
    return;
  }
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
  if (preparedSize(m_real, m_fft) != size || m_preparedPath != m_path) {
    m_preparedPath = m_path;
    m_real.reset();
    m_fft.reset();
    m_kernelFft.reset();
    m_hasTransfer = false;
    if (takesRealInput(m_path, size)) {
      m_real = std::make_unique<RealFft2d>(size, 3);
    } else {
      m_fft = std::make_unique<Fft2d>(size, 2);
      if (!m_load) {
        m_load = gl::Program::fromFiles({"post/fft_load.comp"}, {"LANES 2"});
        m_multiply = gl::Program::fromFiles({"post/fft_multiply.comp"});
      }
    }
  }
  const auto& p = m_prepared;
  const bool same = m_hasTransfer && p.kind == filter.kind && p.cutoff == filter.cutoff && p.low == filter.low &&
                    p.order == filter.order && p.kernel == filter.kernel && p.size == filter.size;
  if (same) return;
  // H(u, v): row-major over every frequency for the complex path; for the real path only
  // u ≤ w/2 (the rest mirrors it), column-major, as its columns read it.
  const int w = size.x, h = size.y, columns = m_real ? m_real->halfWidth() : w;
  const auto at = [&](int u, int v) {
    return m_real ? std::size_t(u) * std::size_t(h) + std::size_t(v) : std::size_t(v) * std::size_t(w) + std::size_t(u);
  };
  std::vector<std::complex<float>> transfer(std::size_t(columns) * std::size_t(h));
  if (filter.kind == FilterKind::Kernel) {
    // H = DFT(kernel), on the GPU: the kernel (image/fourier.h's, the reference's) goes in as
    // real values, once per size and kernel.
    const auto kernel = filterKernel(filter, w, h);
    std::vector<std::complex<float>> values(kernel.size());
    for (std::size_t i = 0; i < kernel.size(); ++i) values[i] = float(kernel[i]);
    if (!m_kernelFft) m_kernelFft = std::make_unique<Fft2d>(size, 1);
    const auto full = m_kernelFft->forward(values);
    for (int v = 0; v < h; ++v)
      for (int u = 0; u < columns; ++u) transfer[at(u, v)] = full[std::size_t(v) * std::size_t(w) + std::size_t(u)];
  } else {
    for (int v = 0; v < h; ++v)
      for (int u = 0; u < columns; ++u) transfer[at(u, v)] = float(filterGain(filter, u, v, w, h));
  }
  m_transfer = gl::Buffer(std::span<const std::complex<float>>(transfer), 0, "fft-transfer");
  m_prepared = filter;
  m_hasTransfer = true;
}

void FrequencyFilterPass::run(const gl::Texture& input, const gl::Texture& output, const FrequencyFilter& filter) {
  checkOutput("frequency filter", input, output);
  const ivec2 size(input.width(), input.height());
  prepare(size, filter);
  if (m_real) {  // 3 dispatches: rows, columns (forward, × H, inverse), inverse rows into the output
    m_real->forwardRows(input);
    m_real->filterColumns(m_transfer);
    m_real->inverseRows(input, output, filter.offset);
    return;
  }
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
  input.bindUnsampled(0);
  m_fft->buffer(result).bindBase(GL_SHADER_STORAGE_BUFFER, 0);
  output.bindImage(0, GL_WRITE_ONLY, output.internalFormat());
  glDispatchCompute(groups(size.x, 8), groups(size.y, 8), 1);
  imageBarrier();
}

}  // namespace glint::render::post

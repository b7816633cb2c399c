// python/module.cpp — `glint._glint`, the compiled half of the Python module (glint/__init__.py
// is the other: keyword arguments, defaults and docstrings). Every function here runs the
// library's own job code (bake::runJob, post::processImage, cut::cut, scenes::renderVariant),
// so the options, checks, messages and results are the command's.
//
// Long work runs on a worker thread while the calling thread waits with the GIL released,
// every 50 ms taking it back to run the progress callback and to look for Ctrl-C
// (PyErr_CheckSignals): a KeyboardInterrupt sets the job's cancel flag, the job stops at its
// next poll and writes nothing (its outputs are staged: core/file.h), and the interrupt is
// raised. glint::Error becomes the Python exception of its kind, with the same one-line message.
#include "glint/bake/job.h"
#include "glint/bake/maps.h"
#include "glint/core/error.h"
#include "glint/core/log.h"
#include "glint/core/progress.h"
#include "glint/core/text.h"
#include "glint/core/tool.h"
#include "glint/cut/cutter.h"
#include "glint/image/image.h"
#include "glint/image/normalmap.h"
#include "glint/mesh/mesh.h"
#include "glint/post/effects.h"
#include "glint/post/job.h"
#include "glint/scenes/bake_gpu.h"
#include "glint/scenes/post_gpu.h"
#include "glint/scenes/model.h"
#include "glint/scenes/runner.h"
#include "glint/video/source.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <tbb/info.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace py = pybind11;
using namespace glint;

namespace {

// ------------------------------------------------------------------ errors
PyObject* g_errors[7] = {};  // by ErrorKind

/// A JSON value (a report) as Python objects: dict, list, str, int, float, bool, None.
py::object pythonJson(const nlohmann::ordered_json& value) {
  switch (value.type()) {
    case nlohmann::json::value_t::object: {
      py::dict d;
      for (const auto& [key, item] : value.items()) d[py::str(utf8Escaped(key))] = pythonJson(item);
      return std::move(d);
    }
    case nlohmann::json::value_t::array: {
      py::list l;
      for (const auto& item : value) l.append(pythonJson(item));
      return std::move(l);
    }
    // A file name that is not UTF-8 as the command's report writes it (core/json.h).
    case nlohmann::json::value_t::string: return py::str(utf8Escaped(value.get_ref<const std::string&>()));
    case nlohmann::json::value_t::boolean: return py::bool_(value.get<bool>());
    case nlohmann::json::value_t::number_integer: return py::int_(value.get<std::int64_t>());
    case nlohmann::json::value_t::number_unsigned: return py::int_(value.get<std::uint64_t>());
    case nlohmann::json::value_t::number_float: return py::float_(value.get<double>());
    default: return py::none();
  }
}

/// Python settings (str, bool, int, float, None, lists and dicts of them) as JSON.
nlohmann::ordered_json jsonFrom(const py::handle& value) {
  if (value.is_none()) return nullptr;
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  if (py::isinstance<py::int_>(value)) return value.cast<std::int64_t>();
  if (py::isinstance<py::float_>(value)) return value.cast<double>();
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::dict>(value)) {
    nlohmann::ordered_json out = nlohmann::ordered_json::object();
    for (const auto& [key, item] : value.cast<py::dict>()) out[py::str(key).cast<std::string>()] = jsonFrom(item);
    return out;
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    nlohmann::ordered_json out = nlohmann::ordered_json::array();
    for (const py::handle item : value) out.push_back(jsonFrom(item));
    return out;
  }
  if (py::hasattr(value, "__fspath__")) return py::module_::import("os").attr("fspath")(value).cast<std::string>();
  fail(ErrorKind::Usage, "a setting must be a string, a number, a bool or a list of them, got {}",
       std::string(py::str(value.get_type().attr("__name__"))));
}

// ------------------------------------------------------------------ long work
/// The latest state of any progress bar, written by the work's threads, read by the caller's.
struct ProgressBoard {
  std::mutex mutex;
  std::string label;
  std::uint64_t done = 0, total = 0;
  bool changed = false;
};

/// Runs work(cancel) on a worker thread; the calling thread keeps the GIL released except to
/// call `progress(label, done, total)` and to check for signals. Returns work's result or
/// rethrows its exception; Ctrl-C (or an exception from the callback) cancels the work,
/// waits for it to stop and raises.
template <typename Work>
auto runReleased(const py::object& progress, Work work) -> decltype(work(std::declval<const std::atomic<bool>*>())) {
  auto board = std::make_shared<ProgressBoard>();
  std::atomic<bool> cancel{false};
  if (!progress.is_none()) {
    setProgressListener([board](std::string_view label, std::uint64_t done, std::uint64_t total) {
      std::lock_guard lock(board->mutex);
      board->label = std::string(label);
      board->done = done;
      board->total = total;
      board->changed = true;
    });
  }
  struct ListenerReset {
    ~ListenerReset() { setProgressListener({}); }
  } reset;
  auto future = std::async(std::launch::async, [&] { return work(&cancel); });
  const auto report = [&] {
    if (progress.is_none()) return;
    std::string label;
    std::uint64_t done = 0, total = 0;
    {
      std::lock_guard lock(board->mutex);
      if (!board->changed) return;
      board->changed = false;
      label = board->label;
      done = board->done;
      total = board->total;
    }
    progress(label, done, total);
  };
  for (;;) {
    bool ready;
    {
      py::gil_scoped_release released;
      ready = future.wait_for(std::chrono::milliseconds(50)) == std::future_status::ready;
    }
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      report();
    } catch (...) {  // Ctrl-C, or the callback raised: stop the work, then raise
      cancel = true;
      {
        py::gil_scoped_release released;
        future.wait();
      }
      throw;
    }
    if (ready) break;
  }
  report();
  return future.get();
}

/// The settings of a run from Python: `base` as the job's options set them (--max-memory,
/// --json: the command's checks), with the call's threads and its Ctrl-C flag.
ToolSettings settingsFor(const std::atomic<bool>* cancel, int threads, ToolSettings base = {}) {
  ToolSettings settings = std::move(base);
  settings.threads = threads;
  settings.cancel = cancel;
  return settings;
}

// ------------------------------------------------------------------ arrays
/// An image as a numpy array that owns it (no copy): H×W for one channel, else H×W×C;
/// uint8, uint16 or float32.
py::array arrayOf(Image&& image) {
  auto* owned = new Image(std::move(image));
  py::capsule owner(owned, [](void* p) { delete static_cast<Image*>(p); });
  const py::ssize_t h = owned->height(), w = owned->width(), c = owned->channels();
  const py::ssize_t item = py::ssize_t(pixelTypeSize(owned->type()));
  std::vector<py::ssize_t> shape{h, w}, strides{w * c * item, c * item};
  if (c > 1) {
    shape.push_back(c);
    strides.push_back(item);
  }
  py::dtype dtype = owned->type() == PixelType::U8    ? py::dtype::of<std::uint8_t>()
                    : owned->type() == PixelType::U16 ? py::dtype::of<std::uint16_t>()
                                                      : py::dtype::of<float>();
  return py::array(dtype, shape, strides, owned->bytes().data(), owner);
}

/// `object` as a C-contiguous numpy array (of `dtype`, when given: "float32", "int64"),
/// checked: numpy's conversion copies a non-contiguous array or casts, and a copy that does
/// not fit in memory raises MemoryError here (pybind11's ensure() would return a null array
/// and drop the error). A value that is no array of numbers is Error(Usage) naming `what`.
py::array contiguous(const py::handle& object, const char* dtype, std::string_view what) {
  const py::object numpy = py::module_::import("numpy");
  try {
    py::object converted = dtype ? numpy.attr("ascontiguousarray")(object, py::arg("dtype") = dtype)
                                 : numpy.attr("ascontiguousarray")(object);
    return py::reinterpret_borrow<py::array>(converted);
  } catch (py::error_already_set& e) {
    if (e.matches(PyExc_MemoryError)) throw;
    fail(ErrorKind::Usage, "{} is not an array of numbers ({})", what, escapedLine(py::str(e.value()).cast<std::string>()));
  }
}

/// A numpy image (H×W or H×W×C, C 1–4; uint8, uint16 or float32) as an Image (one copy:
/// Image owns its pixels). Error(Usage) for another shape or type.
Image imageFrom(const py::array& array, const char* what) {
  if (array.ndim() != 2 && array.ndim() != 3)
    fail(ErrorKind::Usage, "{} must be an H×W or H×W×C array, got {} dimensions", what, array.ndim());
  const int h = int(array.shape(0)), w = int(array.shape(1)), c = array.ndim() == 3 ? int(array.shape(2)) : 1;
  if (c < 1 || c > 4) fail(ErrorKind::Usage, "{} must have 1 to 4 channels, got {}", what, c);
  if (h < 1 || w < 1) fail(ErrorKind::Input, "{} is empty ({}x{})", what, w, h);
  PixelType type;
  if (array.dtype().is(py::dtype::of<std::uint8_t>())) type = PixelType::U8;
  else if (array.dtype().is(py::dtype::of<std::uint16_t>())) type = PixelType::U16;
  else if (array.dtype().is(py::dtype::of<float>())) type = PixelType::F32;
  else fail(ErrorKind::Usage, "{} must be uint8, uint16 or float32, got {}", what, std::string(py::str(array.dtype())));
  const py::array pixels = contiguous(array, nullptr, what);
  Image image(w, h, c, type);
  std::memcpy(image.bytes().data(), pixels.data(), image.bytes().size());
  return image;
}

/// A vector's contents as a numpy array that keeps `owner` alive (no copy).
template <typename T>
py::array viewOf(const std::vector<T>& data, std::vector<py::ssize_t> shape, py::dtype dtype, const py::object& owner) {
  std::vector<py::ssize_t> strides(shape.size());
  py::ssize_t stride = py::ssize_t(dtype.itemsize());
  for (std::size_t i = shape.size(); i-- > 0;) {
    strides[i] = stride;
    stride *= shape[i];
  }
  py::array a(dtype, shape, strides, data.data(), owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

template <typename Vec>
std::vector<Vec> rowsFrom(const py::object& object, int width, const char* what) {
  std::vector<Vec> out;
  if (object.is_none()) return out;
  const py::array a = contiguous(object, "float32", fmt::format("Mesh {}", what));
  if (a.ndim() != 2 || a.shape(1) != width)
    fail(ErrorKind::Usage, "Mesh {} must be an N×{} array of numbers", what, width);
  out.resize(std::size_t(a.shape(0)));
  std::memcpy(out.data(), a.data(), out.size() * sizeof(Vec));
  return out;
}

std::shared_ptr<Mesh> meshFrom(const py::object& positions, const py::object& indices, const py::object& normals,
                               const py::object& uvs) {
  auto mesh = std::make_shared<Mesh>();
  mesh->positions = rowsFrom<vec3>(positions, 3, "positions");
  // uint32 and int32 indices (Blender's and numpy's usual types) are read as they are;
  // anything else is converted to int64 first.
  py::array tri = contiguous(indices, nullptr, "Mesh indices");
  if (!tri.dtype().is(py::dtype::of<std::uint32_t>()) && !tri.dtype().is(py::dtype::of<std::int32_t>()))
    tri = contiguous(indices, "int64", "Mesh indices");
  if (!(tri.ndim() == 2 && tri.shape(1) == 3) && tri.ndim() != 1)
    fail(ErrorKind::Usage, "Mesh indices must be an M×3 array of vertex indices (or a flat array of 3·M)");
  mesh->indices.resize(std::size_t(tri.size()));
  const auto copyChecked = [&](const auto* in) {
    for (std::size_t i = 0; i < mesh->indices.size(); ++i) {
      const std::int64_t v = std::int64_t(in[i]);
      if (v < 0 || std::size_t(v) >= mesh->positions.size())
        fail(ErrorKind::Input, "Mesh index {} at {} is out of range (0..{})", v, i, mesh->positions.size() - 1);
      mesh->indices[i] = std::uint32_t(v);
    }
  };
  if (tri.dtype().is(py::dtype::of<std::uint32_t>())) copyChecked(static_cast<const std::uint32_t*>(tri.data()));
  else if (tri.dtype().is(py::dtype::of<std::int32_t>())) copyChecked(static_cast<const std::int32_t*>(tri.data()));
  else copyChecked(static_cast<const std::int64_t*>(tri.data()));
  mesh->normals = rowsFrom<vec3>(normals, 3, "normals");
  mesh->uvs = rowsFrom<vec2>(uvs, 2, "uvs");
  mesh->validate("glint.Mesh");
  return mesh;
}

/// The image as RGBA floats, bottom row first, flat (Blender's Image.pixels, OpenGL's
/// glTexImage2D): integer types scaled to 0..1, grey replicated, alpha 1 when absent. On
/// every core: a 2048² map in a few milliseconds, where numpy's strided conversion takes 0.1 s.
template <typename T>
void rowsUp(const T* src, int w, int h, int c, float scale, float* dst) {
  tbb::parallel_for(tbb::blocked_range<int>(0, h, 16), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y != rows.end(); ++y) {
      const T* in = src + std::size_t(y) * std::size_t(w) * std::size_t(c);
      float* out = dst + std::size_t(h - 1 - y) * std::size_t(w) * 4;
      for (int x = 0; x < w; ++x, in += c, out += 4) {
        const float v0 = float(in[0]) * scale;
        if (c >= 3) {
          out[0] = v0;
          out[1] = float(in[1]) * scale;
          out[2] = float(in[2]) * scale;
          out[3] = c == 4 ? float(in[3]) * scale : 1.0f;
        } else {  // grey (+ alpha)
          out[0] = out[1] = out[2] = v0;
          out[3] = c == 2 ? float(in[1]) * scale : 1.0f;
        }
      }
    }
  });
}

py::array_t<float> rgbaRowsUp(const py::array& input) {
  const py::array array = contiguous(input, nullptr, "the image");
  if (array.ndim() != 2 && array.ndim() != 3) fail(ErrorKind::Usage, "the image must be an H×W or H×W×C array");
  const int h = int(array.shape(0)), w = int(array.shape(1)), c = array.ndim() == 3 ? int(array.shape(2)) : 1;
  if (c < 1 || c > 4) fail(ErrorKind::Usage, "the image must have 1 to 4 channels, got {}", c);
  py::array_t<float> out(py::ssize_t(w) * h * 4);
  float* dst = out.mutable_data();
  const void* src = array.data();
  const py::dtype dtype = array.dtype();
  py::gil_scoped_release released;
  if (dtype.is(py::dtype::of<std::uint8_t>())) rowsUp(static_cast<const std::uint8_t*>(src), w, h, c, 1.0f / 255.0f, dst);
  else if (dtype.is(py::dtype::of<std::uint16_t>())) rowsUp(static_cast<const std::uint16_t*>(src), w, h, c, 1.0f / 65535.0f, dst);
  else if (dtype.is(py::dtype::of<float>())) rowsUp(static_cast<const float*>(src), w, h, c, 1.0f, dst);
  else fail(ErrorKind::Usage, "the image must be uint8, uint16 or float32");
  return out;
}

// ------------------------------------------------------------------ bake
/// Runs one bake with its maps going to arrays: ({(map, tile): array}, report).
py::tuple bakeIntoArrays(bake::BakeJob& job, const py::object& progress, int threads) {
  std::map<std::pair<std::string, int>, Image> maps;
  job.sink = [&maps](bake::Map map, int tile, Image image) {
    maps[{bake::mapInfo(map).reportKey, tile}] = std::move(image);
  };
  const nlohmann::ordered_json report = runReleased(progress, [&](const std::atomic<bool>* cancel) {
    job.tool = settingsFor(cancel, threads, job.tool);  // keeps max_memory: the command's refusal
    ToolRun run("bake", job.tool);
    // Made on this worker thread, which bakes: a GPU context is current on the thread that made it.
    const auto gpu = scenes::bakeGpuBackend();
    bake::runJob(job, run, nullptr, gpu.get());
    return run.finish();
  });
  py::dict out;
  for (auto& [key, image] : maps) out[py::make_tuple(key.first, key.second)] = arrayOf(std::move(image));
  return py::make_tuple(out, pythonJson(report));
}

py::tuple bakeArrays(const py::dict& settings, std::shared_ptr<Mesh> low, std::shared_ptr<Mesh> high,
                     const py::object& progress, int threads) {
  bake::BakeJob job = bake::jobFromSettings(jsonFrom(settings));
  job.lowMesh = std::move(low);
  job.highMesh = std::move(high);
  return bakeIntoArrays(job, progress, threads);
}

/// Every job of a batch file (bake::loadBatch: the command's parsing and checks), each into
/// arrays: [(maps, report), ...] in the file's order. A job's map paths name its formats.
py::list bakeBatch(const std::string& file, const py::dict& overrides, const py::object& progress, int threads) {
  py::list out;
  for (bake::BatchJob& batchJob : bake::loadBatch(file, jsonFrom(overrides))) out.append(bakeIntoArrays(batchJob.job, progress, threads));
  return out;
}

// ------------------------------------------------------------------ post
/// A chain of effects as glint post runs it, for images and a video's frames.
class Post {
public:
  Post(std::vector<std::string> effects, std::vector<std::string> settings, const std::string& backend, int channels,
       bool floatOutput)
      : m_gpu(scenes::postGpuBackend()) {
    m_job.effects = post::parseEffects(effects, settings);
    m_job.backend = post::parseBackend(backend);
    m_job.channels = channels;
    if (channels < 0 || channels > 4) fail(ErrorKind::Usage, "channels must be 1 (grey), 2 (grey + alpha), 3 (RGB) or 4 (RGBA), got {}", channels);
    if (floatOutput) m_job.output = "result.exr";  // names the format: a float result, linear light
  }

  /// On the calling thread, with the GIL released: a GPU backend's GL context is current on
  /// the thread that made it, so every frame of a chain must come through the same thread
  /// (runReleased's worker threads would each be a new one). One image is quick; Ctrl-C
  /// is raised when it returns.
  py::tuple run(const py::array& array, const py::object& progress) {
    (void)progress;
    Image input = imageFrom(array, "the image");
    post::PostStats stats;
    Image result;
    {
      py::gil_scoped_release released;
      const std::atomic<bool> never{false};
      ToolRun run("post", settingsFor(&never, 0));
      result = post::processImage(m_job, std::move(input), run, m_gpu.get(), stats);
    }
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    py::dict info;
    info["effects"] = stats.effects;
    info["backend"] = stats.backend;
    info["width"] = stats.size.x;
    info["height"] = stats.size.y;
    return py::make_tuple(arrayOf(std::move(result)), info);
  }

private:
  post::PostJob m_job;
  std::unique_ptr<post::GpuBackend> m_gpu;
};

/// A video file's frames, one RGB array each (video::Source).
class Frames {
public:
  Frames(const std::string& path, std::int64_t first, std::int64_t end)
      : m_source(video::Source::open(path, {.firstFrame = first, .lastFrame = end, .keepAudio = false})) {}
  py::array next() {
    bool got;
    {
      py::gil_scoped_release released;
      got = m_source.read(m_frame);
    }
    if (!got) throw py::stop_iteration();
    return arrayOf(m_frame.image.withChannels(3));
  }
  py::dict info() const {
    const video::SourceInfo& i = m_source.info();
    py::dict d;
    d["width"] = i.size.x;
    d["height"] = i.size.y;
    d["fps"] = i.frameRate.valid() ? i.frameRate.value() : 0.0;
    d["frames"] = i.frameCount;
    d["codec"] = i.codec;
    d["rotation"] = i.rotation;
    return d;
  }

private:
  video::Source m_source;
  video::Frame m_frame;
};

// ------------------------------------------------------------------ cut
py::dict cutMesh(std::shared_ptr<Mesh> scene, const std::vector<std::string>& lights, const py::object& progress,
                 int threads) {
  cut::CutOptions options;
  for (const std::string& l : lights) options.lights.push_back(cut::parseLight(l));
  options.progress = !progress.is_none();
  cut::CutResult result = runReleased(progress, [&](const std::atomic<bool>* cancel) {
    ToolRun run("cut", settingsFor(cancel, threads));
    options.cancel = &run.cancelFlag();
    return cut::cut(*scene, options);
  });
  auto triangles = std::make_shared<cut::Triangles>(cut::triangulate(result.mesh));
  std::vector<std::uint32_t> masks(triangles->trianglePolygon.size());
  for (std::size_t t = 0; t < masks.size(); ++t) masks[t] = std::uint32_t(result.mesh.polygonMask[triangles->trianglePolygon[t]]);
  py::object owner = py::capsule(new std::shared_ptr<cut::Triangles>(triangles),
                                 [](void* p) { delete static_cast<std::shared_ptr<cut::Triangles>*>(p); });
  const Mesh& m = triangles->mesh;
  py::dict out;
  out["positions"] = viewOf(m.positions, {py::ssize_t(m.positions.size()), 3}, py::dtype::of<float>(), owner);
  out["triangles"] = viewOf(m.indices, {py::ssize_t(m.indices.size() / 3), 3}, py::dtype::of<std::uint32_t>(), owner);
  out["light_masks"] = py::array_t<std::uint32_t>(py::ssize_t(masks.size()), masks.data());
  out["triangle_polygon"] = viewOf(triangles->trianglePolygon, {py::ssize_t(triangles->trianglePolygon.size())},
                                   py::dtype::of<std::uint32_t>(), owner);
  out["report"] = pythonJson(cut::toJson(result.stats));
  out["lights"] = pythonJson(cut::toJson(result.lights));
  out["warnings"] = result.warnings;
  return out;
}

// ------------------------------------------------------------------ render
scenes::ContextPool& contexts() {
  static scenes::ContextPool pool(false);
  return pool;
}

py::array renderVariant(std::string variant, std::optional<std::pair<int, int>> size, std::optional<double> time,
                        const std::vector<std::string>& options) {
  // As `glint render` resolves it: a scene variant, or a model file as its own scene.
  scenes::Registry model;
  const scenes::VariantRef ref = scenes::registryFor(variant, model).resolve(variant);
  // None: the scene's own size; any given size is checked as --size is.
  const ivec2 chosen = size ? checkSize({size->first, size->second}) : ivec2(0);
  scenes::RenderRequest request{.size = chosen, .time = time, .options = options};
  Image image;
  {
    py::gil_scoped_release released;  // a GL context is per thread: render on this one
    contexts().use(ref.scene->profile);
    image = scenes::renderVariant(ref, request).image;
  }
  return arrayOf(std::move(image));
}

}  // namespace

namespace {

/// glint.Error and one subclass per kind (also a standard exception where one fits), and
/// the translator that raises them with the command's one-line message.
void bindErrors(py::module_& m) {
  static py::exception<Error> base(m, "Error", PyExc_RuntimeError);
  g_errors[int(ErrorKind::Internal)] = base.ptr();
  const auto kind = [&](ErrorKind k, const char* name, PyObject* also) {
    py::object cls = py::reinterpret_steal<py::object>(
        PyErr_NewException((std::string("glint.") + name).c_str(), py::make_tuple(base, py::handle(also)).ptr(), nullptr));
    m.attr(name) = cls;
    g_errors[int(k)] = cls.release().ptr();
  };
  kind(ErrorKind::Usage, "UsageError", PyExc_ValueError);
  kind(ErrorKind::Input, "InputError", PyExc_ValueError);
  kind(ErrorKind::Output, "OutputError", PyExc_OSError);
  kind(ErrorKind::NoGpu, "NoGpuError", PyExc_RuntimeError);
  kind(ErrorKind::OutOfMemory, "OutOfMemoryError", PyExc_MemoryError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      if (e.kind() == ErrorKind::Interrupted) {
        PyErr_SetString(PyExc_KeyboardInterrupt, escapedLine(e.what()).c_str());
        return;
      }
      // One line of valid UTF-8, as the command prints it (a message quoting a file name
      // that is not UTF-8 would otherwise become a UnicodeDecodeError).
      PyErr_SetString(g_errors[int(e.kind())], escapedLine(e.what()).c_str());
    } catch (const std::bad_alloc&) {
      PyErr_SetString(g_errors[int(ErrorKind::OutOfMemory)], "out of memory");
    }
  });
}

/// What this glint is: its version, threads, the bake's maps and options, post's effects,
/// the scenes' variants.
void bindInfo(py::module_& m) {
  m.def("version", [] { return std::string(ToolRun::version()); });
  m.def("threads", [] { return tbb::info::default_concurrency(); });
  // The maps by their report keys ("normal", "ao", "bent_normal"), each with its option's name.
  m.def("map_options", [] {
    std::vector<std::pair<std::string, std::string>> names;
    for (const bake::MapInfo& info : bake::mapTable()) names.emplace_back(info.reportKey, info.name);
    return names;
  });
  // The bake's options and maps as data (bake::describe, `glint bake --describe`): what the
  // Blender add-on builds its panel from.
  m.def("bake_options", [] { return pythonJson(bake::describe()); });
  m.def("effect_names", &post::effectNames);
  m.def("variants", [] {
    std::vector<std::string> names;
    for (const scenes::VariantRef& v : scenes::Registry::builtin().allVariants()) names.push_back(v.fullName());
    return names;
  });
}

/// glint.Mesh: arrays in, read-only views out (the mesh stays alive while a view does).
void bindMesh(py::module_& m) {
  py::class_<Mesh, std::shared_ptr<Mesh>>(m, "Mesh")
      .def(py::init(&meshFrom), py::arg("positions"), py::arg("indices"), py::arg("normals") = py::none(),
           py::arg("uvs") = py::none())
      .def_property_readonly("positions", [](py::object self) {
        const Mesh& mesh = self.cast<const Mesh&>();
        return viewOf(mesh.positions, {py::ssize_t(mesh.positions.size()), 3}, py::dtype::of<float>(), self);
      })
      .def_property_readonly("indices", [](py::object self) {
        const Mesh& mesh = self.cast<const Mesh&>();
        return viewOf(mesh.indices, {py::ssize_t(mesh.triangleCount()), 3}, py::dtype::of<std::uint32_t>(), self);
      })
      .def_property_readonly("normals", [](py::object self) -> py::object {
        const Mesh& mesh = self.cast<const Mesh&>();
        if (mesh.normals.empty()) return py::none();
        return viewOf(mesh.normals, {py::ssize_t(mesh.normals.size()), 3}, py::dtype::of<float>(), self);
      })
      .def_property_readonly("uvs", [](py::object self) -> py::object {
        const Mesh& mesh = self.cast<const Mesh&>();
        if (mesh.uvs.empty()) return py::none();
        return viewOf(mesh.uvs, {py::ssize_t(mesh.uvs.size()), 2}, py::dtype::of<float>(), self);
      })
      .def_property_readonly("vertex_count", &Mesh::vertexCount)
      .def_property_readonly("triangle_count", &Mesh::triangleCount)
      .def("__repr__", [](const Mesh& mesh) {
        return fmt::format("glint.Mesh({} vertices, {} triangles{}{})", mesh.vertexCount(), mesh.triangleCount(),
                           mesh.hasNormals() ? ", normals" : "", mesh.hasUvs() ? ", uvs" : "");
      });
  m.def("load_mesh", [](const std::string& path) {
    py::gil_scoped_release released;
    return std::make_shared<Mesh>(loadMesh(path));
  });
}

/// Images and the tools: reading and writing image files, bake, post, frames, normalmap,
/// cut and render, each through its library job.
void bindTools(py::module_& m) {
  m.def("read_image", [](const std::string& path) {
    Image image;
    {
      py::gil_scoped_release released;
      image = loadImage(path);
    }
    return arrayOf(std::move(image));
  });
  m.def("write_image", [](const std::string& path, const py::array& array) {
    const Image image = imageFrom(array, "the image");
    py::gil_scoped_release released;
    saveImage(image, path);
  });

  m.def("bake", &bakeArrays);
  m.def("rgba_rows_up", &rgbaRowsUp);
  m.def("bake_batch", &bakeBatch);
  py::class_<Post>(m, "Post")
      .def(py::init<std::vector<std::string>, std::vector<std::string>, const std::string&, int, bool>())
      .def("run", &Post::run);
  py::class_<Frames>(m, "Frames")
      .def(py::init<const std::string&, std::int64_t, std::int64_t>())
      .def("__iter__", [](py::object self) { return self; })
      .def("__next__", &Frames::next)
      .def_property_readonly("info", &Frames::info);
  m.def("normalmap", [](const py::array& height, std::optional<float> given, bool wrap, const std::string& formula) {
    // The command's options, checks and words (image/normalmap.h), then its computation.
    const NormalMapOptions options{.scale = given.value_or(NormalMapOptions{}.scale), .wrap = wrap,
                                   .formula = parseNormalFormula(formula)};
    const Image input = imageFrom(height, "the height map");
    checkHeightMap(input, options, "the height array");
    Image out;
    {
      py::gil_scoped_release released;
      out = withHeightAlpha(heightToNormalMap(input, options), input);
    }
    return arrayOf(std::move(out));
  });
  m.def("cut", &cutMesh);
  m.def("render", &renderVariant);
}

}  // namespace

PYBIND11_MODULE(_glint, m) {
  m.doc() = "glint's compiled core; use the glint package (glint/__init__.py)";
  log::setLevel(log::Level::Warn);  // a library in a notebook: warnings and errors only
  bindErrors(m);
  bindInfo(m);
  bindMesh(m);
  bindTools(m);
}

#include "glint/post/effects.h"

#include "glint/core/error.h"
#include "glint/core/text.h"
#include "glint/image/fourier.h"
#include "glint/image/post.h"
#include "cpu_kernels.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <utility>

namespace glint::post {

namespace {
constexpr float kInf = std::numeric_limits<float>::infinity();

// ---------------------------------------------------------------------------
// The frequency-domain effects: their parameters into a FrequencyFilter, which the FFT
// passes of both backends run (and YUV planes take: linear filters commute with the matrix).
using FilterOf = FrequencyFilter (*)(const Effect&);

// An entry whose work is the FFT filter, with image/fourier.h's checks for the frame size.
EffectDef filterEffect(const char* name, const char* summary, std::vector<EffectParam> params, FilterOf filter) {
  return {.name = name,
          .summary = summary,
          .params = std::move(params),
          .cpu = cpu::filter,
          .yuv = cpu::filterYuv,
          .filter = filter,
          .validate = [filter](const Effect& e, ivec2 size) { validateFilter(filter(e), size.x, size.y); }};
}

FrequencyFilter radialFilter(const Effect& e, FilterKind kind, const char* cutoff) {
  FrequencyFilter f;
  f.kind = kind;
  f.cutoff = e.value(cutoff);
  f.order = int(e.value("order"));
  f.offset = e.value("offset");
  return f;
}

FrequencyFilter kernelFilter(KernelShape shape, float size) {
  FrequencyFilter f;
  f.kind = FilterKind::Kernel;
  f.kernel = shape;
  f.size = size;
  return f;
}

std::vector<EffectParam> passParams(float cutoff, float offset) {
  return {{.name = "cutoff", .help = "cutoff frequency, cycles per pixel (0.5 = Nyquist)", .value = cutoff, .min = 0.0f,
           .max = 0.75f, .minExcluded = true, .sliderMin = 0.005f, .sliderMax = 0.5f},
          {.name = "order", .help = "Butterworth order (0: ideal brick wall, rings)", .type = ParamType::Int, .value = 2,
           .min = 0, .max = 16, .sliderMin = 0, .sliderMax = 8},
          {.name = "offset", .help = "added to the result (0.5 shows a high- or band-pass around mid-gray)",
           .value = offset, .sliderMin = 0.0f, .sliderMax = 1.0f}};
}

std::vector<EffectParam> bandParams() {
  std::vector<EffectParam> p = passParams(0.12f, 0.5f);
  p[0].name = "high";
  p[0].help = "upper edge, cycles per pixel";
  p.insert(p.begin(), {.name = "low", .help = "lower edge, cycles per pixel (0.5 = Nyquist)", .value = 0.03f, .min = 0.0f,
                       .max = 0.75f, .sliderMin = 0.0f, .sliderMax = 0.3f});
  return p;
}

EffectParam kernelParam(const char* name, const char* help, float value) {
  return {.name = name, .help = help, .value = value, .min = 0.0f, .max = float(kMaxImageSide / 2), .minExcluded = true,
          .sliderMin = 0.5f, .sliderMax = 24.0f};
}

// ---------------------------------------------------------------------------
// The table. Adding an effect: an entry here.
const std::vector<EffectDef>& table() {
  static const std::vector<EffectDef> defs = {
      {.name = "sepia",
       .summary = "WWDC 2003 session 212's YIQ sepia: keep Y, hard-code I and Q (a dot product and an add)",
       .params = {{.name = "i", .help = "hard-coded I (orange ↔ blue), WWDC 2003 session 212: 0.2", .value = 0.2f, .min = -1.0f,
                   .max = 1.0f, .sliderMin = -0.5f, .sliderMax = 0.5f},
                  {.name = "q", .help = "hard-coded Q (purple ↔ green), WWDC 2003 session 212: 0", .value = 0.0f, .min = -1.0f,
                   .max = 1.0f, .sliderMin = -0.5f, .sliderMax = 0.5f}},
       .cpu = cpu::sepia,
       .yuv = cpu::sepiaYuv},
      {.name = "sobel",
       .summary = "Sobel edges of the luma, gray",
       .params = {{.name = "output",
                   .help = "both directions; horizontal = |Gy|, vertical = |Gx|; dx, dy signed (mid-gray = 0)",
                   .type = ParamType::Choice, .sliderMin = 0, .sliderMax = 4,
                   .choices = {"magnitude", "horizontal", "vertical", "dx", "dy"}},
                  {.name = "scale", .help = "gain before clamping (1: a black-to-white step is white)", .value = 1.0f,
                   .min = 0.0f, .minExcluded = true, .sliderMin = 0.25f, .sliderMax = 8.0f}},
       .cpu = cpu::sobel,
       .yuv = cpu::sobelYuv},
      {.name = "edges",
       .summary = "Sobel lines composited over the image (darkening): the NPR outline",
       .params = {{.name = "scale", .help = "how fast lines darken above the threshold", .value = 2.0f, .min = 0.0f,
                   .minExcluded = true, .sliderMin = 0.25f, .sliderMax = 10.0f},
                  {.name = "threshold", .help = "Sobel magnitudes below this draw nothing", .value = 0.25f,
                   .sliderMin = 0.0f, .sliderMax = 2.0f}},
       .cpu = cpu::edges},
      {.name = "kuwahara",
       .summary = "edge-preserving smoothing: mean of the calmest of four overlapping quadrants (2 passes)",
       .params = {{.name = "size", .help = "quadrant edge length (WWDC 2003 session 212: 3, a 5×5 window)", .type = ParamType::Int,
                   .value = 3, .min = 2, .max = 8, .sliderMin = 2, .sliderMax = 8}},
       .cpu = cpu::kuwahara},
      {.name = "posterize",
       .summary = "kuwahara then edges: WWDC 2003 session 212's NPR look (size, scale, threshold)",
       .expandsTo = {"kuwahara", "edges"}},
      {.name = "spectrum",
       .summary = "log magnitude of the luma's DFT, centred (GPU FFT; FFTW on the CPU)",
       .cpu = cpu::spectrum},
      filterEffect("lowpass", "frequency-domain low-pass (GPU FFT, multiply, inverse FFT)", passParams(0.05f, 0.0f),
                   +[](const Effect& e) { return radialFilter(e, FilterKind::LowPass, "cutoff"); }),
      filterEffect("highpass", "frequency-domain high-pass, around mid-gray", passParams(0.03f, 0.5f),
                   +[](const Effect& e) { return radialFilter(e, FilterKind::HighPass, "cutoff"); }),
      filterEffect("bandpass", "frequency-domain band-pass, around mid-gray", bandParams(), +[](const Effect& e) {
        FrequencyFilter f = radialFilter(e, FilterKind::BandPass, "high");
        f.low = e.value("low");
        return f;
      }),
      filterEffect("blur", "Gaussian blur as a convolution via FFT (circular)",
                   {kernelParam("sigma", "Gaussian σ in pixels", 4.0f)},
                   +[](const Effect& e) { return kernelFilter(KernelShape::Gaussian, e.value("sigma")); }),
      filterEffect("bokeh", "disk blur (a lens's out-of-focus look) as a convolution via FFT (circular)",
                   {kernelParam("radius", "disk radius in pixels", 6.0f)},
                   +[](const Effect& e) { return kernelFilter(KernelShape::Disk, e.value("radius")); }),
  };
  return defs;
}

// ---------------------------------------------------------------------------
std::string number(float v) { return fmt::format("{}", v); }

const EffectParam* findParam(const EffectDef& def, std::string_view name, std::size_t* index = nullptr) {
  for (std::size_t i = 0; i < def.params.size(); ++i) {
    if (name == def.params[i].name) {
      if (index) *index = i;
      return &def.params[i];
    }
  }
  return nullptr;
}

std::string valueText(const EffectParam& p, const std::variant<float, int>& v) {
  if (p.type == ParamType::Choice) return p.choices.at(std::size_t(std::get<int>(v)));
  return p.type == ParamType::Int ? std::to_string(std::get<int>(v)) : number(std::get<float>(v));
}

// Error(Usage) "edges.scale: -1 is out of range (0, ∞)" for a number outside the parameter's range.
void checkRange(const EffectDef& def, const EffectParam& p, float v) {
  if (p.type == ParamType::Choice) {
    if (v < 0 || v >= float(p.choices.size())) {
      fail(ErrorKind::Usage, "{}.{}: choice {} is out of range ({})", def.name, p.name, v, p.rangeText());
    }
    return;
  }
  if (v < p.min || v > p.max || (p.minExcluded && v == p.min)) {
    fail(ErrorKind::Usage, "{}.{}: {} is out of range {}", def.name, p.name, v,
         p.type == ParamType::Int ? "(" + p.rangeText() + ")" : p.rangeText());
  }
}

std::vector<std::string> splitList(std::string_view text) {
  std::vector<std::string> items;
  for (const auto field : splitFields(text, ','))
    if (!field.empty()) items.emplace_back(field);
  return items;
}

std::pair<std::string, std::string> splitAssignment(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size()) {
    fail(ErrorKind::Usage, "parameter '{}' must be name=value", printable(text));
  }
  return {text.substr(0, eq), text.substr(eq + 1)};
}

std::string paramList(const EffectDef& def) {
  std::vector<std::string> names;
  const auto add = [&](const EffectDef& d) {
    for (const auto& p : d.params) names.push_back(p.name);
  };
  add(def);
  for (const char* part : def.expandsTo) add(*findEffect(part));
  return names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "));
}

// The entry named `name`, or Error(Usage) listing them all.
const EffectDef& requireEffect(std::string_view name) {
  const EffectDef* def = findEffect(name);
  if (!def) fail(ErrorKind::Usage, "unknown effect '{}'; effects: {}", printable(name), fmt::join(effectNames(), ", "));
  return *def;
}
}  // namespace

std::string EffectParam::rangeText() const {
  if (type == ParamType::Choice) return fmt::format("{}", fmt::join(choices, "|"));
  if (type == ParamType::Int) return fmt::format("{}..{}", int(min), int(max));
  const auto bound = [](float v) { return std::isinf(v) ? std::string(v < 0 ? "−∞" : "∞") : fmt::format("{}", v); };
  return fmt::format("{}{}, {}{}", minExcluded || std::isinf(min) ? "(" : "[", bound(min), bound(max),
                     std::isinf(max) ? ")" : "]");
}

std::span<const EffectDef> effectTable() { return table(); }

const EffectDef* findEffect(std::string_view name) {
  for (const auto& d : table())
    if (name == d.name) return &d;
  return nullptr;
}

float Effect::value(std::string_view param) const {
  std::size_t i = 0;
  if (!findParam(*def, param, &i)) fail(ErrorKind::Internal, "effect '{}' has no parameter '{}'", def->name, param);
  return std::visit([](auto v) { return float(v); }, values[i]);
}

bool Effect::set(std::string_view param, std::string_view text) {
  std::size_t i = 0;
  const EffectParam* p = findParam(*def, param, &i);
  if (!p) return false;
  const std::string what = fmt::format("{}.{}", def->name, p->name);
  switch (p->type) {
    case ParamType::Float: {
      const float v = parseFloat(text, what);
      checkRange(*def, *p, v);
      values[i] = v;
      break;
    }
    case ParamType::Int: values[i] = parseInt(text, what, int(p->min), int(p->max)); break;
    case ParamType::Choice: {
      const auto it = std::find(p->choices.begin(), p->choices.end(), text);
      if (it == p->choices.end()) {
        fail(ErrorKind::Usage, "{} must be {}, got '{}'", what, fmt::join(p->choices, ", "), printable(text));
      }
      values[i] = int(it - p->choices.begin());
      break;
    }
  }
  return true;
}

std::string Effect::describe() const {
  std::string s = def->name;
  if (def->params.empty()) return s;
  s += "(";
  for (std::size_t i = 0; i < def->params.size(); ++i) {
    s += (i ? "," : "") + std::string(def->params[i].name) + "=" + valueText(def->params[i], values[i]);
  }
  return s + ")";
}

std::string Effect::spec() const {
  std::string s = def->name;
  for (std::size_t i = 0; i < def->params.size(); ++i)
    s += (i ? "," : ":") + std::string(def->params[i].name) + "=" + valueText(def->params[i], values[i]);
  return s;
}

std::vector<std::string> effectNames() {
  std::vector<std::string> names;
  for (const auto& d : table()) names.push_back(d.name);
  return names;
}

Effect makeEffect(std::string_view name) {
  const EffectDef& def = requireEffect(name);
  if (!def.expandsTo.empty()) fail(ErrorKind::Usage, "'{}' is several effects: use parseEffects", def.name);
  Effect e{.def = &def, .values = {}};
  for (const auto& p : def.params) {
    if (p.type == ParamType::Float) e.values.emplace_back(p.value);
    else e.values.emplace_back(int(p.value));
  }
  return e;
}

std::vector<Effect> parseEffects(std::span<const std::string> specs, std::span<const std::string> settings) {
  std::vector<Effect> chain;
  for (const auto& spec : specs) {
    const auto colon = spec.find(':');
    const std::string name = spec.substr(0, colon);
    const std::string params = colon == std::string::npos ? "" : spec.substr(colon + 1);
    const EffectDef& def = requireEffect(name);
    std::vector<Effect> added;
    if (def.expandsTo.empty()) added.push_back(makeEffect(name));
    for (const char* part : def.expandsTo) added.push_back(makeEffect(part));
    for (const auto& assignment : splitList(params)) {
      const auto [param, value] = splitAssignment(assignment);
      bool taken = false;
      for (auto& e : added) taken = e.set(param, value) || taken;
      if (!taken) {
        fail(ErrorKind::Usage, "effect '{}' has no parameter '{}' (it takes: {})", printable(name), printable(param),
             paramList(def));
      }
    }
    chain.insert(chain.end(), added.begin(), added.end());
  }
  for (const auto& setting : settings) {
    for (const auto& assignment : splitList(setting)) {
      auto [param, value] = splitAssignment(assignment);
      std::string only;
      if (const auto dot = param.find('.'); dot != std::string::npos) {
        only = param.substr(0, dot);
        param = param.substr(dot + 1);
        if (!findEffect(only)) fail(ErrorKind::Usage, "--set {}: unknown effect '{}'", printable(assignment), printable(only));
      }
      bool taken = false;
      for (auto& e : chain)
        if (only.empty() || e.name() == only) taken = e.set(param, value) || taken;
      if (!taken) {
        if (!only.empty()) {
          fail(ErrorKind::Usage, "--set {}: no '{}' effect with a parameter '{}' in the chain", printable(assignment),
               printable(only), printable(param));
        }
        fail(ErrorKind::Usage, "--set {}: no effect in the chain has a parameter '{}'", printable(assignment), printable(param));
      }
    }
  }
  return chain;
}

std::string effectHelp() {
  std::string s = "Effects (-e NAME[:param=value,...], in chain order; --set [effect.]param=value):\n";
  for (const auto& d : table()) {
    s += fmt::format("  {:<10} {}\n", d.name, d.summary);
    if (d.params.empty()) continue;
    const Effect e = makeEffect(d.name);
    for (std::size_t i = 0; i < d.params.size(); ++i) {
      const EffectParam& p = d.params[i];
      const std::string range = p.type == ParamType::Choice               ? ", one of " + p.rangeText()
                                : std::isinf(p.min) && std::isinf(p.max) ? ""
                                                                         : " in " + p.rangeText();
      s += fmt::format("  {:<10}   {}={}{}  {}\n", "", p.name, valueText(p, e.values[i]), range, p.help);
    }
  }
  return s;
}

void validateEffect(const Effect& e, ivec2 size) {
  if (!e.def || e.values.size() != e.def->params.size()) fail(ErrorKind::Internal, "an effect without its table entry");
  for (std::size_t i = 0; i < e.values.size(); ++i) {
    checkRange(*e.def, e.def->params[i], std::visit([](auto v) { return float(v); }, e.values[i]));
  }
  if (e.def->validate) e.def->validate(e, size);
}

}  // namespace glint::post

#include "glint/render/post/effects.h"

#include "glint/core/error.h"
#include "glint/core/text.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>
#include <string_view>

namespace glint::render::post {

namespace {
// One parameter of one effect: how to read it into an Effect and how to show its value.
struct Param {
  const char* name;
  const char* help;
  std::function<void(Effect&, const std::string&)> set;
  std::function<std::string(const Effect&)> get;
};

struct EffectDef {
  const char* name;
  const char* help;
  std::function<Effect()> make;
  std::vector<Param> params;
};

float parseFloat(const std::string& text, const char* what) {
  std::size_t used = 0;
  float v = 0;
  try {
    v = std::stof(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(v)) {
    fail(ErrorKind::Usage, "{} must be a number, got '{}'", printable(what), printable(text));
  }
  return v;
}

int parseInt(const std::string& text, const char* what) {
  const float v = parseFloat(text, what);
  if (v != std::floor(v)) fail(ErrorKind::Usage, "{} must be a whole number, got '{}'", printable(what), printable(text));
  // Converting a float past int's range is undefined (found by fuzz_options under UBSan).
  if (std::abs(v) > 1e9f) fail(ErrorKind::Usage, "{} is out of range, got '{}'", printable(what), printable(text));
  return int(v);
}

std::string number(float v) { return fmt::format("{}", v); }

// A float parameter, given as the field it sets (a lambda: the fields sit in different
// option structs).
using FloatField = float& (*)(Effect&);
Param floatParam(const char* name, const char* help, FloatField field) {
  return {name, help, [name, field](Effect& e, const std::string& v) { field(e) = parseFloat(v, name); },
          [field](const Effect& e) {
            Effect copy = e;
            return number(field(copy));
          }};
}
#define GLINT_FIELD(expr) +[](Effect& e) -> float& { return expr; }

std::vector<Param> filterParams(bool band, bool kernel, const char* sizeName) {
  std::vector<Param> p;
  if (kernel) {
    p.push_back(floatParam(sizeName, std::string_view(sizeName) == "radius" ? "disk radius in pixels" : "Gaussian σ in pixels",
                           GLINT_FIELD(e.filter.size)));
    return p;
  }
  if (band) {
    p.push_back(floatParam("low", "lower edge, cycles per pixel (0.5 = Nyquist)", GLINT_FIELD(e.filter.low)));
    p.push_back(floatParam("high", "upper edge, cycles per pixel", GLINT_FIELD(e.filter.cutoff)));
  } else {
    p.push_back(floatParam("cutoff", "cutoff frequency, cycles per pixel (0.5 = Nyquist)",
                           GLINT_FIELD(e.filter.cutoff)));
  }
  p.push_back({"order", "Butterworth order (0: ideal brick wall, rings)",
               [](Effect& e, const std::string& v) { e.filter.order = parseInt(v, "order"); },
               [](const Effect& e) { return std::to_string(e.filter.order); }});
  p.push_back(floatParam("offset", "added to the result (0.5 shows a high- or band-pass around mid-gray)",
                         GLINT_FIELD(e.filter.offset)));
  return p;
}

Effect filterEffect(const char* name, FilterKind kind, float offset, KernelShape shape = KernelShape::Gaussian,
                    float size = 4.0f) {
  Effect e;
  e.name = name;
  e.kind = EffectKind::Filter;
  e.filter.kind = kind;
  e.filter.offset = offset;
  e.filter.kernel = shape;
  e.filter.size = size;
  if (kind == FilterKind::LowPass) e.filter.cutoff = 0.05f;
  if (kind == FilterKind::HighPass) e.filter.cutoff = 0.03f;
  if (kind == FilterKind::BandPass) {
    e.filter.low = 0.03f;
    e.filter.cutoff = 0.12f;
  }
  return e;
}

const std::vector<EffectDef>& definitions() {
  static const std::vector<EffectDef> defs = [] {
    std::vector<EffectDef> d;
    d.push_back({"sepia", "the seed's YIQ sepia: keep Y, hard-code I and Q (a dot product and an add)",
                 [] { Effect e; e.name = "sepia"; e.kind = EffectKind::Sepia; return e; },
                 {floatParam("i", "hard-coded I (orange ↔ blue), the seed: 0.2", GLINT_FIELD(e.sepia.i)),
                  floatParam("q", "hard-coded Q (purple ↔ green), the seed: 0", GLINT_FIELD(e.sepia.q))}});
    d.push_back({"sobel", "Sobel edges of the luma, gray",
                 [] { Effect e; e.name = "sobel"; e.kind = EffectKind::Sobel; return e; },
                 {{"output", "magnitude (both), horizontal (|Gy|), vertical (|Gx|), dx or dy (signed, mid-gray = 0)",
                   [](Effect& e, const std::string& v) {
                     if (v == "magnitude" || v == "both") e.sobel.output = SobelOutput::Magnitude;
                     else if (v == "horizontal") e.sobel.output = SobelOutput::Horizontal;
                     else if (v == "vertical") e.sobel.output = SobelOutput::Vertical;
                     else if (v == "dx") e.sobel.output = SobelOutput::SignedX;
                     else if (v == "dy") e.sobel.output = SobelOutput::SignedY;
                     else fail(ErrorKind::Usage, "sobel output must be magnitude, horizontal, vertical, dx or dy, got '{}'", printable(v));
                   },
                   [](const Effect& e) {
                     switch (e.sobel.output) {
                       case SobelOutput::Horizontal: return std::string("horizontal");
                       case SobelOutput::Vertical: return std::string("vertical");
                       case SobelOutput::SignedX: return std::string("dx");
                       case SobelOutput::SignedY: return std::string("dy");
                       case SobelOutput::Magnitude: break;
                     }
                     return std::string("magnitude");
                   }},
                  floatParam("scale", "gain before clamping (1: a black-to-white step is white)",
                             GLINT_FIELD(e.sobel.scale))}});
    d.push_back({"edges", "Sobel lines composited over the image (darkening): the NPR outline",
                 [] { Effect e; e.name = "edges"; e.kind = EffectKind::Edges; return e; },
                 {floatParam("scale", "how fast lines darken above the threshold", GLINT_FIELD(e.edges.scale)),
                  floatParam("threshold", "Sobel magnitudes below this draw nothing",
                             GLINT_FIELD(e.edges.threshold))}});
    d.push_back({"kuwahara", "edge-preserving smoothing: mean of the calmest of four overlapping quadrants (2 passes)",
                 [] { Effect e; e.name = "kuwahara"; e.kind = EffectKind::Kuwahara; return e; },
                 {{"size", "quadrant edge length 2..8 (the seed: 3)",
                   [](Effect& e, const std::string& v) { e.kuwahara.size = parseInt(v, "size"); },
                   [](const Effect& e) { return std::to_string(e.kuwahara.size); }}}});
    d.push_back({"spectrum", "log magnitude of the luma's 2D DFT, centred (GPU FFT)",
                 [] { Effect e; e.name = "spectrum"; e.kind = EffectKind::Spectrum; return e; }, {}});
    d.push_back({"lowpass", "frequency-domain low-pass (GPU FFT, multiply, inverse FFT)",
                 [] { return filterEffect("lowpass", FilterKind::LowPass, 0.0f); }, filterParams(false, false, "")});
    d.push_back({"highpass", "frequency-domain high-pass, around mid-gray",
                 [] { return filterEffect("highpass", FilterKind::HighPass, 0.5f); }, filterParams(false, false, "")});
    d.push_back({"bandpass", "frequency-domain band-pass, around mid-gray",
                 [] { return filterEffect("bandpass", FilterKind::BandPass, 0.5f); }, filterParams(true, false, "")});
    d.push_back({"blur", "Gaussian blur as a convolution via FFT (circular)",
                 [] { return filterEffect("blur", FilterKind::Kernel, 0.0f, KernelShape::Gaussian, 4.0f); },
                 filterParams(false, true, "sigma")});
    d.push_back({"bokeh", "disk blur (a lens's out-of-focus look) as a convolution via FFT (circular)",
                 [] { return filterEffect("bokeh", FilterKind::Kernel, 0.0f, KernelShape::Disk, 6.0f); },
                 filterParams(false, true, "radius")});
    return d;
  }();
  return defs;
}

const EffectDef* find(const std::string& name) {
  for (const auto& d : definitions())
    if (name == d.name) return &d;
  return nullptr;
}

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) items.push_back(item);
  return items;
}

// Applies "param=value" to `effect`; false when it has no such parameter.
bool apply(Effect& effect, const std::string& param, const std::string& value) {
  const EffectDef* def = find(effect.name);
  for (const auto& p : def->params) {
    if (param == p.name) {
      p.set(effect, value);
      return true;
    }
  }
  return false;
}

std::pair<std::string, std::string> splitAssignment(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size()) {
    fail(ErrorKind::Usage, "parameter '{}' must be name=value", printable(text));
  }
  return {text.substr(0, eq), text.substr(eq + 1)};
}

std::string paramList(const EffectDef& def) {
  if (def.params.empty()) return "none";
  std::string s;
  for (const auto& p : def.params) s += (s.empty() ? "" : ", ") + std::string(p.name);
  return s;
}
}  // namespace

std::vector<std::string> effectNames() {
  std::vector<std::string> names;
  for (const auto& d : definitions()) names.push_back(d.name);
  names.insert(names.begin() + 4, "posterize");
  return names;
}

Effect makeEffect(const std::string& name) {
  const EffectDef* def = find(name);
  if (!def) {
    std::string all;
    for (const auto& n : effectNames()) all += (all.empty() ? "" : ", ") + n;
    fail(ErrorKind::Usage, "unknown effect '{}'; effects: {}", printable(name), all);
  }
  return def->make();
}

std::vector<Effect> parseEffects(std::span<const std::string> specs, std::span<const std::string> settings) {
  std::vector<Effect> chain;
  for (const auto& spec : specs) {
    const auto colon = spec.find(':');
    const std::string name = spec.substr(0, colon);
    const std::string params = colon == std::string::npos ? "" : spec.substr(colon + 1);
    std::vector<Effect> added;
    if (name == "posterize") {
      added = {makeEffect("kuwahara"), makeEffect("edges")};
    } else {
      added = {makeEffect(name)};
    }
    for (const auto& assignment : splitList(params)) {
      const auto [param, value] = splitAssignment(assignment);
      bool taken = false;
      for (auto& e : added) taken = apply(e, param, value) || taken;
      if (!taken) {
        fail(ErrorKind::Usage, "effect '{}' has no parameter '{}' (it takes: {})", printable(name), printable(param),
             name == "posterize" ? "size, scale, threshold" : paramList(*find(name)));
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
        if (!find(only)) fail(ErrorKind::Usage, "--set {}: unknown effect '{}'", printable(assignment), printable(only));
      }
      bool taken = false;
      for (auto& e : chain)
        if (only.empty() || e.name == only) taken = apply(e, param, value) || taken;
      if (!taken) {
        if (!only.empty()) fail(ErrorKind::Usage, "--set {}: no '{}' effect with a parameter '{}' in the chain", printable(assignment), printable(only), printable(param));
        fail(ErrorKind::Usage, "--set {}: no effect in the chain has a parameter '{}'", printable(assignment), printable(param));
      }
    }
  }
  return chain;
}

std::string Effect::describe() const {
  const EffectDef* def = find(name);
  std::string s = name;
  if (!def || def->params.empty()) return s;
  s += "(";
  for (std::size_t i = 0; i < def->params.size(); ++i)
    s += (i ? "," : "") + std::string(def->params[i].name) + "=" + def->params[i].get(*this);
  return s + ")";
}

std::string effectHelp() {
  std::string s = "Effects (-e NAME[:param=value,...], in chain order; --set [effect.]param=value):\n";
  for (const auto& d : definitions()) {
    const Effect e = d.make();
    s += fmt::format("  {:<10} {}\n", d.name, d.help);
    for (const auto& p : d.params) s += fmt::format("  {:<10}   {}={}  {}\n", "", p.name, p.get(e), p.help);
    if (std::string(d.name) == "kuwahara") {
      s += fmt::format("  {:<10} {}\n", "posterize", "kuwahara then edges: the seed's NPR look (size, scale, threshold)");
    }
  }
  return s;
}

void validateEffect(const Effect& e, ivec2 size) {
  switch (e.kind) {
    case EffectKind::Kuwahara:
      if (e.kuwahara.size < 2 || e.kuwahara.size > 8) {
        fail(ErrorKind::Usage, "kuwahara: size must be 2..8, got {}", e.kuwahara.size);
      }
      break;
    case EffectKind::Filter: validateFilter(e.filter, size.x, size.y); break;
    case EffectKind::Sobel:
      if (!(e.sobel.scale > 0.0f)) fail(ErrorKind::Usage, "sobel: scale must be positive, got {}", e.sobel.scale);
      break;
    case EffectKind::Edges:
      if (!(e.edges.scale > 0.0f)) fail(ErrorKind::Usage, "edges: scale must be positive, got {}", e.edges.scale);
      break;
    case EffectKind::Sepia:
      if (std::abs(e.sepia.i) > 1.0f || std::abs(e.sepia.q) > 1.0f) {
        fail(ErrorKind::Usage, "sepia: i and q must be in [-1, 1], got i={} q={}", e.sepia.i, e.sepia.q);
      }
      break;
    case EffectKind::Spectrum: break;
  }
}

}  // namespace glint::render::post

#pragma once
// glint/post/effects.h — the effects of `glint post -e NAME`, by name, with their typed
// parameters and their CPU implementations: one table (effectTable()) from which the command
// line's parsing, `glint post --effects`, the CPU backend (post/cpu.h), the GPU chain
// (render/post/chain.h, whose passes register against the table by name) and the viewer's
// panel (the post/* scenes) all come. GL-free: the table, the CPU backend and the job
// (post/job.h) compile without OpenGL.
//
/// ```cpp
/// #include <glint/post/effects.h>
/// // glint post in.mp4 -o out.mp4 -e kuwahara -e edges:scale=3 --set size=4
/// const std::vector<std::string> specs = {"kuwahara", "edges:scale=3"};
/// const std::vector<std::string> settings = {"size=4"};
/// std::vector<glint::post::Effect> effects = glint::post::parseEffects(specs, settings);
/// // effects[0].describe() == "kuwahara(size=4)", effects[1].value("scale") == 3
/// effects[1].set("threshold", "0.5");              // as a slider or a program would
/// glint::post::validateEffect(effects[1], {1920, 1080});
/// ```
//
// The effects, their parameters, defaults and ranges are the table's: effectHelp() (`glint
// post --effects`) prints it, docs/post.md shows each effect.
//
// Parameters go after the name ("sobel:output=horizontal,scale=2") or in settings
// ("scale=2" applies to every effect in the chain that has a `scale`; "sobel.scale=2" to
// sobel only). Numbers are read by core/text.h's strict parsers; a value outside the
// parameter's range (EffectParam::min/max), a setting no effect takes, an unknown name or a
// bad value is Error(Usage), one line, naming it. The image/ headers (image/post.h,
// image/fourier.h) define what each parameter means.
//
// Adding an effect: one entry in the table in src/post/effects.cpp (name, summary, typed
// parameters, its CPU stage and, when it is defined on luma or linear in colour, its YUV
// stage: src/post/cpu.cpp, cpu_yuv.cpp), and its GPU pass: a class with typed options
// (render/post/passes.h, fft.h), a shader under shaders/post/, and one line registering it
// under the effect's name (src/render/post/effects.cpp). Parsing, --effects, both backends
// and the viewer's panel follow from the entry.

#include "glint/core/math.h"
#include "glint/image/fourier.h"

#include <functional>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace glint::post {

enum class ParamType {
  Float,  ///< a finite number in [min, max] (min excluded when minExcluded)
  Int,    ///< a whole number in [min, max]
  Choice  ///< one of `choices`, held as its index
};

/// One parameter of an effect.
struct EffectParam {
  const char* name;  ///< as typed: "scale" in "sobel:scale=2"
  const char* help;  ///< one line
  ParamType type = ParamType::Float;
  float value = 0.0f;  ///< the default (Choice: its index)
  float min = -std::numeric_limits<float>::infinity();  ///< accepted values (Float, Int)
  float max = std::numeric_limits<float>::infinity();
  bool minExcluded = false;  ///< (min, max]: a parameter that must be above `min`
  float sliderMin = 0.0f, sliderMax = 1.0f;  ///< the viewer's slider (inside the accepted range)
  std::vector<const char*> choices = {};     ///< Choice: the names, in index order

  /// "[-1, 1]", "(0, 0.75]", "(0, ∞)", "2..8", "magnitude|horizontal|...".
  std::string rangeText() const;
};

struct Effect;
class CpuStage;  ///< an effect on the CPU, RGBA frames (src/post/cpu_kernels.h)
class YuvStage;  ///< an effect on a video's YUV planes (src/post/cpu_kernels.h)

/// One entry of the effect table.
struct EffectDef {
  const char* name;     ///< "-e NAME"
  const char* summary;  ///< one line for --effects
  std::vector<EffectParam> params = {};
  /// The effect on the CPU (post/cpu.h's CpuChain), prepared for frames of `size`: its
  /// tables, FFT plans. Null for an alias.
  std::unique_ptr<CpuStage> (*cpu)(const Effect&, ivec2 size) = nullptr;
  /// Its version on a video's YUV planes, for an effect defined on luma or linear in colour
  /// (post/cpu.h explains each); null when it has none. Made for even sizes only.
  std::unique_ptr<YuvStage> (*yuv)(const Effect&, ivec2 size) = nullptr;
  /// The FFT filters' (lowpass, highpass, bandpass, blur, bokeh): the FrequencyFilter its
  /// parameters describe, which both backends' FFT passes run. Null for the others.
  FrequencyFilter (*filter)(const Effect&) = nullptr;
  /// Checks that need the frame size or several parameters at once (a kernel larger than
  /// half the image, a band whose low edge is above its high one): Error(Usage). Optional.
  std::function<void(const Effect&, ivec2 size)> validate = {};
  /// An alias: expands to these effects ("posterize": kuwahara, edges). Empty otherwise.
  std::vector<const char*> expandsTo = {};
};

/// Every effect, in the order `--effects` lists them.
std::span<const EffectDef> effectTable();
/// The entry named `name`; nullptr when there is none.
const EffectDef* findEffect(std::string_view name);

/// One effect of a chain: its entry and a value per parameter (Float as float, Int and
/// Choice as int), in the entry's order. The viewer's sliders point into `values`.
struct Effect {
  const EffectDef* def = nullptr;
  std::vector<std::variant<float, int>> values;

  const char* name() const { return def->name; }
  /// A parameter's value as a number (Choice: its index). Error(Internal) for a name the
  /// effect does not have.
  float value(std::string_view param) const;
  /// Parses `text` for parameter `param` (a number or a choice's name) and checks its range:
  /// false when the effect has no such parameter, Error(Usage) for a bad value.
  bool set(std::string_view param, std::string_view text);
  /// "kuwahara(size=3)": the name and every parameter's value, for reports.
  std::string describe() const;
  /// "kuwahara:size=3": the name and every parameter's value as `-e` takes them
  /// (parseEffects gives this effect back).
  std::string spec() const;
};

/// Parses effect specs ("NAME" or "NAME:param=value,...") in chain order, then applies
/// `settings` ("param=value" or "effect.param=value", comma-separated lists allowed).
/// "posterize" expands to kuwahara and edges. Error(Usage) as described above.
std::vector<Effect> parseEffects(std::span<const std::string> specs, std::span<const std::string> settings = {});
/// One effect by name with default parameters (no alias such as "posterize": it is two effects).
Effect makeEffect(std::string_view name);
/// Every effect name, in the order of the table above.
std::vector<std::string> effectNames();
/// The table of names, parameters, ranges and defaults (for --help and --effects).
std::string effectHelp();

/// Error(Usage) when `effect` cannot run at this frame size: a parameter outside its range
/// (values set by a program or a slider), then the entry's own checks.
void validateEffect(const Effect& effect, ivec2 size);

}  // namespace glint::post

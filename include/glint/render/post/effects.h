#pragma once
// glint/render/post/effects.h — the effects of `glint post -e NAME`, by name, with their
// parameters: what the command line, the post/* scenes and the chain share.
//
//   // glint post in.mp4 -o out.mp4 -e kuwahara -e edges:scale=3 --set size=4
//   const auto effects = render::post::parseEffects({"kuwahara", "edges:scale=3"}, {"size=4"});
//   render::post::Chain chain(size, effects);
//
// Names (effectHelp() prints this table with every parameter):
//   sepia       the seed's YIQ sepia                    i, q
//   sobel       Sobel edges, gray                       output=magnitude|horizontal|vertical|dx|dy, scale
//   edges       Sobel lines darkening the image         scale, threshold
//   kuwahara    the two-pass Kuwahara filter            size
//   posterize   kuwahara then edges (the seed's NPR look): expands to those two effects
//   spectrum    log magnitude of the luma's DFT, centred
//   lowpass     Butterworth / ideal low-pass in the frequency domain    cutoff, order, offset
//   highpass    1 − low-pass                            cutoff, order, offset (default 0.5)
//   bandpass    band between low and high               low, high, order, offset (default 0.5)
//   blur        convolution with a Gaussian, via FFT    sigma
//   bokeh       convolution with a disk (a lens's out-of-focus blur), via FFT   radius
//
// Parameters go after the name ("sobel:output=horizontal,scale=2") or in settings
// ("scale=2" applies to every effect in the chain that has a `scale`; "sobel.scale=2" to
// sobel only). A setting no effect takes, an unknown name or a bad value is Error(Usage),
// one line, naming it. The image/ headers (image/post.h, image/fourier.h) define what each
// parameter means.

#include "glint/image/fourier.h"
#include "glint/image/post.h"

#include <span>
#include <string>
#include <vector>

namespace glint::render::post {

enum class EffectKind {
  Sepia,     ///< image/post.h sepiaReference
  Sobel,     ///< sobelReference
  Edges,     ///< edgesReference
  Kuwahara,  ///< kuwaharaReference (two passes on the GPU)
  Spectrum,  ///< image/fourier.h spectrumReference (GPU FFT)
  Filter     ///< frequencyFilterReference (GPU FFT, multiply, inverse FFT)
};

/// One effect of a chain, with its parameters.
struct Effect {
  std::string name;  ///< the name it was asked for ("lowpass", "blur", ...)
  EffectKind kind = EffectKind::Sepia;
  SepiaOptions sepia;
  SobelOptions sobel;
  EdgesOptions edges;
  KuwaharaOptions kuwahara;
  FrequencyFilter filter;  ///< Filter: which filter (kind, cutoff, kernel, ...)

  /// "kuwahara(size=3)": the name and every parameter's value, for reports.
  std::string describe() const;
};

/// Parses effect specs ("NAME" or "NAME:param=value,...") in chain order, then applies
/// `settings` ("param=value" or "effect.param=value", comma-separated lists allowed).
/// "posterize" expands to kuwahara and edges. Error(Usage) as described above.
std::vector<Effect> parseEffects(std::span<const std::string> specs, std::span<const std::string> settings = {});
/// One effect by name with default parameters (no "posterize": it is two effects).
Effect makeEffect(const std::string& name);
/// Every effect name, in the order of the table above.
std::vector<std::string> effectNames();
/// The table of names, parameters, ranges and defaults (for --help).
std::string effectHelp();

/// Error(Usage) when `effect` cannot run at this frame size (a kernel larger than half the
/// image, a Kuwahara quadrant size outside 2..8, ...).
void validateEffect(const Effect& effect, ivec2 size);

}  // namespace glint::render::post

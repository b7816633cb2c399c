#pragma once
// glint/scenes/gallery.h — `glint gallery`'s job: every registered variant (or those whose
// name contains a filter) rendered headless, timed, saved as DIR/<scene>/<variant>.png, and
// laid out in DIR/index.html (a table of contents, a section per scene, a filter box) with
// DIR/gallery.json (each variant's image, size, GPU and CPU times, notes). Variants that need
// a compatibility-profile context where none exists, or the video module where it cannot
// load, are skipped and marked. With `references`, every picture is compared with
// references/<scene>/<variant>.png at the golden tests' tolerance (checkAgainstReference in
// scenes/runner.h): the figures go into gallery.json, a difference image beside a picture
// beyond it.
//
/// ```cpp
/// glint::scenes::GalleryJob job;
/// job.output = "out/gallery";
/// job.filter = "shadows/";
/// job.repeats = 0;                                   // no timing: faster
/// const int status = glint::scenes::runGallery(job);  // 0; 1 only with references that differ
/// (void)status;
/// ```
#include "glint/core/math.h"

#include <filesystem>
#include <optional>
#include <string>

namespace glint::scenes {

struct GalleryJob {
  std::filesystem::path output = "out/gallery";  ///< the gallery's folder (created if missing)
  std::string filter;                              ///< only variants whose name contains it
  std::optional<ivec2> size;                       ///< every variant at this size, not its own
  std::filesystem::path references;                ///< compare with references/<scene>/<variant>.png
  int repeats = 5;                                 ///< frames timed per variant (0: none)
  bool glDebug = false;                            ///< GL debug output on (glint --gl-debug)
};

/// Runs the job (progress on a terminal, a line per skipped variant). Returns the exit
/// status: 0, or 1 with `references` when a picture differs beyond the tolerance or has no
/// reference. Error(Usage) when no variant matches; Error(Output) when the folder cannot be
/// made or written.
int runGallery(const GalleryJob& job);

}  // namespace glint::scenes

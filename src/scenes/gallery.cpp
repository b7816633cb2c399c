// glint gallery's job (scenes/gallery.h): every variant rendered, timed, and laid out in
// index.html and gallery.json.
#include "glint/scenes/gallery.h"

#include "glint/core/error.h"
#include "glint/core/file.h"
#include "glint/core/json.h"
#include "glint/core/log.h"
#include "glint/core/progress.h"
#include "glint/core/text.h"
#include "glint/gl/context.h"
#include "glint/image/image.h"
#include "glint/scenes/runner.h"
#include "glint/video/source.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

namespace glint::scenes {
namespace fs = std::filesystem;

namespace {
struct Entry {
  VariantRef ref;
  std::string image;  // relative to the gallery directory; empty when skipped
  std::string skipped;
  RenderResult result;
  std::optional<ReferenceCheck> check;  // --references: against DIR/<scene>/<variant>.png
  std::string noReference;              // --references: why there is no comparison
};

std::string timing(double ms) { return ms < 0 ? "–" : fmt::format("{:.2f} ms", ms); }

// The page's body: a table of contents, then a section per scene with a figure per variant.
std::string sections(const std::vector<Entry>& entries) {
  std::string body;
  const SceneDesc* current = nullptr;
  for (const auto& e : entries) {
    if (e.ref.scene != current) {
      if (current) body += "</div></section>\n";
      current = e.ref.scene;
      body += fmt::format("<section><h2 id=\"{0}\">{0}</h2><p class=summary>{1}</p><div class=grid>\n",
                          escapeHtml(current->name), escapeHtml(current->summary));
    }
    body += fmt::format("<figure data-name=\"{}\">", escapeHtml(e.ref.fullName()));
    if (e.skipped.empty()) {
      body += fmt::format("<a href=\"{0}\"><img src=\"{0}\" alt=\"{1}\" width={2} height={3} loading=lazy></a>",
                          escapeHtml(e.image), escapeHtml(e.ref.fullName()), e.result.image.width(),
                          e.result.image.height());
    } else {
      body += fmt::format("<div class=skipped>skipped: {}</div>", escapeHtml(e.skipped));
    }
    body += fmt::format("<figcaption><b>{}</b> <span class=t>GPU {} · CPU {}</span><br>{}", escapeHtml(e.ref.desc().name),
                        timing(e.result.gpuMs), timing(e.result.cpuMs), escapeHtml(e.ref.desc().description));
    if (!e.result.notes.empty()) body += fmt::format("<br><span class=notes>{}</span>", escapeHtml(e.result.notes));
    body += fmt::format("<br><code>glint render {}</code></figcaption></figure>\n", escapeHtml(e.ref.fullName()));
  }
  if (current) body += "</div></section>\n";
  // A table of contents: one link per scene, grouped as the sections are.
  std::string nav;
  const SceneDesc* listed = nullptr;
  for (const auto& e : entries) {
    if (e.ref.scene == listed) continue;
    listed = e.ref.scene;
    nav += fmt::format("<a href=\"#{0}\">{0}</a> ", escapeHtml(listed->name));
  }
  return "<nav>" + nav + "</nav>\n" + body;
}

std::string html(const std::vector<Entry>& entries, const gl::ContextInfo& info) {
  return fmt::format(R"(<!doctype html>
<html lang=en><head><meta charset=utf-8><title>glint gallery</title>
<meta name=viewport content="width=device-width, initial-scale=1">
<style>
body {{ font: 15px/1.45 system-ui, sans-serif; margin: 2em auto; max-width: 1400px; padding: 0 1em; background: #15171c; color: #dde; }}
h1 {{ margin-bottom: .2em; }} h2 {{ margin: 1.6em 0 .2em; border-bottom: 1px solid #333; }}
.summary {{ color: #aab; margin-top: .2em; }}
.grid {{ display: grid; grid-template-columns: repeat(auto-fill, minmax(300px, 1fr)); gap: 1.2em; }}
figure {{ margin: 0; background: #1d2027; border-radius: 6px; overflow: hidden; }}
img {{ width: 100%; height: auto; display: block; background: #000; }}
figcaption {{ padding: .6em .8em; font-size: 13.5px; }}
.t {{ color: #8c8; float: right; }} .notes {{ color: #cb8; }} code {{ color: #99a; font-size: 12px; }}
.skipped {{ padding: 3em 1em; color: #c88; text-align: center; }}
.meta {{ color: #889; }} nav a {{ color: #9bd; margin-right: .8em; white-space: nowrap; }}
#filter {{ font: inherit; margin: .4em 0 .8em; padding: .3em .6em; width: 22em; max-width: 100%; background: #1d2027;
  color: #dde; border: 1px solid #445; border-radius: 4px; }}
[hidden] {{ display: none !important; }}
</style></head><body>
<h1>glint gallery</h1>
<p class=meta>{} variants · rendered on {} ({}) · frame times are the median of several frames at each picture's size,
GPU time from GL_TIME_ELAPSED queries, CPU time including glFinish.{}</p>
<input type=search id=filter placeholder="Filter variants: shadows/, aniso …" aria-label="Filter variants" autocomplete=off>
{}
<script>
// The filter box: a variant shows when its name contains the text; a scene's section
// and its link in the table of contents show while one of its variants does.
document.getElementById('filter').addEventListener('input', (event) => {{
  const text = event.target.value.trim();
  for (const section of document.querySelectorAll('section')) {{
    let shown = 0;
    for (const figure of section.querySelectorAll('figure')) {{
      figure.hidden = !figure.dataset.name.includes(text);
      if (!figure.hidden) ++shown;
    }}
    section.hidden = shown === 0;
    const link = document.querySelector(`nav a[href="#${{CSS.escape(section.querySelector('h2').id)}}"]`);
    if (link) link.hidden = section.hidden;
  }}
}});
</script>
</body></html>
)",
                     entries.size(), escapeHtml(info.renderer), escapeHtml(info.version),
                     info.software ? " This is a software rasterizer: it defers rasterization to the next flush, so its "
                                     "GPU timer queries miss most of the work; the CPU time is the meaningful figure here."
                                   : "",
                     sections(entries));
}

// --references: the variant against DIR/<scene>/<variant>.png; a difference image beside
// the picture when it is beyond the tolerance.
void compareWithReference(Entry& e, const fs::path& references, const fs::path& dir) {
  const fs::path reference = references / (e.ref.fullName() + ".png");
  std::error_code ec;
  if (!fs::exists(reference, ec)) {
    e.noReference = fmt::format("no reference image {}", reference.string());
    return;
  }
  const Image expected = loadImage(reference);
  if (expected.width() != e.result.image.width() || expected.height() != e.result.image.height()) {
    e.noReference = fmt::format("the reference is {}x{}, the picture {}x{} (render at the default size)", expected.width(),
                                expected.height(), e.result.image.width(), e.result.image.height());
    return;
  }
  e.check = checkAgainstReference(expected, e.result.image, e.ref.desc().implementationDefined);
  if (!e.check->pass) saveImage(e.check->visual, dir / (e.ref.fullName() + ".diff.png"));
}

// The comparison's summary: one line, plus a line per variant beyond the tolerance. 1 when any.
int referenceSummary(const std::vector<Entry>& entries, const std::string& references) {
  std::size_t compared = 0, passed = 0, missing = 0, skipped = 0;
  double worstMean = 0.0;
  for (const Entry& e : entries) {
    skipped += e.skipped.empty() ? 0 : 1;
    if (!e.noReference.empty()) {
      ++missing;
      log::warn("{}: {}", e.ref.fullName(), e.noReference);
    }
    if (!e.check) continue;
    ++compared;
    worstMean = std::max(worstMean, e.check->meanAbs);
    if (e.check->pass) {
      ++passed;
    } else {
      log::warn("{}: beyond the reference's tolerance: mean {:.2f}/255, {:.3f} % of pixels differ, max {:.0f}/255",
                e.ref.fullName(), e.check->meanAbs * 255.0, e.check->differingFraction * 100.0, e.check->maxAbs * 255.0);
    }
  }
  log::info("gallery: {} of {} variants within the tolerance of {} (worst mean {:.2f}/255){}{}", passed, compared,
            references, worstMean * 255.0, missing ? fmt::format("; {} without a reference", missing) : "",
            skipped ? fmt::format("; {} skipped (see above)", skipped) : "");
  return passed == compared && missing == 0 ? 0 : 1;
}

std::string json(const std::vector<Entry>& entries, const gl::ContextInfo& info) {
  nlohmann::ordered_json variants = nlohmann::ordered_json::array();
  for (const auto& e : entries) {
    variants.push_back({{"name", e.ref.fullName()},
                        {"image", e.image},
                        {"skipped", e.skipped},
                        {"width", e.skipped.empty() ? e.result.image.width() : 0},
                        {"height", e.skipped.empty() ? e.result.image.height() : 0},
                        {"gpu_ms", e.result.gpuMs},
                        {"cpu_ms", e.result.cpuMs},
                        {"notes", e.result.notes}});
    if (e.check) {
      variants.back()["reference"] = {{"pass", e.check->pass},
                                      {"mean_steps", e.check->meanAbs * 255.0},
                                      {"max_steps", e.check->maxAbs * 255.0},
                                      {"differing_percent", e.check->differingFraction * 100.0}};
    } else if (!e.noReference.empty()) {
      variants.back()["reference"] = {{"pass", false}, {"missing", e.noReference}};
    }
  }
  const nlohmann::ordered_json out{{"renderer", info.renderer}, {"version", info.version}, {"variants", variants}};
  return jsonText(out);
}
}  // namespace

int runGallery(const GalleryJob& job) {
  const auto variants = Registry::builtin().match(job.filter);
  if (variants.empty()) fail(ErrorKind::Usage, "no variant matches '{}' (`glint list` shows them)", job.filter);
  const fs::path dir = job.output;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) fail(ErrorKind::Output, "cannot create '{}': {}", dir.string(), ec.message());
  checkWritable(dir / "index.html");

  RenderRequest request;
  if (job.size) request.size = *job.size;
  request.timingRepeats = job.repeats;
  ContextPool contexts(job.glDebug);
  contexts.use(gl::Profile::Core);
  const auto info = gl::queryContextInfo();

  std::vector<Entry> entries;
  Progress progress("gallery", variants.size());
  const auto start = std::chrono::steady_clock::now();
  for (const auto& ref : variants) {
    progress.setDetail(ref.fullName());
    Entry e{.ref = ref};
    if (!contexts.available(ref.scene->profile)) {
      e.skipped = contexts.unavailableReason(ref.scene->profile);
      log::warn("{}: skipped ({})", ref.fullName(), e.skipped);
    } else if (const std::string why = ref.scene->needsVideo ? video::unavailableReason() : ""; !why.empty()) {
      e.skipped = "its frames come through the video module: " + why;
      log::warn("{}: skipped ({})", ref.fullName(), e.skipped);
    } else {
      contexts.use(ref.scene->profile);
      e.result = renderVariant(ref, request);
      e.image = ref.fullName() + ".png";
      fs::create_directories(dir / fs::path(e.image).parent_path());
      saveImage(e.result.image, dir / e.image);
      if (!job.references.empty()) compareWithReference(e, job.references, dir);
    }
    entries.push_back(std::move(e));
    progress.advance();
  }
  progress.finish();
  writeTextAtomically(dir / "index.html", html(entries, info));
  writeTextAtomically(dir / "gallery.json", json(entries, info));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  log::info("gallery: {} variants in {:.1f} s → {}", entries.size(), seconds, (dir / "index.html").string());
  if (!job.references.empty()) return referenceSummary(entries, job.references.string());
  return 0;
}

}  // namespace glint::scenes

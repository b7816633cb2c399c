// bake_batch JOBS.json [--json REPORT] [--samples N] — `glint bake --batch` as a program
// linking the installed glint::bake: every job of the file checked, baked (high meshes
// shared), written and reported as the command does, through public headers only.
#include <glint/bake/job.h>
#include <glint/core/error.h>

#include <cstdio>
#include <cstring>

int main(int argc, char** argv) {
  glint::bake::BatchRequest request;
  request.tool.quiet = true;
  try {
    for (int i = 1; i < argc; ++i) {
      const bool hasValue = i + 1 < argc;
      if (std::strcmp(argv[i], "--json") == 0 && hasValue) request.tool.json = argv[++i];
      else if (std::strcmp(argv[i], "--samples") == 0 && hasValue) request.overrides["samples"] = argv[++i];
      else request.file = argv[i];
    }
    return glint::bake::runBatch(request);
  } catch (const glint::Error& e) {
    std::fprintf(stderr, "bake_batch: %s\n", e.what());
    return glint::exitCode(e.kind());
  }
}

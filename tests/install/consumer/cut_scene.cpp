// cut_scene IN... -o OUT --light X,Y,Z[,NAME]... [--json REPORT] — `glint cut` as a program
// linking the installed glint::cut: its job (cut/job.h) with the command's checks, memory
// estimate, outputs (all or none) and report, through public headers only.
#include <glint/core/error.h>
#include <glint/core/tool.h>
#include <glint/cut/job.h>

#include <cstdio>
#include <cstring>

int main(int argc, char** argv) {
  glint::cut::CutJob job;
  glint::ToolSettings settings;
  settings.quiet = true;
  try {
    for (int i = 1; i < argc; ++i) {
      const bool hasValue = i + 1 < argc;
      if (std::strcmp(argv[i], "-o") == 0 && hasValue) job.outputs.push_back(argv[++i]);
      else if (std::strcmp(argv[i], "--light") == 0 && hasValue) job.lights.push_back(argv[++i]);
      else if (std::strcmp(argv[i], "--json") == 0 && hasValue) settings.json = argv[++i];
      else job.inputs.push_back(argv[i]);
    }
    glint::ToolRun run("cut", settings);
    glint::cut::runJob(job, run);  // the checks first, as the command makes them
    run.finish();                  // the outputs and the report, together
  } catch (const glint::Error& e) {
    std::fprintf(stderr, "cut_scene: %s\n", e.what());
    return glint::exitCode(e.kind());
  }
  return 0;
}

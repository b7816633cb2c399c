// cut_scene IN... -o OUT --light X,Y,Z[,NAME]... --json REPORT — `glint cut` as a program
// linking the installed glint::cut: the same load, checks, memory estimate, cut, output
// and report fields as the command (public headers only).
#include <glint/core/error.h>
#include <glint/core/file.h>
#include <glint/cut/cutter.h>
#include <glint/cut/output.h>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  std::vector<std::filesystem::path> inputs;
  std::filesystem::path output, reportPath;
  glint::cut::CutOptions options;
  try {
    for (int i = 1; i < argc; ++i) {
      const bool hasValue = i + 1 < argc;
      if (std::strcmp(argv[i], "-o") == 0 && hasValue) output = argv[++i];
      else if (std::strcmp(argv[i], "--light") == 0 && hasValue) options.lights.push_back(glint::cut::parseLight(argv[++i]));
      else if (std::strcmp(argv[i], "--json") == 0 && hasValue) reportPath = argv[++i];
      else inputs.emplace_back(argv[i]);
    }
    if (inputs.empty() || output.empty() || options.lights.empty()) {
      std::fprintf(stderr, "usage: %s IN... -o OUT --light X,Y,Z[,NAME]... [--json REPORT]\n", argv[0]);
      return 2;
    }
    glint::cut::checkOutputFormat(output);                 // before any work, as the command does
    const glint::Mesh scene = glint::cut::loadScene(inputs);
    const double mib = glint::cut::estimatePeakMemoryMiB(scene.triangleCount(), options.lights.size());
    const glint::cut::CutResult result = glint::cut::cut(scene, options);
    glint::cut::saveCutMesh(result.mesh, result.lights, output);  // atomically
    if (!reportPath.empty()) {
      nlohmann::ordered_json report = glint::cut::toJson(result.stats);
      report["lights"] = glint::cut::toJson(result.lights);
      report["estimated_peak_memory_mib"] = mib;
      glint::writeTextAtomically(reportPath, report.dump(2));
    }
  } catch (const glint::Error& e) {
    std::fprintf(stderr, "cut_scene: %s\n", e.what());
    return glint::exitCode(e.kind());
  }
  return 0;
}

#pragma once
// Runs a program and captures what it prints (farm: sbatch, squeue, scontrol, scancel).
#include <string>
#include <vector>

namespace glint::farm::detail {

struct ProcessResult {
  int exitCode = -1;   ///< the exit status; 127 when the program could not be started
  std::string output;  ///< stdout and stderr together
};

/// Runs argv[0] (looked up on PATH) with argv, waits for it, and returns its exit status
/// and output. Never throws for a failing program; 127 when it cannot be started.
ProcessResult runProcess(const std::vector<std::string>& argv);

/// Whether `program` is an executable file on PATH.
bool onPath(const std::string& program);

}  // namespace glint::farm::detail

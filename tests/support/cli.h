#pragma once
// Running the glint command from tests, as a user would: its exit status and what it
// printed (stdout and stderr together). Targets using this define GLINT_EXE (the path
// of the built glint) and depend on the glint target.
#include <sys/wait.h>

#include <csignal>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

namespace glint::testing {

/// Whether this build runs under AddressSanitizer (make sanitize): its shadow memory and
/// quarantine multiply a process's peak memory, so peaks measured there say nothing about
/// a plain build's.
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kAddressSanitizer = true;
#else
inline constexpr bool kAddressSanitizer = false;
#endif
#else
inline constexpr bool kAddressSanitizer = false;
#endif

struct CliRun {
  int status = -1;     ///< exit status; -1 when killed by a signal
  std::string output;  ///< stdout + stderr
};

/// Runs a shell command line, capturing stdout and stderr together.
inline CliRun runShell(const std::string& commandLine) {
  CliRun r;
  const std::string command = commandLine + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  char buffer[4096];
  while (pipe && fgets(buffer, sizeof buffer, pipe)) r.output += buffer;
  const int raw = pipe ? pclose(pipe) : -1;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
}

/// Runs `env glint args` through the shell; env is a prefix such as "VAR=1" or "xvfb-run -a".
inline CliRun runGlint(const std::string& args, const std::string& env = "") {
  return runShell(env + " " GLINT_EXE " " + args);
}

inline std::size_t fileCount(const std::filesystem::path& dir) {
  return std::size_t(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()));
}

/// An empty folder test-output/<suite>/<name> for one test's files (each test its own:
/// ctest runs tests in parallel processes).
inline std::filesystem::path freshDir(const std::string& suite, const std::string& name) {
  const std::filesystem::path d = std::filesystem::path(GLINT_TEST_OUTPUT_DIR) / suite / name;
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

/// A file's bytes ("" when it cannot be read).
inline std::string readBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

/// `p` as one shell word: in single quotes, any single quote in it closed, escaped and reopened.
inline std::string shellQuote(const std::filesystem::path& p) {
  std::string out = "'";
  for (char c : p.string()) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

/// glint's errors are exactly one line.
inline bool oneLine(const std::string& s) { return !s.empty() && s.find('\n') == s.size() - 1; }

/// Waits (up to `seconds`) until a file in `dir` whose name starts with `prefix` (a
/// tool's temporary output, ".clip.tmp") holds more than `bytes`: the run is writing.
inline bool waitUntilWriting(const std::filesystem::path& dir, const std::string& prefix, std::uintmax_t bytes,
                             int seconds = 60) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
  while (std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    std::error_code ec;
    for (const auto& e : std::filesystem::directory_iterator(dir, ec))
      if (e.path().filename().string().starts_with(prefix) && e.file_size(ec) > bytes) return true;
  }
  return false;
}

/// Ctrl-C to a child process, and its exit status once it has ended (-1: killed by a signal).
inline int interruptAndWait(pid_t pid) {
  kill(pid, SIGINT);
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace glint::testing

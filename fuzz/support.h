#pragma once
// fuzz/support.h — what every libFuzzer harness shares.
//
// A harness feeds the fuzzer's bytes to one of glint's parsers. The rule it checks, besides
// the sanitizers' (no out-of-bounds access, no use after free, no undefined behaviour, no
// leak, no hang): bad input ends in glint::Error with a one-line message, the way the glint
// command reports it. Any other exception escapes the harness, and libFuzzer reports it
// as a crash together with the input.
#include "glint/core/error.h"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <span>
#include <string_view>

namespace glint::fuzz {

/// The bytes as a file named input.<extension> in this process's scratch directory (in
/// /dev/shm when there is one: the loaders read paths, not memory). The same path is
/// rewritten for every input.
std::filesystem::path inputFile(std::span<const std::uint8_t> bytes, std::string_view extension);

/// The usual shape of a file harness's input: its first byte (shifted right by
/// `selectorShift`, whose low bits the harness keeps for its own choices) picks one of
/// `extensions`, and the rest is written as input.<extension>. nullopt for an empty input.
std::optional<std::filesystem::path> inputFile(const std::uint8_t* data, std::size_t size,
                                               std::span<const char* const> extensions, int selectorShift = 0);

/// This process's scratch directory (created on first use, removed at exit).
const std::filesystem::path& scratchDirectory();

/// Runs `f`, which parses one input: a glint::Error is an accepted outcome when its
/// message is one line; anything else escapes (a finding).
template <class F>
void parse(F&& f) {
  try {
    f();
  } catch (const glint::Error& e) {
    for (const char* p = e.what(); *p; ++p) {
      if (*p == '\n') std::abort();  // an error message must be one line
    }
  }
}

/// Aborts with `what` on stderr unless `ok` (an invariant of a parser's result).
void check(bool ok, const char* what);

}  // namespace glint::fuzz

#pragma once
// The registry of documentation examples compiled into docs_snippets_test
// (tests/docs/extract_snippets.cpp writes the registrations).
#include <vector>

namespace glint::docs {

struct Snippet {
  const char* where;  ///< "FILE:LINE" of the opening fence
  void (*body)();
  bool run;  ///< fenced ```cpp run: the test runs it, not only compiles it
};

inline std::vector<Snippet>& snippets() {
  static std::vector<Snippet> all;
  return all;
}

struct Registration {
  Registration(const char* where, void (*body)(), bool run) { snippets().push_back({where, body, run}); }
};

}  // namespace glint::docs

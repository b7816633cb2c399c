// glint view, when built without GLINT_BUILD_VIEWER.
#include "common.h"

#include "glint/core/error.h"

namespace glint::app {

Command viewCommand(CLI::App& app, const GlobalOptions&) {
  app.add_subcommand("view", "Interactive viewer (not built: configure with -DGLINT_BUILD_VIEWER=ON)")
      ->allow_extras();
  return Command{.run = [] () -> int { fail(ErrorKind::Usage, "this glint was built without the viewer (GLINT_BUILD_VIEWER=OFF)"); }};
}

}  // namespace glint::app

// Finding the glint_oiio module: core/locations.h's moduleCandidates with its paths.
#include "oiio_locate.h"

#include "glint/core/locations.h"

#if !defined(GLINT_OIIO_MODULE) || !defined(GLINT_OIIO_MODULE_INSTALLED)
#error "GLINT_OIIO_MODULE and GLINT_OIIO_MODULE_INSTALLED (the module's build and install paths) must be defined"
#endif

namespace glint::oiio {
namespace fs = std::filesystem;

const ModuleLocation& module() {
  static const ModuleLocation location{GLINT_OIIO_MODULE, GLINT_OIIO_MODULE_INSTALLED, "GLINT_OIIO_MODULE"};
  return location;
}

}  // namespace glint::oiio

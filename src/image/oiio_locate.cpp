// Finding the glint_oiio module: core/locations.h's moduleCandidates with its paths.
#include "oiio_locate.h"

#include "glint/core/locations.h"

#if !defined(GLINT_OIIO_MODULE) || !defined(GLINT_OIIO_MODULE_INSTALLED)
#error "GLINT_OIIO_MODULE and GLINT_OIIO_MODULE_INSTALLED (the module's build and install paths) must be defined"
#endif

namespace glint::oiio {
namespace {
// At namespace scope, not a function's static: it is built before main() and so destroyed
// after image_io.cpp's loader, whose destructor joins a background load that still reads it
// (a function's static, built by that thread, was destroyed first: a use after free at exit).
const ModuleLocation kModule{GLINT_OIIO_MODULE, GLINT_OIIO_MODULE_INSTALLED, "GLINT_OIIO_MODULE"};
}  // namespace

const ModuleLocation& module() { return kModule; }

}  // namespace glint::oiio

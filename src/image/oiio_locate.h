#pragma once
// oiio_locate.h — where image_io.cpp looks for the glint_oiio module (private).
//
// In order; the first that exists and loads wins:
//   $GLINT_OIIO_MODULE          a file; when set, the only candidate (an explicit choice
//                               is not second-guessed)
//   beside the executable       a copied glint (next to its module)
//   the executable's library    LD_LIBRARY_PATH and RUNPATH: the installed glint has
//     search path               RUNPATH $ORIGIN/../lib/glint (a moved prefix still works),
//                               and programs linking glint::image through find_package(glint)
//                               get RUNPATH <prefix>/lib/glint from the package
//   the build tree's module     build/src/image (tests, build/app/glint)
//   <prefix>/lib/glint          the prefix configured at build time: programs linked to an
//                               installed glint without its CMake package

#include "glint/core/locations.h"

namespace glint::oiio {

/// The module's build and install paths and its override variable, for core/locations.h's
/// moduleCandidates and loadModule.
const ModuleLocation& module();

}  // namespace glint::oiio

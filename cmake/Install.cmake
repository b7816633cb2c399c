# `cmake --install build [--prefix P]`: the glint command, the public headers, the
# static libraries with a CMake package (find_package(glint) → glint::<module>), the
# OpenImageIO module and the downloaded data. Layout (GNUInstallDirs):
#
#   bin/glint                         the command (RUNPATH $ORIGIN/../lib/glint)
#   include/glint/<module>/*.h        every public header (the whole directory)
#   lib/libglint_<module>.a           one static library per module
#   lib/glint/libglint_oiio.so        the dlopen()ed image I/O module (src/image/oiio_locate.h)
#   lib/glint/libglint_ffmpeg.so      the dlopen()ed video module (src/video/backend.h)
#   lib/cmake/glint/                  glintConfig.cmake, glintConfigVersion.cmake, glintTargets*.cmake,
#                                     PeerDependencies.cmake (FFTW, OpenCV targets)
#   share/glint/env, share/glint/bunny  data/ from scripts/setup, when it is there (core/locations.h)
#
# Exported targets, namespace glint:: (the same names work in this build as aliases):
#   glint::core glint::image glint::video glint::mesh glint::raytrace glint::bake glint::cut glint::raster
#   glint::sim glint::gl glint::render glint::scenes glint::bench [glint::window]
#   glint::glint (the command, an imported executable)
# Each library brings the layers below it: linking glint::scenes is enough to render
# registered scenes. tests/install checks all of this with a consumer project.
include(CMakePackageConfigHelpers)

set(glint_libraries
  glint_core glint_image glint_video glint_mesh glint_raytrace glint_bake glint_cut glint_raster glint_sim
  glint_gl glint_render glint_scenes glint_bench)
list(APPEND glint_libraries glint_post)  # `glint post`'s job (render/post/job.h)
if(GLINT_BUILD_VIEWER)
  list(APPEND glint_libraries glint_window)
endif()
foreach(library IN LISTS glint_libraries)
  string(REGEX REPLACE "^glint_" "" name "${library}")
  set_target_properties(${library} PROPERTIES EXPORT_NAME ${name})
  add_library(glint::${name} ALIAS ${library})
endforeach()
add_executable(glint::glint ALIAS glint)

install(TARGETS ${glint_libraries} glint EXPORT glintTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS glint_oiio glint_ffmpeg LIBRARY DESTINATION ${GLINT_INSTALL_MODULE_DIR})
# The directory as a whole: headers added or moved need no change here.
install(DIRECTORY "${PROJECT_SOURCE_DIR}/include/glint" DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})

install(EXPORT glintTargets NAMESPACE glint:: DESTINATION ${GLINT_INSTALL_CMAKE_DIR})
configure_package_config_file(cmake/glintConfig.cmake.in "${PROJECT_BINARY_DIR}/glintConfig.cmake"
  INSTALL_DESTINATION ${GLINT_INSTALL_CMAKE_DIR})
# 0.x: a minor version may break the API, so only the same minor version is compatible.
write_basic_package_version_file("${PROJECT_BINARY_DIR}/glintConfigVersion.cmake"
  COMPATIBILITY SameMinorVersion)
install(FILES "${PROJECT_BINARY_DIR}/glintConfig.cmake" "${PROJECT_BINARY_DIR}/glintConfigVersion.cmake"
  "${PROJECT_SOURCE_DIR}/cmake/PeerDependencies.cmake"
  DESTINATION ${GLINT_INSTALL_CMAKE_DIR})

# Data, where scripts/setup put it; absent data is not an install error (the scenes
# that need it then fail with a one-line Error naming where they looked).
install(DIRECTORY "${GLINT_DATA_DIR}/env" DESTINATION ${GLINT_INSTALL_DATA_DIR} OPTIONAL)
install(FILES "${GLINT_DATA_DIR}/bunny/bunny.ply" DESTINATION ${GLINT_INSTALL_DATA_DIR}/bunny OPTIONAL)

# `cmake --install build [--prefix P]`: the glint command, the public headers, the
# static libraries with a CMake package (find_package(glint) → glint::<module>), the
# OpenImageIO module and the downloaded data. Layout (GNUInstallDirs):
#
#   bin/glint                         the command (RUNPATH $ORIGIN/../lib/glint)
#   include/glint/<module>/*.h        every public header (the whole directory)
#   lib/libglint_<module>.a           one static library per module
#   lib/glint/libglint_oiio.so        the dlopen()ed image I/O module (src/image/oiio_locate.h)
#   lib/glint/libglint_ffmpeg.so      the dlopen()ed video module (src/video/backend.h)
#   lib/cmake/glint/                  glintConfig.cmake, glintConfigVersion.cmake, one
#                                     glint-<component>-targets*.cmake per component,
#                                     PeerDependencies.cmake (FFTW, OpenCV targets: post's CPU backend, bench)
#   share/glint/env, share/glint/bunny, share/glint/web  data/ from scripts/setup, when it is there (core/locations.h)
#
# Exported targets, namespace glint:: (the same names work in this build as aliases), one
# package component each, named as the target (find_package(glint COMPONENTS render)):
#   glint::core glint::farm glint::image glint::effects glint::post glint::mesh glint::pipedream glint::shadows
#   glint::raytrace glint::bake glint::raster glint::sim
#   glint::gl glint::render glint::scenes glint::video (without GLINT_BUILD_VIDEO: no FFmpeg module),
#   glint::cut (GLINT_BUILD_CUT), glint::bench (GLINT_BUILD_BENCH), glint::window and glint::viewer (GLINT_BUILD_VIEWER)
#   glint::glint (component glint: the command, an imported executable)
# Each library brings the layers below it: linking glint::scenes is enough to render
# registered scenes. Each component is also an install component (cmake --install
# --component render), with its library, its headers and its targets file; core carries
# the package files. tests/install checks all of this with consumer projects.
include(CMakePackageConfigHelpers)

# Layer order, lowest first: an installed package loads the targets files in this order.
# video is always a component: without GLINT_BUILD_VIDEO it is the library without its
# FFmpeg module (opening a video is a usage error naming the option), which scenes links for
# `glint render`'s clips and post's job reads and writes through. post (GL-free: the effect
# table and CPU backend: effects; the job: post) sits below render, whose GPU passes register
# against the table.
set(glint_components core farm image video effects post)  # GL-free (post/effects.h, cpu.h; post/job.h)
list(APPEND glint_components mesh pipedream shadows raytrace bake)
if(GLINT_BUILD_CUT)
  list(APPEND glint_components cut)
endif()
list(APPEND glint_components raster sim gl render)
list(APPEND glint_components scenes)
if(GLINT_BUILD_BENCH)
  list(APPEND glint_components bench)
endif()
if(GLINT_BUILD_VIEWER)
  list(APPEND glint_components window viewer)
endif()
# The parts a configuration can leave out, and the option that does (glintConfig names it).
set(glint_optional_components cut=GLINT_BUILD_CUT bench=GLINT_BUILD_BENCH window=GLINT_BUILD_VIEWER viewer=GLINT_BUILD_VIEWER)

# How an installed glint finds each third-party target its libraries link: a name that
# glintConfig.cmake's glint_find_dependency knows. A linked target missing here stops the
# configure, so the package cannot silently lack a dependency.
set(glint_dependency_names
  fmt::fmt=fmt glm::glm=glm nlohmann_json::nlohmann_json=nlohmann_json Threads::Threads=Threads TBB::tbb=TBB
  assimp::assimp=assimp tinyobjloader::tinyobjloader=tinyobjloader draco::draco=draco embree=embree
  CGAL::CGAL=CGAL TinyGLTF::TinyGLTF=TinyGLTF glfw=glfw3 CLI11::CLI11=CLI11
  PkgConfig::EPOXY=epoxy PkgConfig::EGL=egl PkgConfig::SPNG=spng PkgConfig::IMGUI=imgui
  JPEG::JPEG=JPEG OpenEXR::OpenEXR=OpenEXR
  PkgConfig::FFTW=peers glint_deps::fftw_threads=peers glint_deps::opencv=peers)

# What linking glint_<component> brings, read from the link graph: its direct glint
# components and third-party dependency names. A static library's consumers link all it
# links (its private dependencies are link-only ones of theirs), so both properties count.
function(glint_direct_dependencies component out_components out_dependencies)
  get_target_property(links glint_${component} LINK_LIBRARIES)
  get_target_property(interface glint_${component} INTERFACE_LINK_LIBRARIES)
  set(components "")
  set(dependencies "")
  foreach(item IN LISTS links interface)
    string(REGEX REPLACE "^\\$<LINK_ONLY:(.*)>$" "\\1" item "${item}")
    set(name "")
    foreach(pair IN LISTS glint_dependency_names)
      if(pair MATCHES "^(.*)=(.*)$" AND CMAKE_MATCH_1 STREQUAL item)
        set(name ${CMAKE_MATCH_2})
      endif()
    endforeach()
    if(item STREQUAL "" OR item IN_LIST CMAKE_DL_LIBS)
      continue()  # a system library the linker finds (dl)
    elseif(name)
      list(APPEND dependencies ${name})
    elseif(item MATCHES "^glint_([a-z]+)$" AND TARGET ${item})
      if(NOT CMAKE_MATCH_1 IN_LIST glint_components)
        message(FATAL_ERROR "glint::${component} links ${item}, which this configuration does not export")
      endif()
      list(APPEND components ${CMAKE_MATCH_1})
    else()
      # (An imported target found in a subdirectory is not visible here: hence a table.)
      message(FATAL_ERROR "glint::${component} links '${item}': add how an installed glint finds it to "
                          "glint_dependency_names (cmake/Install.cmake) and glintConfig.cmake.in")
    endif()
  endforeach()
  set(${out_components} ${components} PARENT_SCOPE)
  set(${out_dependencies} ${dependencies} PARENT_SCOPE)
endfunction()

# Per component, everything it needs (the components below it, itself, in layer order) and
# the third-party dependencies of all of those: written into glintConfig.cmake.
set(GLINT_COMPONENT_TABLE "set(_glint_built ${glint_components} glint)\n")
string(APPEND GLINT_COMPONENT_TABLE "set(_glint_optional ${glint_optional_components})\n")
foreach(component IN LISTS glint_components)
  glint_direct_dependencies(${component} direct dependencies)
  set(needs ${component})
  foreach(below IN LISTS direct)
    list(FIND glint_components ${below} below_at)
    list(FIND glint_components ${component} at)
    if(below_at GREATER at)
      message(FATAL_ERROR "glint::${component} links glint::${below}, a higher layer (cmake/Install.cmake's order)")
    endif()
    list(APPEND needs ${glint_needs_${below}})
    list(APPEND dependencies ${glint_dependencies_${below}})
  endforeach()
  set(ordered "")
  foreach(candidate IN LISTS glint_components)  # layer order, each once
    if(candidate IN_LIST needs)
      list(APPEND ordered ${candidate})
    endif()
  endforeach()
  list(REMOVE_DUPLICATES dependencies)
  list(SORT dependencies)
  set(glint_needs_${component} ${ordered})
  set(glint_dependencies_${component} ${dependencies})
  string(APPEND GLINT_COMPONENT_TABLE "set(_glint_needs_${component} ${ordered})\n"
                                      "set(_glint_dependencies_${component} ${dependencies})\n")
endforeach()
string(APPEND GLINT_COMPONENT_TABLE "set(_glint_needs_glint glint)\nset(_glint_dependencies_glint \"\")\n")

# What each layer may use, checked on the link graph (a violation stops the configure):
#   - the GL-free modules need neither glint::gl nor a GL library (EGL, epoxy, GLFW, ImGui);
#   - render/ (the code that needs a GL context) needs neither the video layer, the farm nor
#     a tool's job: what it draws comes from GL-free modules below it.
# The graph is written to glint-layers.md in the build, the table README's architecture
# section shows (ctest docs.layers compares the two).
set(glint_gl_free core farm image video effects post mesh pipedream shadows raytrace bake cut raster sim)
set(glint_gl_libraries epoxy egl glfw3 imgui)
set(GLINT_LAYERS_TABLE "| module | GL | links (glint modules, directly) |\n|---|---|---|\n")
foreach(component IN LISTS glint_components)
  glint_direct_dependencies(${component} direct dependencies)
  list(REMOVE_DUPLICATES direct)
  set(gl "GL")
  if(component IN_LIST glint_gl_free)
    set(gl "no GL")
    if("gl" IN_LIST glint_needs_${component} OR "window" IN_LIST glint_needs_${component})
      message(FATAL_ERROR "glint::${component} is GL-free but needs glint::gl (through: ${glint_needs_${component}})")
    endif()
    foreach(library IN LISTS glint_gl_libraries)
      if(library IN_LIST glint_dependencies_${component})
        message(FATAL_ERROR "glint::${component} is GL-free but links ${library}")
      endif()
    endforeach()
  endif()
  string(REPLACE ";" " " direct_text "${direct}")
  string(APPEND GLINT_LAYERS_TABLE "| `${component}` | ${gl} | ${direct_text} |\n")
endforeach()
foreach(forbidden IN ITEMS video farm post bake cut scenes)
  if(forbidden IN_LIST glint_needs_render)
    message(FATAL_ERROR "glint::render needs glint::${forbidden} (through: ${glint_needs_render}): "
                        "render/ may use only GL-free modules below it")
  endif()
endforeach()
file(WRITE "${CMAKE_BINARY_DIR}/glint-layers.md" "${GLINT_LAYERS_TABLE}")

foreach(component IN LISTS glint_components)
  set(library glint_${component})
  set_target_properties(${library} PROPERTIES EXPORT_NAME ${component})
  add_library(glint::${component} ALIAS ${library})
  install(TARGETS ${library} EXPORT glint-${component} ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT ${component})
  install(EXPORT glint-${component} FILE glint-${component}-targets.cmake NAMESPACE glint::
          DESTINATION ${GLINT_INSTALL_CMAKE_DIR} COMPONENT ${component})
  # A module's public headers (window's header is gl/window.h, in gl's directory).
  if(IS_DIRECTORY "${PROJECT_SOURCE_DIR}/include/glint/${component}")
    set(exclude "")
    if(component STREQUAL "post")
      set(exclude PATTERN effects.h EXCLUDE PATTERN cpu.h EXCLUDE)  # component effects's
    endif()
    if(component STREQUAL "scenes" AND NOT GLINT_BUILD_CUT)
      set(exclude PATTERN pipedream.h EXCLUDE)  # the pipedream stage: a cut
    endif()
    install(DIRECTORY "${PROJECT_SOURCE_DIR}/include/glint/${component}" DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/glint
            COMPONENT ${component} ${exclude})
  endif()
  if(component STREQUAL "effects")  # the effect table's headers sit with post's
    install(FILES "${PROJECT_SOURCE_DIR}/include/glint/post/effects.h" "${PROJECT_SOURCE_DIR}/include/glint/post/cpu.h"
            DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/glint/post COMPONENT ${component})
  endif()
endforeach()
add_executable(glint::glint ALIAS glint)
install(TARGETS glint EXPORT glint-glint RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT glint)
install(EXPORT glint-glint FILE glint-glint-targets.cmake NAMESPACE glint:: DESTINATION ${GLINT_INSTALL_CMAKE_DIR}
        COMPONENT glint)
install(TARGETS glint_oiio LIBRARY DESTINATION ${GLINT_INSTALL_MODULE_DIR} COMPONENT image)
# The modules again as their own component, for the Python wheel (pyproject.toml), which
# takes them without the C++ package's libraries and headers.
install(TARGETS glint_oiio LIBRARY DESTINATION ${GLINT_INSTALL_MODULE_DIR} COMPONENT modules)
if(GLINT_BUILD_VIDEO)
  install(TARGETS glint_ffmpeg LIBRARY DESTINATION ${GLINT_INSTALL_MODULE_DIR} COMPONENT video)
  install(TARGETS glint_ffmpeg LIBRARY DESTINATION ${GLINT_INSTALL_MODULE_DIR} COMPONENT modules)
endif()

configure_package_config_file(cmake/glintConfig.cmake.in "${PROJECT_BINARY_DIR}/glintConfig.cmake"
  INSTALL_DESTINATION ${GLINT_INSTALL_CMAKE_DIR})
# 0.x: a minor version may break the API, so only the same minor version is compatible.
write_basic_package_version_file("${PROJECT_BINARY_DIR}/glintConfigVersion.cmake"
  COMPATIBILITY SameMinorVersion)
install(FILES "${PROJECT_BINARY_DIR}/glintConfig.cmake" "${PROJECT_BINARY_DIR}/glintConfigVersion.cmake"
  DESTINATION ${GLINT_INSTALL_CMAKE_DIR} COMPONENT core)
# glint::post's CPU backend (and so glint::render, whose GPU passes register against post's
# table) and glint::bench's peers link FFTW and OpenCV.
install(FILES "${PROJECT_SOURCE_DIR}/cmake/PeerDependencies.cmake" DESTINATION ${GLINT_INSTALL_CMAKE_DIR} COMPONENT core)

# Data, where scripts/setup put it; absent data is not an install error (the scenes
# that need it then fail with a one-line Error naming where they looked).
install(DIRECTORY "${GLINT_DATA_DIR}/env" DESTINATION ${GLINT_INSTALL_DATA_DIR} COMPONENT data OPTIONAL)
install(FILES "${GLINT_DATA_DIR}/bunny/bunny.ply" DESTINATION ${GLINT_INSTALL_DATA_DIR}/bunny COMPONENT data OPTIONAL)
# three.js, copied beside every page `glint bake --preview` writes (bake/asset.h).
install(DIRECTORY "${GLINT_DATA_DIR}/web" DESTINATION ${GLINT_INSTALL_DATA_DIR} COMPONENT data OPTIONAL)

# The libraries `glint bench post` measures glint against and the post tests use as
# oracles, found the same way in glint's build and in an installed glint's package
# (glintConfig.cmake includes this file: glint::bench links them), so the imported
# targets exist in both:
#
#   PkgConfig::FFTW      fftw3 (double: the tests' oracle) and fftw3f (float: the bench's peer)
#   glint_deps::fftw_threads  fftw3f_threads (the bench's FFTW on every core; not in fftw3f.pc)
#   glint_deps::opencv   OpenCV core + imgproc (the bench's peers, the tests' oracles)
#
# Debian's split libopencv-core-dev and libopencv-imgproc-dev ship neither opencv4.pc nor
# OpenCVConfig.cmake (those come with libopencv-dev, which pulls in every OpenCV module),
# so the OpenCV target is made here from the headers and the two libraries.
#
# Sets GLINT_PEER_DEPENDENCIES_FOUND and, when something is missing,
# GLINT_PEER_DEPENDENCIES_MISSING (what, and the Debian package to install).
find_package(PkgConfig REQUIRED)
set(GLINT_PEER_DEPENDENCIES_FOUND TRUE)
set(GLINT_PEER_DEPENDENCIES_MISSING "")

if(NOT TARGET PkgConfig::FFTW)
  pkg_check_modules(FFTW QUIET IMPORTED_TARGET fftw3 fftw3f)
  if(NOT FFTW_FOUND)
    set(GLINT_PEER_DEPENDENCIES_FOUND FALSE)
    string(APPEND GLINT_PEER_DEPENDENCIES_MISSING " FFTW (Debian: libfftw3-dev)")
  endif()
endif()

if(NOT TARGET glint_deps::fftw_threads)
  find_library(GLINT_FFTW3F_THREADS_LIBRARY fftw3f_threads)
  mark_as_advanced(GLINT_FFTW3F_THREADS_LIBRARY)
  if(GLINT_FFTW3F_THREADS_LIBRARY)
    add_library(glint_deps::fftw_threads INTERFACE IMPORTED)
    set_target_properties(glint_deps::fftw_threads PROPERTIES INTERFACE_LINK_LIBRARIES "${GLINT_FFTW3F_THREADS_LIBRARY}")
  else()
    set(GLINT_PEER_DEPENDENCIES_FOUND FALSE)
    string(APPEND GLINT_PEER_DEPENDENCIES_MISSING " FFTW's threads library (Debian: libfftw3-dev)")
  endif()
endif()

if(NOT TARGET glint_deps::opencv)
  find_path(GLINT_OPENCV_INCLUDE_DIR opencv2/imgproc.hpp PATH_SUFFIXES opencv4)
  find_library(GLINT_OPENCV_CORE_LIBRARY opencv_core)
  find_library(GLINT_OPENCV_IMGPROC_LIBRARY opencv_imgproc)
  mark_as_advanced(GLINT_OPENCV_INCLUDE_DIR GLINT_OPENCV_CORE_LIBRARY GLINT_OPENCV_IMGPROC_LIBRARY)
  if(GLINT_OPENCV_INCLUDE_DIR AND GLINT_OPENCV_CORE_LIBRARY AND GLINT_OPENCV_IMGPROC_LIBRARY)
    add_library(glint_deps::opencv INTERFACE IMPORTED)
    set_target_properties(glint_deps::opencv PROPERTIES
      INTERFACE_INCLUDE_DIRECTORIES "${GLINT_OPENCV_INCLUDE_DIR}"
      INTERFACE_LINK_LIBRARIES "${GLINT_OPENCV_IMGPROC_LIBRARY};${GLINT_OPENCV_CORE_LIBRARY}")
  else()
    set(GLINT_PEER_DEPENDENCIES_FOUND FALSE)
    string(APPEND GLINT_PEER_DEPENDENCIES_MISSING
      " OpenCV core and imgproc (Debian: libopencv-core-dev libopencv-imgproc-dev)")
  endif()
endif()

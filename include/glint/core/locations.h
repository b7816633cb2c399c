#pragma once
// glint/core/locations.h — where glint finds the files it does not compile in: its
// downloaded data (environment maps, the Stanford bunny) and the running executable
// (image/image.h's I/O module is looked up beside it).
//
/// ```cpp
/// const std::filesystem::path exr = glint::findDataFile("env/courtyard.exr", "environment 'courtyard'");
/// ```
//
// Data is what scripts/setup fetches into <source>/data; `cmake --install` copies it to
// <prefix>/share/glint. findDataFile looks in these directories, first match wins:
//
//   $GLINT_DATA_DIR                when set, the only place: an explicit choice is not
//                                  second-guessed by a fallback
//   <exe>/../share/glint           beside an installed glint command, wherever its
//                                  prefix was moved (relative to bin/, GNUInstallDirs)
//   <source>/data                  the build's default (CMake: GLINT_DATA_DIR)
//   <prefix>/share/glint           the prefix configured at build time, for other
//                                  programs linked to an installed glint
//
// A program linked to an install that was moved elsewhere (cmake --install --prefix P
// with P not the configured prefix) and built on another machine finds its data only
// through GLINT_DATA_DIR=P/share/glint; findDataFile's error says so.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace glint {

/// The running executable (/proc/self/exe); empty when it cannot be read.
std::filesystem::path executablePath();

/// The directories findDataFile searches, in order (see above); duplicates removed.
/// Directories that do not exist are included: the list is where glint looks.
std::vector<std::filesystem::path> dataDirectories();

/// A module glint dlopen()s instead of linking (a library with hundreds of dependencies
/// that only some commands need): libglint_oiio.so (OpenImageIO), libglint_ffmpeg.so
/// (FFmpeg). moduleCandidates() looks, in order, first existing file wins:
///   $<overrideVariable>      when set, the only candidate (an explicit choice is not
///                            second-guessed)
///   beside the executable    a copied glint, next to its modules
///   the executable's library LD_LIBRARY_PATH and RUNPATH: the installed glint has RUNPATH
///     search path            $ORIGIN/../lib/glint (a moved prefix still works), programs
///                            linked through find_package(glint) get <prefix>/lib/glint
///   `built`                  the build tree's module (tests, build/app/glint)
///   `installed`              <prefix>/lib/glint as configured at build time
struct ModuleLocation {
  std::filesystem::path built;      ///< the module in the build tree (its file name is the module's)
  std::filesystem::path installed;  ///< the module under the configured install prefix
  const char* overrideVariable = "";  ///< e.g. "GLINT_OIIO_MODULE"
};

/// The candidates that exist, in the order above, duplicates removed; with the override
/// variable set, that path alone (or none).
std::vector<std::filesystem::path> moduleCandidates(const ModuleLocation& module);
/// Where moduleCandidates() looks, for error messages: one line.
std::string moduleSearchDescription(const ModuleLocation& module);

/// Loads a module: dlopen()s the first candidate that loads and calls its C entry point
/// `entry`, a function without arguments that returns the module's function table, whose
/// first member is the int ABI version the module was built with. A table of another
/// version is refused (a stale build). The module stays mapped for the life of the
/// process. Error(Internal), one line, when no candidate loads: `what` ("image I/O",
/// "video"), the module and the first candidate's reason, or where it was searched.
/// `call` calls the entry point at the address it is given through its real type (a call
/// through another function type is undefined; UBSan's -fsanitize=function stops it).
const void* loadModuleTable(const ModuleLocation& module, std::string_view what, const char* entry, int abiVersion,
                            const void* (*call)(void* entryPoint));
/// The same, typed: `Table` is the module's function table (its first member the version),
/// and the entry point is a `const Table* entry()`.
template <class Table>
const Table& loadModule(const ModuleLocation& module, std::string_view what, const char* entry, int abiVersion) {
  const auto call = [](void* entryPoint) -> const void* {
    return reinterpret_cast<const Table* (*)()>(entryPoint)();
  };
  return *static_cast<const Table*>(loadModuleTable(module, what, entry, abiVersion, call));
}

/// The first dataDirectories()/`relative` that is a regular file. Error(Input), one line,
/// when there is none: `what` (e.g. "environment 'courtyard'"), every directory searched,
/// and how to get the data (scripts/setup, GLINT_DATA_DIR).
std::filesystem::path findDataFile(const std::filesystem::path& relative, std::string_view what);

}  // namespace glint

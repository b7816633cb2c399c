#pragma once
// The image formats glint reads without its image I/O module (OpenImageIO, a dlopen()ed
// module of some 260 libraries): PNG, JPEG and OpenEXR, through libspng, libjpeg-turbo and
// OpenEXR's own library, linked into glint::image. image_io.cpp falls back on them when
// the module cannot load — a bare GPU machine running scripts/gpu-check's pack renders
// every gallery variant with them — and the tests hold them to the module's reads.
#include "glint/image/image.h"

#include <filesystem>
#include <span>
#include <string>
#include <string_view>

namespace glint::builtin {

/// Whether `extension` (lower case, with the dot: ".png") has a built-in reader.
bool reads(std::string_view extension);

/// The image in `path`, as OpenImageIO reads it: the file's channels (a palette expanded,
/// tRNS as alpha; EXR's R, G, B and A, or Y and A), 8 or 16 bits, EXR as 32-bit float.
/// Error(Input) for a file it cannot read.
Image read(const std::filesystem::path& path, std::string_view extension);

/// A PNG or JPEG file's bytes (told apart by their signature) decoded as read() decodes
/// the file; `name` is what messages call it. Error(Input) for other or corrupt data.
Image decode(std::span<const unsigned char> bytes, const std::string& name);

}  // namespace glint::builtin

#pragma once
// oiio_module.h — the private plain-C ABI between glint_image (image_io.cpp) and the
// glint_oiio module (oiio_module.cpp), the only code that touches OpenImageIO.
//
// Why a module: Debian's libOpenImageIO pulls in ~260 shared libraries (OpenCV,
// ffmpeg, DCMTK, OpenVDB, GDAL, ...); linked into glint, the dynamic loader spent
// ~0.3 s on them before main() of every command. image_io.cpp dlopen()s the module
// on first use (or in the background, see preloadImageIo()).
//
// Rules: plain C types only; no exception crosses the boundary (the module catches
// everything and returns GLINT_OIIO_EXCEPTION; the caller's allocation callback must
// not throw either). Bump GLINT_OIIO_ABI_VERSION on any change to this file.

#include <stddef.h>

#define GLINT_OIIO_ABI_VERSION 2

#ifdef __cplusplus
extern "C" {
#endif

/// Status codes. The module writes a one-line reason (no path) into the caller's
/// error buffer for every code but GLINT_OIIO_OK and GLINT_OIIO_ALLOC_FAILED.
enum GlintOiioStatus {
  GLINT_OIIO_OK = 0,
  GLINT_OIIO_OPEN_FAILED = 1,     ///< read: the file cannot be opened / is not an image
  GLINT_OIIO_EMPTY = 2,           ///< read: width or height is not positive
  GLINT_OIIO_ALLOC_FAILED = 3,    ///< read: the allocation callback returned NULL
  GLINT_OIIO_READ_FAILED = 4,     ///< read: the pixels cannot be read (corrupt file)
  GLINT_OIIO_UNKNOWN_FORMAT = 5,  ///< write: no writer for the file name's extension
  GLINT_OIIO_WRITE_FAILED = 6,    ///< write: open / write / close failed
  GLINT_OIIO_EXCEPTION = 7        ///< an unexpected C++ exception (its what()) — a bug
};

/// Pixel types; the same order as glint::PixelType.
enum GlintOiioPixelType { GLINT_OIIO_U8 = 0, GLINT_OIIO_U16 = 1, GLINT_OIIO_F32 = 2 };

/// Called once by glint_oiio_read with the image's size, channel count (1..4) and
/// pixel type; returns a buffer of width*height*channels*size(type) bytes that stays
/// valid until glint_oiio_read returns, or NULL to abort the read.
typedef void* (*GlintOiioAllocFn)(void* user, int width, int height, int channels, int pixelType);

typedef int (*GlintOiioReadFn)(const char* path, GlintOiioAllocFn alloc, void* user, char* error,
                               size_t errorSize);
typedef int (*GlintOiioWriteFn)(const char* path, int width, int height, int channels, int pixelType,
                                const void* pixels, int hasAlpha, char* error, size_t errorSize);

/// The module's function table, the one thing it exports (glint_oiio_api), as the video
/// module's: core/locations.h's loadModule checks `abiVersion` against
/// GLINT_OIIO_ABI_VERSION and refuses a module that differs.
typedef struct GlintOiioApi {
  int abiVersion;
  GlintOiioReadFn read;    ///< glint_oiio_read below
  GlintOiioWriteFn write;  ///< glint_oiio_write below
} GlintOiioApi;

const GlintOiioApi* glint_oiio_api(void);

/// Reads the first subimage of `path` with unassociated (straight) alpha: 8-bit files
/// as U8, 16-bit as U16, anything else as F32; at most 4 channels.
int glint_oiio_read(const char* path, GlintOiioAllocFn alloc, void* user, char* error, size_t errorSize);

/// Writes interleaved pixels to `path` (the format follows its extension). When
/// `hasAlpha` is non-zero, channel 3 is alpha, straight (unassociated).
int glint_oiio_write(const char* path, int width, int height, int channels, int pixelType,
                     const void* pixels, int hasAlpha, char* error, size_t errorSize);

#ifdef __cplusplus
}
#endif

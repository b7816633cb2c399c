#pragma once
// glint/gl/debug.h — KHR_debug output: GL errors become log lines and are counted.
//
// enableDebugOutput() installs a synchronous callback on the current context.
// Errors and undefined behaviour are logged as errors and counted; performance
// and portability notes of low severity are logged at debug level, those of medium or
// high severity as warnings. Tests assert that debugErrorCount() did not grow while a
// scene rendered, and the gallery test that debugNotableCount() did not either. The CLI turns it on
// with --gl-debug.

#include <cstdint>

namespace glint::gl {

/// Installs the callback on the current context (idempotent).
void enableDebugOutput();
/// GL_DEBUG_TYPE_ERROR / UNDEFINED_BEHAVIOR messages seen so far in this process.
std::uint64_t debugErrorCount();
/// Messages of medium or high severity of any type (errors included) seen so far: what a
/// driver thinks worth saying (performance traps, deprecated use, ...).
std::uint64_t debugNotableCount();
/// Throws Error(Internal) naming the first pending glGetError code, if any. Cheap
/// enough for once per frame; a safety net when the debug callback is off.
void checkGlError(const char* where);

}  // namespace glint::gl

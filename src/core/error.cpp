#include "glint/core/error.h"

namespace glint {

int exitCode(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::Internal: return 1;
    case ErrorKind::Usage: return 2;
    case ErrorKind::Input: return 3;
    case ErrorKind::Output: return 4;
    case ErrorKind::NoGpu: return 5;
    case ErrorKind::OutOfMemory: return 6;
    case ErrorKind::Interrupted: return 130;
  }
  return 1;
}

}  // namespace glint

#include "glint/gl/context.h"

#include "glint/core/error.h"
#include "glint/core/log.h"
#include "glint/gl/debug.h"

#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <cstring>
#include <vector>

namespace glint::gl {
namespace {

constexpr const char* kInstallHint = "install Mesa's EGL and drivers: apt-get install libegl-mesa0 libgl1-mesa-dri";

// Whether the space-separated extension list `exts` (may be null) names `name`: whole
// words, since one extension name can be a prefix of another.
bool listsExtension(const char* exts, const char* name) {
  if (!exts) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = std::strstr(exts, name); p; p = std::strstr(p + 1, name)) {
    if ((p == exts || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  }
  return false;
}

bool hasClientExtension(const char* name) { return listsExtension(eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS), name); }

struct Candidate {
  EGLDisplay display;
  const char* platform;
};

std::vector<Candidate> candidateDisplays() {
  std::vector<Candidate> out;
  if (hasClientExtension("EGL_MESA_platform_surfaceless")) {
    EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d != EGL_NO_DISPLAY) out.push_back({d, "surfaceless"});
  }
  if (hasClientExtension("EGL_EXT_platform_device") && hasClientExtension("EGL_EXT_device_enumeration")) {
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (eglQueryDevicesEXT(16, devices, &count)) {
      for (EGLint i = 0; i < count; ++i) {
        EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (d != EGL_NO_DISPLAY) out.push_back({d, "device"});
      }
    }
  }
  EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  if (d != EGL_NO_DISPLAY) out.push_back({d, "default"});
  return out;
}

EGLContext tryCreate(EGLDisplay display, const ContextOptions& options) {
  if (!eglBindAPI(EGL_OPENGL_API)) return EGL_NO_CONTEXT;
  const EGLint configAttribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint numConfigs = 0;
  const bool noConfig = epoxy_has_egl_extension(display, "EGL_KHR_no_config_context");
  if (!noConfig && (!eglChooseConfig(display, configAttribs, &config, 1, &numConfigs) || numConfigs == 0)) {
    return EGL_NO_CONTEXT;
  }
  const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                            4,
                            EGL_CONTEXT_MINOR_VERSION,
                            5,
                            EGL_CONTEXT_OPENGL_PROFILE_MASK,
                            options.profile == Profile::Core ? EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT
                                                             : EGL_CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT,
                            EGL_CONTEXT_OPENGL_DEBUG,
                            options.debug ? EGL_TRUE : EGL_FALSE,
                            EGL_NONE};
  return eglCreateContext(display, noConfig ? EGL_NO_CONFIG_KHR : config, EGL_NO_CONTEXT, attribs);
}

}  // namespace

bool onlySoftwareDevices() {
  if (!epoxy_has_egl()) return false;
  const bool enumerate = hasClientExtension("EGL_EXT_device_base") || hasClientExtension("EGL_EXT_device_enumeration");
  const bool query = hasClientExtension("EGL_EXT_device_base") || hasClientExtension("EGL_EXT_device_query");
  if (!enumerate || !query) return false;
  EGLDeviceEXT devices[16];
  EGLint count = 0;
  if (!eglQueryDevicesEXT(16, devices, &count) || count <= 0) return false;
  for (EGLint i = 0; i < count; ++i) {
    if (!listsExtension(eglQueryDeviceStringEXT(devices[i], EGL_EXTENSIONS), "EGL_MESA_device_software")) return false;
  }
  return true;
}

std::unique_ptr<HeadlessContext> HeadlessContext::create(const ContextOptions& options) {
  if (!epoxy_has_egl()) fail(ErrorKind::NoGpu, "no OpenGL 4.5 context: libEGL is not available ({})", kInstallHint);
  const char* profileName = options.profile == Profile::Core ? "core" : "compatibility";
  bool anyDisplay = false;
  for (const Candidate& c : candidateDisplays()) {
    EGLint major = 0, minor = 0;
    if (!eglInitialize(c.display, &major, &minor)) continue;
    anyDisplay = true;
    if (!epoxy_has_egl_extension(c.display, "EGL_KHR_surfaceless_context")) {
      eglTerminate(c.display);
      continue;
    }
    EGLContext ctx = tryCreate(c.display, options);
    if (ctx == EGL_NO_CONTEXT) {
      log::debug("EGL {} platform: no OpenGL 4.5 {} context (0x{:x})", c.platform, profileName, eglGetError());
      eglTerminate(c.display);
      continue;
    }
    if (!eglMakeCurrent(c.display, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
      eglDestroyContext(c.display, ctx);
      eglTerminate(c.display);
      continue;
    }
    auto context = std::unique_ptr<HeadlessContext>(new HeadlessContext());
    context->m_display = c.display;
    context->m_context = ctx;
    context->m_options = options;
    context->m_platform = c.platform;
    if (options.debug) enableDebugOutput();
    log::debug("OpenGL {} on EGL {} platform: {}", profileName, c.platform,
               reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
    return context;
  }
  if (!anyDisplay) fail(ErrorKind::NoGpu, "no OpenGL 4.5 context: EGL found no usable display ({})", kInstallHint);
  fail(ErrorKind::NoGpu, "no OpenGL 4.5 {} context: the EGL drivers offer none ({})", profileName, kInstallHint);
}

HeadlessContext::~HeadlessContext() {
  auto display = static_cast<EGLDisplay>(m_display);
  if (eglGetCurrentContext() == static_cast<EGLContext>(m_context)) {
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
  eglDestroyContext(display, static_cast<EGLContext>(m_context));
  // The display is shared by every context on it (EGL displays are per-process
  // singletons), so it is not terminated here; eglReleaseThread frees this thread's state.
  eglReleaseThread();
}

void HeadlessContext::makeCurrent() const {
  if (!eglMakeCurrent(static_cast<EGLDisplay>(m_display), EGL_NO_SURFACE, EGL_NO_SURFACE,
                      static_cast<EGLContext>(m_context))) {
    fail(ErrorKind::NoGpu, "cannot make the OpenGL context current (EGL error 0x{:x})", eglGetError());
  }
}

ContextInfo queryContextInfo() {
  ContextInfo info;
  auto str = [](GLenum e) {
    const auto* s = reinterpret_cast<const char*>(glGetString(e));
    return std::string(s ? s : "?");
  };
  info.vendor = str(GL_VENDOR);
  info.renderer = str(GL_RENDERER);
  info.version = str(GL_VERSION);
  info.glslVersion = str(GL_SHADING_LANGUAGE_VERSION);
  GLint mask = 0;
  glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &mask);
  info.profile = (mask & GL_CONTEXT_CORE_PROFILE_BIT) ? "core" : "compatibility";
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &info.maxTextureSize);
  glGetIntegerv(GL_MAX_CUBE_MAP_TEXTURE_SIZE, &info.maxCubeMapSize);
  glGetIntegerv(GL_MAX_SAMPLES, &info.maxSamples);
  glGetIntegerv(GL_MAX_COLOR_ATTACHMENTS, &info.maxColorAttachments);
  if (epoxy_gl_version() >= 46 || epoxy_has_gl_extension("GL_ARB_texture_filter_anisotropic") ||
      epoxy_has_gl_extension("GL_EXT_texture_filter_anisotropic")) {
    glGetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY, &info.maxAnisotropy);
  }
  // Stencil bits of the depth-stencil format glint renders with.
  GLint stencil = 0;
  glGetInternalformativ(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, GL_INTERNALFORMAT_STENCIL_SIZE, 1, &stencil);
  info.stencilBits = stencil;
  const std::string r = info.renderer;
  info.software = r.find("llvmpipe") != std::string::npos || r.find("softpipe") != std::string::npos ||
                  r.find("swrast") != std::string::npos;
  return info;
}

}  // namespace glint::gl

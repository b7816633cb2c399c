#pragma once
// glint/gl/context.h — OpenGL 4.5 contexts: headless (EGL) and what they offer.
//
// Contents
//   ContextOptions     profile (core / compatibility) and debug output
//   HeadlessContext    an EGL context without a window; render into framebuffer objects
//   ContextInfo        vendor, renderer, version and the limits glint cares about
//
// Headless contexts come from EGL: Mesa's surfaceless platform first (llvmpipe
// on machines without a GPU, the GPU driver otherwise), then the EGL device
// platform (NVIDIA without a display), then the default display. A headless
// context has no default framebuffer: scenes draw into a gl::RenderTarget.
// Windows (GLFW) are in gl/window.h.
//
// Both profiles are 4.5. The compatibility profile exists for the "classic"
// variants that show the 2001 fixed-function API next to the shader versions;
// when a driver has none, createHeadless throws Error(NoGpu) and callers skip
// those variants.

#include <memory>
#include <string>

namespace glint::gl {

enum class Profile {
  Core,          ///< OpenGL 4.5 core: what every technique uses
  Compatibility  ///< OpenGL 4.5 compatibility: fixed-function paths of the classic variants
};

struct ContextOptions {
  Profile profile = Profile::Core;
  bool debug = false;  ///< KHR_debug context and callback (see gl/debug.h); tests turn it on
};

class HeadlessContext {
public:
  /// Creates and makes current a 4.5 context. Throws Error(NoGpu) with what to install
  /// when EGL or a 4.5 context of the requested profile is unavailable.
  static std::unique_ptr<HeadlessContext> create(const ContextOptions& options = {});
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  void makeCurrent() const;
  const ContextOptions& options() const { return m_options; }
  /// Which EGL platform served the context ("surfaceless", "device", "default").
  const std::string& platform() const { return m_platform; }

private:
  HeadlessContext() = default;
  void* m_display = nullptr;
  void* m_context = nullptr;
  ContextOptions m_options;
  std::string m_platform;
};

struct ContextInfo {
  std::string vendor, renderer, version, glslVersion, profile;
  int stencilBits = 0;          ///< of the framebuffers glint creates (DEPTH24_STENCIL8)
  int maxTextureSize = 0;
  int maxCubeMapSize = 0;
  int maxSamples = 0;
  int maxColorAttachments = 0;
  float maxAnisotropy = 1.0f;   ///< GL_MAX_TEXTURE_MAX_ANISOTROPY (1 when unsupported)
  bool software = false;        ///< llvmpipe / softpipe / swrast
};

/// Queries the current context.
ContextInfo queryContextInfo();

/// Whether EGL lists its devices and every one is a software rasterizer (Mesa's
/// EGL_MESA_device_software: llvmpipe): then any context glint makes renders on the CPU.
/// About 2 ms, where making a context to read GL_RENDERER takes 50 (no display is
/// initialized). False when EGL, its device enumeration or query is missing, or when any
/// device is a GPU — callers then make a context and ask it.
bool onlySoftwareDevices();

}  // namespace glint::gl

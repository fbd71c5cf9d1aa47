// OpenGL ES 3 contexts without a window or a display server: EGL devices (EGL_EXT_device_enumeration
// and EGL_EXT_platform_device, which NVIDIA's driver and Mesa both offer), and Mesa's surfaceless
// platform where no device can be enumerated. The gl engine (gl_engine.h) and the transform-feedback
// runs of the tests and bench/compare_llvmpipe (gl_runner.h) run on these contexts.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vm/core/result.h"

namespace vs11::gl {

// One EGL device, as `--gl-device list` prints it.
struct GlDeviceInfo {
  int index = 0;
  bool software = false;    // Mesa's llvmpipe (the device has EGL_MESA_device_software)
  std::string extensions;   // the device's own EGL extensions
  std::string drm_file;     // EGL_DRM_DEVICE_FILE_EXT where the driver names one ("/dev/dri/card0")
  std::string renderer;     // GL_RENDERER of an OpenGL ES 3.0 context on it; empty when none could be made
  std::string version;      // GL_VERSION of that context
  std::string error;        // why no context could be made
};

// Every EGL device, each tried with an OpenGL ES 3.0 context. An error (kGlUnavailable) where EGL has
// no device enumeration (no EGL at all, or a libEGL without EGL_EXT_device_enumeration) or lists no
// device.
Result<std::vector<GlDeviceInfo>> ListGlDevices();

// `--gl-device list` as text: one line per device (index, llvmpipe or not, DRM file, GL_RENDERER and
// GL_VERSION or why no context could be made).
std::string FormatGlDeviceList(const std::vector<GlDeviceInfo>& devices);

// "3" -> 3, the --gl-device N of both tools; nullopt for anything but a non-negative decimal number.
std::optional<int> GlDeviceIndex(std::string_view text);

// A context of OpenGL ES 3.0 or later on a device, with no surface: a 1x1 framebuffer object is bound
// (without one every draw fails with GL_INVALID_FRAMEBUFFER_OPERATION) and rasterisation is discarded,
// since only transform feedback's outputs are wanted. A context is current on at most one thread at a
// time: an engine makes its context current for each call (ScopedCurrent) and so may move between
// threads, as vm/core/machine.h allows.
class GlContext {
 public:
  // `device`: an index of ListGlDevices; nullopt: Mesa's llvmpipe, the device with
  // EGL_MESA_device_software, or else Mesa's surfaceless platform with llvmpipe asked for through
  // LIBGL_ALWAYS_SOFTWARE and GALLIUM_DRIVER (set only where the environment does not set them).
  // An error (kGlUnavailable) where there is no EGL, no such device, or no OpenGL ES 3.0 on it. What
  // was current on the calling thread before is current again when it returns.
  static Result<std::unique_ptr<GlContext>> Create(std::optional<int> device);
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // Makes the context current on the calling thread (a no-op where it already is), for good.
  Status MakeCurrent();
  const std::string& renderer() const { return renderer_; }  // GL_RENDERER
  const std::string& version() const { return version_; }    // GL_VERSION
  bool es32() const { return es32_; }                         // OpenGL ES 3.2 or later: GLSL ES 3.20

 private:
  GlContext() = default;
  Status SetUp();  // the framebuffer object, rasterizer discard, the version check

  friend class ScopedCurrent;
  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
  unsigned framebuffer_ = 0, renderbuffer_ = 0;
  std::string renderer_, version_;
  bool es32_ = false;
};

// Makes `context` current on the calling thread for the scope, then makes current again whatever
// was current before (another engine's context, a test's, or none).
class ScopedCurrent {
 public:
  explicit ScopedCurrent(GlContext& context);
  ~ScopedCurrent();
  ScopedCurrent(const ScopedCurrent&) = delete;
  ScopedCurrent& operator=(const ScopedCurrent&) = delete;
  // Whether the context could be made current, and why not.
  const Status& status() const { return status_; }
  bool ok() const { return status_.ok(); }

 private:
  GlContext& context_;
  void* previous_display_ = nullptr;
  void* previous_context_ = nullptr;
  void* previous_draw_ = nullptr;
  void* previous_read_ = nullptr;
  Status status_;
};

}  // namespace vs11::gl

#include "vm/gl/gl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES3/gl3.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>

#include <fmt/format.h>

namespace vs11::gl {
namespace {

bool HasExtension(const char* list, std::string_view name) {
  if (list == nullptr) return false;
  for (const char* p = std::strstr(list, std::string(name).c_str()); p != nullptr;
       p = std::strstr(p + 1, std::string(name).c_str())) {
    if ((p == list || p[-1] == ' ') && (p[name.size()] == ' ' || p[name.size()] == '\0')) return true;
  }
  return false;
}

Diagnostic EglFailure(const char* call) {
  return Failure(DiagnosticCode::kGlUnavailable, fmt::format("{} failed (EGL error 0x{:04X})", call, eglGetError()));
}

// The EGL_EXT_device_* and EGL_EXT_platform_base entry points, where libEGL has them.
struct EglEntryPoints {
  PFNEGLQUERYDEVICESEXTPROC query_devices = nullptr;
  PFNEGLQUERYDEVICESTRINGEXTPROC query_device_string = nullptr;
  PFNEGLGETPLATFORMDISPLAYEXTPROC get_platform_display = nullptr;
  std::string client_extensions;

  // EGL_EXT_device_base is EGL_EXT_device_enumeration and EGL_EXT_device_query in one name.
  bool CanEnumerateDevices() const {
    return query_devices != nullptr && query_device_string != nullptr && get_platform_display != nullptr &&
           (HasExtension(client_extensions.c_str(), "EGL_EXT_device_enumeration") ||
            HasExtension(client_extensions.c_str(), "EGL_EXT_device_base")) &&
           HasExtension(client_extensions.c_str(), "EGL_EXT_platform_device");
  }
  // Why CanEnumerateDevices is false, with what libEGL offers.
  Diagnostic CannotEnumerate() const {
    return Failure(
        DiagnosticCode::kGlUnavailable,
        fmt::format(
            "EGL cannot enumerate devices (it needs EGL_EXT_device_enumeration or EGL_EXT_device_base, "
            "EGL_EXT_platform_device and their entry points; is libegl1 with a vendor library such as libegl-mesa0 "
            "installed?); EGL's client extensions: {}",
            client_extensions.empty() ? "none" : client_extensions));
  }
};

const EglEntryPoints& Entry() {
  static const EglEntryPoints entry = [] {
    EglEntryPoints e;
    // Without EGL_EXT_client_extensions this is NULL with EGL_BAD_DISPLAY: no platforms to choose from.
    const char* extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (extensions != nullptr) e.client_extensions = extensions;
    e.query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    e.query_device_string =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
    e.get_platform_display =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    return e;
  }();
  return entry;
}

std::vector<EGLDeviceEXT> Devices() {
  const EglEntryPoints& entry = Entry();
  if (!entry.CanEnumerateDevices()) return {};
  EGLint count = 0;
  if (entry.query_devices(0, nullptr, &count) != EGL_TRUE || count <= 0) return {};
  std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
  if (entry.query_devices(count, devices.data(), &count) != EGL_TRUE) return {};
  devices.resize(static_cast<std::size_t>(std::max<EGLint>(count, 0)));
  return devices;
}

std::string DeviceString(EGLDeviceEXT device, EGLint name) {
  const char* text = Entry().query_device_string(device, name);
  return text != nullptr ? text : "";
}

// Mesa reads its driver choice when a display is initialised: ask for llvmpipe on the surfaceless
// platform unless the user chose otherwise.
void AskMesaForLlvmpipe() {
  setenv("LIBGL_ALWAYS_SOFTWARE", "1", 0);
  setenv("GALLIUM_DRIVER", "llvmpipe", 0);
}

// The display of `device` (ListGlDevices' index), or of llvmpipe for nullopt; initialised.
Result<EGLDisplay> OpenDisplay(std::optional<int> device) {
  const EglEntryPoints& entry = Entry();
  const std::vector<EGLDeviceEXT> devices = Devices();
  EGLDisplay display = EGL_NO_DISPLAY;
  if (device) {
    if (!entry.CanEnumerateDevices()) return entry.CannotEnumerate();
    if (*device < 0 || *device >= static_cast<int>(devices.size())) {
      return Failure(DiagnosticCode::kGlUnavailable,
                     fmt::format("no EGL device {}: EGL lists {} (see --gl-device list)", *device, devices.size()));
    }
    display = entry.get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[static_cast<std::size_t>(*device)], nullptr);
  } else {
    for (EGLDeviceEXT candidate : devices) {
      if (HasExtension(DeviceString(candidate, EGL_EXTENSIONS).c_str(), "EGL_MESA_device_software")) {
        display = entry.get_platform_display(EGL_PLATFORM_DEVICE_EXT, candidate, nullptr);
        break;
      }
    }
    if (display == EGL_NO_DISPLAY) {
      if (entry.get_platform_display == nullptr ||
          !HasExtension(entry.client_extensions.c_str(), "EGL_MESA_platform_surfaceless")) {
        return Failure(DiagnosticCode::kGlUnavailable,
                       fmt::format("no EGL device is Mesa's llvmpipe ({} EGL devices; see --gl-device list) and EGL "
                                   "has no EGL_MESA_platform_surfaceless (is Mesa's libegl-mesa0 installed?)",
                                   devices.size()));
      }
      AskMesaForLlvmpipe();
      display = entry.get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    }
  }
  if (display == EGL_NO_DISPLAY) return EglFailure("eglGetPlatformDisplayEXT");
  // Initialising an initialised display does nothing; displays stay open until the process ends
  // (eglTerminate would end every context on them, other engines' included).
  EGLint major = 0, minor = 0;
  if (eglInitialize(display, &major, &minor) != EGL_TRUE) return EglFailure("eglInitialize");
  return display;
}

// An OpenGL ES 3.0 context: without a config where the display allows (EGL_KHR_no_config_context),
// else with the first config that renders OpenGL ES 3.
Result<EGLContext> CreateEs3Context(EGLDisplay display) {
  const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
  if (!HasExtension(extensions, "EGL_KHR_surfaceless_context")) {
    return Failure(DiagnosticCode::kGlUnavailable,
                   "the EGL display lacks EGL_KHR_surfaceless_context (a context without a window)");
  }
  if (eglBindAPI(EGL_OPENGL_ES_API) != EGL_TRUE) return EglFailure("eglBindAPI(EGL_OPENGL_ES_API)");
  EGLConfig config = EGL_NO_CONFIG_KHR;
  if (!HasExtension(extensions, "EGL_KHR_no_config_context")) {
    const EGLint wanted[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT, EGL_SURFACE_TYPE, EGL_DONT_CARE, EGL_NONE};
    EGLint found = 0;
    if (eglChooseConfig(display, wanted, &config, 1, &found) != EGL_TRUE || found < 1) {
      return Failure(DiagnosticCode::kGlUnavailable, "the EGL display has no config that renders OpenGL ES 3");
    }
  }
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 0, EGL_NONE};
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, attributes);
  if (context == EGL_NO_CONTEXT) return EglFailure("eglCreateContext (OpenGL ES 3.0)");
  return context;
}

// Displays are opened, and contexts made, under one lock: EGL implementations differ in how much of
// their set-up tolerates two threads.
std::mutex& CreationMutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace

Result<std::unique_ptr<GlContext>> GlContext::Create(std::optional<int> device) {
  std::unique_ptr<GlContext> context(new GlContext());
  {
    std::lock_guard<std::mutex> lock(CreationMutex());
    Result<EGLDisplay> display = OpenDisplay(device);
    if (!display) return display.error();
    context->display_ = *display;
    Result<EGLContext> made = CreateEs3Context(*display);
    if (!made) return made.error();
    context->context_ = *made;
  }
  ScopedCurrent current(*context);
  if (!current.ok()) return current.status().error();
  if (Status set_up = context->SetUp(); !set_up) return set_up.error();
  return context;
}

Status GlContext::SetUp() {
  const char* version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  const char* renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  version_ = version != nullptr ? version : "";
  renderer_ = renderer != nullptr ? renderer : "";
  int major = 0, minor = 0;
  if (std::sscanf(version_.c_str(), "OpenGL ES %d.%d", &major, &minor) != 2 || major < 3) {
    return Failure(DiagnosticCode::kGlUnavailable,
                   fmt::format("the context is '{}' on '{}', not OpenGL ES 3.0 or later", version_, renderer_));
  }
  es32_ = major > 3 || minor >= 2;
  glGenFramebuffers(1, &framebuffer_);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glGenRenderbuffers(1, &renderbuffer_);
  glBindRenderbuffer(GL_RENDERBUFFER, renderbuffer_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, 1, 1);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, renderbuffer_);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
    return Failure(DiagnosticCode::kGlError, "the 1x1 framebuffer object is not complete");
  }
  glEnable(GL_RASTERIZER_DISCARD);
  if (const GLenum code = glGetError(); code != GL_NO_ERROR) {
    return Failure(DiagnosticCode::kGlError, fmt::format("setting up the framebuffer: GL error 0x{:04X}", code));
  }
  return {};
}

GlContext::~GlContext() {
  if (context_ == nullptr) return;
  {
    ScopedCurrent current(*this);
    if (current.ok()) {
      glDeleteRenderbuffers(1, &renderbuffer_);
      glDeleteFramebuffers(1, &framebuffer_);
    }
  }
  eglDestroyContext(display_, context_);
}

Status GlContext::MakeCurrent() {
  if (eglGetCurrentContext() == context_) return {};
  if (eglBindAPI(EGL_OPENGL_ES_API) != EGL_TRUE ||
      eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_) != EGL_TRUE) {
    return EglFailure("eglMakeCurrent without a surface");
  }
  return {};
}

ScopedCurrent::ScopedCurrent(GlContext& context)
    : context_(context),
      previous_display_(eglGetCurrentDisplay()),
      previous_context_(eglGetCurrentContext()),
      previous_draw_(eglGetCurrentSurface(EGL_DRAW)),
      previous_read_(eglGetCurrentSurface(EGL_READ)) {
  status_ = context_.MakeCurrent();
}

ScopedCurrent::~ScopedCurrent() {
  if (previous_context_ == context_.context_) return;
  if (previous_context_ != EGL_NO_CONTEXT) {
    eglMakeCurrent(previous_display_, previous_draw_, previous_read_, previous_context_);
  } else if (eglGetCurrentContext() == context_.context_) {
    eglMakeCurrent(context_.display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
}

Result<std::vector<GlDeviceInfo>> ListGlDevices() {
  if (!Entry().CanEnumerateDevices()) return Entry().CannotEnumerate();
  std::vector<GlDeviceInfo> list;
  const std::vector<EGLDeviceEXT> devices = Devices();
  for (std::size_t i = 0; i < devices.size(); ++i) {
    GlDeviceInfo info;
    info.index = static_cast<int>(i);
    info.extensions = DeviceString(devices[i], EGL_EXTENSIONS);
    info.software = HasExtension(info.extensions.c_str(), "EGL_MESA_device_software");
    if (HasExtension(info.extensions.c_str(), "EGL_EXT_device_drm")) {
      info.drm_file = DeviceString(devices[i], EGL_DRM_DEVICE_FILE_EXT);
    }
    if (Result<std::unique_ptr<GlContext>> context = GlContext::Create(info.index)) {
      info.renderer = (*context)->renderer();
      info.version = (*context)->version();
    } else {
      info.error = context.message();
    }
    list.push_back(std::move(info));
  }
  if (list.empty()) return Failure(DiagnosticCode::kGlUnavailable, "EGL lists no device");
  return list;
}

}  // namespace vs11::gl

namespace vs11::gl {

std::string FormatGlDeviceList(const std::vector<GlDeviceInfo>& devices) {
  std::string text;
  for (const GlDeviceInfo& device : devices) {
    text += fmt::format("{}: {}{}: {}\n", device.index, device.software ? "Mesa software device (the default)" : "device",
                        device.drm_file.empty() ? "" : " " + device.drm_file,
                        device.renderer.empty() ? "no OpenGL ES 3.0 context: " + device.error
                                                : fmt::format("{} ({})", device.renderer, device.version));
  }
  return text;
}

std::optional<int> GlDeviceIndex(std::string_view text) {
  int index = -1;
  const auto [end, code] = std::from_chars(text.data(), text.data() + text.size(), index);
  if (text.empty() || code != std::errc() || end != text.data() + text.size() || index < 0) return std::nullopt;
  return index;
}

}  // namespace vs11::gl

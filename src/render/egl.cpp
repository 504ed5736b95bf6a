// EGL display selection. Mesa's surfaceless platform needs no display server and no
// device; the device platform is the route on NVIDIA. Plain eglGetDisplay fails on
// Mesa without EGL_PLATFORM set, so it is never used.
#define EGL_NO_X11  // keep X11 headers out of eglplatform.h
#include "render/egl.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <glad/gl.h>

#include <cstdio>
#include <cstring>
#include <vector>

#include "render/image.h"

namespace sluice::render {

std::optional<EglPlatform> parse_egl_platform(const std::string& s) {
  if (s == "auto") return EglPlatform::automatic;
  if (s == "surfaceless") return EglPlatform::surfaceless;
  if (s == "device") return EglPlatform::device;
  return std::nullopt;
}

namespace {

bool has_extension(const char* list, const char* name) {
  if (!list) return false;
  const size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

std::string egl_error_name(EGLint e) {
  switch (e) {
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    default: {
      char buf[32];
      std::snprintf(buf, sizeof buf, "EGL error 0x%04x", e);
      return buf;
    }
  }
}

template <class F>
F egl_proc(const char* name) {
  return reinterpret_cast<F>(eglGetProcAddress(name));
}

// An initialised display and how it was found, or the reason it was not.
struct Candidate {
  EGLDisplay display = EGL_NO_DISPLAY;
  std::string name;
};

EGLDisplay initialise(EGLDisplay d, const std::string& what, std::vector<std::string>& tried) {
  if (d == EGL_NO_DISPLAY) {
    tried.push_back(what + ": no display (" + egl_error_name(eglGetError()) + ")");
    return EGL_NO_DISPLAY;
  }
  EGLint major = 0, minor = 0;
  if (!eglInitialize(d, &major, &minor)) {
    tried.push_back(what + ": eglInitialize failed (" + egl_error_name(eglGetError()) + ")");
    return EGL_NO_DISPLAY;
  }
  return d;
}

Candidate try_surfaceless(const char* client_ext, std::vector<std::string>& tried) {
  if (!has_extension(client_ext, "EGL_MESA_platform_surfaceless")) {
    tried.push_back("surfaceless: EGL_MESA_platform_surfaceless not supported by this libEGL");
    return {};
  }
  auto get_display = egl_proc<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
  if (!get_display) {
    tried.push_back("surfaceless: eglGetPlatformDisplayEXT missing");
    return {};
  }
  EGLDisplay d = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  return {initialise(d, "surfaceless", tried), "surfaceless"};
}

// Hardware devices first: a device advertising EGL_MESA_device_software is llvmpipe.
Candidate try_devices(const char* client_ext, std::vector<std::string>& tried) {
  // EGL_EXT_device_base is the older name of device_enumeration + device_query, and the one
  // some NVIDIA drivers advertise.
  if (!has_extension(client_ext, "EGL_EXT_platform_device") ||
      !(has_extension(client_ext, "EGL_EXT_device_enumeration") || has_extension(client_ext, "EGL_EXT_device_base"))) {
    tried.push_back(std::string("device: EGL_EXT_platform_device with EGL_EXT_device_enumeration (or _base) not "
                                "supported by this libEGL (its client extensions: ") +
                    (client_ext ? client_ext : "none") + ")");
    return {};
  }
  auto query_devices = egl_proc<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
  auto query_string = egl_proc<PFNEGLQUERYDEVICESTRINGEXTPROC>("eglQueryDeviceStringEXT");
  auto get_display = egl_proc<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
  EGLint n = 0;
  if (!query_devices || !get_display || !query_devices(0, nullptr, &n) || n == 0) {
    tried.push_back("device: no EGL devices found");
    return {};
  }
  std::vector<EGLDeviceEXT> devices(static_cast<size_t>(n));
  query_devices(n, devices.data(), &n);
  std::vector<EGLDeviceEXT> ordered;
  for (int pass = 0; pass < 2; ++pass)
    for (EGLDeviceEXT dev : devices) {
      const char* ext = query_string ? query_string(dev, EGL_EXTENSIONS) : nullptr;
      const bool software = has_extension(ext, "EGL_MESA_device_software");
      if (software == (pass == 1)) ordered.push_back(dev);
    }
  for (size_t i = 0; i < ordered.size(); ++i) {
    const char* ext = query_string ? query_string(ordered[i], EGL_EXTENSIONS) : nullptr;
    const std::string what = std::string("device ") + std::to_string(i) +
                             (has_extension(ext, "EGL_MESA_device_software") ? " (software)" : "");
    EGLDisplay d = initialise(get_display(EGL_PLATFORM_DEVICE_EXT, ordered[i], nullptr), what, tried);
    if (d != EGL_NO_DISPLAY) return {d, what};
  }
  return {};
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& t : v) s += (s.empty() ? "" : "; ") + t;
  return s;
}

}  // namespace

EglContext::EglContext(EglPlatform platform) {
  std::vector<std::string> tried;
  const char* client_ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  Candidate c;
  if (platform != EglPlatform::device) c = try_surfaceless(client_ext, tried);
  if (c.display == EGL_NO_DISPLAY && platform != EglPlatform::surfaceless) c = try_devices(client_ext, tried);
  if (c.display == EGL_NO_DISPLAY)
    throw RenderError("no headless EGL display (tried " + joined(tried) +
                      "); install libegl-mesa0 and libgl1-mesa-dri, or pick another platform with --egl");

  auto fail = [&](const std::string& step) {
    const std::string msg = c.name + ": " + step + " failed (" + egl_error_name(eglGetError()) + ")";
    eglTerminate(c.display);
    throw RenderError("cannot create an OpenGL 3.3 core context through EGL: " + msg);
  };
  if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API)");
  EGLConfig config = nullptr;  // EGL_NO_CONFIG_KHR where allowed
  if (!has_extension(eglQueryString(c.display, EGL_EXTENSIONS), "EGL_KHR_no_config_context")) {
    const EGLint attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_NONE};
    EGLint count = 0;
    if (!eglChooseConfig(c.display, attribs, &config, 1, &count) || count == 0) fail("eglChooseConfig");
  }
  const EGLint ctx_attribs[] = {
      EGL_CONTEXT_MAJOR_VERSION,           3,       EGL_CONTEXT_MINOR_VERSION, 3, EGL_CONTEXT_OPENGL_PROFILE_MASK,
      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext ctx = eglCreateContext(c.display, config, EGL_NO_CONTEXT, ctx_attribs);
  if (ctx == EGL_NO_CONTEXT) fail("eglCreateContext (OpenGL 3.3 core)");
  if (!eglMakeCurrent(c.display, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) {
    eglDestroyContext(c.display, ctx);
    fail("eglMakeCurrent without surface");
  }
  display_ = c.display;
  context_ = ctx;
  if (!gladLoadGL(reinterpret_cast<GLADloadfunc>(eglGetProcAddress))) {
    eglMakeCurrent(c.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(c.display, ctx);
    eglTerminate(c.display);
    throw RenderError(c.name + ": cannot load the OpenGL 3.3 core functions");
  }
  description_ = c.name + ", " + reinterpret_cast<const char*>(glGetString(GL_RENDERER)) + ", OpenGL " +
                 reinterpret_cast<const char*>(glGetString(GL_VERSION));
}

EglContext::~EglContext() {
  if (!display_) return;
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (context_) eglDestroyContext(display_, context_);
  eglTerminate(display_);
  display_ = context_ = nullptr;
}

}  // namespace sluice::render

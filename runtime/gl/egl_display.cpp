#include "gl/egl_display.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <map>
#include <mutex>
#include <sstream>

#include "gl/egl_runner.hpp"

namespace bl::gl::detail {
namespace {

std::string egl_error_name(EGLint e) {
  switch (e) {
    case EGL_SUCCESS:
      return "EGL_SUCCESS";
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
      std::ostringstream s;
      s << "EGL error 0x" << std::hex << e;
      return s.str();
    }
  }
}

[[noreturn]] void fail(const std::string& step) {
  throw Error("EGL: " + step + " failed (" + egl_error_name(eglGetError()) + ")");
}

bool has_extension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n) {
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  }
  return false;
}

// eglTerminate tears down every context of a display, and displays are shared per platform:
// count users so one Context's destruction does not break another's.
std::mutex g_mutex;
std::map<EGLDisplay, int> g_users;

EGLDisplay open_display(std::string& platform) {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (has_extension(client, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay d = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    EGLint major = 0, minor = 0;
    if (d != EGL_NO_DISPLAY && eglInitialize(d, &major, &minor)) {
      platform = "surfaceless";
      return d;
    }
  }
  // A GPU driver without Mesa (e.g. NVIDIA's) exposes its devices instead.
  if (has_extension(client, "EGL_EXT_platform_device")) {
    auto query = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    EGLDeviceEXT devices[8];
    EGLint count = 0;
    if (query != nullptr && query(8, devices, &count)) {
      for (EGLint i = 0; i < count; ++i) {
        EGLDisplay d = eglGetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        EGLint major = 0, minor = 0;
        if (d != EGL_NO_DISPLAY && eglInitialize(d, &major, &minor)) {
          platform = "device";
          return d;
        }
      }
    }
  }
  if (!has_extension(client, "EGL_MESA_platform_surfaceless") &&
      !has_extension(client, "EGL_EXT_platform_device")) {
    throw Error(
        "EGL: neither EGL_MESA_platform_surfaceless nor EGL_EXT_platform_device is offered "
        "(client extensions: " +
        std::string(client ? client : "none") + ")");
  }
  fail("eglInitialize on the surfaceless and device platforms");
}

}  // namespace

EglContext create_egl_context() {
  std::lock_guard<std::mutex> lock(g_mutex);
  EglContext c;
  EGLDisplay d = open_display(c.platform);
  ++g_users[d];
  c.display = d;
  try {
    if (!has_extension(eglQueryString(d, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context")) {
      throw Error("EGL: the display lacks EGL_KHR_surfaceless_context");
    }
    if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API)");
    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!has_extension(eglQueryString(d, EGL_EXTENSIONS), "EGL_KHR_no_config_context")) {
      const EGLint want[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
      EGLint n = 0;
      if (!eglChooseConfig(d, want, &config, 1, &n) || n < 1) fail("eglChooseConfig(EGL_OPENGL_BIT)");
    }
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                              4,
                              EGL_CONTEXT_MINOR_VERSION,
                              5,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK,
                              EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                              EGL_NONE};
    EGLContext ctx = eglCreateContext(d, config, EGL_NO_CONTEXT, attribs);
    if (ctx == EGL_NO_CONTEXT) fail("eglCreateContext(OpenGL 4.5 core)");
    c.context = ctx;
    if (!eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) fail("eglMakeCurrent(surfaceless)");
  } catch (...) {
    if (c.context != nullptr) eglDestroyContext(d, c.context);
    if (--g_users[d] == 0) eglTerminate(d);
    throw;
  }
  return c;
}

void destroy_egl_context(EglContext& c) {
  if (c.display == nullptr) return;
  std::lock_guard<std::mutex> lock(g_mutex);
  EGLDisplay d = c.display;
  eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (c.context != nullptr) eglDestroyContext(d, c.context);
  if (--g_users[d] == 0) {
    g_users.erase(d);
    eglTerminate(d);
  }
  c = EglContext{};
}

void make_current(const EglContext& c) {
  if (eglGetCurrentContext() == c.context) return;
  if (!eglMakeCurrent(c.display, EGL_NO_SURFACE, EGL_NO_SURFACE, c.context)) fail("eglMakeCurrent");
}

}  // namespace bl::gl::detail

// Internal: an EGL display and a desktop GL 4.5 core context with no surface.
#pragma once

#include <string>

namespace bl::gl::detail {

struct EglContext {
  void* display = nullptr;  // EGLDisplay
  void* context = nullptr;  // EGLContext
  std::string platform;     // "surfaceless" or "device"
};

// Throws bl::gl::Error naming the failing step and the EGL error code.
EglContext create_egl_context();
void destroy_egl_context(EglContext& c);
void make_current(const EglContext& c);

}  // namespace bl::gl::detail

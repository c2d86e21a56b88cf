// A GL 3.3 core context from EGL without a display or surface (EGL_MESA_platform_surfaceless), made
// current on this thread with the GL entry points of gl.h loaded through eglGetProcAddress.
#pragma once

namespace slime {

class EglContext {
 public:
  EglContext();  // throws std::runtime_error naming the EGL step that failed
  ~EglContext();
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

 private:
  void release();
  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
};

}  // namespace slime

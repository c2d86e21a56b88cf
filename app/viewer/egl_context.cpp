#include "app/viewer/egl_context.h"

#include "app/viewer/gl_loader.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <stdexcept>
#include <string>

namespace slime {
namespace {

[[noreturn]] void failEgl(const char* step) {
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", static_cast<unsigned>(eglGetError()));
  throw std::runtime_error(std::string("EGL: ") + step + " failed (EGL error " + code +
                           "); is Mesa's EGL installed?");
}

}  // namespace

EglContext::EglContext() {
  EGLDisplay display = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display == EGL_NO_DISPLAY) failEgl("eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA)");
  if (!eglInitialize(display, nullptr, nullptr)) failEgl("eglInitialize");
  display_ = display;
  try {
    if (!eglBindAPI(EGL_OPENGL_API)) failEgl("eglBindAPI(EGL_OPENGL_API)");
    const EGLint configAttributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT,
                                       EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configCount = 0;
    if (!eglChooseConfig(display, configAttributes, &config, 1, &configCount) || configCount == 0)
      failEgl("eglChooseConfig");
    const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                        EGL_NONE};
    EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttributes);
    if (context == EGL_NO_CONTEXT) failEgl("eglCreateContext(GL 3.3 core)");
    context_ = context;
    if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) failEgl("eglMakeCurrent (surfaceless)");
    // Mesa's EGL has EGL_KHR_get_all_proc_addresses: core entry points come from eglGetProcAddress too.
    loadGl([](const char* name) { return reinterpret_cast<void*>(eglGetProcAddress(name)); });
  } catch (...) {
    release();
    throw;
  }
}

EglContext::~EglContext() { release(); }

void EglContext::release() {
  if (display_ == nullptr) return;
  if (context_ != nullptr) {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
  }
  eglTerminate(display_);
  eglReleaseThread();  // the thread's EGL state, which eglTerminate leaves allocated
  context_ = display_ = nullptr;
}

}  // namespace slime

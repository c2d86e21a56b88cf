// A GL 3.3 core context from Mesa's off-screen OSMesa (llvmpipe in this process, no EGL, no display),
// made current on this thread with the GL entry points of gl.h loaded through OSMesaGetProcAddress.
// libOSMesa is opened with dlopen(RTLD_LOCAL): it exports its own gl* symbols, which would collide
// with GLVND's libOpenGL at link time; kept local, only the entry points it hands out are used.
#pragma once

#include <vector>

namespace slime {

class OsMesaContext {
 public:
  OsMesaContext(int width, int height);  // throws std::runtime_error naming what failed
  ~OsMesaContext();
  OsMesaContext(const OsMesaContext&) = delete;
  OsMesaContext& operator=(const OsMesaContext&) = delete;

 private:
  void release();
  void* library_ = nullptr;  // dlopen handle of libOSMesa.so.8
  void* context_ = nullptr;  // OSMesaContext
  void (*destroy_)(void*) = nullptr;
  std::vector<unsigned char> buffer_;  // the default framebuffer OSMesa insists on; frames go to an FBO
};

}  // namespace slime

#include "app/viewer/osmesa_context.h"

#include "app/viewer/gl_loader.h"

#include <GL/osmesa.h>
#include <dlfcn.h>

#include <stdexcept>
#include <string>

namespace slime {
namespace {

constexpr const char* kLibrary = "libOSMesa.so.8";  // Debian's libosmesa6 (Mesa 22)

using CreateContextAttribs = OSMesaContext (*)(const int*, OSMesaContext);
using MakeCurrent = GLboolean (*)(OSMesaContext, void*, GLenum, GLsizei, GLsizei);
using GetProcAddress = OSMESAproc (*)(const char*);

GetProcAddress getProcAddress = nullptr;  // of the library opened last; the loader below needs a plain function

void* symbol(void* library, const char* name) {
  void* address = dlsym(library, name);
  if (address == nullptr) throw std::runtime_error(std::string("OSMesa: ") + kLibrary + " has no " + name);
  return address;
}

}  // namespace

OsMesaContext::OsMesaContext(int width, int height)
    : buffer_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4) {
  library_ = dlopen(kLibrary, RTLD_NOW | RTLD_LOCAL);
  if (library_ == nullptr)
    throw std::runtime_error(std::string("OSMesa: cannot open ") + kLibrary + " (apt-get install libosmesa6): " +
                             dlerror());
  try {
    const auto create = reinterpret_cast<CreateContextAttribs>(symbol(library_, "OSMesaCreateContextAttribs"));
    const auto makeCurrent = reinterpret_cast<MakeCurrent>(symbol(library_, "OSMesaMakeCurrent"));
    getProcAddress = reinterpret_cast<GetProcAddress>(symbol(library_, "OSMesaGetProcAddress"));
    destroy_ = reinterpret_cast<void (*)(void*)>(symbol(library_, "OSMesaDestroyContext"));
    const int attributes[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_STENCIL_BITS, 0,
                              OSMESA_PROFILE, OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 3,
                              OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
    context_ = create(attributes, nullptr);
    if (context_ == nullptr) throw std::runtime_error("OSMesa: OSMesaCreateContextAttribs(GL 3.3 core) failed");
    if (!makeCurrent(static_cast<OSMesaContext>(context_), buffer_.data(), GL_UNSIGNED_BYTE, width, height))
      throw std::runtime_error("OSMesa: OSMesaMakeCurrent failed");
    loadGl([](const char* name) { return reinterpret_cast<void*>(getProcAddress(name)); });
  } catch (...) {
    release();
    throw;
  }
}

OsMesaContext::~OsMesaContext() { release(); }

void OsMesaContext::release() {
  if (context_ != nullptr) destroy_(context_);
  // The library stays loaded: Mesa keeps per-thread state and atexit handlers that refer to it.
  context_ = nullptr;
}

}  // namespace slime

#include "app/viewer/gl_loader.h"

#include "app/viewer/gl.h"

#include <stdexcept>
#include <string>

namespace slime {

#define SLIME_GL_DEFINE(type, name) type name = nullptr;
SLIME_GL_FUNCTIONS(SLIME_GL_DEFINE)
#undef SLIME_GL_DEFINE

void loadGl(GlProcLoader loader) {
#define SLIME_GL_LOAD(type, name)                                                        \
  name = reinterpret_cast<type>(loader(#name));                                          \
  if (name == nullptr) throw std::runtime_error("GL: the context has no " #name);
  SLIME_GL_FUNCTIONS(SLIME_GL_LOAD)
#undef SLIME_GL_LOAD
}

}  // namespace slime

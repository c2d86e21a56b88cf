// Loading the GL entry points of app/viewer/gl.h from the current context; no GL header needed, so
// the window (GLFW, GLX) and the headless back-ends can call it beside their own headers.
#pragma once

namespace slime {

// Where a context's entry points come from: glfwGetProcAddress, eglGetProcAddress, OSMesaGetProcAddress.
using GlProcLoader = void* (*)(const char* name);

// Loads every entry point of gl.h from `loader` (the context must be current). Throws
// std::runtime_error naming the first one the context does not have.
void loadGl(GlProcLoader loader);

}  // namespace slime

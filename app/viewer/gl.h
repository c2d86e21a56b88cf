// The GL 3.3 core API for app/. GLVND's libOpenGL exports every core entry point and dispatches it to
// whichever context is current (GLX from GLFW or EGL headless), so no loader is needed.
#pragma once

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>

// The GL 3.3 core entry points app/ calls, as function pointers loaded from whichever context is
// current: GLFW's (window), EGL's or OSMesa's (headless). Loading them, rather than linking GLVND's
// libOpenGL, is what lets OSMesa live in the same program: libOSMesa exports its own gl* symbols,
// which would collide with libOpenGL's at link time, so it is dlopen'ed and asked for its entry points.
#pragma once

#include "app/viewer/gl_loader.h"

#include <GL/glcorearb.h>

namespace slime {

#define SLIME_GL_FUNCTIONS(X)                                                                               \
  X(PFNGLACTIVETEXTUREPROC, glActiveTexture) X(PFNGLATTACHSHADERPROC, glAttachShader)                       \
  X(PFNGLBINDBUFFERPROC, glBindBuffer) X(PFNGLBINDFRAMEBUFFERPROC, glBindFramebuffer)                       \
  X(PFNGLBINDRENDERBUFFERPROC, glBindRenderbuffer) X(PFNGLBINDTEXTUREPROC, glBindTexture)                   \
  X(PFNGLBINDVERTEXARRAYPROC, glBindVertexArray) X(PFNGLBLENDEQUATIONPROC, glBlendEquation)                 \
  X(PFNGLBLENDFUNCSEPARATEPROC, glBlendFuncSeparate) X(PFNGLBLITFRAMEBUFFERPROC, glBlitFramebuffer)         \
  X(PFNGLBUFFERDATAPROC, glBufferData) X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, glCheckFramebufferStatus)         \
  X(PFNGLCLEARPROC, glClear) X(PFNGLCLEARCOLORPROC, glClearColor) X(PFNGLCOMPILESHADERPROC, glCompileShader) \
  X(PFNGLCREATEPROGRAMPROC, glCreateProgram) X(PFNGLCREATESHADERPROC, glCreateShader)                       \
  X(PFNGLDELETEBUFFERSPROC, glDeleteBuffers) X(PFNGLDELETEFRAMEBUFFERSPROC, glDeleteFramebuffers)           \
  X(PFNGLDELETEPROGRAMPROC, glDeleteProgram) X(PFNGLDELETERENDERBUFFERSPROC, glDeleteRenderbuffers)         \
  X(PFNGLDELETESHADERPROC, glDeleteShader) X(PFNGLDELETETEXTURESPROC, glDeleteTextures)                     \
  X(PFNGLDELETEVERTEXARRAYSPROC, glDeleteVertexArrays) X(PFNGLDISABLEPROC, glDisable)                       \
  X(PFNGLDRAWARRAYSPROC, glDrawArrays) X(PFNGLDRAWELEMENTSPROC, glDrawElements) X(PFNGLENABLEPROC, glEnable) \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, glEnableVertexAttribArray) X(PFNGLFINISHPROC, glFinish)               \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, glFramebufferRenderbuffer)                                            \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, glFramebufferTexture2D) X(PFNGLGENBUFFERSPROC, glGenBuffers)             \
  X(PFNGLGENFRAMEBUFFERSPROC, glGenFramebuffers) X(PFNGLGENRENDERBUFFERSPROC, glGenRenderbuffers)           \
  X(PFNGLGENTEXTURESPROC, glGenTextures) X(PFNGLGENVERTEXARRAYSPROC, glGenVertexArrays)                     \
  X(PFNGLGETATTRIBLOCATIONPROC, glGetAttribLocation) X(PFNGLGETINTEGERVPROC, glGetIntegerv)                 \
  X(PFNGLGETPROGRAMINFOLOGPROC, glGetProgramInfoLog) X(PFNGLGETPROGRAMIVPROC, glGetProgramiv)               \
  X(PFNGLGETSHADERINFOLOGPROC, glGetShaderInfoLog) X(PFNGLGETSHADERIVPROC, glGetShaderiv)                   \
  X(PFNGLGETSTRINGPROC, glGetString) X(PFNGLGETUNIFORMLOCATIONPROC, glGetUniformLocation)                   \
  X(PFNGLISENABLEDPROC, glIsEnabled) X(PFNGLLINKPROGRAMPROC, glLinkProgram)                                 \
  X(PFNGLPIXELSTOREIPROC, glPixelStorei) X(PFNGLREADPIXELSPROC, glReadPixels)                               \
  X(PFNGLRENDERBUFFERSTORAGEPROC, glRenderbufferStorage) X(PFNGLSCISSORPROC, glScissor)                     \
  X(PFNGLSHADERSOURCEPROC, glShaderSource) X(PFNGLTEXIMAGE2DPROC, glTexImage2D)                             \
  X(PFNGLTEXPARAMETERIPROC, glTexParameteri) X(PFNGLTEXSUBIMAGE2DPROC, glTexSubImage2D)                     \
  X(PFNGLUNIFORM1IPROC, glUniform1i) X(PFNGLUNIFORMMATRIX4FVPROC, glUniformMatrix4fv)                       \
  X(PFNGLUSEPROGRAMPROC, glUseProgram) X(PFNGLVERTEXATTRIBPOINTERPROC, glVertexAttribPointer)               \
  X(PFNGLVIEWPORTPROC, glViewport)

#define SLIME_GL_DECLARE(type, name) extern type name;
SLIME_GL_FUNCTIONS(SLIME_GL_DECLARE)
#undef SLIME_GL_DECLARE

}  // namespace slime

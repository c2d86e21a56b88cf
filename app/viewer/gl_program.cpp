#include "app/viewer/gl_program.h"

#include "app/viewer/gl.h"

#include <stdexcept>
#include <string>

namespace slime {
namespace {

unsigned compileShader(GLenum kind, const char* source, const char* what) {
  const unsigned shader = glCreateShader(kind);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[1024] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    throw std::runtime_error(std::string(what) + ": a shader does not compile: " + log);
  }
  return shader;
}

}  // namespace

unsigned linkShaderProgram(const char* vertexSource, const char* fragmentSource, const char* what) {
  const unsigned vertex = compileShader(GL_VERTEX_SHADER, vertexSource, what);
  const unsigned fragment = compileShader(GL_FRAGMENT_SHADER, fragmentSource, what);
  const unsigned program = glCreateProgram();
  glAttachShader(program, vertex);
  glAttachShader(program, fragment);
  glLinkProgram(program);
  glDeleteShader(vertex);
  glDeleteShader(fragment);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[1024] = {};
    glGetProgramInfoLog(program, sizeof log, nullptr, log);
    glDeleteProgram(program);
    throw std::runtime_error(std::string(what) + ": the shader program does not link: " + log);
  }
  return program;
}

}  // namespace slime

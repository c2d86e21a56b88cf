#include "app/viewer/gl_blit.h"

#include "app/viewer/gl.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace slime {
namespace {

// Two triangles that make the viewport's rectangle (six vertices: llvmpipe draws a pair of triangles
// that form an axis-aligned rectangle as one rectangle); texture v runs downwards because the image's
// top row is first.
constexpr const char* kVertexShader = R"(#version 330 core
out vec2 uv;
const vec2 kCorners[6] = vec2[6](vec2(0.0, 0.0), vec2(1.0, 0.0), vec2(0.0, 1.0),
                                 vec2(0.0, 1.0), vec2(1.0, 0.0), vec2(1.0, 1.0));
void main() {
  vec2 corner = kCorners[gl_VertexID];
  uv = vec2(corner.x, 1.0 - corner.y);
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
)";
constexpr int kRectangleVertices = 6;

// The texture holds sRGB bytes already; the default framebuffer stores what it is given.
constexpr const char* kFragmentShader = R"(#version 330 core
in vec2 uv;
out vec4 color;
uniform sampler2D image;
void main() { color = vec4(texture(image, uv).rgb, 1.0); }
)";

unsigned compileShader(GLenum kind, const char* source) {
  const unsigned shader = glCreateShader(kind);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[1024] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    throw std::runtime_error(std::string("image blit shader: ") + log);
  }
  return shader;
}

}  // namespace

GlBlit::GlBlit() {
  const unsigned vertex = compileShader(GL_VERTEX_SHADER, kVertexShader);
  const unsigned fragment = compileShader(GL_FRAGMENT_SHADER, kFragmentShader);
  program_ = glCreateProgram();
  glAttachShader(program_, vertex);
  glAttachShader(program_, fragment);
  glLinkProgram(program_);
  glDeleteShader(vertex);
  glDeleteShader(fragment);
  GLint ok = 0;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (!ok) throw std::runtime_error("image blit shader: link failed");
  glGenVertexArrays(1, &vertexArray_);  // core profile draws need a bound vertex array, even an empty one
  glGenTextures(1, &texture_);
  glBindTexture(GL_TEXTURE_2D, texture_);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

GlBlit::~GlBlit() {
  glDeleteTextures(1, &texture_);
  glDeleteVertexArrays(1, &vertexArray_);
  glDeleteProgram(program_);
}

void GlBlit::upload(const std::vector<std::uint8_t>& rgba, int width, int height) {
  if (width <= 0 || height <= 0 || rgba.size() < 4 * static_cast<std::size_t>(width) * height) return;
  glBindTexture(GL_TEXTURE_2D, texture_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);  // 4 bytes a pixel: rows are always 4-byte aligned
  if (textureSize_ != glm::ivec2(width, height)) {
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    textureSize_ = {width, height};
  } else {
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  }
}

void GlBlit::draw(glm::ivec2 framebufferSize, int left) const {
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  // Nothing traced yet, or a strip left of the image (under the panel column): background.
  if (textureSize_.x == 0 || left > 0) {
    glViewport(0, 0, framebufferSize.x, framebufferSize.y);
    glClearColor(kViewerBackground[0], kViewerBackground[1], kViewerBackground[2], kViewerBackground[3]);
    glClear(GL_COLOR_BUFFER_BIT);
    if (textureSize_.x == 0) return;
  }
  const glm::ivec2 viewportSize{std::max(1, framebufferSize.x - left), framebufferSize.y};
  glViewport(left, 0, viewportSize.x, viewportSize.y);
  glUseProgram(program_);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, texture_);
  // Texel for pixel when the sizes agree (software GL then takes its fast path), else bilinear.
  const GLint filter = textureSize_ == viewportSize ? GL_NEAREST : GL_LINEAR;
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
  glUniform1i(glGetUniformLocation(program_, "image"), 0);
  glBindVertexArray(vertexArray_);
  glDrawArrays(GL_TRIANGLES, 0, kRectangleVertices);
  glBindVertexArray(0);
  glUseProgram(0);
}

}  // namespace slime

#include "app/viewer/gl_blit.h"

#include "app/viewer/gl.h"
#include "app/viewer/gl_program.h"

#include <algorithm>
#include <cmath>

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


}  // namespace

GlBlit::GlBlit() {
  program_ = linkShaderProgram(kVertexShader, kFragmentShader, "image blit");
  glUseProgram(program_);
  glUniform1i(glGetUniformLocation(program_, "image"), 0);  // the sampler reads texture unit 0
  glUseProgram(0);
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

PixelRect GlBlit::upload(const std::vector<std::uint8_t>& rgba, int width, int height, PixelRect changed) {
  if (width <= 0 || height <= 0 || rgba.size() < 4 * static_cast<std::size_t>(width) * height) return {};
  glBindTexture(GL_TEXTURE_2D, texture_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);  // 4 bytes a pixel: rows are always 4-byte aligned
  if (textureSize_ != glm::ivec2(width, height)) {
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    textureSize_ = {width, height};
    return {0, 0, width, height};
  }
  const PixelRect part = changed.intersectedWith({0, 0, width, height});
  if (part.empty()) return {};
  // The texture's rows are the image's, top row first, as glTexImage2D took them.
  glPixelStorei(GL_UNPACK_ROW_LENGTH, width);
  glTexSubImage2D(GL_TEXTURE_2D, 0, part.x0, part.y0, part.x1 - part.x0, part.y1 - part.y0, GL_RGBA, GL_UNSIGNED_BYTE,
                  rgba.data() + 4 * (static_cast<std::size_t>(part.y0) * width + part.x0));
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  return part;
}

PixelRect GlBlit::framebufferPixels(PixelRect changed, glm::ivec2 framebufferSize, int left) const {
  const PixelRect viewport{left, 0, framebufferSize.x, framebufferSize.y};
  if (changed.empty() || textureSize_.x <= 0 || textureSize_.y <= 0) return {};
  const int width = std::max(1, framebufferSize.x - left);
  if (textureSize_ == glm::ivec2(width, framebufferSize.y))
    return PixelRect{left + changed.x0, changed.y0, left + changed.x1, changed.y1}.intersectedWith(viewport);
  // Stretched: a framebuffer pixel samples between the two texels nearest its centre, so a texel
  // reaches less than a texel's width beyond its own span; one more on each side covers it.
  const double scaleX = static_cast<double>(width) / textureSize_.x;
  const double scaleY = static_cast<double>(framebufferSize.y) / textureSize_.y;
  const PixelRect reached{left + static_cast<int>(std::floor((changed.x0 - 1) * scaleX)),
                          static_cast<int>(std::floor((changed.y0 - 1) * scaleY)),
                          left + static_cast<int>(std::ceil((changed.x1 + 1) * scaleX)),
                          static_cast<int>(std::ceil((changed.y1 + 1) * scaleY))};
  return reached.intersectedWith(viewport);
}

void GlBlit::draw(glm::ivec2 framebufferSize, int left, PixelRect rect) const {
  rect = rect.intersectedWith({0, 0, framebufferSize.x, framebufferSize.y});
  if (rect.empty()) return;
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  glEnable(GL_SCISSOR_TEST);
  const auto scissor = [&](const PixelRect& pixels) {  // GL's rows run upwards
    glScissor(pixels.x0, framebufferSize.y - pixels.y1, pixels.x1 - pixels.x0, pixels.y1 - pixels.y0);
  };
  // Nothing traced yet, or the strip left of the image (under the panel column): background.
  const PixelRect background = textureSize_.x == 0 ? rect : rect.intersectedWith({0, 0, left, framebufferSize.y});
  if (!background.empty()) {
    scissor(background);
    glClearColor(kViewerBackground[0], kViewerBackground[1], kViewerBackground[2], kViewerBackground[3]);
    glClear(GL_COLOR_BUFFER_BIT);
  }
  const PixelRect image = rect.intersectedWith({left, 0, framebufferSize.x, framebufferSize.y});
  if (textureSize_.x > 0 && !image.empty()) {
    const glm::ivec2 viewportSize{std::max(1, framebufferSize.x - left), framebufferSize.y};
    glViewport(left, 0, viewportSize.x, viewportSize.y);
    scissor(image);
    glUseProgram(program_);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, texture_);
    // Texel for pixel when the sizes agree (software GL then takes its fast path), else bilinear.
    const GLint filter = textureSize_ == viewportSize ? GL_NEAREST : GL_LINEAR;
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
    glBindVertexArray(vertexArray_);
    glDrawArrays(GL_TRIANGLES, 0, kRectangleVertices);
    glBindVertexArray(0);
    glUseProgram(0);
  }
  glDisable(GL_SCISSOR_TEST);
  glViewport(0, 0, framebufferSize.x, framebufferSize.y);
}

}  // namespace slime

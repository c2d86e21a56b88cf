#include "app/viewer/panel_layer.h"

#include "app/viewer/gl.h"
#include "app/viewer/gl_blit.h"

#include <imgui.h>
#include <backends/imgui_impl_opengl3.h>

#include <algorithm>

namespace slime {
namespace {

// Lists [first, first + count) of `data` as draw data of their own, placed as `data` is.
ImDrawData subset(const ImDrawData& data, int first, int count) {
  ImDrawData part = data;
  part.CmdLists = data.CmdLists + first;
  part.CmdListsCount = count;
  part.TotalVtxCount = part.TotalIdxCount = 0;
  for (int i = 0; i < count; ++i) {
    part.TotalVtxCount += part.CmdLists[i]->VtxBuffer.Size;
    part.TotalIdxCount += part.CmdLists[i]->IdxBuffer.Size;
  }
  return part;
}

// The bytes of `count` values at `values`, after those already in `bytes`.
template <typename T>
void append(std::vector<std::uint8_t>& bytes, const T* values, std::size_t count = 1) {
  const auto* begin = reinterpret_cast<const std::uint8_t*>(values);
  bytes.insert(bytes.end(), begin, begin + sizeof(T) * count);
}
template <typename T>
void append(std::vector<std::uint8_t>& bytes, const ImVector<T>& values) {
  append(bytes, values.Data, static_cast<std::size_t>(values.Size));
}

}  // namespace

PanelLayer::PanelLayer() {
  glGenFramebuffers(1, &framebuffer_);
  glGenTextures(1, &texture_);
}

PanelLayer::~PanelLayer() {
  glDeleteTextures(1, &texture_);
  glDeleteFramebuffers(1, &framebuffer_);
}

// How many lists from the first draw only in the column: each command's pixels lie left of both its
// clip rectangle's right edge and the list's rightmost vertex (a window's frame is clipped to the
// whole display, its contents to the window), in framebuffer pixels as the GL back-end places them;
// a pixel is drawn when its centre is covered, so an edge at the column's right edge draws nothing
// right of it. A user callback ends the column (what it draws is unknown).
int PanelLayer::columnLists(const ImDrawData& data, glm::ivec2 framebufferSize, int columnPixels) const {
  if (columnPixels <= 0 || columnPixels > framebufferSize.x) return 0;
  const float edge = static_cast<float>(columnPixels);
  const auto toPixels = [&](float x) { return (x - data.DisplayPos.x) * data.FramebufferScale.x; };
  int lists = 0;
  for (; lists < data.CmdListsCount; ++lists) {
    const ImDrawList& list = *data.CmdLists[lists];
    float rightmost = -1e30f;
    for (const ImDrawVert& vertex : list.VtxBuffer) rightmost = std::max(rightmost, vertex.pos.x);
    const bool inColumn = std::all_of(list.CmdBuffer.begin(), list.CmdBuffer.end(), [&](const ImDrawCmd& command) {
      return command.UserCallback == nullptr && std::min(toPixels(command.ClipRect.z), toPixels(rightmost)) <= edge;
    });
    if (!inColumn) break;
  }
  return lists;
}

// Draws the column's lists into the texture over the background, as they would be drawn in the
// framebuffer: the same viewport (the whole framebuffer's; the texture is its left part) and scissors.
void PanelLayer::drawColumn(const ImDrawData& data, int lists, glm::ivec2 framebufferSize, int columnPixels) {
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer_);
  if (kept_.columnPixels != columnPixels || kept_.framebufferSize.y != framebufferSize.y) {  // a new size
    glBindTexture(GL_TEXTURE_2D, texture_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, columnPixels, framebufferSize.y, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture_, 0);
  }
  glDisable(GL_SCISSOR_TEST);
  glClearColor(kViewerBackground[0], kViewerBackground[1], kViewerBackground[2], kViewerBackground[3]);
  glClear(GL_COLOR_BUFFER_BIT);
  ImDrawData column = subset(data, 0, lists);
  ImGui_ImplOpenGL3_RenderDrawData(&column);
}

void PanelLayer::draw(const ImDrawData& data, glm::ivec2 framebufferSize, int columnPixels) {
  const int lists = columnLists(data, framebufferSize, columnPixels);
  if (lists > 0) {
    // What the column's lists would draw: their vertices, indices and commands (clip rectangles,
    // texture, offsets), and where.
    current_.clear();
    for (int i = 0; i < lists; ++i) {
      append(current_, data.CmdLists[i]->VtxBuffer);
      append(current_, data.CmdLists[i]->IdxBuffer);
      append(current_, data.CmdLists[i]->CmdBuffer);
    }
    append(current_, &data.DisplayPos);
    append(current_, &data.DisplaySize);
    append(current_, &data.FramebufferScale);

    GLint target = 0, source = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &source);
    const GLboolean scissor = glIsEnabled(GL_SCISSOR_TEST);
    const bool same = kept_.framebufferSize == framebufferSize && kept_.columnPixels == columnPixels &&
                      kept_.bytes == current_;
    if (same) {
      ++columnCopies_;
    } else {
      drawColumn(data, lists, framebufferSize, columnPixels);
      kept_.bytes.swap(current_);
      kept_.framebufferSize = framebufferSize;
      kept_.columnPixels = columnPixels;
      ++columnDraws_;
    }
    // The kept column, texel for pixel (a copy: no scissor, no blending).
    glDisable(GL_SCISSOR_TEST);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(target));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
    glBlitFramebuffer(0, 0, columnPixels, framebufferSize.y, 0, 0, columnPixels, framebufferSize.y, GL_COLOR_BUFFER_BIT,
                      GL_NEAREST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(source));
    if (scissor) glEnable(GL_SCISSOR_TEST);
  }
  if (lists < data.CmdListsCount) {
    ImDrawData rest = subset(data, lists, data.CmdListsCount - lists);
    ImGui_ImplOpenGL3_RenderDrawData(&rest);
  }
}

}  // namespace slime

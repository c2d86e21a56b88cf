#include "app/viewer/panel_layer.h"

#include "app/viewer/gl.h"
#include "app/viewer/imgui_gl.h"
#include "app/viewer/gl_blit.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>

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
void PanelLayer::drawColumnLists(const ImDrawData& data, glm::ivec2 framebufferSize, int columnPixels) {
  GLint target = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer_);
  if (kept_.columnPixels != columnPixels || kept_.framebufferSize.y != framebufferSize.y) {  // a new size
    glBindTexture(GL_TEXTURE_2D, texture_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, columnPixels, framebufferSize.y, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture_, 0);
  }
  glDisable(GL_SCISSOR_TEST);
  glClearColor(kViewerBackground[0], kViewerBackground[1], kViewerBackground[2], kViewerBackground[3]);
  glClear(GL_COLOR_BUFFER_BIT);
  ImDrawData column = subset(data, 0, lists_);
  renderImGuiGl(column);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(target));
}

bool PanelLayer::prepare(const ImDrawData& data, glm::ivec2 framebufferSize, int columnPixels) {
  const int lastLists = lists_;
  lists_ = columnLists(data, framebufferSize, columnPixels);
  if (lists_ == 0) return lastLists > 0;  // what the texture showed is now drawn as overlays, or gone
  // What the column's lists would draw: their vertices, indices and commands (clip rectangles,
  // texture, offsets), and where.
  current_.clear();
  for (int i = 0; i < lists_; ++i) {
    append(current_, data.CmdLists[i]->VtxBuffer);
    append(current_, data.CmdLists[i]->IdxBuffer);
    append(current_, data.CmdLists[i]->CmdBuffer);
  }
  append(current_, &data.DisplayPos);
  append(current_, &data.DisplaySize);
  append(current_, &data.FramebufferScale);
  if (kept_.framebufferSize == framebufferSize && kept_.columnPixels == columnPixels && kept_.bytes == current_) {
    ++columnKeeps_;
    return false;
  }
  drawColumnLists(data, framebufferSize, columnPixels);
  kept_.bytes.swap(current_);
  kept_.framebufferSize = framebufferSize;
  kept_.columnPixels = columnPixels;
  ++columnDraws_;
  return true;
}

void PanelLayer::overlayBounds(const ImDrawData& data, glm::ivec2 framebufferSize, std::vector<PixelRect>& bounds) const {
  // Each command's triangles' box within its clip rectangle, in whole pixels and a pixel wider each
  // way (a pixel is drawn when its centre is covered; anti-aliased edges are vertices too); a list's
  // rectangle holds its commands'.
  const auto toPixelsX = [&](float x) { return (x - data.DisplayPos.x) * data.FramebufferScale.x; };
  const auto toPixelsY = [&](float y) { return (y - data.DisplayPos.y) * data.FramebufferScale.y; };
  const auto outwards = [](float pixels, bool low) {  // within the int range, a pixel further out
    return static_cast<int>(std::clamp(low ? std::floor(pixels) - 1.0f : std::ceil(pixels) + 1.0f, -1e9f, 1e9f));
  };
  const PixelRect framebuffer{0, 0, framebufferSize.x, framebufferSize.y};
  bounds.clear();
  for (int i = lists_; i < data.CmdListsCount; ++i) {
    const ImDrawList& list = *data.CmdLists[i];
    PixelRect drawn;
    for (const ImDrawCmd& command : list.CmdBuffer) {
      if (command.UserCallback != nullptr) {  // what a callback draws is unknown: all of it
        drawn = framebuffer;
        break;
      }
      ImVec2 low(1e30f, 1e30f), high(-1e30f, -1e30f);
      for (unsigned k = command.IdxOffset; k < command.IdxOffset + command.ElemCount; ++k) {
        const ImVec2 position = list.VtxBuffer[static_cast<int>(command.VtxOffset + list.IdxBuffer[static_cast<int>(k)])].pos;
        low = ImVec2(std::min(low.x, position.x), std::min(low.y, position.y));
        high = ImVec2(std::max(high.x, position.x), std::max(high.y, position.y));
      }
      const ImVec4& clip = command.ClipRect;
      if (!(high.x >= low.x)) continue;  // no triangles
      const PixelRect part{outwards(toPixelsX(std::max(low.x, clip.x)), true), outwards(toPixelsY(std::max(low.y, clip.y)), true),
                           outwards(toPixelsX(std::min(high.x, clip.z)), false), outwards(toPixelsY(std::min(high.y, clip.w)), false)};
      drawn = drawn.unitedWith(part);
    }
    const PixelRect inside = drawn.intersectedWith(framebuffer);
    if (!inside.empty()) bounds.push_back(inside);
  }
}

void PanelLayer::drawColumn(PixelRect rect, glm::ivec2 framebufferSize) const {
  if (lists_ == 0) return;
  const PixelRect part = rect.intersectedWith({0, 0, kept_.columnPixels, framebufferSize.y});
  if (part.empty()) return;
  // The kept column, texel for pixel (a copy: no scissor, no blending); GL's rows run upwards.
  GLint target = 0, source = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &source);
  const GLboolean scissor = glIsEnabled(GL_SCISSOR_TEST);
  glDisable(GL_SCISSOR_TEST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
  const int bottom = framebufferSize.y - part.y1, top = framebufferSize.y - part.y0;
  glBlitFramebuffer(part.x0, bottom, part.x1, top, part.x0, bottom, part.x1, top, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(source));
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(target));
  if (scissor) glEnable(GL_SCISSOR_TEST);
}

void PanelLayer::drawOverlays(const ImDrawData& data, PixelRect rect, glm::ivec2 framebufferSize) {
  if (lists_ >= data.CmdListsCount || rect.empty()) return;
  // Each command's clip rectangle narrowed to `rect` (the lists' own are put back before it returns).
  // The GL back-end scissors a command to the whole pixels [int(x0), int(x0) + int(x1 − x0)) of its
  // clip rectangle, the rows likewise counted from the bottom: the narrowed one's edges are placed a
  // quarter or half a pixel off whole pixels so that, whatever the rounding, it gives exactly the
  // command's pixels within `rect`.
  const ImVec2 scale = data.FramebufferScale;
  const auto pixelsOf = [&](const ImVec4& clip) {  // the back-end's scissor, in framebuffer pixels
    const float x0 = (clip.x - data.DisplayPos.x) * scale.x, y0 = (clip.y - data.DisplayPos.y) * scale.y;
    const float x1 = (clip.z - data.DisplayPos.x) * scale.x, y1 = (clip.w - data.DisplayPos.y) * scale.y;
    if (!(x1 > x0 && y1 > y0)) return PixelRect{};
    const int left = static_cast<int>(std::clamp(x0, -1e9f, 1e9f)), bottomUp = static_cast<int>(std::clamp(framebufferSize.y - y1, -1e9f, 1e9f));
    const int width = static_cast<int>(std::clamp(x1 - x0, 0.0f, 2e9f)), height = static_cast<int>(std::clamp(y1 - y0, 0.0f, 2e9f));
    return PixelRect{left, framebufferSize.y - (bottomUp + height), left + width, framebufferSize.y - bottomUp};
  };
  const auto toDisplay = [&](const PixelRect& pixels) {
    return ImVec4((static_cast<float>(pixels.x0) + 0.25f) / scale.x + data.DisplayPos.x,
                  (static_cast<float>(pixels.y0) - 0.5f) / scale.y + data.DisplayPos.y,
                  (static_cast<float>(pixels.x1) + 0.5f) / scale.x + data.DisplayPos.x,
                  (static_cast<float>(pixels.y1) - 0.25f) / scale.y + data.DisplayPos.y);
  };
  clipRects_.clear();
  for (int i = lists_; i < data.CmdListsCount; ++i)
    for (ImDrawCmd& command : data.CmdLists[i]->CmdBuffer) {
      clipRects_.push_back(command.ClipRect);
      const PixelRect narrowed = pixelsOf(command.ClipRect).intersectedWith(rect);
      command.ClipRect = narrowed.empty() ? ImVec4(0.0f, 0.0f, 0.0f, 0.0f) : toDisplay(narrowed);
    }
  ImDrawData rest = subset(data, lists_, data.CmdListsCount - lists_);
  renderImGuiGl(rest);
  auto own = clipRects_.begin();
  for (int i = lists_; i < data.CmdListsCount; ++i)
    for (ImDrawCmd& command : data.CmdLists[i]->CmdBuffer) command.ClipRect = *own++;
}

}  // namespace slime

// Dear ImGui's frame in two parts: the panel column, kept from frame to frame, and the lists drawn
// over the image. Under software GL (llvmpipe) drawing the column's widgets and text costs about as
// much as drawing the whole traced image (~1.5 ms of a core at 1280×720, 2026-11-24), yet while a
// person drags the slime the column does not change. The draw lists that lie wholly in the column
// (their clip rectangles end at its right edge) and come first in ImGui's order are drawn into a
// texture of their own only when their vertices, indices or commands differ from the last ones
// drawn there; the other lists (the Stats window, popups, the grab marks over the image) are drawn
// live, each time within a rectangle (app/viewer/frame_compositor.h draws only what changed). The
// pixels are those of drawing every list live: the column is drawn over the same background colour
// the image blit clears it to, with the same viewport, projection and scissor rectangles.
#pragma once

#include "render/image/image.h"  // PixelRect

#include <glm/vec2.hpp>

#include <cstdint>
#include <vector>

struct ImDrawData;
struct ImVec4;

namespace slime {

class PanelLayer {
 public:
  PanelLayer();  // needs a current GL 3.3 core context
  ~PanelLayer();
  PanelLayer(const PanelLayer&) = delete;
  PanelLayer& operator=(const PanelLayer&) = delete;

  // Takes this frame's `data` for a framebuffer of `framebufferSize` pixels whose left `columnPixels`
  // columns are the panel column: finds the column's lists and draws them into the texture if they
  // changed. True when it drew them (the column's pixels are new).
  bool prepare(const ImDrawData& data, glm::ivec2 framebufferSize, int columnPixels);

  // Into `bounds` (emptied first): the framebuffer pixels the lists over the image (those after the
  // column's) may touch this frame, one rectangle a list, clipped to the framebuffer.
  void overlayBounds(const ImDrawData& data, glm::ivec2 framebufferSize, std::vector<PixelRect>& bounds) const;

  // Into the bound draw framebuffer, within `rect` only (framebuffer pixels, top row 0): the kept
  // column's pixels (nothing when it has no lists), then the lists over the image. `rect` must lie
  // over pixels already drawn below them (the background and the image, GlBlit::draw).
  void drawColumn(PixelRect rect, glm::ivec2 framebufferSize) const;
  void drawOverlays(const ImDrawData& data, PixelRect rect, glm::ivec2 framebufferSize);

  // How many frames drew the column afresh, and how many kept the texture as it was.
  long long columnDraws() const { return columnDraws_; }
  long long columnKeeps() const { return columnKeeps_; }

 private:
  // The bytes of the column's lists as last drawn into the texture (with what placed them), and the
  // sizes it was drawn for: the texture is columnPixels × framebufferSize.y.
  struct Kept {
    std::vector<std::uint8_t> bytes;
    glm::ivec2 framebufferSize{0, 0};
    int columnPixels = 0;
  };

  int columnLists(const ImDrawData& data, glm::ivec2 framebufferSize, int columnPixels) const;
  void drawColumnLists(const ImDrawData& data, glm::ivec2 framebufferSize, int columnPixels);

  unsigned framebuffer_ = 0;
  unsigned texture_ = 0;
  Kept kept_;
  int lists_ = 0;  // this frame's column lists (the first ones of its draw data)
  std::vector<std::uint8_t> current_;
  std::vector<ImVec4> clipRects_;  // the overlays' own clip rectangles, kept while drawOverlays narrows them
  long long columnDraws_ = 0;
  long long columnKeeps_ = 0;
};

}  // namespace slime

// The viewer's picture, composed in the framebuffer: the traced image right of the panel column, the
// column (PanelLayer's kept texture), the lists over the image (the Stats window, popups, the grab
// marks). Where the framebuffer keeps its pixels from frame to frame (an FBO; a window presented by
// copying rectangles, app/viewer/window.h), a frame draws again only what changed since the last:
// the image's new pixels (the renderer says which, RenderStats::bytesWritten), the column when its
// lists changed, and where the lists over the image lie now and lay before. While a person drags the
// slime that is its footprint and the small windows, not the whole window: under software GL the
// whole image costs ~1.6 ms a frame to draw at 947×720, and the window's copy to the X server as
// much again (2026-11-24). Each pixel is drawn as drawing everything would draw it.
#pragma once

#include "app/viewer/gl_blit.h"
#include "app/viewer/panel_layer.h"
#include "render/image/image.h"

#include <glm/vec2.hpp>

#include <cstdint>
#include <vector>

struct ImDrawData;

namespace slime {

// Adds `rect` to disjoint rectangles, merging it with every one it overlaps into their bounding box
// until none overlap: each pixel then lies in at most one, so what is blended there is blended once.
void addDisjoint(std::vector<PixelRect>& rects, PixelRect rect);

class FrameCompositor {
 public:
  // Copies the image's pixels `changed` (image pixels; all of them when the size is new) to the GL
  // texture; what it copied is drawn again by the next draw().
  void upload(const std::vector<std::uint8_t>& rgba, int width, int height, PixelRect changed);

  // Draws the frame into the bound framebuffer of `framebufferSize` pixels, the column `columnPixels`
  // wide: all of it when `whole` (or on the first frame, or when the sizes changed), else what
  // changed since the last draw. Returns the rectangles drawn (framebuffer pixels, top row 0): what a
  // window must show again (valid until the next draw).
  const std::vector<PixelRect>& draw(const ImDrawData& data, glm::ivec2 framebufferSize, int columnPixels, bool whole);

  const PanelLayer& panels() const { return panels_; }
  long long pixelsDrawn() const { return pixelsDrawn_; }  // over every draw(), for the tests and reports

 private:
  GlBlit blit_;
  PanelLayer panels_;
  PixelRect imageChanged_;                // image pixels uploaded since the last draw
  std::vector<PixelRect> overlays_;       // where the lists over the image lie in this frame
  std::vector<PixelRect> lastOverlays_;   // ... and lay in the last
  std::vector<PixelRect> rects_;          // what this frame drew (kept: a steady frame allocates nothing)
  glm::ivec2 lastFramebuffer_{0, 0};
  int lastColumn_ = -1;
  long long pixelsDrawn_ = 0;
};

}  // namespace slime

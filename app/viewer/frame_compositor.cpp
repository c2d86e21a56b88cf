#include "app/viewer/frame_compositor.h"

#include <imgui.h>

namespace slime {

void addDisjoint(std::vector<PixelRect>& rects, PixelRect rect) {
  if (rect.empty()) return;
  for (bool merged = true; merged;) {
    merged = false;
    for (auto it = rects.begin(); it != rects.end(); ++it) {
      if (it->intersectedWith(rect).empty()) continue;
      rect = rect.unitedWith(*it);
      rects.erase(it);
      merged = true;
      break;
    }
  }
  rects.push_back(rect);
}

void FrameCompositor::upload(const std::vector<std::uint8_t>& rgba, int width, int height, PixelRect changed) {
  imageChanged_ = imageChanged_.unitedWith(blit_.upload(rgba, width, height, changed));
}

const std::vector<PixelRect>& FrameCompositor::draw(const ImDrawData& data, glm::ivec2 framebufferSize, int columnPixels,
                                                    bool whole) {
  const bool columnChanged = panels_.prepare(data, framebufferSize, columnPixels);
  panels_.overlayBounds(data, framebufferSize, overlays_);
  const PixelRect framebuffer{0, 0, framebufferSize.x, framebufferSize.y};
  whole = whole || framebufferSize != lastFramebuffer_ || columnPixels != lastColumn_;
  rects_.clear();
  if (whole) {
    addDisjoint(rects_, framebuffer);
  } else {
    addDisjoint(rects_, blit_.framebufferPixels(imageChanged_, framebufferSize, columnPixels));
    if (columnChanged) addDisjoint(rects_, {0, 0, columnPixels, framebufferSize.y});
    for (const PixelRect& overlay : overlays_) addDisjoint(rects_, overlay);
    for (const PixelRect& overlay : lastOverlays_) addDisjoint(rects_, overlay.intersectedWith(framebuffer));
  }
  for (const PixelRect& rect : rects_) {
    blit_.draw(framebufferSize, columnPixels, rect);
    panels_.drawColumn(rect, framebufferSize);
    panels_.drawOverlays(data, rect, framebufferSize);
    pixelsDrawn_ += static_cast<long long>(rect.x1 - rect.x0) * (rect.y1 - rect.y0);
  }
  imageChanged_ = {};
  lastOverlays_.swap(overlays_);
  lastFramebuffer_ = framebufferSize;
  lastColumn_ = columnPixels;
  return rects_;
}

}  // namespace slime

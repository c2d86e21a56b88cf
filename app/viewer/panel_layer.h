// Draws Dear ImGui's frame with the panel column kept from frame to frame. Under software GL
// (llvmpipe) drawing the column's widgets and text costs about as much as drawing the whole traced
// image (~1.5 ms of a core at 1280×720, 2026-11-24), yet while a person drags the slime the column
// does not change. The draw lists that lie wholly in the column (their clip rectangles end at its
// right edge) and come first in ImGui's order are drawn into a texture of their own only when their
// vertices, indices or commands differ from the last ones drawn there; every frame that texture is
// copied into the column and the other lists (the Stats window, popups, the grab marks over the
// image) are drawn live over it. The pixels are those of drawing every list live: the column is
// drawn over the same background colour the image blit clears it to, with the same viewport,
// projection and scissor rectangles.
#pragma once

#include <glm/vec2.hpp>

#include <cstdint>
#include <vector>

struct ImDrawData;

namespace slime {

class PanelLayer {
 public:
  PanelLayer();  // needs a current GL 3.3 core context
  ~PanelLayer();
  PanelLayer(const PanelLayer&) = delete;
  PanelLayer& operator=(const PanelLayer&) = delete;

  // Draws `data` into the bound draw framebuffer of `framebufferSize` pixels whose left
  // `columnPixels` columns are the panel column, already cleared to the background (GlBlit::draw).
  void draw(const ImDrawData& data, glm::ivec2 framebufferSize, int columnPixels);

  // How many frames drew the column afresh, and how many copied the kept one.
  long long columnDraws() const { return columnDraws_; }
  long long columnCopies() const { return columnCopies_; }

 private:
  // The bytes of the column's lists as last drawn into the texture (with what placed them), and the
  // sizes it was drawn for: the texture is columnPixels × framebufferSize.y.
  struct Kept {
    std::vector<std::uint8_t> bytes;
    glm::ivec2 framebufferSize{0, 0};
    int columnPixels = 0;
  };

  int columnLists(const ImDrawData& data, glm::ivec2 framebufferSize, int columnPixels) const;
  void drawColumn(const ImDrawData& data, int lists, glm::ivec2 framebufferSize, int columnPixels);

  unsigned framebuffer_ = 0;
  unsigned texture_ = 0;
  Kept kept_;
  std::vector<std::uint8_t> current_;
  long long columnDraws_ = 0, columnCopies_ = 0;
};

}  // namespace slime

// Checkerboard tracing inside the slime's footprint while things move (issue 28): a frame traces
// the pixels of one colour of a checkerboard, (x + y + parity) even, and fills each pixel of the
// other colour from its four neighbours, all of which were traced (or lie outside the footprint,
// where every pixel is exact). Where the neighbours disagree — an edge of the slime, of its shadow,
// of a plank or a highlight seen through it — the pixel is traced as well, so what is filled in is a
// smooth stretch, where a neighbour's average is close to the pixel's own ray. The parity alternates
// frame by frame. Real-time ray tracers use the same scheme ("checkerboard rendering") with temporal
// reprojection as well; here it is spatial only, so a frame depends on nothing but this frame's rays.
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>

namespace slime {

// Above this range of the neighbours' values (per channel, in √linear, close to sRGB's scale: 0.12
// ≈ 30 of 255 levels), the pixel between them is traced rather than filled in. Issue 28: 0.06 traced
// 11,300 skipped pixels of a held 1280×720 frame after all (more than the tiles' own 8,000), 0.12
// traces 7,200 for the same --check-every PSNR while handled (41.3 dB mean either way: the caustic
// map's noise, not the fill, sets it); 0.2 would trace 3,800 at 40.1 dB.
constexpr float kCheckerboardContrast = 0.12f;

inline bool checkerboardTraced(int x, int y, int parity) { return ((x + y + parity) & 1) == 0; }

// The quarter checkerboard (render.checkerboardQuarter): of the traced colour only the rows with
// (y + phase) even are traced; the traced colour's pixels of the other rows have all four diagonal
// neighbours traced (x ± 1, y ± 1: the same colour, the traced rows) and are filled from them first;
// then the other colour is filled from its four neighbours beside it, as with the half checkerboard.
// A quarter of the footprint's pixels traced, and every fill reads only finished pixels.
// The sixteenth (render.checkerboardSixteenth, issue 28): the same one level further. Of each 4 × 4
// block only the pixel at (ox, oy) modulo 4 is traced; the quarter's lattice (both offsets from it
// even) is filled first, from neighbours two pixels away: the block's centre (2, 2) from its four
// diagonal ones (all traced), then (2, 0) and (0, 2) from the four beside them (traced, or filled
// just before); then the quarter's two passes at one pixel, as above. Each pass still reads only
// pixels finished before it. The fills are passes in this order; the enum's value marks a skipped pixel.
enum class CheckerboardPass : std::uint8_t { Traced = 0, FromBeside = 1, FromDiagonals = 2, FromBesideWide = 3, FromDiagonalsWide = 4 };

inline CheckerboardPass checkerboardPass(int x, int y, int parity, bool quarter, int phase) {
  if (!checkerboardTraced(x, y, parity)) return CheckerboardPass::FromBeside;
  return quarter && ((y + phase) & 1) != 0 ? CheckerboardPass::FromDiagonals : CheckerboardPass::Traced;
}

// The sixteenth's pass of pixel (x, y) with the traced pixel of each block at (ox, oy) modulo 4.
inline CheckerboardPass checkerboardSixteenthPass(int x, int y, int ox, int oy) {
  const int dx = (x - ox) & 3, dy = (y - oy) & 3;
  if (((dx | dy) & 1) != 0)  // off the quarter's lattice: its own two passes
    return (dx & dy & 1) != 0 ? CheckerboardPass::FromDiagonals : CheckerboardPass::FromBeside;
  if (dx == 0 && dy == 0) return CheckerboardPass::Traced;
  return dx == 2 && dy == 2 ? CheckerboardPass::FromDiagonalsWide : CheckerboardPass::FromBesideWide;
}

// The distance of a pass's neighbours, in pixels.
inline int checkerboardStep(CheckerboardPass pass) {
  return pass == CheckerboardPass::FromBesideWide || pass == CheckerboardPass::FromDiagonalsWide ? 2 : 1;
}

// neighbours: left, right, up, down (or, for the quarter's diagonal pass, up-left, down-right,
// up-right, down-left: two opposite pairs alike); null where outside the image. Returns false when they disagree
// by more than `contrast` (the pixel must be traced); else `color` is their average along the
// direction they vary least (left–right or up–down; all four when alike), i.e. edge-directed.
bool fillFromNeighbours(const glm::vec3* const neighbours[4], glm::vec3& color,
                        float contrast = kCheckerboardContrast);

}  // namespace slime

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

// Above this range of the neighbours' values (per channel, in √linear, close to sRGB's scale: 0.06
// ≈ 15 of 255 levels), the pixel between them is traced rather than filled in.
constexpr float kCheckerboardContrast = 0.06f;

inline bool checkerboardTraced(int x, int y, int parity) { return ((x + y + parity) & 1) == 0; }

// The quarter checkerboard (render.checkerboardQuarter): of the traced colour only the rows with
// (y + phase) even are traced; the traced colour's pixels of the other rows have all four diagonal
// neighbours traced (x ± 1, y ± 1: the same colour, the traced rows) and are filled from them first;
// then the other colour is filled from its four neighbours beside it, as with the half checkerboard.
// A quarter of the footprint's pixels traced, and every fill reads only finished pixels.
enum class CheckerboardPass : std::uint8_t { Traced = 0, FromBeside = 1, FromDiagonals = 2 };

inline CheckerboardPass checkerboardPass(int x, int y, int parity, bool quarter, int phase) {
  if (!checkerboardTraced(x, y, parity)) return CheckerboardPass::FromBeside;
  return quarter && ((y + phase) & 1) != 0 ? CheckerboardPass::FromDiagonals : CheckerboardPass::Traced;
}

// neighbours: left, right, up, down (or, for the quarter's diagonal pass, up-left, down-right,
// up-right, down-left: two opposite pairs alike); null where outside the image. Returns false when they disagree
// by more than `contrast` (the pixel must be traced); else `color` is their average along the
// direction they vary least (left–right or up–down; all four when alike), i.e. edge-directed.
bool fillFromNeighbours(const glm::vec3* const neighbours[4], glm::vec3& color,
                        float contrast = kCheckerboardContrast);

}  // namespace slime

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

namespace slime {

// Above this range of the neighbours' values (per channel, in √linear, close to sRGB's scale: 0.06
// ≈ 15 of 255 levels), the pixel between them is traced rather than filled in.
constexpr float kCheckerboardContrast = 0.06f;

inline bool checkerboardTraced(int x, int y, int parity) { return ((x + y + parity) & 1) == 0; }

// neighbours: left, right, up, down; null where outside the image. Returns false when they disagree
// by more than `contrast` (the pixel must be traced); else `color` is their average along the
// direction they vary least (left–right or up–down; all four when alike), i.e. edge-directed.
bool fillFromNeighbours(const glm::vec3* const neighbours[4], glm::vec3& color,
                        float contrast = kCheckerboardContrast);

}  // namespace slime

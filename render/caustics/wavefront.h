// Caustics as a wavefront: the light's cone of directions cut into a grid of triangles, each
// vertex traced through the slime (PhotonTracer::traceVertex), each triangle's power spread evenly
// over the floor triangle its three vertices land on. A light triangle squeezed to a sliver by the
// lens puts all its power on a sliver of floor: the focus and the cusp keep their peak, and the
// power is conserved by construction (no density estimate, no noise).
#pragma once

#include "render/caustics/photon_tracer.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace slime {

// Branches one vertex keeps (the first ones in the order they land; the rest are tallied as dropped).
constexpr int kMaxWavefrontBranches = 4;

// One landing of a vertex's light: its path (kDirectPath: it missed the slime; else a hash of the
// crossings' outcomes, transmitted or reflected, and the pieces crossed), where, with what weight.
struct WavefrontBranch {
  std::uint64_t path = 0;
  float x = 0.0f, y = 0.0f;
  glm::vec3 weight{0.0f};
};
constexpr std::uint64_t kDirectPath = 0;

// A traced vertex: its straight line's floor point (`straight`: the line meets the floor) and its
// landings, each branch of its path tree once (no Russian roulette: a neighbour takes the same
// branches, so their landings make a triangle).
struct WavefrontVertex {
  float sx = 0.0f, sy = 0.0f;
  bool straight = false;
  std::uint8_t count = 0;
  WavefrontBranch branches[kMaxWavefrontBranches];
};

// The grid over the cone: (side + 1)² vertices on the square [−1, 1]², mapped to the disk by the
// concentric map (Shirley and Chiu 1997, area preserving) and the disk to the cone uniformly in solid
// angle (cos θ = 1 − ρ² (1 − cos α)), so every cell of the square holds Ω / side² and each of its two
// triangles half of it, exactly. With `levels` > 1 the vertices are ordered coarse to fine: those of
// the grid of side / 2^(levels − 1) first, then those the next finer grid adds, and so on, so that a
// prefix of the order holds whole coarser grids (the progressive map, caustics.h).
class WavefrontGrid {
 public:
  WavefrontGrid() = default;
  WavefrontGrid(int side, int levels);
  int side() const { return side_; }
  int levels() const { return static_cast<int>(levelEnds_.size()); }
  std::uint64_t vertices() const { return order_.size(); }
  // Vertices in the order up to and including level `level` (0: the coarsest).
  std::uint64_t levelEnd(int level) const { return levelEnds_[static_cast<std::size_t>(level)]; }
  // The finest level whose vertices all lie within the first `traced` of the order; −1: none.
  int completeLevel(std::uint64_t traced) const;
  // The k-th vertex of the order: its column and row, and its place in the order.
  int column(std::uint64_t k) const { return static_cast<int>(order_[k] % static_cast<std::uint32_t>(side_ + 1)); }
  int row(std::uint64_t k) const { return static_cast<int>(order_[k] / static_cast<std::uint32_t>(side_ + 1)); }
  std::uint32_t rank(int column, int row) const { return rank_[static_cast<std::size_t>(row) * (side_ + 1) + column]; }
  // The direction of the grid point (column, row), which may be fractional, on `cone`.
  glm::vec3 direction(const PhotonCone& cone, double column, double row) const;

 private:
  int side_ = 0;
  std::vector<std::uint32_t> order_, rank_;
  std::vector<std::uint64_t> levelEnds_;
};

// The vertices [first, first + count) of `grid`'s order traced: their results appended to `out`.
void traceWavefront(const PhotonTracer& tracer, const PhotonCone& cone, const WavefrontGrid& grid, std::uint64_t first,
                    std::uint64_t count, std::vector<WavefrontVertex>& out, PhotonTally& tally);
// The vertices of `grid`'s order whose places are ranks[0, count) traced: each into byRank[its place].
void traceWavefrontAt(const PhotonTracer& tracer, const PhotonCone& cone, const WavefrontGrid& grid, const std::uint32_t* ranks,
                      std::uint64_t count, WavefrontVertex* byRank, PhotonTally& tally);

// Whether the light square of `grid` at (column, row), `step` grid points wide, needs its finer
// vertices (the moving map's refinement, caustics.h): its four corners (traced, in byRank) do not take
// the same paths: the slime's outline, the edge of total internal reflection, a branch cut off. There
// a coarse square spreads its corners' light over squares as wide as itself (caustic_map.h), the
// moving map's largest error against the finished one. (A square whose shared path lands folded or
// unevenly, a focus inside it, refined as well: no measurable gain on the default slime, 2026-11-29.)
bool needsFinerVertices(const WavefrontGrid& grid, const std::vector<WavefrontVertex>& byRank, int column, int row, int step);

}  // namespace slime

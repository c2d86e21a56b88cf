// Caustics, step two: the photons' landings gathered on the floor in a grid, a density estimate of
// the light that came through the slime, read as a gain on the unblocked direct light.
#pragma once

#include "render/caustics/photon_tracer.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <vector>

namespace slime {

// A rectangle of the floor, [low, high].
struct FloorRegion {
  glm::vec2 low{0.0f}, high{0.0f};
};

// Where the caustic map is needed: the bounding box of the shadow that the cone's sphere (the
// slime's bounds) casts on the floor, the only points whose shadow rays the slime can block; out to
// kShadowReach bounding radii from the slime's centre where the light is low and the shadow long.
constexpr float kShadowReach = 12.0f;
FloorRegion shadowRegion(const PhotonCone& cone, const glm::vec3& center, float radius);

class CausticMap {
 public:
  // The irradiance of the landings, per unit intensity of the light: each photon carries Ω/N of it
  // (N = `emitted`, Ω the cone's solid angle), over `region` (photons landing outside it are left
  // out). The kernel adapts to the photon count, globally and locally: on a grid of cells s,
  //   s = ¼ √(A K / n),  K = 16 (n / 10⁴)^(1/3) (at least 8),
  // (A the region's area, n the photons landed in it), each node's estimate is the power in the
  // smallest square of (2h + 1)² cells about it holding K photons, over its area (a balloon
  // estimator, a k-nearest-neighbour density: narrow at a focus, wide where photons are sparse), then
  // smoothed by the binomial [1 2 1]/4 along each axis and read bilinearly. More photons: a finer
  // grid (s ∝ n^(−1/3)) and more of them per estimate (K ∝ n^(1/3)), so bias and noise both fall.
  //
  // With `straight` (PhotonTracer::trace's: each photon's straight landing, weight 1 where it missed
  // the slime), the map also holds the ratio that gain() reads: at each node,
  //   g = [Σ_box(h) w_through + Σ_box(h) w_direct] / area(h)  ÷  [N_straight in box(H)] / area(H),
  // all the light that arrived (through the slime or past it) over the light that would have arrived
  // with nothing in the way, each a balloon estimate over its own photons (h: the smallest box holding
  // K arrived photons, H: K straight ones), then [1 2 1]/4 along each axis. Where the kernel reaches
  // past the shadow's outline the direct photons fill it, so a slime that bends and absorbs nothing
  // (n = 1) gives g = 1 exactly: the arrived photons are the straight ones, cell for cell.
  void build(const std::vector<PhotonLanding>& landings, double emitted, double solidAngle, const FloorRegion& region,
             const std::vector<PhotonLanding>* straight = nullptr);
  void clear() {
    nodes_.clear();
    ratios_.clear();
  }
  bool empty() const { return nodes_.empty(); }

  // E(x) / I in 1/m² (per channel) at floor point (x, y): zero outside the grid.
  glm::vec3 irradiance(float x, float y) const;
  // The light that reaches floor point `point` (its shadow ray blocked by the slime), as a multiple of
  // the direct light it would get from `light` unblocked (litFloor: I cos θ, the seed's light without
  // fall-off): the ratio g above, read bilinearly; built without `straight`, the irradiance's
  //   g = (E / I) · r² / cos θ,  r = |light − point|, cos θ = (light − point)_z / r.
  glm::vec3 gain(const glm::vec3& point, const glm::vec3& light) const;

  float cellSize() const { return cell_; }
  int columns() const { return columns_; }
  int rows() const { return rows_; }

 private:
  glm::vec2 origin_{0.0f};  // the floor point of node (0, 0)
  float cell_ = 0.0f;
  int columns_ = 0, rows_ = 0;
  std::vector<glm::vec3> nodes_;   // row-major, E / I at each node
  std::vector<glm::vec3> ratios_;  // row-major, g at each node (empty: built without `straight`)
  glm::vec3 bilinear(const std::vector<glm::vec3>& grid, float x, float y) const;
};

}  // namespace slime

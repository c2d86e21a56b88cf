// Caustics, step two: the light's wavefront spread over the floor in a grid of cells, the light that
// came through the slime read as a gain on the unblocked direct light.
#pragma once

#include "render/caustics/photon_tracer.h"
#include "render/caustics/wavefront.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <tbb/task_arena.h>

#include <cstdint>
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
  // The wavefront's map (wavefront.h): the triangles of `grid` at `level` (its grid of side
  // grid.side() / 2^(levels − 1 − level)), `vertices` the traced ones in the grid's order, each light
  // triangle carrying Ω / (2 side²) of the intensity. A triangle whose three vertices took the same
  // paths through the slime (the same branches through the same pieces) spreads its power times each
  // branch's mean weight evenly over the floor triangle that branch's three landings make, by exact
  // area on a grid of cells of the floor (a landed sliver: a sharp focus); one whose three vertices
  // all missed the slime spreads nothing. Where they took different paths (the slime's outline, the
  // edge of total internal reflection) each vertex's branch through the slime spreads a third of the
  // power over a square as wide as the triangle's straight landing. The gain is then, cell by cell,
  // the light that arrived through the slime plus what the straight light the slime blocks (the same
  // triangles' straight landings spread by the same rule) leaves of the unblocked light, over the
  // larger of the two (caustic_map.cpp): a slime of index 1 that absorbs nothing gives g = 1. No smoothing.
  // `arena`: the triangles spread in its threads (null: on this one; the map is the same).
  // `cellPerTriangle`: the cells' width in light triangles' mean straight landing over the region
  // (kFineCells: half, which keeps the clear slime's peak; as wide, 0.71 of the reference's and 18 mm
  // from it, caustics_test.cpp; kCoarseCells, the moving frames' preview: a quarter of the cells to fill).
  static constexpr double kFineCells = 0.5, kCoarseCells = 1.0;
  void buildWavefront(const WavefrontGrid& grid, int level, const std::vector<WavefrontVertex>& vertices, const PhotonCone& cone,
                      const FloorRegion& region, tbb::task_arena* arena = nullptr, double cellPerTriangle = kFineCells);
  void clear();
  bool empty() const { return nodes_.empty(); }

  // buildWavefront over several calls, as the vertices arrive (the viewer's still frames): begin
  // clears the map and readies the spreading, without spreading anything; each spread spreads, on
  // `arena`'s threads, the light squares whose four corners lie within the first `traced` vertices
  // of the grid's order (kAllTraced: all), each band in its order up to its first square that does
  // not, and once all are spread makes the map from the sums and returns true. The map is the same
  // however the calls cut it. `grid` and `vertices` must outlive the spreading, the vertices only
  // appended to.
  static constexpr std::uint64_t kAllTraced = ~std::uint64_t{0};
  // `refined` (one flag per light square of `level`, row-major; null: none): a flagged square spreads
  // the four squares of the next finer level in its place, their vertices traced in `vertices`.
  void beginWavefront(const WavefrontGrid& grid, int level, const std::vector<WavefrontVertex>& vertices, const PhotonCone& cone,
                      const FloorRegion& region, double cellPerTriangle = kFineCells,
                      const std::vector<std::uint8_t>* refined = nullptr);
  bool spreadWavefront(tbb::task_arena* arena, std::uint64_t traced);
  bool spreading() const { return spreading_.grid != nullptr; }
  std::uint64_t squaresLeft() const;  // the most light squares a band has left to spread

  // E(x) / I in 1/m² (per channel) of the light through the slime at floor point (x, y): zero outside the grid.
  glm::vec3 irradiance(float x, float y) const;
  // The light that reaches floor point `point` (its shadow ray blocked by the slime), as a multiple of
  // the direct light it would get from the light unblocked (litFloor: I cos θ, the seed's light
  // without fall-off): the ratio g above, read bilinearly between the cells' centres.
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
  // The spreading under way (beginWavefront): the light grid, the floor's cells, and per band of
  // light squares its sums (spreadTriangle's rows of differences) and the squares it has left.
  struct Spreading {
    const WavefrontGrid* grid = nullptr;
    const std::vector<WavefrontVertex>* vertices = nullptr;
    const std::vector<std::uint8_t>* refined = nullptr;
    glm::vec3 apex{0.0f};
    std::uint64_t needed = 0;  // the vertices of the grid's order up to the level's
    std::size_t cells = 0;     // a band's sums: (columns + 2) × rows
    int step = 1, side = 0, columns = 0, rows = 0;
    float flux = 0.0f;
    glm::dvec2 low{0.0};
    double cell = 0.0;
    struct Band {
      std::vector<glm::vec3> through;  // the power arrived through the slime,
      std::vector<float> straight;     // and the straight reference's (where the slime blocks it)
      std::uint64_t next = 0, end = 0;
    };
    std::vector<Band> bands;
  };
  Spreading spreading_;
  void spreadBand(Spreading::Band& band, std::uint64_t traced) const;
  void finishWavefront(tbb::task_arena* arena);
  glm::vec3 bilinear(const std::vector<glm::vec3>& grid, float x, float y) const;
};

}  // namespace slime

// The light's wavefront spread over the floor (caustic_map.h).
#include "render/caustics/caustic_map.h"

#include "render/trace/tsan_handoff.h"

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace slime {
namespace {

constexpr int kMaxNodesPerSide = 1024;
constexpr int kMargin = 3;  // cells beyond the region: the bilinear read stays inside
// The wavefront map's light rows in this many bands, each summed on its own (buildWavefront).
constexpr int kBands = 4;

}  // namespace

FloorRegion shadowRegion(const PhotonCone& cone, const glm::vec3& center, float radius) {
  // The cone's boundary rays (half angle α about the axis) met with the floor; where one does not
  // meet it (the light low), as far as the reach allows along its horizontal direction.
  const float reach = kShadowReach * radius;
  const glm::vec2 middle(center.x, center.y);
  FloorRegion region{middle - glm::vec2(radius), middle + glm::vec2(radius)};  // the floor under the slime
  if (cone.cosHalfAngle <= -1.0f) return FloorRegion{middle - glm::vec2(reach), middle + glm::vec2(reach)};
  const float sinAlpha = std::sqrt(std::max(0.0f, 1.0f - cone.cosHalfAngle * cone.cosHalfAngle));
  for (int k = 0; k < 64; ++k) {
    const float phi = 6.2831853f * static_cast<float>(k) / 64.0f;
    const glm::vec3 d = cone.cosHalfAngle * cone.axis + sinAlpha * (std::cos(phi) * cone.u + std::sin(phi) * cone.v);
    glm::vec2 point;
    const glm::vec2 horizontal(d.x, d.y);
    if (d.z < 0.0f) {
      const glm::vec3 hit = cone.apex + (cone.apex.z / -d.z) * d;
      point = glm::vec2(hit.x, hit.y);
    } else {
      point = glm::vec2(cone.apex.x, cone.apex.y) + (glm::length(horizontal) > 0.0f ? glm::normalize(horizontal) : glm::vec2(0.0f)) * 1e6f;
    }
    const glm::vec2 offset = point - middle;
    const float length = glm::length(offset);
    if (length > reach) point = middle + offset * (reach / length);
    region.low = glm::min(region.low, point);
    region.high = glm::max(region.high, point);
  }
  return region;
}

glm::vec3 CausticMap::irradiance(float x, float y) const { return bilinear(nodes_, x, y); }

glm::vec3 CausticMap::bilinear(const std::vector<glm::vec3>& grid, float x, float y) const {
  if (grid.empty()) return glm::vec3(0.0f);
  const float gx = (x - origin_.x) / cell_, gy = (y - origin_.y) / cell_;
  if (!(gx >= 0.0f && gy >= 0.0f && gx < static_cast<float>(columns_ - 1) && gy < static_cast<float>(rows_ - 1)))
    return glm::vec3(0.0f);
  const int ix = static_cast<int>(gx), iy = static_cast<int>(gy);
  const float fx = gx - static_cast<float>(ix), fy = gy - static_cast<float>(iy);
  const std::size_t i = static_cast<std::size_t>(iy) * columns_ + ix;
  return (1.0f - fy) * ((1.0f - fx) * grid[i] + fx * grid[i + 1]) +
         fy * ((1.0f - fx) * grid[i + columns_] + fx * grid[i + columns_ + 1]);
}

glm::vec3 CausticMap::gain(const glm::vec3& point, const glm::vec3&) const { return bilinear(ratios_, point.x, point.y); }

namespace {

// The part of convex polygon `in` (n ≤ 8 corners) on one side of the line x_axis = value.
int clipPolygon(const glm::dvec2* in, int n, int axis, double value, bool below, glm::dvec2* out) {
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const glm::dvec2 &a = in[i], &b = in[(i + 1) % n];
    const double da = below ? value - a[axis] : a[axis] - value, db = below ? value - b[axis] : b[axis] - value;
    if (da >= 0.0) out[m++] = a;
    if ((da >= 0.0) != (db >= 0.0)) out[m++] = a + (b - a) * (da / (da - db));
  }
  return m;
}

double polygonArea(const glm::dvec2* p, int n) {
  double twice = 0.0;
  for (int i = 0; i < n; ++i) twice += p[i].x * p[(i + 1) % n].y - p[(i + 1) % n].x * p[i].y;
  return 0.5 * std::abs(twice);
}

// A grid of floor cells: columns × rows of side `cell`, cell (0, 0)'s low corner at `low`.
struct CellGrid {
  glm::dvec2 low{0.0};
  double cell = 1.0;
  int columns = 0, rows = 0;
  int column(double x) const { return static_cast<int>(std::floor((x - low.x) / cell)); }
  int row(double y) const { return static_cast<int>(std::floor((y - low.y) / cell)); }
};

// Calls add(cell index, fraction) for each cell of `grid` that triangle (a, b, c) covers, with the
// fraction of the triangle's area inside it (exact: the triangle clipped to each row, then to each
// column); cells outside the grid get nothing. A triangle of no area puts a third in each corner's cell.
template <class Add>
void coverTriangle(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c, const CellGrid& grid, Add&& add) {
  const double area = 0.5 * std::abs((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y));
  const auto inCell = [&](const glm::dvec2& p, double fraction) {
    const int x = grid.column(p.x), y = grid.row(p.y);
    if (x >= 0 && y >= 0 && x < grid.columns && y < grid.rows) add(static_cast<std::size_t>(y) * grid.columns + x, fraction);
  };
  if (!(area > 1e-9 * grid.cell * grid.cell)) {
    if (std::isfinite(area)) inCell(a, 1.0 / 3.0), inCell(b, 1.0 / 3.0), inCell(c, 1.0 / 3.0);
    return;
  }
  const int r0 = std::max(0, grid.row(std::min({a.y, b.y, c.y}))), r1 = std::min(grid.rows - 1, grid.row(std::max({a.y, b.y, c.y})));
  const int c0 = std::max(0, grid.column(std::min({a.x, b.x, c.x}))),
            c1 = std::min(grid.columns - 1, grid.column(std::max({a.x, b.x, c.x})));
  if (r0 > r1 || c0 > c1) return;
  if (r0 == r1 && c0 == c1) return add(static_cast<std::size_t>(r0) * grid.columns + c0, 1.0);
  const glm::dvec2 corners[3] = {a, b, c};
  glm::dvec2 upper[8], strip[8], left[8];
  for (int r = r0; r <= r1; ++r) {
    const double y0 = grid.low.y + r * grid.cell;
    const int nu = clipPolygon(corners, 3, 1, y0, false, upper);
    const int ns = clipPolygon(upper, nu, 1, y0 + grid.cell, true, strip);
    if (ns < 3) continue;
    double xMin = strip[0].x, xMax = strip[0].x;
    for (int i = 1; i < ns; ++i) xMin = std::min(xMin, strip[i].x), xMax = std::max(xMax, strip[i].x);
    const int first = std::max(c0, grid.column(xMin)), last = std::min(c1, grid.column(xMax));
    double before = 0.0;  // the strip's area left of the first column's low edge (outside the grid or not)
    if (first > 0 || xMin < grid.low.x) {
      const int nl = clipPolygon(strip, ns, 0, grid.low.x + first * grid.cell, true, left);
      before = nl >= 3 ? polygonArea(left, nl) : 0.0;
    }
    for (int x = first; x <= last; ++x) {
      double upTo;
      if (x == last && grid.low.x + (x + 1) * grid.cell >= xMax) {
        upTo = polygonArea(strip, ns);
      } else {
        const int nl = clipPolygon(strip, ns, 0, grid.low.x + (x + 1) * grid.cell, true, left);
        upTo = nl >= 3 ? polygonArea(left, nl) : 0.0;
      }
      if (upTo > before) add(static_cast<std::size_t>(r) * grid.columns + x, (upTo - before) / area);
      before = upTo;
    }
  }
}

}  // namespace

void CausticMap::buildWavefront(const WavefrontGrid& grid, int level, const std::vector<WavefrontVertex>& vertices,
                                const PhotonCone& cone, const FloorRegion& region, tbb::task_arena* arena,
                                double cellPerTriangle) {
  const double solidAngle = cone.solidAngle;
  nodes_.clear();
  ratios_.clear();
  if (level < 0 || vertices.size() < grid.levelEnd(level)) return;
  const int step = 1 << (grid.levels() - 1 - level), side = grid.side() / step;
  const double flux = solidAngle / (2.0 * side * side);  // each light triangle's share of the intensity
  const float fluxF = static_cast<float>(flux);
  // Cells `cellPerTriangle` as wide as the light triangles' mean landing, at most kMaxNodesPerSide a side.
  const glm::dvec2 extent = glm::max(glm::dvec2(region.high - region.low), glm::dvec2(1e-6));
  double cell = cellPerTriangle * std::sqrt(extent.x * extent.y / (static_cast<double>(side) * side));
  cell = std::max({cell, extent.x / (kMaxNodesPerSide - 2 * kMargin), extent.y / (kMaxNodesPerSide - 2 * kMargin), 1e-6});
  CellGrid cells;
  cells.cell = cell;
  cells.columns = static_cast<int>(std::ceil(extent.x / cell)) + 2 * kMargin;
  cells.rows = static_cast<int>(std::ceil(extent.y / cell)) + 2 * kMargin;
  cells.low = glm::dvec2(region.low) - kMargin * cell;
  cell_ = static_cast<float>(cell);
  columns_ = cells.columns;
  rows_ = cells.rows;
  origin_ = glm::vec2(cells.low + 0.5 * cell);  // node (i, j): the centre of cell (i, j)
  const std::size_t size = static_cast<std::size_t>(columns_) * rows_;
  // The power arrived through the slime, arrived past it, and the straight reference's, per cell.
  struct Sums {
    std::vector<glm::vec3> through;
    std::vector<float> direct, straight;
  };
  const auto vertexAt = [&](int column, int row) -> const WavefrontVertex& {
    return vertices[grid.rank(column * step, row * step)];
  };
  const auto depositBranch = [&](Sums& sums, const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c, bool isDirect,
                                 const glm::vec3& power) {
    if (isDirect) coverTriangle(a, b, c, cells, [&](std::size_t i, double f) { sums.direct[i] += static_cast<float>(f) * power.x; });
    else coverTriangle(a, b, c, cells, [&](std::size_t i, double f) { sums.through[i] += static_cast<float>(f) * power; });
  };
  const auto square = [&](Sums& sums, const glm::dvec2& centre, double half, bool isDirect, bool isStraight, const glm::vec3& power) {
    const glm::dvec2 p0 = centre - half, p1(centre.x + half, centre.y - half), p2 = centre + half, p3(centre.x - half, centre.y + half);
    const glm::vec3 halfPower = 0.5f * power;
    if (isStraight) {
      const auto add = [&](std::size_t i, double f) { sums.straight[i] += static_cast<float>(f) * halfPower.x; };
      coverTriangle(p0, p1, p2, cells, add), coverTriangle(p0, p2, p3, cells, add);
    } else {
      depositBranch(sums, p0, p1, p2, isDirect, halfPower), depositBranch(sums, p0, p2, p3, isDirect, halfPower);
    }
  };
  const auto triangle = [&](Sums& sums, const WavefrontVertex& a, const WavefrontVertex& b, const WavefrontVertex& c) {
    const WavefrontVertex* corner[3] = {&a, &b, &c};
    // Which path reaches each corner's branches at all three corners (the index there, else −1).
    const auto find = [](const WavefrontVertex& v, std::uint64_t path) {
      for (int m = 0; m < v.count; ++m)
        if (v.branches[m].path == path) return m;
      return -1;
    };
    const auto isDirect = [](const WavefrontVertex& v) { return v.count == 1 && v.branches[0].path == kDirectPath; };
    const bool straightLands = a.straight && b.straight && c.straight;
    const glm::dvec2 sa(a.sx, a.sy), sb(b.sx, b.sy), sc(c.sx, c.sy);
    // Each path the three corners share spreads over the floor triangle of its landings.
    for (int k = 0; k < a.count; ++k) {
      const WavefrontBranch& ba = a.branches[k];
      const int mb = find(b, ba.path), mc = find(c, ba.path);
      if (mb < 0 || mc < 0) continue;
      const WavefrontBranch &bb = b.branches[mb], &bc = c.branches[mc];
      const glm::vec3 power = fluxF * ((ba.weight + bb.weight + bc.weight) / 3.0f);
      depositBranch(sums, {ba.x, ba.y}, {bb.x, bb.y}, {bc.x, bc.y}, ba.path == kDirectPath, power);
    }
    const int directCorners = isDirect(a) + isDirect(b) + isDirect(c);
    if (directCorners == 0 && straightLands)  // all three met the slime: the light it blocks, as a triangle
      coverTriangle(sa, sb, sc, cells, [&](std::size_t i, double f) { sums.straight[i] += static_cast<float>(f) * fluxF; });
    // A path at one or two corners only (the slime's outline, the edge of total internal reflection,
    // a branch cut off at one corner): a third of the power for each of its landings, over a square
    // as wide as the straight landing's triangle (at least a cell); where the triangle straddles the
    // outline its straight light too.
    double half = 0.5 * cell;
    if (straightLands) half = std::max(half, 0.5 * std::max({glm::length(sb - sa), glm::length(sc - sb), glm::length(sa - sc)}));
    const float third = fluxF / 3.0f;
    for (int v = 0; v < 3; ++v) {
      const WavefrontVertex& x = *corner[v];
      for (int k = 0; k < x.count; ++k) {
        const WavefrontBranch& branch = x.branches[k];
        bool shared = true;
        for (int o = 1; o < 3; ++o) shared = shared && find(*corner[(v + o) % 3], branch.path) >= 0;
        if (!shared) square(sums, {branch.x, branch.y}, half, branch.path == kDirectPath, false, third * branch.weight);
      }
      if (directCorners > 0 && directCorners < 3 && !isDirect(x) && x.straight) square(sums, {x.sx, x.sy}, half, false, true, glm::vec3(third));
    }
  };
  // The light grid's rows in kBands bands, each into its own sums on the arena's threads, added in
  // order: the same map whatever the threads.
  std::vector<Sums> bands(static_cast<std::size_t>(std::min(kBands, side)));
  const auto band = [&](std::size_t b) {
    Sums& sums = bands[b];
    sums.through.assign(size, glm::vec3(0.0f));
    sums.direct.assign(size, 0.0f);
    sums.straight.assign(size, 0.0f);
    const int first = static_cast<int>(b * side / bands.size()), last = static_cast<int>((b + 1) * side / bands.size());
    for (int row = first; row < last; ++row)
      for (int column = 0; column < side; ++column) {
        const WavefrontVertex &v00 = vertexAt(column, row), &v10 = vertexAt(column + 1, row), &v11 = vertexAt(column + 1, row + 1),
                              &v01 = vertexAt(column, row + 1);
        triangle(sums, v00, v10, v11);
        triangle(sums, v00, v11, v01);
      }
  };
  if (arena) {
    handOff(this);  // the vertices, to the workers (tsan_handoff.h)
    arena->execute([&] {
      tbb::parallel_for(std::size_t{0}, bands.size(), [&](std::size_t b) {
        takeOver(this);
        band(b);
        handOff(this);  // the band's sums, back
      });
    });
    takeOver(this);
  } else {
    for (std::size_t b = 0; b < bands.size(); ++b) band(b);
  }
  std::vector<glm::vec3>& through = bands[0].through;
  std::vector<float>&direct = bands[0].direct, &straight = bands[0].straight;
  for (std::size_t b = 1; b < bands.size(); ++b)
    for (std::size_t i = 0; i < size; ++i) {
      through[i] += bands[b].through[i];
      direct[i] += bands[b].direct[i];
      straight[i] += bands[b].straight[i];
    }
  // E / I of the light through the slime, and g, cell by cell.
  const float perArea = static_cast<float>(1.0 / (cell * cell));
  nodes_.resize(size);
  ratios_.assign(size, glm::vec3(0.0f));
  for (int y = 0; y < rows_; ++y)
    for (int x = 0; x < columns_; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * columns_ + x;
      nodes_[i] = through[i] * perArea;
      // The light of the directions outside the cone, which are not traced, reaches the cells where
      // the cone's straight light falls short of the unblocked light's I cos θ / r² (at the cone's rim):
      //   g = [through + direct + max(0, U − S)] / max(U, S),  S = straight + direct,
      // U the unblocked light over the cell (at its centre); with a slime of index 1, through = straight
      // and g = 1 still.
      const glm::dvec3 toCell = glm::dvec3(cells.low.x + (x + 0.5) * cell, cells.low.y + (y + 0.5) * cell, 0.0) - glm::dvec3(cone.apex);
      const double r = glm::length(toCell);
      const float unblocked = r > 0.0 ? static_cast<float>(static_cast<double>(cone.apex.z) / (r * r * r) * cell * cell) : 0.0f;
      const float expected = straight[i] + direct[i];
      const float reference = std::max(unblocked, expected);
      if (reference > 0.0f) ratios_[i] = (through[i] + glm::vec3(direct[i] + std::max(0.0f, unblocked - expected))) / reference;
    }
}

}  // namespace slime

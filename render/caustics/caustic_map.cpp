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

// A grid of floor cells: columns × rows of side `cell`, cell (0, 0)'s low corner at `low`.
struct CellGrid {
  glm::dvec2 low{0.0};
  double cell = 1.0;
  int columns = 0, rows = 0;
  int column(double x) const { return static_cast<int>(std::floor((x - low.x) / cell)); }
  int row(double y) const { return static_cast<int>(std::floor((y - low.y) / cell)); }
};

// Spreads `value` over the cells of `grid` that triangle (a, b, c) covers, each getting the fraction
// of the triangle's area inside it, exactly (cells outside the grid get nothing), as a vector
// rasteriser does (the signed area each edge leaves to its right, row by row, as in font-rs, Levien
// 2016): into `deltas`, rows of grid.columns + 2, whose running sums along a row (finishWavefront)
// are the cells' shares. Its cost is the edges' length in cells, not the cells covered. A triangle of
// no area puts a third in each corner's cell.
template <class T>
void spreadTriangle(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c, const CellGrid& grid, const T& value,
                    std::vector<T>& deltas) {
  const std::size_t stride = static_cast<std::size_t>(grid.columns) + 2;
  const double columns = grid.columns;
  glm::dvec2 p[8] = {(a - grid.low) / grid.cell, (b - grid.low) / grid.cell, (c - grid.low) / grid.cell};
  const auto inCell = [&](const glm::dvec2& q, const T& v) {
    const double x = std::floor(q.x), y = std::floor(q.y);
    if (!(x >= 0.0 && y >= 0.0 && x < columns && y < grid.rows)) return;
    const std::size_t i = static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(x);
    deltas[i] += v, deltas[i + 1] -= v;
  };
  const double twice = (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[2].x - p[0].x) * (p[1].y - p[0].y);
  if (!(std::abs(twice) > 2e-9)) {
    if (std::isfinite(twice)) {
      const T third = value * (1.0f / 3.0f);
      inCell(p[0], third), inCell(p[1], third), inCell(p[2], third);
    }
    return;
  }
  const double xMin = std::min({p[0].x, p[1].x, p[2].x}), xMax = std::max({p[0].x, p[1].x, p[2].x});
  const double yMin = std::min({p[0].y, p[1].y, p[2].y}), yMax = std::max({p[0].y, p[1].y, p[2].y});
  if (!(xMax > 0.0 && yMax > 0.0 && xMin < columns && yMin < grid.rows)) return;
  if (std::floor(xMin) == std::floor(xMax) && std::floor(yMin) == std::floor(yMax)) return inCell(p[0], value);
  // Inside, left of an edge going down and right of one going up: −1 for a counter-clockwise triangle.
  const float scale = static_cast<float>((twice > 0.0 ? -2.0 : 2.0) / std::abs(twice));
  int n = 3;
  if (xMin < 0.0 || xMax > columns) {  // the parts beyond the grid's sides cut off
    glm::dvec2 kept[8];
    n = clipPolygon(p, n, 0, 0.0, false, kept);
    n = clipPolygon(kept, n, 0, columns, true, p);
    if (n < 3) return;
  }
  for (int e = 0; e < n; ++e) {
    glm::dvec2 p0 = p[e], p1 = p[(e + 1) % n];
    if (p0.y == p1.y) continue;
    float direction = scale;
    if (p0.y > p1.y) std::swap(p0, p1), direction = -scale;
    const T d = value * direction;
    const double dxdy = (p1.x - p0.x) / (p1.y - p0.y);
    const int first = std::max(0, static_cast<int>(std::floor(p0.y))), end = std::min(grid.rows, static_cast<int>(std::ceil(p1.y)));
    for (int y = first; y < end; ++y) {
      const double top = std::max(static_cast<double>(y), p0.y), bottom = std::min(y + 1.0, p1.y), dy = bottom - top;
      if (!(dy > 0.0)) continue;
      const double xa = std::clamp(p0.x + (top - p0.y) * dxdy, 0.0, columns), xb = std::clamp(p0.x + (bottom - p0.y) * dxdy, 0.0, columns);
      const double x0 = std::min(xa, xb), x1 = std::max(xa, xb);
      T* row = &deltas[static_cast<std::size_t>(y) * stride];
      const double x0Floor = std::floor(x0), x1Ceil = std::ceil(x1);
      const int i0 = static_cast<int>(x0Floor), i1 = static_cast<int>(x1Ceil);
      if (i1 <= i0 + 1) {  // within one cell: the part right of the edge, and all of the cells beyond
        const double right = 0.5 * (xa + xb) - x0Floor;
        row[i0] += d * static_cast<float>(dy * (1.0 - right));
        row[i0 + 1] += d * static_cast<float>(dy * right);
        continue;
      }
      const double s = 1.0 / (x1 - x0), f0 = x0 - x0Floor, f1 = x1 - x1Ceil + 1.0;
      const double a0 = 0.5 * s * (1.0 - f0) * (1.0 - f0), am = 0.5 * s * f1 * f1;
      row[i0] += d * static_cast<float>(dy * a0);
      if (i1 == i0 + 2) {
        row[i0 + 1] += d * static_cast<float>(dy * (1.0 - a0 - am));
      } else {
        const double a1 = s * (1.5 - f0);
        row[i0 + 1] += d * static_cast<float>(dy * (a1 - a0));
        for (int x = i0 + 2; x < i1 - 1; ++x) row[x] += d * static_cast<float>(dy * s);
        const double a2 = a1 + (i1 - i0 - 3) * s;
        row[i1 - 1] += d * static_cast<float>(dy * (1.0 - a2 - am));
      }
      row[i1] += d * static_cast<float>(dy * am);
    }
  }
}

}  // namespace

void CausticMap::buildWavefront(const WavefrontGrid& grid, int level, const std::vector<WavefrontVertex>& vertices,
                                const PhotonCone& cone, const FloorRegion& region, tbb::task_arena* arena,
                                double cellPerTriangle) {
  beginWavefront(grid, level, vertices, cone, region, cellPerTriangle);
  if (spreading()) spreadWavefront(arena, kAllTraced);
}

void CausticMap::clear() {
  nodes_.clear();
  ratios_.clear();
  spreading_.grid = nullptr;
  spreading_.vertices = nullptr;
  spreading_.refined = nullptr;
}

void CausticMap::beginWavefront(const WavefrontGrid& grid, int level, const std::vector<WavefrontVertex>& vertices,
                                const PhotonCone& cone, const FloorRegion& region, double cellPerTriangle,
                                const std::vector<std::uint8_t>* refined) {
  clear();
  if (level < 0 || level >= grid.levels()) return;
  Spreading& w = spreading_;
  w.needed = grid.levelEnd(level);
  w.grid = &grid;
  w.vertices = &vertices;
  w.apex = cone.apex;
  w.step = 1 << (grid.levels() - 1 - level);
  w.refined = refined && w.step > 1 ? refined : nullptr;
  w.side = grid.side() / w.step;
  const int side = w.side;
  w.flux = static_cast<float>(cone.solidAngle / (2.0 * side * side));  // each light triangle's share of the intensity
  // Cells `cellPerTriangle` as wide as the light triangles' mean landing, at most kMaxNodesPerSide a side.
  const glm::dvec2 extent = glm::max(glm::dvec2(region.high - region.low), glm::dvec2(1e-6));
  double cell = cellPerTriangle * std::sqrt(extent.x * extent.y / (static_cast<double>(side) * side));
  cell = std::max({cell, extent.x / (kMaxNodesPerSide - 2 * kMargin), extent.y / (kMaxNodesPerSide - 2 * kMargin), 1e-6});
  w.cell = cell;
  w.columns = static_cast<int>(std::ceil(extent.x / cell)) + 2 * kMargin;
  w.rows = static_cast<int>(std::ceil(extent.y / cell)) + 2 * kMargin;
  w.low = glm::dvec2(region.low) - kMargin * cell;
  // The light grid's squares in kBands bands, each spread in order into its own sums (on the arena's
  // threads, over as many calls as it takes), added in order: the same map whatever the threads and
  // however the calls cut it.
  // A band's sums are zeroed when it first spreads (spreadWavefront), not here.
  w.cells = static_cast<std::size_t>(w.columns + 2) * w.rows;
  const std::uint64_t squares = static_cast<std::uint64_t>(side) * side;
  w.bands.resize(static_cast<std::size_t>(std::min(kBands, side)));
  for (std::size_t b = 0; b < w.bands.size(); ++b) {
    Spreading::Band& band = w.bands[b];
    band.through.clear();  // its memory kept (finishWavefront)
    band.straight.clear();
    band.next = b * squares / w.bands.size();
    band.end = (b + 1) * squares / w.bands.size();
  }
}

std::uint64_t CausticMap::squaresLeft() const {
  std::uint64_t left = 0;
  for (const Spreading::Band& band : spreading_.bands) left = std::max(left, band.end - band.next);
  return spreading() ? left : 0;
}

void CausticMap::spreadBand(Spreading::Band& sums, std::uint64_t traced) const {
  const Spreading& w = spreading_;
  const WavefrontGrid& grid = *w.grid;
  const std::vector<WavefrontVertex>& vertices = *w.vertices;
  const int step = w.step, side = w.side;
  const double cell = w.cell;
  CellGrid cells;
  cells.low = w.low;
  cells.cell = w.cell;
  cells.columns = w.columns;
  cells.rows = w.rows;
  using Sums = Spreading::Band;
  const auto vertexAt = [&](int column, int row) -> const WavefrontVertex& { return vertices[grid.rank(column, row)]; };
  // A branch's landings: the light through the slime spread; the light past it is U − S's (finishWavefront).
  const auto depositBranch = [&](Sums& sums, const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c, bool isDirect,
                                 const glm::vec3& power) {
    if (!isDirect) spreadTriangle(a, b, c, cells, power, sums.through);
  };
  const auto square = [&](Sums& sums, const glm::dvec2& centre, double half, bool isDirect, bool isStraight, const glm::vec3& power) {
    const glm::dvec2 p0 = centre - half, p1(centre.x + half, centre.y - half), p2 = centre + half, p3(centre.x - half, centre.y + half);
    const glm::vec3 halfPower = 0.5f * power;
    if (isStraight) {
      spreadTriangle(p0, p1, p2, cells, halfPower.x, sums.straight), spreadTriangle(p0, p2, p3, cells, halfPower.x, sums.straight);
    } else {
      depositBranch(sums, p0, p1, p2, isDirect, halfPower), depositBranch(sums, p0, p2, p3, isDirect, halfPower);
    }
  };
  const auto triangle = [&](Sums& sums, const WavefrontVertex& a, const WavefrontVertex& b, const WavefrontVertex& c, float fluxF) {
    const WavefrontVertex* corner[3] = {&a, &b, &c};
    // Which path reaches each corner's branches at all three corners (the index there, else −1).
    const auto find = [](const WavefrontVertex& v, std::uint64_t path) {
      for (int m = 0; m < v.count; ++m)
        if (v.branches[m].path == path) return m;
      return -1;
    };
    const auto isDirect = [](const WavefrontVertex& v) { return v.count == 1 && v.branches[0].path == kDirectPath; };
    const int directCorners = isDirect(a) + isDirect(b) + isDirect(c);
    if (directCorners == 3) return;  // all past the slime: U − S has its light
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
    if (directCorners == 0 && straightLands)  // all three met the slime: the light it blocks, as a triangle
      spreadTriangle(sa, sb, sc, cells, fluxF, sums.straight);
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
  std::uint64_t q = sums.next;
  for (; q < sums.end; ++q) {
    const int row = static_cast<int>(q / static_cast<std::uint64_t>(side)), column = static_cast<int>(q % static_cast<std::uint64_t>(side));
    if (traced != kAllTraced &&
        std::max({grid.rank(column * step, row * step), grid.rank((column + 1) * step, row * step),
                  grid.rank(column * step, (row + 1) * step), grid.rank((column + 1) * step, (row + 1) * step)}) >= traced)
      break;  // a corner not traced yet: the band goes on from here
    // A refined square (the moving map's, caustics.h): its four squares of the next finer level.
    const int width = w.refined && (*w.refined)[q] ? step / 2 : step;
    for (int y = row * step; y < (row + 1) * step; y += width)
      for (int x = column * step; x < (column + 1) * step; x += width) {
        const WavefrontVertex &v00 = vertexAt(x, y), &v10 = vertexAt(x + width, y), &v11 = vertexAt(x + width, y + width),
                              &v01 = vertexAt(x, y + width);
        triangle(sums, v00, v10, v11, width == step ? w.flux : 0.25f * w.flux);
        triangle(sums, v00, v11, v01, width == step ? w.flux : 0.25f * w.flux);
      }
  }
  sums.next = q;
}

bool CausticMap::spreadWavefront(tbb::task_arena* arena, std::uint64_t traced) {
  if (!spreading()) return false;
  Spreading& w = spreading_;
  if (traced == kAllTraced && w.vertices->size() < w.needed) {  // vertices missing (an empty cone): no map
    clear();
    return false;
  }
  // The bands' sums zeroed as they are first needed: all at once for a whole map, else one a call,
  // so that no viewer frame zeroes all four of the finest level's (tens of MB; 68 ms in one frame
  // on a loaded 2-core machine); a band spreads once its sums are ready.
  int zeroings = traced == kAllTraced ? static_cast<int>(w.bands.size()) : 1;
  for (Spreading::Band& band : w.bands)
    if (band.through.size() != w.cells && zeroings-- > 0) {
      band.through.assign(w.cells, glm::vec3(0.0f));
      band.straight.assign(w.cells, 0.0f);
    }
  const auto ready = [&](const Spreading::Band& band) { return band.through.size() == w.cells; };
  traced = std::min<std::uint64_t>(traced, w.vertices->size());
  const std::uint64_t left = squaresLeft();
  if (left > 0) {
    if (arena) {
      handOff(this);  // the vertices, to the workers (tsan_handoff.h)
      arena->execute([&] {
        tbb::parallel_for(std::size_t{0}, w.bands.size(), [&](std::size_t b) {
          takeOver(this);
          if (ready(w.bands[b])) spreadBand(w.bands[b], traced);
          handOff(this);  // the band's sums, back
        });
      });
      takeOver(this);
    } else {
      for (Spreading::Band& band : w.bands)
        if (ready(band)) spreadBand(band, traced);
    }
    if (squaresLeft() > 0) return false;
  }
  finishWavefront(arena);
  return true;
}

void CausticMap::finishWavefront(tbb::task_arena* arena) {
  Spreading& w = spreading_;
  CellGrid cells;
  cells.low = w.low;
  cells.cell = w.cell;
  cells.columns = w.columns;
  cells.rows = w.rows;
  const double cell = w.cell;
  const glm::vec3 apex = w.apex;
  cell_ = static_cast<float>(cell);
  columns_ = cells.columns;
  rows_ = cells.rows;
  origin_ = glm::vec2(cells.low + 0.5 * cell);  // node (i, j): the centre of cell (i, j)
  const std::size_t size = static_cast<std::size_t>(columns_) * rows_, stride = static_cast<std::size_t>(columns_) + 2;
  std::vector<glm::vec3>& through = w.bands[0].through;
  std::vector<float>& straight = w.bands[0].straight;
  nodes_.resize(size);
  ratios_.assign(size, glm::vec3(0.0f));
  const float perArea = static_cast<float>(1.0 / (cell * cell));
  // Row by row (each on its own: the same on any threads): the bands added in order, the running sums, E / I and g.
  const auto floorRow = [&](int y) {
    const std::size_t from = static_cast<std::size_t>(y) * stride, to = from + stride;
    for (std::size_t b = 1; b < w.bands.size(); ++b)
      for (std::size_t i = from; i < to; ++i) {
        through[i] += w.bands[b].through[i];
        straight[i] += w.bands[b].straight[i];
      }
    for (std::size_t i = from + 1; i < from + static_cast<std::size_t>(columns_); ++i) {
      through[i] += through[i - 1];
      straight[i] += straight[i - 1];
    }
    for (int x = 0; x < columns_; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * columns_ + x, k = static_cast<std::size_t>(y) * (columns_ + 2) + x;
        // (A row's running sum leaves a rounding's residue where its triangles end: never below zero.)
        const glm::vec3 arrived = glm::max(through[k], glm::vec3(0.0f));
        const float expected = std::max(straight[k], 0.0f);
        nodes_[i] = arrived * perArea;
        // The light that passed the slime (its triangles are not spread) and that of the directions
        // outside the cone, which are not traced, reach what the straight light the slime blocks
        // leaves of the unblocked light's I cos θ / r²:
        //   g = [through + max(0, U − S)] / max(U, S),
        // S the straight light the slime blocks, U the unblocked light over the cell (at its centre);
        // with a slime of index 1, through = S and g = 1 still.
        const glm::dvec3 toCell = glm::dvec3(cells.low.x + (x + 0.5) * cell, cells.low.y + (y + 0.5) * cell, 0.0) - glm::dvec3(apex);
        const double r = glm::length(toCell);
        const float unblocked = r > 0.0 ? static_cast<float>(static_cast<double>(apex.z) / (r * r * r) * cell * cell) : 0.0f;
        const float reference = std::max(unblocked, expected);
        if (reference > 0.0f) ratios_[i] = (arrived + glm::vec3(std::max(0.0f, unblocked - expected))) / reference;
    }
  };
  if (arena) {
    handOff(this);
    arena->execute([&] {
      tbb::parallel_for(0, rows_, [&](int y) {
        takeOver(this);
        floorRow(y);
        handOff(this);
      });
    });
    takeOver(this);
  } else {
    for (int y = 0; y < rows_; ++y) floorRow(y);
  }
  w.grid = nullptr;
  w.vertices = nullptr;
  // The bands' memory is kept for the next map this object builds (tens of MB for the finished map):
  // a fresh allocation's page faults and zeroing made the viewer's still frame that begins the
  // finest level a lump of 95-135 ms on a loaded 2-core machine; assign() reuses it.
}

}  // namespace slime

// The floor-space density estimate of the photons' landings (caustic_map.h).
#include "render/caustics/caustic_map.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace slime {
namespace {

constexpr int kMaxNodesPerSide = 1024;
constexpr int kMargin = 3;  // nodes beyond the landings' box: the splat and the smoothing stay inside
// The widest box a node grows to, in cells either side (an average density needs h ≈ 2): wider, the
// estimate would spill far out of a lit patch (a balloon estimate does not keep the total power).
constexpr int kMaxHalfWidth = 6;

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

void CausticMap::build(const std::vector<PhotonLanding>& landings, double emitted, double solidAngle, const FloorRegion& region,
                       const std::vector<PhotonLanding>* straight) {
  nodes_.clear();
  ratios_.clear();
  if (landings.empty() || !(emitted > 0.0)) return;
  const glm::vec2 low = region.low, high = region.high;
  std::size_t inside = 0;
  for (const PhotonLanding& l : landings) inside += l.x >= low.x && l.x <= high.x && l.y >= low.y && l.y <= high.y;
  if (inside == 0) return;
  const double n = static_cast<double>(inside);
  // The grid: fine cells, a quarter of the width s = √(A K / n) an average box of K photons has.
  const double photonsPerBox = std::max(8.0, 16.0 * std::cbrt(n / 1e4));
  const glm::vec2 extent = glm::max(high - low, glm::vec2(1e-6f));
  double cell = 0.25 * std::sqrt(static_cast<double>(extent.x) * extent.y * photonsPerBox / n);
  cell = std::max({cell, static_cast<double>(extent.x) / (kMaxNodesPerSide - 2 * kMargin),
                   static_cast<double>(extent.y) / (kMaxNodesPerSide - 2 * kMargin), 1e-6});
  cell_ = static_cast<float>(cell);
  columns_ = static_cast<int>(std::ceil(extent.x / cell)) + 1 + 2 * kMargin;
  rows_ = static_cast<int>(std::ceil(extent.y / cell)) + 1 + 2 * kMargin;
  origin_ = low - static_cast<float>(kMargin) * cell_;
  const std::size_t size = static_cast<std::size_t>(columns_) * rows_;
  // Summed-area tables of the photons' weights and counts, each photon in its nearest node's cell.
  const int w = columns_ + 1;
  const std::size_t tableSize = static_cast<std::size_t>(w) * (rows_ + 1);
  const auto cellOf = [&](const PhotonLanding& l) {
    const int x = std::clamp(static_cast<int>(std::lround((l.x - origin_.x) / cell_)), 0, columns_ - 1);
    const int y = std::clamp(static_cast<int>(std::lround((l.y - origin_.y) / cell_)), 0, rows_ - 1);
    return static_cast<std::size_t>(y + 1) * w + (x + 1);
  };
  const auto insideRegion = [&](const PhotonLanding& l) { return l.x >= low.x && l.x <= high.x && l.y >= low.y && l.y <= high.y; };
  const auto add = [&](const std::vector<PhotonLanding>& photons, bool directOnly, std::vector<glm::dvec3>& weights,
                       std::vector<double>& counts) {
    for (const PhotonLanding& l : photons) {
      if (!insideRegion(l) || (directOnly && l.weight.x <= 0.0f)) continue;
      const std::size_t i = cellOf(l);
      weights[i] += glm::dvec3(l.weight);
      counts[i] += 1.0;
    }
  };
  const auto integrate = [&](std::vector<glm::dvec3>& weights, std::vector<double>& counts) {
    for (int y = 1; y <= rows_; ++y)
      for (int x = 1; x <= columns_; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * w + x;
        weights[i] += weights[i - 1] + weights[i - w] - weights[i - w - 1];
        counts[i] += counts[i - 1] + counts[i - w] - counts[i - w - 1];
      }
  };
  std::vector<glm::dvec3> weights(tableSize, glm::dvec3(0.0));
  std::vector<double> counts(tableSize, 0.0);
  add(landings, false, weights, counts);
  // The ratio's "arrived" tables start from the same photons through the slime (see below).
  std::vector<glm::dvec3> arrived;
  std::vector<double> arrivedCounts;
  if (straight) arrived = weights, arrivedCounts = counts;
  integrate(weights, counts);
  const auto box = [&](const auto& table, int x0, int y0, int x1, int y1) {  // nodes [x0, x1] × [y0, y1]
    x0 = std::max(x0, 0), y0 = std::max(y0, 0), x1 = std::min(x1, columns_ - 1), y1 = std::min(y1, rows_ - 1);
    const std::size_t a = static_cast<std::size_t>(y0) * w + x0, b = static_cast<std::size_t>(y0) * w + x1 + 1,
                      c = static_cast<std::size_t>(y1 + 1) * w + x0, d = static_cast<std::size_t>(y1 + 1) * w + x1 + 1;
    return table[d] - table[b] - table[c] + table[a];
  };
  // Each node: the smallest square of (2h + 1)² cells about it that holds K photons (h ≤ kMaxHalfWidth): a
  // balloon estimate, narrow where photons crowd (the focus), wide where they are sparse.
  std::vector<glm::vec3> estimate(size, glm::vec3(0.0f));
  const double scale = solidAngle / emitted / (cell * cell);  // each photon: Ω/N of the intensity
  for (int y = 0; y < rows_; ++y)
    for (int x = 0; x < columns_; ++x) {
      // No photon in the 3 × 3 cells about it: outside the light (the box would reach in and spill it out).
      if (box(counts, x - 1, y - 1, x + 1, y + 1) == 0.0) continue;
      int h = 0;
      while (h < kMaxHalfWidth && box(counts, x - h, y - h, x + h, y + h) < photonsPerBox) ++h;
      const double area = (2.0 * h + 1.0) * (2.0 * h + 1.0);
      estimate[static_cast<std::size_t>(y) * columns_ + x] = glm::vec3(box(weights, x - h, y - h, x + h, y + h) * (scale / area));
    }
  // A balloon estimate does not integrate to the power it was given (its box stops growing where the
  // count first reaches K, an upward fluctuation more often than not; at a patch's edge it spills):
  // scaled so that it does, the power the photons brought is kept (the smoothing keeps it too).
  glm::dvec3 given(0.0), estimated(0.0);
  given = box(weights, 0, 0, columns_ - 1, rows_ - 1) * scale;
  for (const glm::vec3& e : estimate) estimated += glm::dvec3(e);
  for (int c = 0; c < 3; ++c) {
    const float ratio = estimated[c] > 0.0 ? static_cast<float>(given[c] / estimated[c]) : 0.0f;
    for (glm::vec3& e : estimate) e[c] *= ratio;
  }
  // Then [1 2 1]/4 along each axis, against the steps where h changes.
  const auto at = [&](std::vector<glm::vec3>& grid, int x, int y) -> glm::vec3& {
    return grid[static_cast<std::size_t>(std::clamp(y, 0, rows_ - 1)) * columns_ + std::clamp(x, 0, columns_ - 1)];
  };
  std::vector<glm::vec3> smoothed(size);
  const auto smooth = [&](std::vector<glm::vec3>& grid, std::vector<glm::vec3>& result) {
    for (int y = 0; y < rows_; ++y)
      for (int x = 0; x < columns_; ++x)
        at(smoothed, x, y) = 0.25f * at(grid, x - 1, y) + 0.5f * at(grid, x, y) + 0.25f * at(grid, x + 1, y);
    result.assign(size, glm::vec3(0.0f));
    for (int y = 0; y < rows_; ++y)
      for (int x = 0; x < columns_; ++x)
        at(result, x, y) = 0.25f * at(smoothed, x, y - 1) + 0.5f * at(smoothed, x, y) + 0.25f * at(smoothed, x, y + 1);
  };
  smooth(estimate, nodes_);
  if (!straight) return;
  // The ratio (see the header): the arrived photons (through the slime, and the direct ones) against
  // the straight ones, each in the smallest box holding K of its own.
  std::vector<glm::dvec3> reference(tableSize, glm::dvec3(0.0));
  std::vector<double> referenceCounts(tableSize, 0.0);
  add(*straight, true, arrived, arrivedCounts);
  add(*straight, false, reference, referenceCounts);
  integrate(arrived, arrivedCounts);
  integrate(reference, referenceCounts);
  const auto halfWidth = [&](const std::vector<double>& table, int x, int y) {
    int h = 0;
    while (h < kMaxHalfWidth && box(table, x - h, y - h, x + h, y + h) < photonsPerBox) ++h;
    return h;
  };
  std::vector<glm::vec3> ratio(size, glm::vec3(0.0f));
  for (int y = 0; y < rows_; ++y)
    for (int x = 0; x < columns_; ++x) {
      const int big = halfWidth(referenceCounts, x, y);
      const double expected = box(referenceCounts, x - big, y - big, x + big, y + big);
      if (expected == 0.0) continue;  // beyond the cone's photons: no shadow of the slime reaches here
      const int h = halfWidth(arrivedCounts, x, y);
      const double areas = (2.0 * big + 1.0) * (2.0 * big + 1.0) / ((2.0 * h + 1.0) * (2.0 * h + 1.0));
      ratio[static_cast<std::size_t>(y) * columns_ + x] = glm::vec3(box(arrived, x - h, y - h, x + h, y + h) * (areas / expected));
    }
  smooth(ratio, ratios_);
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

glm::vec3 CausticMap::gain(const glm::vec3& point, const glm::vec3& light) const {
  if (!ratios_.empty()) return bilinear(ratios_, point.x, point.y);
  const glm::vec3 toLight = light - point;
  if (!(toLight.z > 0.0f)) return glm::vec3(0.0f);
  const float r2 = glm::dot(toLight, toLight);
  const float cosTheta = toLight.z / std::sqrt(r2);
  return irradiance(point.x, point.y) * (r2 / cosTheta);
}

}  // namespace slime

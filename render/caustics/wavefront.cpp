// The light's wavefront as a grid of triangles over the cone (wavefront.h).
#include "render/caustics/wavefront.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace slime {

WavefrontGrid::WavefrontGrid(int side, int levels) : side_(side) {
  const int n = side + 1;
  rank_.assign(static_cast<std::size_t>(n) * n, 0);
  order_.reserve(rank_.size());
  std::vector<bool> placed(rank_.size(), false);
  for (int level = 0; level < levels; ++level) {
    const int step = 1 << (levels - 1 - level);
    for (int row = 0; row <= side; row += step)
      for (int column = 0; column <= side; column += step) {
        const std::size_t id = static_cast<std::size_t>(row) * n + column;
        if (placed[id]) continue;
        placed[id] = true;
        rank_[id] = static_cast<std::uint32_t>(order_.size());
        order_.push_back(static_cast<std::uint32_t>(id));
      }
    levelEnds_.push_back(order_.size());
  }
}

int WavefrontGrid::completeLevel(std::uint64_t traced) const {
  int level = -1;
  for (std::size_t l = 0; l < levelEnds_.size(); ++l)
    if (levelEnds_[l] <= traced) level = static_cast<int>(l);
  return level;
}

glm::vec3 WavefrontGrid::direction(const PhotonCone& cone, double column, double row) const {
  // The square [−1, 1]² to the unit disk (concentric map), the disk to the cone.
  const double a = 2.0 * column / side_ - 1.0, b = 2.0 * row / side_ - 1.0;
  constexpr double kQuarterPi = 0.7853981633974483;
  double radius = 0.0, phi = 0.0;
  if (a == 0.0 && b == 0.0) {
    radius = 0.0;
  } else if (std::abs(a) > std::abs(b)) {
    radius = a;
    phi = kQuarterPi * (b / a);
  } else {
    radius = b;
    phi = 2.0 * kQuarterPi - kQuarterPi * (a / b);
  }
  const double cosTheta = 1.0 - radius * radius * (1.0 - static_cast<double>(cone.cosHalfAngle));
  const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
  const double sign = radius < 0.0 ? -1.0 : 1.0;  // the concentric map's negative radius: the opposite side
  return glm::normalize(static_cast<float>(cosTheta) * cone.axis + static_cast<float>(sign * sinTheta * std::cos(phi)) * cone.u +
                        static_cast<float>(sign * sinTheta * std::sin(phi)) * cone.v);
}

void traceWavefront(const PhotonTracer& tracer, const PhotonCone& cone, const WavefrontGrid& grid, std::uint64_t first,
                    std::uint64_t count, std::vector<WavefrontVertex>& out, PhotonTally& tally) {
  if (cone.empty()) return;
  for (std::uint64_t k = first; k < first + count; ++k) {
    const glm::vec3 direction = grid.direction(cone, grid.column(k), grid.row(k));
    out.emplace_back();
    tracer.traceVertex(Ray{cone.apex, direction, 0.0f, kInfinity}, out.back(), tally);
  }
}

void traceWavefrontAt(const PhotonTracer& tracer, const PhotonCone& cone, const WavefrontGrid& grid, const std::uint32_t* ranks,
                      std::uint64_t count, WavefrontVertex* byRank, PhotonTally& tally) {
  if (cone.empty()) return;
  for (std::uint64_t i = 0; i < count; ++i) {
    const std::uint32_t k = ranks[i];
    const glm::vec3 direction = grid.direction(cone, grid.column(k), grid.row(k));
    byRank[k] = WavefrontVertex{};
    tracer.traceVertex(Ray{cone.apex, direction, 0.0f, kInfinity}, byRank[k], tally);
  }
}

namespace {

bool samePaths(const WavefrontVertex& a, const WavefrontVertex& b) {
  if (a.count != b.count) return false;
  for (int i = 0; i < a.count; ++i) {
    bool found = false;
    for (int j = 0; j < b.count && !found; ++j) found = a.branches[i].path == b.branches[j].path;
    if (!found) return false;
  }
  return true;
}

}  // namespace

bool needsFinerVertices(const WavefrontGrid& grid, const std::vector<WavefrontVertex>& byRank, int column, int row, int step) {
  const WavefrontVertex& v00 = byRank[grid.rank(column, row)];
  return !samePaths(v00, byRank[grid.rank(column + step, row)]) || !samePaths(v00, byRank[grid.rank(column + step, row + step)]) ||
         !samePaths(v00, byRank[grid.rank(column, row + step)]);
}

}  // namespace slime

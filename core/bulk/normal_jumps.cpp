#include "core/bulk/normal_jumps.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace slime {

NormalJumps normalJumps(const std::vector<glm::dvec3>& x, const std::vector<Triangle>& triangles) {
  std::vector<glm::dvec3> unit(triangles.size());
  std::vector<bool> valid(triangles.size());
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Triangle& t = triangles[f];
    const glm::dvec3 n = glm::cross(x[t.y] - x[t.x], x[t.z] - x[t.x]);
    const double length = glm::length(n);
    valid[f] = length > 0.0 && std::isfinite(length);
    unit[f] = valid[f] ? n / length : glm::dvec3(0.0);
  }
  // (smaller vertex, larger vertex, triangle) for every side, sorted: an edge's two triangles meet.
  std::vector<std::array<std::uint32_t, 3>> sides;
  sides.reserve(3 * triangles.size());
  for (std::size_t f = 0; f < triangles.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = triangles[f][k], b = triangles[f][(k + 1) % 3];
      sides.push_back({std::min(a, b), std::max(a, b), static_cast<std::uint32_t>(f)});
    }
  std::sort(sides.begin(), sides.end());
  std::vector<double> angles;
  double largest = -1.0;
  glm::dvec3 largestAt(0.0);
  angles.reserve(sides.size() / 2);
  for (std::size_t s = 0; s + 1 < sides.size();) {
    std::size_t end = s + 1;
    while (end < sides.size() && sides[end][0] == sides[s][0] && sides[end][1] == sides[s][1]) ++end;
    if (end - s == 2 && valid[sides[s][2]] && valid[sides[s + 1][2]]) {
      const glm::dvec3 cross = glm::cross(unit[sides[s][2]], unit[sides[s + 1][2]]);
      // atan2(|n1 × n2|, n1·n2): accurate for small and large angles alike.
      angles.push_back(std::atan2(glm::length(cross), glm::dot(unit[sides[s][2]], unit[sides[s + 1][2]])));
      if (angles.back() > largest) {
        largest = angles.back();
        largestAt = 0.5 * (x[sides[s][0]] + x[sides[s][1]]);
      }
    }
    s = end;
  }
  NormalJumps jumps;
  jumps.edges = angles.size();
  if (angles.empty()) return jumps;
  std::sort(angles.begin(), angles.end());
  jumps.largest = angles.back();
  jumps.largestAt = largestAt;
  jumps.percentile99 = angles[std::min(angles.size() - 1, static_cast<std::size_t>(0.99 * angles.size()))];
  jumps.median = angles[angles.size() / 2];
  return jumps;
}

}  // namespace slime

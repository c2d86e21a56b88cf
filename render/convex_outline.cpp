#include "render/convex_outline.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace slime {
namespace {

// > 0 when o → a → b turns counter-clockwise.
double turn(const glm::dvec2& o, const glm::dvec2& a, const glm::dvec2& b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

}  // namespace

void ConvexOutline::build(std::vector<glm::dvec2>& points) {
  corners_.clear();
  std::sort(points.begin(), points.end(), [](const glm::dvec2& a, const glm::dvec2& b) {
    return a.x < b.x || (a.x == b.x && a.y < b.y);
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return;
  // Lower hull left to right, then upper hull right to left; collinear points are dropped.
  std::vector<glm::dvec2> hull(2 * points.size());
  std::size_t k = 0;
  for (const glm::dvec2& p : points) {
    while (k >= 2 && turn(hull[k - 2], hull[k - 1], p) <= 0.0) --k;
    hull[k++] = p;
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && turn(hull[k - 2], hull[k - 1], points[i]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);  // the last point is the first
  if (hull.size() >= 3) corners_ = std::move(hull);
}

bool ConvexOutline::clip(const glm::dvec2& a, const glm::dvec2& d, double& low, double& high) const {
  // Cyrus–Beck: inside every edge's left half-plane, cross(e, p − c) ≥ 0 for p = a + s d.
  low = -std::numeric_limits<double>::infinity();
  high = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < corners_.size(); ++i) {
    const glm::dvec2& c = corners_[i];
    const glm::dvec2 e = corners_[(i + 1) % corners_.size()] - c;
    const double offset = e.x * (a.y - c.y) - e.y * (a.x - c.x);  // f(0)
    const double rate = e.x * d.y - e.y * d.x;                      // df/ds
    if (rate == 0.0) {
      if (offset < 0.0) return false;  // parallel to the edge, outside it
      continue;
    }
    const double s = -offset / rate;
    if (rate > 0.0) low = std::max(low, s);
    else high = std::min(high, s);
  }
  return low <= high;
}

}  // namespace slime

#include "render/slime/convex_outline.h"

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
  if (points.size() > 64) {
    // Akl–Toussaint: the points extreme along x, y, x + y and x − y span an octagon inside the hull;
    // the points strictly inside it cannot be corners (most of a dense cloud) and need no sorting.
    glm::dvec2 extremes[8];
    double reach[8];
    for (int k = 0; k < 8; ++k) reach[k] = -std::numeric_limits<double>::infinity();
    for (const glm::dvec2& p : points) {
      const double along[8] = {p.x, p.x + p.y, p.y, p.y - p.x, -p.x, -p.x - p.y, -p.y, p.x - p.y};
      for (int k = 0; k < 8; ++k)
        if (along[k] > reach[k]) {
          reach[k] = along[k];
          extremes[k] = p;
        }
    }
    // In the order of their directions the extremes go round counter-clockwise (repeats allowed).
    glm::dvec2 octagon[8];
    std::size_t n = 0;
    for (const glm::dvec2& e : extremes)
      if (n == 0 || (e != octagon[n - 1] && e != octagon[0])) octagon[n++] = e;
    bool convex = n >= 3;
    for (std::size_t i = 0; convex && i < n; ++i) convex = turn(octagon[i], octagon[(i + 1) % n], octagon[(i + 2) % n]) > 0.0;
    if (convex) {
      const auto strictlyInside = [&](const glm::dvec2& p) {
        for (std::size_t i = 0; i < n; ++i)
          if (turn(octagon[i], octagon[(i + 1) % n], p) <= 0.0) return false;
        return true;
      };
      points.erase(std::remove_if(points.begin(), points.end(), strictlyInside), points.end());
    }
  }
  std::sort(points.begin(), points.end(), [](const glm::dvec2& a, const glm::dvec2& b) {
    return a.x < b.x || (a.x == b.x && a.y < b.y);
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return;
  // Lower hull left to right, then upper hull right to left; collinear points are dropped. Built in
  // corners_ (its storage kept from call to call).
  std::vector<glm::dvec2>& hull = corners_;
  hull.resize(2 * points.size());
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
  if (hull.size() < 3) hull.clear();
}

void ConvexOutline::crossRows(int rows, std::vector<Crossing>& crossings) const {
  crossings.assign(static_cast<std::size_t>(std::max(0, rows)), Crossing{});
  // Each edge gives x on the rows whose line it spans (ends included); a convex outline's row
  // crossing runs between the smallest and largest of those.
  for (std::size_t i = 0; i < corners_.size(); ++i) {
    const glm::dvec2 a = corners_[i], b = corners_[(i + 1) % corners_.size()];
    if (a.y == b.y) continue;  // a horizontal edge: its ends belong to the edges beside it
    const double low = std::min(a.y, b.y), high = std::max(a.y, b.y);
    const int first = static_cast<int>(std::clamp(std::ceil(low - 0.5), 0.0, static_cast<double>(rows)));
    const int last = static_cast<int>(std::clamp(std::floor(high - 0.5), -1.0, static_cast<double>(rows - 1)));
    const double slope = (b.x - a.x) / (b.y - a.y);
    for (int row = first; row <= last; ++row) {
      const double x = a.x + (row + 0.5 - a.y) * slope;
      Crossing& crossing = crossings[static_cast<std::size_t>(row)];
      crossing.low = crossing.any ? std::min(crossing.low, x) : x;
      crossing.high = crossing.any ? std::max(crossing.high, x) : x;
      crossing.any = true;
    }
  }
}

}  // namespace slime

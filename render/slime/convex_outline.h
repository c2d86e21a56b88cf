// A convex polygon in the plane, the convex hull of a cloud of points: the outline of the slime's
// vertices as the eye sees them (on the image) or as the light casts them (on the floor). The slime
// lies inside the convex hull of its vertices, so its image and its shadow lie inside these outlines,
// which hug a sagging or stretched slime far closer than its bounding sphere's (screen_footprint.h).
#pragma once

#include <glm/vec2.hpp>

#include <vector>

namespace slime {

class ConvexOutline {
 public:
  // The convex hull of `points` (Andrew's monotone chain; `points` is sorted in place). Fewer than
  // three distinct corners (all the points on one line) make an outline that bounds nothing.
  void build(std::vector<glm::dvec2>& points);

  // Whether the outline has an inside (at least three corners not on one line).
  bool bounded() const { return corners_.size() >= 3; }

  // Where each horizontal line y = row + 0.5, row in [0, rows), crosses the outline: [low, high] in
  // x, or no crossing (any = false). One walk round the corners. Needs bounded().
  struct Crossing {
    bool any = false;
    double low = 0.0, high = 0.0;
  };
  void crossRows(int rows, std::vector<Crossing>& crossings) const;

  const std::vector<glm::dvec2>& corners() const { return corners_; }  // counter-clockwise

 private:
  std::vector<glm::dvec2> corners_;
};

}  // namespace slime

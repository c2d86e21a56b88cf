// The pixels the slime can change: where a primary ray may meet its bounding sphere (or, on a
// varnished floor, that sphere's mirror image), or see a floor point the sphere may shadow. Every
// other pixel shows the floor or the sky exactly as it did last frame while the camera stays, so the
// renderer copies it instead of tracing it again.
#pragma once

#include <vector>

#include "core/geometry/camera.h"
#include "render/slime/convex_outline.h"
#include "render/trace/shading_parameters.h"
#include "render/slime/slime_geometry.h"

namespace slime {

// Row by row, the columns the slime can affect: row y's pixels [rows[y].x0, rows[y].x1).
struct ScreenFootprint {
  struct Span {
    int x0 = 0, x1 = 0;  // empty when x0 >= x1
  };
  std::vector<Span> rows;
  // The mesh's outlines on the image (of the slime, its mirror image and its shadow), their points
  // and each row's crossing (storage kept from frame to frame).
  struct Outline {
    std::vector<glm::dvec2> points;
    ConvexOutline hull;
    std::vector<ConvexOutline::Crossing> rows;
  };
  Outline outlines[3];

  bool contains(int x, int y) const { return x >= rows[y].x0 && x < rows[y].x1; }
  // Whether the pixels [x0, x0 + count) of row y all lie outside.
  bool outside(int x0, int count, int y) const { return x0 + count <= rows[y].x0 || x0 >= rows[y].x1; }
  long long area() const;
};

// Every pixel the slime can affect in a width × height image, into `footprint` (its storage is
// reused from frame to frame). Each row's span is exact for the three regions, then widened by two
// pixels each way and to the two rows above and below, for rounding. A mesh slime lies in the convex
// hull of its vertices: each region is that hull's outline (on the image; in the mirror; its shadow
// on the floor, the vertices cast from the light) where it can be drawn (the vertices in front of the
// eye, the light above them), else the bounding sphere's:
//  - the pixels whose ray meets the bounding sphere (its image is an ellipse: along a row of the
//    image the ray directions a + x s form a line, and a line cuts the sphere's cone of directions
//    k |d|² − (d·c)² ≤ 0, c the centre seen from the eye and k = |c|² − r², in one interval);
//  - with a varnished floor, the same for the sphere's mirror image below z = 0;
//  - the pixels whose floor point lies in the sphere's shadow: a row's floor points lie on a line
//    (the camera has no roll), which cuts the cone from the light through the sphere in one interval.
// Whole rows when an interval cannot be bounded: the sphere not wholly in front of the eye, the eye
// not above the floor, or the light not above the sphere.
void slimeFootprint(const Camera& camera, const SlimeGeometry& geometry, const ShadingParameters& parameters,
                    int width, int height, ScreenFootprint& footprint);

ScreenFootprint slimeFootprint(const Camera& camera, const SlimeGeometry& geometry,
                               const ShadingParameters& parameters, int width, int height);

}  // namespace slime

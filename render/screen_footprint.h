// The pixels the slime can change: where a primary ray may meet its bounding sphere (or, on a
// varnished floor, that sphere's mirror image), or see a floor point the sphere may shadow. Every
// other pixel shows the floor or the sky exactly as it did last frame while the camera stays, so the
// renderer copies it instead of tracing it again.
#pragma once

#include "core/camera.h"
#include "render/shading_parameters.h"
#include "render/slime_geometry.h"

namespace slime {

// Pixels [x0, x1) × [y0, y1); empty when x0 >= x1 or y0 >= y1.
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
};

// A rectangle holding every pixel the slime can affect in a width × height image: the screen bounds
// of the sphere's bounding box, and of the box's shadow on the floor z = 0 cast from the point light
// (the shadow of a box below the light lies inside the hull of its corners projected from the light),
// widened by two pixels for rounding. Conservative: the whole image when a corner lies behind the eye
// or a shadow reaches to infinity (the light no higher than the box's top).
PixelRect slimeFootprint(const Camera& camera, const SlimeGeometry& geometry, const ShadingParameters& parameters,
                         int width, int height);

}  // namespace slime

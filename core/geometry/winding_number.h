// The generalised winding number of closed triangle surfaces (Jacobson, Kavan & Sorkine-Hornung,
// "Robust inside-outside segmentation using generalized winding numbers", SIGGRAPH 2013):
//     w(p) = Σ_t Ω_t(p) / 4π,
// Ω_t the signed solid angle of triangle t seen from p (Van Oosterom & Strackee 1983:
// tan(Ω/2) = a·(b×c) / (|a||b||c| + (a·b)|c| + (b·c)|a| + (c·a)|b|), a, b, c its corners − p).
// Outside every surface w = 0, inside one 1; where a slime has passed through itself, the points inside
// both sheets have w = 2. The fold's oracle (docs/physics.md, self-contact) counts them.
#pragma once

#include "core/geometry/surface_view.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <span>

namespace slime {

double solidAngle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& point);

// w(point) summed over every surface.
double windingNumber(std::span<const SurfaceView> surfaces, const glm::dvec3& point);

// Points taken, and of them those inside two sheets (w ≥ 1.5) deeper than the measure's depth.
struct InsideTwice {
  std::size_t points = 0;
  std::size_t insideTwice = 0;
  double deepest = 0.0;  // the largest distance to the surfaces of a point counted, m
  double share() const { return points > 0 ? static_cast<double>(insideTwice) / static_cast<double>(points) : 0.0; }
};

// A grid of n × n × n points over the surfaces' bounding box (cell centres): a point counts when its
// winding number is at least 1.5 and it lies more than `depth` from every triangle.
InsideTwice insideTwiceOnGrid(std::span<const SurfaceView> surfaces, int n, double depth);

// One point under each vertex, `depth` inward along its area-weighted normal: counts when its winding
// number is at least 1.5 (the vertex's own sheet lies more than `depth` inside another one).
InsideTwice insideTwiceUnderVertices(std::span<const SurfaceView> surfaces, double depth);

// The distance from `point` to the nearest triangle of the surfaces, m.
double distanceToSurfaces(std::span<const SurfaceView> surfaces, const glm::dvec3& point);

}  // namespace slime

// Grabbing the slime: find the surface point nearest to where the user points, take the mass points
// within a radius of it, and drive them kinematically (inverse mass 0) towards a moving target,
// like the seed ("move the grabbed points to where the mouse points") but rate-limited so a jump of
// the mouse never injects an absurd velocity. Release restores their masses.
#pragma once

#include "core/icosphere.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace slime {

// The fastest the grabbed points follow the grab target, m/s: a target that jumps (a mouse flick, a
// scenario's 1 m drag in 10 ms) is followed at this speed, never faster. Tests that drag quickly
// state their physical limit with it.
constexpr double kGrabSpeed = 1.5;

// Closest point to p on triangle abc (Ericson, Real-Time Collision Detection, 2005, §5.1.5).
glm::dvec3 closestPointOnTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                  const glm::dvec3& c);

// The point of the mesh surface nearest to `point` (brute force over the triangles).
glm::dvec3 nearestSurfacePoint(const std::vector<glm::dvec3>& positions,
                               const std::vector<Triangle>& triangles, const glm::dvec3& point);

// Indices (ascending) of the positions within `radius` of `center`.
std::vector<std::uint32_t> pointsWithinRadius(const std::vector<glm::dvec3>& positions,
                                              const glm::dvec3& center, double radius);

// Moves `anchor` towards `target` by at most maxStep (m).
glm::dvec3 stepTowards(const glm::dvec3& anchor, const glm::dvec3& target, double maxStep);

}  // namespace slime

#include "core/geometry/winding_number.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace slime {
namespace {

constexpr double kInsideTwice = 1.5;  // w of a point inside two sheets is 2; inside one, 1

// The squared distance from p to triangle abc (Ericson, Real-Time Collision Detection, 5.1.5).
double squaredDistanceToTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  const auto squared = [&](const glm::dvec3& q) { return glm::dot(p - q, p - q); };
  if (d1 <= 0.0 && d2 <= 0.0) return squared(a);
  const glm::dvec3 bp = p - b;
  const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return squared(b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return squared(a + (d1 / (d1 - d3)) * ab);
  const glm::dvec3 cp = p - c;
  const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return squared(c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return squared(a + (d2 / (d2 - d6)) * ac);
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return squared(b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b));
  const double denominator = 1.0 / (va + vb + vc);
  return squared(a + ab * (vb * denominator) + ac * (vc * denominator));
}

}  // namespace

double solidAngle(const glm::dvec3& a0, const glm::dvec3& b0, const glm::dvec3& c0, const glm::dvec3& point) {
  const glm::dvec3 a = a0 - point, b = b0 - point, c = c0 - point;
  const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
  const double numerator = glm::dot(a, glm::cross(b, c));
  const double denominator = la * lb * lc + glm::dot(a, b) * lc + glm::dot(b, c) * la + glm::dot(c, a) * lb;
  return 2.0 * std::atan2(numerator, denominator);
}

double windingNumber(std::span<const SurfaceView> surfaces, const glm::dvec3& point) {
  double total = 0.0;
  for (const SurfaceView& surface : surfaces)
    for (const Triangle& t : surface.triangles)
      total += solidAngle(surface.positions[t.x], surface.positions[t.y], surface.positions[t.z], point);
  return total / (4.0 * std::numbers::pi);
}

double distanceToSurfaces(std::span<const SurfaceView> surfaces, const glm::dvec3& point) {
  double nearest = std::numeric_limits<double>::infinity();
  for (const SurfaceView& surface : surfaces)
    for (const Triangle& t : surface.triangles)
      nearest = std::min(nearest, squaredDistanceToTriangle(point, surface.positions[t.x], surface.positions[t.y],
                                                            surface.positions[t.z]));
  return std::sqrt(nearest);
}

InsideTwice insideTwiceOnGrid(std::span<const SurfaceView> surfaces, int n, double depth) {
  InsideTwice measure;
  glm::dvec3 low(std::numeric_limits<double>::infinity()), high(-std::numeric_limits<double>::infinity());
  for (const SurfaceView& surface : surfaces)
    for (const glm::dvec3& p : surface.positions) {
      low = glm::min(low, p);
      high = glm::max(high, p);
    }
  if (n <= 0 || !(low.x <= high.x)) return measure;
  const glm::dvec3 cell = (high - low) / static_cast<double>(n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const glm::dvec3 point = low + cell * glm::dvec3(i + 0.5, j + 0.5, k + 0.5);
        ++measure.points;
        if (windingNumber(surfaces, point) < kInsideTwice) continue;
        const double distance = distanceToSurfaces(surfaces, point);
        if (distance <= depth) continue;
        ++measure.insideTwice;
        measure.deepest = std::max(measure.deepest, distance);
      }
  return measure;
}

InsideTwice insideTwiceUnderVertices(std::span<const SurfaceView> surfaces, double depth) {
  InsideTwice measure;
  std::vector<glm::dvec3> normals;
  for (const SurfaceView& surface : surfaces) {
    normals.assign(surface.positions.size(), glm::dvec3(0.0));
    for (const Triangle& t : surface.triangles) {
      const glm::dvec3 n = glm::cross(surface.positions[t.y] - surface.positions[t.x],
                                      surface.positions[t.z] - surface.positions[t.x]);  // 2 A n̂
      normals[t.x] += n;
      normals[t.y] += n;
      normals[t.z] += n;
    }
    for (std::size_t v = 0; v < surface.positions.size(); ++v) {
      const double length = glm::length(normals[v]);
      if (length <= 0.0) continue;
      const glm::dvec3 point = surface.positions[v] - (depth / length) * normals[v];
      ++measure.points;
      if (windingNumber(surfaces, point) < kInsideTwice) continue;
      ++measure.insideTwice;
      measure.deepest = std::max(measure.deepest, distanceToSurfaces(surfaces, point));
    }
  }
  return measure;
}

}  // namespace slime

#include "render/trace/brute_tracer.h"

#include <glm/geometric.hpp>

#include <cmath>

namespace slime {

float intersectTriangle(const Ray& ray, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, float& u, float& v) {
  const glm::vec3 edge1 = b - a, edge2 = c - a;
  const glm::vec3 p = glm::cross(ray.direction, edge2);
  const float determinant = glm::dot(edge1, p);
  if (determinant == 0.0f || !std::isfinite(determinant)) return kInfinity;  // parallel or degenerate
  const float inverse = 1.0f / determinant;
  const glm::vec3 s = ray.origin - a;
  u = glm::dot(s, p) * inverse;
  if (u < 0.0f || u > 1.0f) return kInfinity;
  const glm::vec3 q = glm::cross(s, edge1);
  v = glm::dot(ray.direction, q) * inverse;
  if (v < 0.0f || u + v > 1.0f) return kInfinity;
  const float t = glm::dot(edge2, q) * inverse;
  return t >= ray.tNear && t <= ray.tFar ? t : kInfinity;
}

float intersectSphere(const Ray& ray, const glm::vec3& center, float radius) {
  // t² − 2 t (d·(c−o)) + |c−o|² − r² = 0 with unit d; the half-b form keeps precision.
  const glm::vec3 toCenter = center - ray.origin;
  const float halfB = glm::dot(ray.direction, toCenter);
  const glm::vec3 perpendicular = toCenter - halfB * ray.direction;
  const float discriminant = radius * radius - glm::dot(perpendicular, perpendicular);
  if (discriminant < 0.0f) return kInfinity;
  const float root = std::sqrt(discriminant);
  const float nearT = halfB - root, farT = halfB + root;
  if (nearT >= ray.tNear && nearT <= ray.tFar) return nearT;
  if (farT >= ray.tNear && farT <= ray.tFar) return farT;
  return kInfinity;
}

SlimeHit BruteTracer::intersect(const Ray& ray) const {
  SlimeHit hit;
  if (!geometry_.mayHit(ray)) return hit;
  if (geometry_.analyticSphere) {
    const float t = intersectSphere(ray, geometry_.sphereCenter, geometry_.sphereRadius);
    if (t < kInfinity) {
      hit.t = t;
      hit.primitive = 0;
    }
    return hit;
  }
  return closestTriangleHit(ray, geometry_.triangles, nullptr);
}

void BruteTracer::intersectNonSupporting8(const Ray* rays, const bool* active, SlimeHit* hits) const {
  for (int i = 0; i < 8; ++i) {
    hits[i] = SlimeHit{};
    if (!active[i] || geometry_.analyticSphere || !geometry_.mayHit(rays[i])) continue;
    hits[i] = closestTriangleHit(rays[i], geometry_.nonSupportingTriangles, &geometry_.nonSupportingPrimitives);
  }
}

SlimeHit BruteTracer::closestTriangleHit(const Ray& ray, const std::vector<Triangle>& triangles,
                                         const std::vector<std::uint32_t>* primitives) const {
  SlimeHit hit;
  Ray segment = ray;
  const auto& positions = geometry_.positions;
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const Triangle& triangle = triangles[i];
    float u = 0.0f, v = 0.0f;
    const float t = intersectTriangle(segment, positions[triangle.x], positions[triangle.y], positions[triangle.z], u, v);
    if (t < segment.tFar) {
      segment.tFar = t;
      hit = SlimeHit{t, primitives ? (*primitives)[i] : static_cast<std::uint32_t>(i), u, v};
    }
  }
  return hit;
}

}  // namespace slime

#include "render/slime_geometry.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace slime {
namespace {

// For each edge shared by two triangles: (a, b, opposite in one triangle, opposite in the other).
std::vector<glm::u32vec4> buildEdgeQuads(const std::vector<Triangle>& triangles) {
  std::unordered_map<std::uint64_t, glm::u32vec3> firstSide;  // edge key → (a, b, opposite)
  std::vector<glm::u32vec4> quads;
  firstSide.reserve(triangles.size() * 2);
  quads.reserve(triangles.size() * 3 / 2);
  for (const Triangle& t : triangles) {
    const std::uint32_t corners[3] = {t.x, t.y, t.z};
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = corners[k], b = corners[(k + 1) % 3], opposite = corners[(k + 2) % 3];
      const std::uint64_t key = (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
      const auto found = firstSide.find(key);
      if (found == firstSide.end()) {
        firstSide.emplace(key, glm::u32vec3(a, b, opposite));
      } else {
        quads.emplace_back(found->second.x, found->second.y, found->second.z, opposite);
        firstSide.erase(found);
      }
    }
  }
  // An edge with one triangle (an open mesh) leaves the surface non-closed: never call it convex.
  if (!firstSide.empty()) quads.clear();
  return quads;
}

}  // namespace

bool SlimeGeometry::update(const std::vector<glm::dvec3>& newPositions, const std::vector<Triangle>& newTriangles) {
  const bool topologyChanged = newTriangles != triangles || newPositions.size() != vertexCount();
  if (topologyChanged) {
    triangles = newTriangles;
    edgeQuads = buildEdgeQuads(triangles);
  }
  positions.resize(newPositions.size() + 1);
  glm::vec3 low(kInfinity), high(-kInfinity);
  for (std::size_t i = 0; i < newPositions.size(); ++i) {
    positions[i] = glm::vec3(newPositions[i]);
    // A non-finite vertex (a diverged simulation) would poison the BVH: pin it to the origin.
    if (!std::isfinite(positions[i].x + positions[i].y + positions[i].z)) positions[i] = glm::vec3(0.0f);
    low = glm::min(low, positions[i]);
    high = glm::max(high, positions[i]);
  }
  positions.back() = glm::vec3(0.0f);

  // Vertex normals: the sum of the faces' cross products, i.e. area-weighted face normals.
  // The faces' own unit normals are kept too: a hit then costs a lookup, not three vertex loads.
  normals.assign(newPositions.size(), glm::vec3(0.0f));
  faceNormals.resize(triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const Triangle& t = triangles[i];
    faceNormals[i] = glm::cross(positions[t.y] - positions[t.x], positions[t.z] - positions[t.x]);
    normals[t.x] += faceNormals[i];
    normals[t.y] += faceNormals[i];
    normals[t.z] += faceNormals[i];
  }
  for (glm::vec3& n : normals) {
    const float length = glm::length(n);
    n = length > 0.0f && std::isfinite(length) ? n / length : glm::vec3(0.0f, 0.0f, 1.0f);
  }
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const Triangle& t = triangles[i];
    const float length = glm::length(faceNormals[i]);
    if (length > 0.0f && std::isfinite(length)) {
      faceNormals[i] /= length;
    } else {
      // A collapsed (zero-area) triangle has no normal of its own: fall back to its vertex normals.
      const glm::vec3 average = normals[t.x] + normals[t.y] + normals[t.z];
      const float averageLength = glm::length(average);
      faceNormals[i] = averageLength > 0.0f ? average / averageLength : glm::vec3(0.0f, 0.0f, 1.0f);
    }
  }

  boundCenter = newPositions.empty() ? glm::vec3(0.0f) : 0.5f * (low + high);
  float radius2 = 0.0f;
  glm::vec3 sum(0.0f);
  for (std::size_t i = 0; i < newPositions.size(); ++i) {
    const glm::vec3 d = positions[i] - boundCenter;
    radius2 = std::max(radius2, glm::dot(d, d));
    sum += positions[i];
  }
  boundRadius = std::sqrt(radius2);
  meshBoundCenter = boundCenter;
  meshBoundRadius = boundRadius;
  if (!newPositions.empty()) sphereCenter = sum / static_cast<float>(newPositions.size());
  analyticSphere = sphereRequested && !newPositions.empty();
  if (analyticSphere) {
    boundCenter = sphereCenter;
    boundRadius = sphereRadius;
  }

  // Convex when, across every edge, the far vertex of one triangle lies below the other's plane.
  const float tolerance = kConvexTolerance * boundRadius;
  convex = !edgeQuads.empty() && boundRadius > 0.0f;
  for (std::size_t i = 0; convex && i < edgeQuads.size(); ++i) {
    const glm::u32vec4& q = edgeQuads[i];
    const glm::vec3 a = positions[q.x], b = positions[q.y], c = positions[q.z], far = positions[q.w];
    const glm::vec3 normal = glm::cross(b - a, c - a);  // outward for the triangle (a, b, c)
    const float length = glm::length(normal);
    if (!(length > 0.0f)) continue;  // a collapsed triangle says nothing
    if (glm::dot(far - a, normal) > tolerance * length) convex = false;
  }
  return topologyChanged;
}

void SlimeGeometry::setAnalyticSphere(bool enabled, float radius) {
  sphereRequested = enabled;
  analyticSphere = enabled && vertexCount() > 0;
  sphereRadius = radius;
  boundCenter = analyticSphere ? sphereCenter : meshBoundCenter;
  boundRadius = analyticSphere ? sphereRadius : meshBoundRadius;
}

glm::vec3 SlimeGeometry::shadingNormal(const SlimeHit& hit, const glm::vec3& point, bool smooth) const {
  if (analyticSphere || !smooth) return geometricNormal(hit, point);
  const Triangle& t = triangles[hit.primitive];
  const glm::vec3 n = (1.0f - hit.u - hit.v) * normals[t.x] + hit.u * normals[t.y] + hit.v * normals[t.z];
  const float length = glm::length(n);
  return length > 1e-6f && std::isfinite(length) ? n / length : geometricNormal(hit, point);
}

}  // namespace slime

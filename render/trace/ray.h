// A ray, a hit on the slime, and the one query both intersection back-ends answer (Embree and the
// brute-force oracle). Everything downstream of the hit (normals, shading, transport) is shared.
#pragma once

#include <glm/vec3.hpp>

#include <cstdint>
#include <limits>

namespace slime {

constexpr float kInfinity = std::numeric_limits<float>::infinity();
constexpr std::uint32_t kNoPrimitive = 0xFFFFFFFFu;

struct Ray {
  glm::vec3 origin{0.0f};
  glm::vec3 direction{0.0f, 0.0f, 1.0f};  // unit length
  float tNear = 0.0f;
  float tFar = kInfinity;
};

// The first crossing of a ray with the slime's surface.
struct SlimeHit {
  float t = kInfinity;
  std::uint32_t primitive = kNoPrimitive;  // triangle index (mesh) or 0 (analytic sphere)
  float u = 0.0f, v = 0.0f;                // barycentrics of vertices 1 and 2 (mesh)
  bool valid() const { return primitive != kNoPrimitive; }
};

// Every crossing of one segment with the slime's surface, nearest first
// (SlimeIntersector::lightCrossings8).
struct SegmentCrossings {
  static constexpr int kCapacity = 16;
  int count = 0;  // kCapacity + 1: more crossings than that (hits then holds kCapacity of them, unsorted)
  SlimeHit hits[kCapacity];
};

// Closest-hit queries against the slime alone (the floor and sky are analytic, see whitted_tracer.h).
class SlimeIntersector {
 public:
  virtual ~SlimeIntersector() = default;
  // The closest crossing with t in [ray.tNear, ray.tFar]; an invalid hit if none.
  virtual SlimeHit intersect(const Ray& ray) const = 0;
  // Up to 8 coherent primary rays at once; rays with active[i] == false are skipped.
  virtual void intersect8(const Ray* rays, const bool* active, SlimeHit* hits) const {
    for (int i = 0; i < 8; ++i) hits[i] = active[i] ? intersect(rays[i]) : SlimeHit{};
  }
  // intersect8 against the triangles that do not support the slime alone (SlimeGeometry::
  // nonSupportingTriangles; none for the analytic sphere); a hit names the triangle by its index in
  // the whole mesh. A small set: this query costs a fraction of intersect8's.
  virtual void intersectNonSupporting8(const Ray* rays, const bool* active, SlimeHit* hits) const = 0;
  // Every crossing of each active segment [tNear, tFar] with the slime's surface, for shadow rays
  // (segments with one end at the light): true if this back-end answers such questions for the
  // current light, false (and nothing written) if the caller must walk from crossing to crossing
  // with intersect8.
  virtual bool lightCrossings8(const Ray* rays, const bool* active, SegmentCrossings* crossings) const {
    (void)rays, (void)active, (void)crossings;
    return false;
  }
  // For kExitRays rays (those active) whose origins lie inside the slime: where each leaves it through
  // a supporting triangle (render/slime/exit_walk.h), found without a query where it can be, else an
  // invalid hit; `exitPoints[i]` is a point of ray i beyond the slime. True if this back-end answers
  // such questions, false (nothing written) if the caller must ask intersect8 (the reversed query).
  static constexpr int kExitRays = 16;
  virtual bool supportingExits(const Ray* rays, const glm::vec3* exitPoints, const bool* active, SlimeHit* hits) const {
    (void)rays, (void)exitPoints, (void)active, (void)hits;
    return false;
  }
  // The closest crossings of up to 8 rays from the eye (primary rays): true if this back-end answers
  // them for the current eye without intersect8, false (nothing written) if the caller must ask intersect8.
  virtual bool primaryHits8(const Ray* rays, const bool* active, SlimeHit* hits) const {
    (void)rays, (void)active, (void)hits;
    return false;
  }
};

}  // namespace slime

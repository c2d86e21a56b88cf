#include "render/slime/exit_walk.h"

#include "render/slime/slime_geometry.h"
#include "render/simd/wide_lanes.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace slime {

void ExitWalk::connect(const std::vector<Triangle>& triangles) {
  // Each edge once per side, keyed by its two vertices; the two sides of an edge meet when sorted.
  struct Side {
    std::uint64_t key;
    std::uint32_t slot;  // 3 × triangle + edge
  };
  std::vector<Side> sides;
  sides.reserve(3 * triangles.size());
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Triangle& t = triangles[f];
    const std::uint32_t ends[3][2] = {{t.y, t.z}, {t.z, t.x}, {t.x, t.y}};
    for (std::uint32_t e = 0; e < 3; ++e) {
      const std::uint64_t low = std::min(ends[e][0], ends[e][1]), high = std::max(ends[e][0], ends[e][1]);
      sides.push_back({low << 32 | high, static_cast<std::uint32_t>(3 * f + e)});
    }
  }
  std::sort(sides.begin(), sides.end(), [](const Side& a, const Side& b) { return a.key < b.key || (a.key == b.key && a.slot < b.slot); });
  neighbours_.assign(3 * triangles.size(), kNoPrimitive);
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t end = i + 1;
    while (end < sides.size() && sides[end].key == sides[i].key) ++end;
    if (end - i == 2) {  // an edge of exactly two triangles
      neighbours_[sides[i].slot] = sides[i + 1].slot / 3;
      neighbours_[sides[i + 1].slot] = sides[i].slot / 3;
    }
    i = end;
  }
}

std::size_t ExitWalk::cell(const glm::vec3& direction) const {
  // The cube face of the largest component, then that face's two other coordinates over [−1, 1].
  const glm::vec3 magnitude = glm::abs(direction);
  int face = 0;
  float s = 0.0f, t = 0.0f, major = 0.0f;
  if (magnitude.x >= magnitude.y && magnitude.x >= magnitude.z) {
    face = direction.x >= 0.0f ? 0 : 1;
    major = magnitude.x, s = direction.y, t = direction.z;
  } else if (magnitude.y >= magnitude.z) {
    face = direction.y >= 0.0f ? 2 : 3;
    major = magnitude.y, s = direction.z, t = direction.x;
  } else {
    face = direction.z >= 0.0f ? 4 : 5;
    major = magnitude.z, s = direction.x, t = direction.y;
  }
  const float scale = 0.5f * static_cast<float>(side_) / major;
  const int column = std::clamp(static_cast<int>((s + major) * scale), 0, side_ - 1);
  const int row = std::clamp(static_cast<int>((t + major) * scale), 0, side_ - 1);
  return (static_cast<std::size_t>(face) * side_ + row) * side_ + column;
}

void ExitWalk::map(const SlimeGeometry& geometry) {
  const std::vector<Triangle>& triangles = geometry.triangles;
  const std::vector<glm::vec3>& positions = geometry.positions;
  corners_.resize(triangles.size());
  // About two triangles a cell on a round slime: the guess is then a step or two from the exit.
  side_ = std::max(1, static_cast<int>(std::lround(std::sqrt(static_cast<double>(triangles.size()) / 12.0))));
  cells_.assign(6 * static_cast<std::size_t>(side_) * side_, kNoPrimitive);
  center_ = geometry.meshBoundCenter;
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Triangle& t = triangles[f];
    corners_[f] = Corner{positions[t.x], positions[t.y] - positions[t.x], positions[t.z] - positions[t.x], geometry.faceNormals[f]};
    const glm::vec3 direction = (positions[t.x] + positions[t.y] + positions[t.z]) * (1.0f / 3.0f) - center_;
    if (glm::dot(direction, direction) > 0.0f) cells_[cell(direction)] = static_cast<std::uint32_t>(f);
  }
  // An empty cell (a flattened or stretched part of the surface) takes the last filled one's
  // triangle: a worse guess, which the walk mends or gives up on.
  std::uint32_t last = triangles.empty() ? kNoPrimitive : 0u;
  for (std::uint32_t& c : cells_) {
    if (c == kNoPrimitive) c = last;
    else last = c;
  }
}

bool ExitWalk::ready(const SlimeGeometry& geometry) const {
  return !cells_.empty() && corners_.size() == geometry.triangles.size() && neighbours_.size() == 3 * geometry.triangles.size();
}

void ExitWalk::supportingExits(const SlimeGeometry& geometry, const Ray* rays, const glm::vec3* exitPoints,
                               const bool* active, SlimeHit* hits) const {
#if defined(SLIME_WIDE_LANES)
  for (int first = 0; first < kBatch; first += kWidestLanes)
    walkInLanes<kWidestLanes>(geometry, rays + first, exitPoints + first, active + first, hits + first);
#else
  for (int first = 0; first < kBatch; first += 8) walkOneByOne(geometry, rays + first, exitPoints + first, active + first, hits + first);
#endif
}

void ExitWalk::walkOneByOne(const SlimeGeometry& geometry, const Ray* rays, const glm::vec3* exitPoints,
                            const bool* active, SlimeHit* hits) const {
  std::uint32_t at[8];
  bool walking[8];
  const bool walks = ready(geometry);
  for (int i = 0; i < 8; ++i) {
    hits[i] = SlimeHit{};
    walking[i] = false;
    if (!active[i] || !walks) continue;
    const Ray& ray = rays[i];
    const glm::vec3 direction = exitPoints[i] - center_;
    if (!(glm::dot(direction, direction) > 0.0f)) continue;
    std::uint32_t f = cells_[cell(direction)];
    // A better guess: the cell in the direction where the ray meets the first guess's plane.
    const Corner& corner = corners_[f];
    const float distance = glm::dot(corner.normal, corner.a - ray.origin) / glm::dot(corner.normal, ray.direction);
    if (distance > 0.0f && distance <= ray.tFar) {
      const glm::vec3 seen = ray.origin + distance * ray.direction - center_;
      if (glm::dot(seen, seen) > 0.0f) f = cells_[cell(seen)];
    }
    at[i] = f;
    walking[i] = true;
  }
  // The rays step side by side: each step of one lane is independent of the others'.
  for (int step = 0; step < kMaxSteps; ++step) {
    bool any = false;
    for (int i = 0; i < 8; ++i) {
      if (!walking[i]) continue;
      const Ray& ray = rays[i];
      const std::uint32_t f = at[i];
      // Möller–Trumbore, as intersectTriangle (brute_tracer.cpp); the coordinates, scaled by the
      // determinant's sign, choose the edge to step over when the crossing lies outside.
      const Corner& corner = corners_[f];
      const glm::vec3 p = glm::cross(ray.direction, corner.edge2);
      const float determinant = glm::dot(corner.edge1, p);
      const glm::vec3 s = ray.origin - corner.a;
      const glm::vec3 q = glm::cross(s, corner.edge1);
      const float sign = determinant > 0.0f ? 1.0f : -1.0f;
      const float u = sign * glm::dot(s, p), v = sign * glm::dot(ray.direction, q), w = sign * determinant - u - v;
      if (u >= 0.0f && v >= 0.0f && w >= 0.0f) {
        walking[i] = false;
        if (determinant == 0.0f || !std::isfinite(determinant) || !geometry.supports(f)) continue;
        const float inverse = 1.0f / determinant;
        const float distance = glm::dot(corner.edge2, q) * inverse;
        if (distance >= ray.tNear && distance <= ray.tFar)
          hits[i] = SlimeHit{distance, f, glm::dot(s, p) * inverse, glm::dot(ray.direction, q) * inverse};
        continue;
      }
      // Over the edge opposite the most negative coordinate: (b, c) for w, (c, a) for u, (a, b) for v.
      const int edge = w <= u && w <= v ? 0 : u <= v ? 1 : 2;
      at[i] = neighbours_[3 * static_cast<std::size_t>(f) + edge];
      walking[i] = at[i] != kNoPrimitive;
      any = any || walking[i];
    }
    if (!any) break;
  }
}

#if defined(SLIME_WIDE_LANES)
namespace {

// base[index] lane by lane, in the build's widest lanes. (The zero-masked forms with AVX-512: GCC 12
// warns that the plain ones read an uninitialised vector.)
#if defined(SLIME_WIDE_LANES_16)
Wide<16>::F gather(const float* base, Wide<16>::I index) {
  return (Wide<16>::F)_mm512_mask_i32gather_ps(_mm512_setzero_ps(), 0xFFFF, (__m512i)index, base, 4);
}
Wide<16>::I gather(const std::uint32_t* base, Wide<16>::I index) {
  return (Wide<16>::I)_mm512_mask_i32gather_epi32(_mm512_setzero_si512(), 0xFFFF, (__m512i)index,
                                                   reinterpret_cast<const int*>(base), 4);
}
#else
Wide<8>::F gather(const float* base, Wide<8>::I index) { return (Wide<8>::F)_mm256_i32gather_ps(base, (__m256i)index, 4); }
Wide<8>::I gather(const std::uint32_t* base, Wide<8>::I index) {
  return (Wide<8>::I)_mm256_i32gather_epi32(reinterpret_cast<const int*>(base), (__m256i)index, 4);
}
#endif

template <int N>
struct Vectors {
  typename Wide<N>::F x, y, z;
};
// glm::cross and glm::dot, lane by lane, in their order of operations.
template <int N>
Vectors<N> cross(const Vectors<N>& a, const Vectors<N>& b) {
  return {a.y * b.z - b.y * a.z, a.z * b.x - b.z * a.x, a.x * b.y - b.x * a.y};
}
template <int N>
typename Wide<N>::F dot(const Vectors<N>& a, const Vectors<N>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

}  // namespace

template <int N>
void ExitWalk::walkInLanes(const SlimeGeometry& geometry, const Ray* rays, const glm::vec3* exitPoints,
                           const bool* active, SlimeHit* hits) const {
  using F = typename Wide<N>::F;
  using I = typename Wide<N>::I;
  using V = Vectors<N>;
  for (int i = 0; i < N; ++i) hits[i] = SlimeHit{};
  if (!ready(geometry)) return;
  V origin, direction, exitPoint;
  F tNear, tFar;
  I walking{};
  for (int i = 0; i < N; ++i) {
    const Ray& ray = active[i] ? rays[i] : rays[0];  // an inactive lane walks a copy, unused
    origin.x[i] = ray.origin.x, origin.y[i] = ray.origin.y, origin.z[i] = ray.origin.z;
    direction.x[i] = ray.direction.x, direction.y[i] = ray.direction.y, direction.z[i] = ray.direction.z;
    const glm::vec3& exit = active[i] ? exitPoints[i] : exitPoints[0];
    exitPoint.x[i] = exit.x, exitPoint.y[i] = exit.y, exitPoint.z[i] = exit.z;
    tNear[i] = ray.tNear, tFar[i] = ray.tFar;
    walking[i] = active[i] ? -1 : 0;
  }
  const float* corner = &corners_[0].a.x;
  constexpr int kStride = sizeof(Corner) / sizeof(float);
  const F none{};
  const F sideHalf = splat<F>(0.5f * static_cast<float>(side_));
  const F lastCell = splat<F>(static_cast<float>(side_ - 1));
  // cell() in lanes.
  const auto cellOf = [&](const V& d) {
    const F ax = absLanes(d.x), ay = absLanes(d.y), az = absLanes(d.z);
    const I alongX = (ax >= ay) & (ax >= az), alongY = ~alongX & (ay >= az);
    const F major = alongX ? ax : alongY ? ay : az;
    const F s = alongX ? d.y : alongY ? d.z : d.x;
    const F t = alongX ? d.z : alongY ? d.x : d.y;
    const I positive = alongX ? (d.x >= 0.0f) : alongY ? (d.y >= 0.0f) : (d.z >= 0.0f);
    const I face = (alongX ? I{} + 0 : alongY ? I{} + 2 : I{} + 4) + (positive ? I{} : I{} + 1);
    const F scale = sideHalf / major;
    // std::clamp(int(x), 0, side − 1): the conversion truncates; clamping before it keeps it in range.
    const I column = __builtin_convertvector(minLanes(maxLanes((s + major) * scale, none), lastCell), I);
    const I row = __builtin_convertvector(minLanes(maxLanes((t + major) * scale, none), lastCell), I);
    return (face * side_ + row) * side_ + column;
  };
  const auto field = [&](I f, int offset) { return gather(corner + offset, f * kStride); };
  const V fromCenter{exitPoint.x - center_.x, exitPoint.y - center_.y, exitPoint.z - center_.z};
  walking &= dot(fromCenter, fromCenter) > 0.0f;
  I f = gather(cells_.data(), walking ? cellOf(fromCenter) : I{});
  {
    // A better guess: the cell in the direction where the ray meets the first guess's plane.
    const V a{field(f, 0), field(f, 1), field(f, 2)}, normal{field(f, 9), field(f, 10), field(f, 11)};
    const V toCorner{a.x - origin.x, a.y - origin.y, a.z - origin.z};
    const F distance = dot(normal, toCorner) / dot(normal, direction);
    const V seen{origin.x + distance * direction.x - center_.x, origin.y + distance * direction.y - center_.y,
                 origin.z + distance * direction.z - center_.z};
    const I better = walking & (distance > 0.0f) & (distance <= tFar) & (dot(seen, seen) > 0.0f);
    if (maskBits(better) != 0) f = better ? gather(cells_.data(), better ? cellOf(seen) : I{}) : f;
  }
  I found{};
  F foundT{}, foundU{}, foundV{};
  for (int step = 0; step < kMaxSteps && maskBits(walking) != 0; ++step) {
    const I at = walking ? f : I{};
    const V a{field(at, 0), field(at, 1), field(at, 2)};
    const V edge1{field(at, 3), field(at, 4), field(at, 5)}, edge2{field(at, 6), field(at, 7), field(at, 8)};
    const V p = cross(direction, edge2);
    const F determinant = dot(edge1, p);
    const V s{origin.x - a.x, origin.y - a.y, origin.z - a.z};
    const V q = cross(s, edge1);
    const F sign = determinant > 0.0f ? splat<F>(1.0f) : splat<F>(-1.0f);
    const F su = dot(s, p), sv = dot(direction, q);
    const F u = sign * su, v = sign * sv, w = sign * determinant - u - v;
    const I inside = walking & (u >= 0.0f) & (v >= 0.0f) & (w >= 0.0f);
    if (maskBits(inside) != 0) {
      // The scalar test's checks, then t, u, v divided by the determinant as intersectTriangle does.
      const F inverse = 1.0f / determinant;
      const F distance = dot(edge2, q) * inverse;
      const I finite = (determinant != 0.0f) & (absLanes(determinant) <= splat<F>(3.402823466e38f));
      const I accepted = inside & finite & (distance >= tNear) & (distance <= tFar);
      found |= accepted;
      foundT = accepted ? distance : foundT;
      foundU = accepted ? su * inverse : foundU;
      foundV = accepted ? sv * inverse : foundV;
    }
    // Over the edge opposite the most negative coordinate: (b, c) for w, (c, a) for u, (a, b) for v.
    const I edge = (w <= u) & (w <= v) ? I{} : (u <= v) ? I{} + 1 : I{} + 2;
    const I stepping = walking & ~inside;
    const I next = gather(neighbours_.data(), stepping ? at * 3 + edge : I{});
    f = stepping ? next : f;
    walking = stepping & (next != static_cast<std::int32_t>(kNoPrimitive));
  }
  for (int i = 0; i < N; ++i) {
    if (found[i] == 0 || !geometry.supports(static_cast<std::uint32_t>(f[i]))) continue;
    hits[i] = SlimeHit{foundT[i], static_cast<std::uint32_t>(f[i]), foundU[i], foundV[i]};
  }
}
#endif

}  // namespace slime

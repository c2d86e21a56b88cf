#include "render/slime/pencil_grid.h"

#include "render/simd/lanes.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace slime {
namespace {

// Cells over the grid's square per triangle. The headline's deforming frame took, with 0.25: 47.9,
// 0.5: 46.1, 1: 47.0, 2: 48.1, 4: 48.9 ms on one thread (fewer cells: more triangles to test each
// query; more: a triangle in more cells, a longer build; 2026-11-24).
constexpr float kCellsPerTriangle = 0.5f;
constexpr int kMaxCellsPerSide = 1024;
// The apex must stand this many bounding radii from the centre (the slime within ±56° of the axis).
constexpr float kMinApexDistance = 1.2f;
// Rounding slack of a projected point, relative to the grid's extent (the projection is computed in
// float: about 1e-7 relative; a bin one part in 10^5 too wide costs nothing).
constexpr float kProjectionSlack = 1e-5f;
// Above this many triangles the grid is not built: it is rebuilt for every new shape (and, seen from
// the eye, for every new view), at about 75 ns a triangle (one thread; 0.4 ms at level 4, 1.9 ms at
// level 5, 8.2 ms at level 6 for the light's), while what it saves a frame hardly grows with the
// triangles (the rays are the pixels'). Level 6 (81,920) traced about 1.5× slower with grids, level 5
// (20,480) about as fast (`slime bench render --levels 5-6`, 2026-11-24).
constexpr std::size_t kMaxTriangles = 32768;
// A triangle counts as facing the apex unless its plane has the apex behind it by more than this
// cosine (its normal is rounded: a triangle seen edge-on is kept).
constexpr float kFacingSlack = 1e-4f;

}  // namespace

void PencilGrid::clear() {
  ready_ = false;
  columns_ = rows_ = 0;
  blockBegin_.clear();
  blocks_.clear();
  entries_ = 0;
}

void PencilGrid::project(const glm::vec3& point, float& u, float& v) const {
  const glm::vec3 q = point - apex_;
  const float w = glm::dot(q, axis_);
  u = glm::dot(q, across_) / w;
  v = glm::dot(q, up_) / w;
}

bool PencilGrid::build(const SlimeGeometry& geometry, const glm::vec3& apex, bool facingApexOnly) {
  clear();
  apex_ = apex;
  const std::size_t triangleCount = geometry.triangles.size();
  const float radius = geometry.boundRadius * 1.001f + 1e-6f;
  const glm::vec3 toCenter = geometry.boundCenter - apex;
  const float distance = glm::length(toCenter);
  if (geometry.analyticSphere || triangleCount == 0 || triangleCount > kMaxTriangles || !(radius > 0.0f) || !std::isfinite(distance) ||
      !(distance > kMinApexDistance * radius))
    return false;
  axis_ = toCenter / distance;
  const glm::vec3 helper = std::abs(axis_.x) < 0.6f ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 1.0f, 0.0f);
  across_ = glm::normalize(glm::cross(axis_, helper));
  up_ = glm::cross(axis_, across_);
  wMin_ = distance - radius;
  wMax_ = distance + radius;

  // Every vertex projected; the grid spans them.
  const std::size_t vertexCount = geometry.vertexCount();
  vertexU_.resize(vertexCount);
  vertexV_.resize(vertexCount);
  float uMin = INFINITY, uMax = -INFINITY, vMin = INFINITY, vMax = -INFINITY;
  for (std::size_t i = 0; i < vertexCount; ++i) {
    project(geometry.positions[i], vertexU_[i], vertexV_[i]);
    // SlimeGeometry pins non-finite vertices; a projection that overflows would still make bins of garbage.
    if (!std::isfinite(vertexU_[i]) || !std::isfinite(vertexV_[i])) return false;
    uMin = std::min(uMin, vertexU_[i]);
    uMax = std::max(uMax, vertexU_[i]);
    vMin = std::min(vMin, vertexV_[i]);
    vMax = std::max(vMax, vertexV_[i]);
  }
  if (!(uMax >= uMin && vMax >= vMin) || !std::isfinite(uMax - uMin) || !std::isfinite(vMax - vMin)) return false;
  const float slack = kProjectionSlack * std::max({uMax - uMin, vMax - vMin, 1e-6f});
  uMin -= slack;
  vMin -= slack;
  uMax += slack;
  vMax += slack;
  const float width = uMax - uMin, height = vMax - vMin;
  const float cell = std::sqrt(width * height / (kCellsPerTriangle * static_cast<float>(triangleCount)));
  columns_ = std::clamp(static_cast<int>(std::ceil(width / cell)), 1, kMaxCellsPerSide);
  rows_ = std::clamp(static_cast<int>(std::ceil(height / cell)), 1, kMaxCellsPerSide);
  u0_ = uMin;
  v0_ = vMin;
  inverseCell_ = std::min(static_cast<float>(columns_) / width, static_cast<float>(rows_) / height);

  // Each triangle's cells: those its projection's box (with the slack) touches.
  const auto cellRange = [&](const Triangle& t, int& c0, int& c1, int& r0, int& r1) {
    const float lowU = std::min({vertexU_[t.x], vertexU_[t.y], vertexU_[t.z]}) - slack;
    const float highU = std::max({vertexU_[t.x], vertexU_[t.y], vertexU_[t.z]}) + slack;
    const float lowV = std::min({vertexV_[t.x], vertexV_[t.y], vertexV_[t.z]}) - slack;
    const float highV = std::max({vertexV_[t.x], vertexV_[t.y], vertexV_[t.z]}) + slack;
    c0 = std::clamp(static_cast<int>((lowU - u0_) * inverseCell_), 0, columns_ - 1);
    c1 = std::clamp(static_cast<int>((highU - u0_) * inverseCell_), 0, columns_ - 1);
    r0 = std::clamp(static_cast<int>((lowV - v0_) * inverseCell_), 0, rows_ - 1);
    r1 = std::clamp(static_cast<int>((highV - v0_) * inverseCell_), 0, rows_ - 1);
  };
  const std::size_t cells = static_cast<std::size_t>(columns_) * static_cast<std::size_t>(rows_);
  binned_.assign(triangleCount, 1);
  if (facingApexOnly) {
    // Facing away: the apex more than a hair (cos 1e-4) behind the triangle's plane.
    for (std::size_t f = 0; f < triangleCount; ++f) {
      const glm::vec3 fromApex = geometry.positions[geometry.triangles[f].x] - apex;
      binned_[f] = glm::dot(geometry.faceNormals[f], fromApex) < kFacingSlack * glm::length(fromApex);
    }
  }
  fill_.assign(cells, 0);
  for (std::size_t f = 0; f < triangleCount; ++f) {
    if (!binned_[f]) continue;
    const Triangle& t = geometry.triangles[f];
    int c0, c1, r0, r1;
    cellRange(t, c0, c1, r0, r1);
    for (int r = r0; r <= r1; ++r)
      for (int c = c0; c <= c1; ++c) ++fill_[static_cast<std::size_t>(r) * columns_ + c];
  }
  blockBegin_.resize(cells + 1);
  std::uint32_t blocks = 0;
  for (std::size_t c = 0; c < cells; ++c) {
    blockBegin_[c] = blocks;
    entries_ += fill_[c];
    blocks += (fill_[c] + 7) / 8;
    fill_[c] = 0;
  }
  blockBegin_[cells] = blocks;
  blocks_.assign(blocks, Block{});  // empty lanes: zero edges, never a hit
  for (Block& block : blocks_) std::fill(std::begin(block.primitive), std::end(block.primitive), kNoPrimitive);
  const auto& p = geometry.positions;
  for (std::size_t f = 0; f < triangleCount; ++f) {
    if (!binned_[f]) continue;
    const Triangle& t = geometry.triangles[f];
    const glm::vec3 a = p[t.x], edge1 = p[t.y] - a, edge2 = p[t.z] - a;  // as intersectTriangle computes them
    int c0, c1, r0, r1;
    cellRange(t, c0, c1, r0, r1);
    for (int r = r0; r <= r1; ++r) {
      for (int c = c0; c <= c1; ++c) {
        const std::size_t cellIndex = static_cast<std::size_t>(r) * columns_ + c;
        const std::uint32_t slot = fill_[cellIndex]++;
        Block& block = blocks_[blockBegin_[cellIndex] + slot / 8];
        const int lane = static_cast<int>(slot % 8);
        for (int k = 0; k < 3; ++k) {
          block.corner[k][lane] = a[k];
          block.edge1[k][lane] = edge1[k];
          block.edge2[k][lane] = edge2[k];
        }
        block.primitive[lane] = static_cast<std::uint32_t>(f);
      }
    }
  }
  ready_ = true;
  return true;
}

unsigned PencilGrid::hitLanes(const Block& block, const Ray& ray, float* ts, float* us, float* vs) const {
  // intersectTriangle's operations in its order, 8 triangles against one ray.
  const Lanes dx(ray.direction.x), dy(ray.direction.y), dz(ray.direction.z);
  const Lanes e1x = Lanes::load(block.edge1[0]), e1y = Lanes::load(block.edge1[1]), e1z = Lanes::load(block.edge1[2]);
  const Lanes e2x = Lanes::load(block.edge2[0]), e2y = Lanes::load(block.edge2[1]), e2z = Lanes::load(block.edge2[2]);
  const Lanes px = dy * e2z - e2y * dz, py = dz * e2x - e2z * dx, pz = dx * e2y - e2x * dy;
  const Lanes determinant = e1x * px + e1y * py + e1z * pz;
  const Lanes magnitude = max(determinant, -determinant);
  const LaneMask usable = (magnitude > Lanes(0.0f)) && (magnitude < Lanes(INFINITY));
  if (usable.mask() == 0) return 0;
  const Lanes inverse = Lanes(1.0f) / determinant;
  const Lanes sx = Lanes(ray.origin.x) - Lanes::load(block.corner[0]);
  const Lanes sy = Lanes(ray.origin.y) - Lanes::load(block.corner[1]);
  const Lanes sz = Lanes(ray.origin.z) - Lanes::load(block.corner[2]);
  const Lanes u = (sx * px + sy * py + sz * pz) * inverse;
  const Lanes qx = sy * e1z - e1y * sz, qy = sz * e1x - e1z * sx, qz = sx * e1y - e1x * sy;
  const Lanes v = (dx * qx + dy * qy + dz * qz) * inverse;
  const Lanes t = (e2x * qx + e2y * qy + e2z * qz) * inverse;
  const LaneMask hit = usable && (u >= Lanes(0.0f)) && (u <= Lanes(1.0f)) && (v >= Lanes(0.0f)) &&
                       (u + v <= Lanes(1.0f)) && (t >= Lanes(ray.tNear)) && (t <= Lanes(ray.tFar));
  const unsigned mask = hit.mask();
  if (mask != 0) {
    t.store(ts);
    u.store(us);
    v.store(vs);
  }
  return mask;
}

template <typename Visit>
void PencilGrid::visitBlocks(const Ray& ray, Visit visit) const {
  if (!ready_) return;
  // The part of the segment within the slime's slab along the axis, where w > 0 (projectable).
  const float w0 = glm::dot(ray.origin - apex_, axis_), dw = glm::dot(ray.direction, axis_);
  float tLow = ray.tNear, tHigh = ray.tFar;
  if (std::abs(dw) > 0.0f) {
    const float ta = (wMin_ - w0) / dw, tb = (wMax_ - w0) / dw;
    tLow = std::max(tLow, std::min(ta, tb));
    tHigh = std::min(tHigh, std::max(ta, tb));
  } else if (w0 < wMin_ || w0 > wMax_) {
    return;
  }
  if (!(tLow <= tHigh)) return;
  float ua, va, ub, vb;
  if (ray.origin == apex_) {  // a ray from the apex projects to one point: its direction's
    project(apex_ + ray.direction, ua, va);
    ub = ua;
    vb = va;
  } else {
    project(ray.origin + tLow * ray.direction, ua, va);
    project(ray.origin + tHigh * ray.direction, ub, vb);
  }
  const float slack = kProjectionSlack / inverseCell_;  // about the build's slack, in u and v
  const float lowU = (std::min(ua, ub) - slack - u0_) * inverseCell_, highU = (std::max(ua, ub) + slack - u0_) * inverseCell_;
  const float lowV = (std::min(va, vb) - slack - v0_) * inverseCell_, highV = (std::max(va, vb) + slack - v0_) * inverseCell_;
  if (!(highU >= 0.0f && lowU < static_cast<float>(columns_) && highV >= 0.0f && lowV < static_cast<float>(rows_))) return;
  const int c0 = static_cast<int>(std::max(0.0f, lowU)), c1 = static_cast<int>(std::min(columns_ - 1.0f, highU));
  const int r0 = static_cast<int>(std::max(0.0f, lowV)), r1 = static_cast<int>(std::min(rows_ - 1.0f, highV));
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      const std::size_t cell = static_cast<std::size_t>(r) * columns_ + c;
      for (std::uint32_t b = blockBegin_[cell]; b < blockBegin_[cell + 1]; ++b)
        if (!visit(blocks_[b])) return;
    }
  }
}

void PencilGrid::crossings(const Ray& ray, SegmentCrossings& out) const {
  out.count = 0;
  alignas(32) float ts[8], us[8], vs[8];
  visitBlocks(ray, [&](const Block& block) {
    for (unsigned mask = hitLanes(block, ray, ts, us, vs); mask != 0; mask &= mask - 1) {
      const int lane = __builtin_ctz(mask);
      const std::uint32_t primitive = block.primitive[lane];
      bool seen = false;  // the same triangle from a second cell of the segment's
      for (int k = 0; k < out.count; ++k) seen = seen || out.hits[k].primitive == primitive;
      if (seen) continue;
      if (out.count == SegmentCrossings::kCapacity) {
        out.count = SegmentCrossings::kCapacity + 1;
        return false;
      }
      out.hits[out.count++] = SlimeHit{ts[lane], primitive, us[lane], vs[lane]};
    }
    return true;
  });
  if (out.count > SegmentCrossings::kCapacity) return;
  // Nearest first (insertion sort: a handful of crossings).
  for (int i = 1; i < out.count; ++i) {
    const SlimeHit hit = out.hits[i];
    int j = i;
    for (; j > 0 && out.hits[j - 1].t > hit.t; --j) out.hits[j] = out.hits[j - 1];
    out.hits[j] = hit;
  }
}

SlimeHit PencilGrid::nearest(const Ray& ray) const {
  // As the brute force's closest hit: each hit shortens the segment the next tests ask about.
  SlimeHit best;
  Ray segment = ray;
  alignas(32) float ts[8], us[8], vs[8];
  visitBlocks(ray, [&](const Block& block) {
    for (unsigned mask = hitLanes(block, segment, ts, us, vs); mask != 0; mask &= mask - 1) {
      const int lane = __builtin_ctz(mask);
      if (ts[lane] < segment.tFar || !best.valid()) {
        segment.tFar = ts[lane];
        best = SlimeHit{ts[lane], block.primitive[lane], us[lane], vs[lane]};
      }
    }
    return true;
  });
  return best;
}

}  // namespace slime

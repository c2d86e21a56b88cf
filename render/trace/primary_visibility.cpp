#include "render/trace/primary_visibility.h"

#include "render/simd/lanes.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace slime {
namespace {

// As the eye's grid (pencil_grid.cpp): the eye this many bounding radii from the centre at least,
// and a triangle faces the eye unless its plane has the eye behind it by more than this cosine.
constexpr float kMinEyeDistance = 1.2f;
constexpr float kFacingSlack = 1e-4f;
// Every vertex at least this far in front of the camera, relative to the bounding radius.
constexpr float kMinDepth = 1e-3f;
// Added around each projected box, in pixels: the projection (in double, kept in float) and the
// rays' directions (in float) are rounded by about 1e-4 pixel; the test itself is exact.
constexpr double kMargin = 0.01;

}  // namespace

bool PrimaryVisibility::build(const SlimeGeometry& geometry, const Camera& camera, int width, int height, glm::vec2 offset) {
  ready_ = false;
  pixelTests_ = 0;
  const std::size_t vertexCount = geometry.vertexCount(), triangleCount = geometry.triangles.size();
  const glm::vec3 eye(camera.position);
  const float radius = geometry.boundRadius * 1.001f + 1e-6f;
  const float distance = glm::length(geometry.boundCenter - eye);
  if (geometry.analyticSphere || triangleCount == 0 || width <= 0 || height <= 0 || !(radius > 0.0f) ||
      !std::isfinite(distance) || !(distance > kMinEyeDistance * radius))
    return false;

  // Each vertex's image point: the inverse of primaryDirections8's mapping, in double.
  const glm::dvec3 forward = camera.forward, right = camera.right, up = camera.up;
  const double spanX = camera.tanHalfFov * camera.aspect, spanY = camera.tanHalfFov;
  projected_.resize(vertexCount);
  double low[2] = {INFINITY, INFINITY}, high[2] = {-INFINITY, -INFINITY};
  for (std::size_t i = 0; i < vertexCount; ++i) {
    const glm::dvec3 q = glm::dvec3(geometry.positions[i]) - camera.position;
    const double depth = glm::dot(q, forward);
    if (!(depth > kMinDepth * radius)) return false;  // at or behind the camera: no image point
    const double across = glm::dot(q, right) / (depth * spanX), down = glm::dot(q, up) / (depth * spanY);
    const double column = 0.5 * (across + 1.0) * width - offset.x, row = 0.5 * (1.0 - down) * height - offset.y;
    if (!std::isfinite(column) || !std::isfinite(row)) return false;
    projected_[i] = glm::vec2(static_cast<float>(column), static_cast<float>(row));
    low[0] = std::min(low[0], column), high[0] = std::max(high[0], column);
    low[1] = std::min(low[1], row), high[1] = std::max(high[1], row);
  }
  // The pixels whose sample point (column or row + offset) lies within [low, high] of the image points.
  const auto first = [](double value, int size) { return static_cast<int>(std::clamp(std::ceil(value - kMargin), 0.0, double(size))); };
  const auto last = [](double value, int size) { return static_cast<int>(std::clamp(std::floor(value + kMargin), -1.0, double(size - 1))); };
  left_ = first(low[0], width), top_ = first(low[1], height);
  columns_ = std::max(0, last(high[0], width) - left_ + 1), rows_ = std::max(0, last(high[1], height) - top_ + 1);
  const std::size_t pixels = static_cast<std::size_t>(columns_) * static_cast<std::size_t>(rows_);
  t_.assign(pixels, kInfinity);
  u_.resize(pixels);
  v_.resize(pixels);
  primitive_.assign(pixels, kNoPrimitive);

  // The region's rays, computed once (rows padded to whole packets of 8).
  const PrimaryView view(camera, width, height);
  stride_ = (columns_ + 7) / 8 * 8;
  for (auto& d : directions_) d.resize(static_cast<std::size_t>(stride_) * rows_ + 8);  // + a packet past the last row
  for (int row = 0; row < rows_; ++row) {
    const float y = static_cast<float>(top_ + row) + offset.y;
    for (int column = 0; column < columns_; column += 8) {
      const std::size_t k = static_cast<std::size_t>(row) * stride_ + column;
      primaryDirections8(view, left_ + column, offset.x, y, &directions_[0][k], &directions_[1][k], &directions_[2][k]);
    }
  }
  const Lanes ox(eye.x), oy(eye.y), oz(eye.z);
  for (std::size_t f = 0; f < triangleCount; ++f) {
    const Triangle& triangle = geometry.triangles[f];
    const glm::vec3 a = geometry.positions[triangle.x];
    const glm::vec3 fromEye = a - eye;
    if (!(glm::dot(geometry.faceNormals[f], fromEye) < kFacingSlack * glm::length(fromEye))) continue;
    const glm::vec2 pa = projected_[triangle.x], pb = projected_[triangle.y], pc = projected_[triangle.z];
    // The box, relative to the region.
    const int c0 = first(std::min({pa.x, pb.x, pc.x}), width) - left_;
    const int c1 = std::min(last(std::max({pa.x, pb.x, pc.x}), width) - left_, columns_ - 1);
    const int r0 = first(std::min({pa.y, pb.y, pc.y}), height) - top_;
    const int r1 = std::min(last(std::max({pa.y, pb.y, pc.y}), height) - top_, rows_ - 1);
    if (c0 > c1 || r0 > r1 || c0 < 0 || r0 < 0) continue;
    // PencilGrid::hitLanes's operations in its order, one triangle against eight rays.
    const glm::vec3 edge1 = geometry.positions[triangle.y] - a, edge2 = geometry.positions[triangle.z] - a;
    const Lanes e1x(edge1.x), e1y(edge1.y), e1z(edge1.z), e2x(edge2.x), e2y(edge2.y), e2z(edge2.z);
    const Lanes sx = ox - Lanes(a.x), sy = oy - Lanes(a.y), sz = oz - Lanes(a.z);
    const Lanes qx = sy * e1z - e1y * sz, qy = sz * e1x - e1z * sx, qz = sx * e1y - e1x * sy;
    const Lanes tNumerator = e2x * qx + e2y * qy + e2z * qz;
    for (int row = r0; row <= r1; ++row) {
      for (int column = c0; column <= c1; column += 8) {
        // Lanes past the box read the row's padding, the next row or the packet past the last row:
        // their hits are masked off below.
        const std::size_t at = static_cast<std::size_t>(row) * stride_ + column;
        const Lanes dx = Lanes::load(&directions_[0][at]), dy = Lanes::load(&directions_[1][at]),
                    dz = Lanes::load(&directions_[2][at]);
        const Lanes px = dy * e2z - e2y * dz, py = dz * e2x - e2z * dx, pz = dx * e2y - e2x * dy;
        const Lanes determinant = e1x * px + e1y * py + e1z * pz;
        const Lanes magnitude = max(determinant, -determinant);
        const LaneMask usable = (magnitude > Lanes(0.0f)) && (magnitude < Lanes(INFINITY));
        if (usable.mask() == 0) continue;
        const Lanes inverse = Lanes(1.0f) / determinant;
        const Lanes u = (sx * px + sy * py + sz * pz) * inverse;
        const Lanes v = (dx * qx + dy * qy + dz * qz) * inverse;
        const Lanes t = tNumerator * inverse;
        const LaneMask hit = usable && (u >= Lanes(0.0f)) && (u <= Lanes(1.0f)) && (v >= Lanes(0.0f)) &&
                             (u + v <= Lanes(1.0f)) && (t >= Lanes(0.0f)) && (t <= Lanes(INFINITY));
        pixelTests_ += static_cast<std::uint64_t>(std::min(8, c1 - column + 1));
        unsigned mask = hit.mask();
        if (mask == 0) continue;
        if (c1 - column < 7) mask &= (1u << (c1 - column + 1)) - 1u;  // lanes past the box: not this triangle's
        alignas(32) float ts[8], us[8], vs[8];
        t.store(ts);
        u.store(us);
        v.store(vs);
        for (; mask != 0; mask &= mask - 1) {
          const int lane = __builtin_ctz(mask);
          const std::size_t k = static_cast<std::size_t>(row) * columns_ + (column + lane);
          if (ts[lane] < t_[k]) {  // a later triangle at the same distance does not replace an earlier one
            t_[k] = ts[lane];
            u_[k] = us[lane];
            v_[k] = vs[lane];
            primitive_[k] = static_cast<std::uint32_t>(f);
          }
        }
      }
    }
  }
  ready_ = true;
  return true;
}

void PrimaryVisibility::hits8(int column, int row, int count, const bool* active, SlimeHit* hits) const {
  for (int i = 0; i < 8; ++i) {
    hits[i] = SlimeHit{};
    const int x = column + i - left_, y = row - top_;
    if (i >= count || !active[i] || x < 0 || x >= columns_ || y < 0 || y >= rows_) continue;
    const std::size_t k = static_cast<std::size_t>(y) * columns_ + x;
    if (primitive_[k] != kNoPrimitive) hits[i] = SlimeHit{t_[k], primitive_[k], u_[k], v_[k]};
  }
}

}  // namespace slime

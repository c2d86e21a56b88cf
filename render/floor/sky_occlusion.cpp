#include "render/floor/sky_occlusion.h"

#include "render/slime/convex_outline.h"

#include <cmath>

namespace slime {
namespace {

struct Solid {
  glm::vec3 centroid{0.0f};
  float volume = 0.0f, area = 0.0f;
};

// Each piece's enclosed volume, area and the centroid of its solid (the divergence theorem over its
// triangles), or the analytic sphere's.
std::vector<Solid> solidsOf(const SlimeGeometry& geometry) {
  std::vector<Solid> solids;
  if (geometry.analyticSphere) {
    const float r = geometry.sphereRadius;
    solids.push_back({geometry.sphereCenter, 4.18879020f * r * r * r, 12.5663706f * r * r});
    return solids;
  }
  const std::size_t pieces = geometry.pieceTriangleStarts.size();
  for (std::size_t piece = 0; piece < pieces; ++piece) {
    const std::size_t begin = geometry.pieceTriangleStarts[piece];
    const std::size_t end = piece + 1 < pieces ? geometry.pieceTriangleStarts[piece + 1] : geometry.triangles.size();
    double volume = 0.0, area = 0.0;
    glm::dvec3 moment(0.0);
    for (std::size_t f = begin; f < end; ++f) {
      const Triangle& t = geometry.triangles[f];
      const glm::dvec3 a(geometry.positions[t.x]), b(geometry.positions[t.y]), c(geometry.positions[t.z]);
      const double v = glm::dot(a, glm::cross(b, c)) / 6.0;  // the tetrahedron (0, a, b, c)
      volume += v;
      moment += v * (a + b + c) / 4.0;
      area += 0.5 * glm::length(glm::cross(b - a, c - a));
    }
    if (!(volume > 0.0) || !(area > 0.0)) continue;
    solids.push_back({glm::vec3(moment / volume), static_cast<float>(volume), static_cast<float>(area)});
  }
  return solids;
}

float cross(glm::vec2 a, glm::vec2 b) { return a.x * b.y - a.y * b.x; }

}  // namespace

SkyOcclusion::SkyOcclusion(const SlimeGeometry& geometry, const ShadingParameters& p) {
  if (!(p.ambientLight.x > 0.0f || p.ambientLight.y > 0.0f || p.ambientLight.z > 0.0f) || !p.shadows) return;
  const std::size_t vertices = geometry.vertexCount();
  if (vertices == 0) return;
  // The shadow: every vertex cast from the light onto z = 0 (the light above them all), then their hull.
  const glm::dvec3 light(p.lightPosition);
  std::vector<glm::dvec2> cast;
  cast.reserve(vertices);
  for (std::size_t i = 0; i < vertices; ++i) {
    const glm::dvec3 v(geometry.positions[i]);
    if (!(light.z - v.z > 1e-9 * std::max(1.0, light.z))) return;
    const double s = light.z / (light.z - v.z);
    cast.emplace_back(light.x + (v.x - light.x) * s, light.y + (v.y - light.y) * s);
  }
  ConvexOutline outline;
  outline.build(cast);
  if (!outline.bounded()) return;
  low_ = glm::vec2(kInfinity);
  high_ = glm::vec2(-kInfinity);
  for (const glm::dvec2& corner : outline.corners()) {
    hull_.emplace_back(corner);
    low_ = glm::min(low_, hull_.back());
    high_ = glm::max(high_, hull_.back());
  }
  for (const Solid& s : solidsOf(geometry)) {
    const float r = std::cbrt(s.volume * (3.0f / 12.5663706f));
    SkyBlocker& b = blockers_.emplace_back();
    b.centroid = s.centroid;
    b.radius2 = r * r;
    const float path = p.ior * p.ior * 4.0f * s.volume / s.area;
    for (int c = 0; c < 3; ++c) b.absorbed[c] = 1.0f - p.transmission * std::exp(-p.slimeAbsorption[c] * path);
  }
}

bool SkyOcclusion::inShadow(glm::vec2 p) const {
  const std::size_t n = hull_.size();
  const glm::vec2 origin = hull_[0], q = p - origin;
  if (cross(hull_[1] - origin, q) < 0.0f || cross(hull_[n - 1] - origin, q) > 0.0f) return false;
  std::size_t lowEnd = 1, highEnd = n - 1;  // q lies between the rays to hull_[lowEnd] and hull_[highEnd]
  while (highEnd - lowEnd > 1) {
    const std::size_t middle = (lowEnd + highEnd) / 2;
    if (cross(hull_[middle] - origin, q) >= 0.0f) lowEnd = middle;
    else highEnd = middle;
  }
  return cross(hull_[highEnd] - hull_[lowEnd], p - hull_[lowEnd]) >= 0.0f;
}

}  // namespace slime

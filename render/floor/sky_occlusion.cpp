#include "render/floor/sky_occlusion.h"

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

float equivalentRadius(float volume) { return std::cbrt(volume * (3.0f / 12.5663706f)); }

}  // namespace

std::vector<SkyDisc> skyOcclusionDiscs(const SlimeGeometry& geometry) {
  std::vector<SkyDisc> discs;
  for (const Solid& s : solidsOf(geometry))
    discs.push_back({s.centroid.x, s.centroid.y, kSkyOcclusionReach * equivalentRadius(s.volume)});
  return discs;
}

std::vector<SkyBlocker> skyBlockers(const SlimeGeometry& geometry, const ShadingParameters& p) {
  std::vector<SkyBlocker> blockers;
  if (!(p.ambientLight.x > 0.0f || p.ambientLight.y > 0.0f || p.ambientLight.z > 0.0f)) return blockers;
  for (const Solid& s : solidsOf(geometry)) {
    const float r = equivalentRadius(s.volume);
    SkyBlocker& b = blockers.emplace_back();
    b.centroid = s.centroid;
    b.radius2 = r * r;
    b.taperStart2 = kSkyOcclusionTaperStart * kSkyOcclusionTaperStart * r * r;
    b.reach2 = kSkyOcclusionReach * kSkyOcclusionReach * r * r;
    const float path = p.ior * p.ior * 4.0f * s.volume / s.area;
    for (int c = 0; c < 3; ++c) b.absorbed[c] = 1.0f - p.transmission * std::exp(-p.slimeAbsorption[c] * path);
  }
  return blockers;
}

}  // namespace slime

#include "core/geometry/volume.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace slime {

double enclosedVolume(const std::vector<glm::dvec3>& positions,
                      const std::vector<glm::u32vec3>& triangles) {
  if (positions.empty()) return 0.0;
  const glm::dvec3 origin = positions[0];  // a nearby origin keeps the sum well conditioned
  double sixTimesVolume = 0.0;
  for (const glm::u32vec3& t : triangles) {
    const glm::dvec3 a = positions[t.x] - origin, b = positions[t.y] - origin, c = positions[t.z] - origin;
    sixTimesVolume += glm::dot(a, glm::cross(b, c));
  }
  return sixTimesVolume / 6.0;
}

double sixTimesVolumeGradient(const std::vector<glm::dvec3>& positions, const std::vector<glm::u32vec3>& triangles,
                              std::size_t count, std::vector<glm::dvec3>& gradient) {
  gradient.assign(count, glm::dvec3(0.0));
  if (positions.empty() || count == 0) return 0.0;
  const glm::dvec3 origin = positions[0];
  double sixTimesVolume = 0.0;
  for (const glm::u32vec3& t : triangles) {
    const glm::dvec3 a = positions[t.x] - origin, b = positions[t.y] - origin, c = positions[t.z] - origin;
    const glm::dvec3 bc = glm::cross(b, c);
    sixTimesVolume += glm::dot(a, bc);
    gradient[t.x] += bc;
    gradient[t.y] += glm::cross(c, a);
    gradient[t.z] += glm::cross(a, b);
  }
  return sixTimesVolume;
}

double volumeGradient(const std::vector<glm::dvec3>& positions,
                      const std::vector<glm::u32vec3>& triangles, std::vector<glm::dvec3>& gradient) {
  const double sixTimesVolume = sixTimesVolumeGradient(positions, triangles, positions.size(), gradient);
  for (glm::dvec3& g : gradient) g /= 6.0;
  return sixTimesVolume / 6.0;
}

std::vector<glm::u32vec2> edgeOpposites(const std::vector<glm::u32vec2>& edges,
                                        const std::vector<glm::u32vec3>& triangles) {
  // Every directed edge from → to of every triangle with its third vertex, sorted by (from, to).
  struct HalfEdge {
    std::uint64_t key;  // from << 32 | to
    std::uint32_t third;
  };
  std::vector<HalfEdge> halfEdges;
  halfEdges.reserve(triangles.size() * 3);
  auto key = [](std::uint32_t from, std::uint32_t to) { return std::uint64_t{from} << 32 | to; };
  for (const glm::u32vec3& t : triangles) {
    halfEdges.push_back({key(t.x, t.y), t.z});
    halfEdges.push_back({key(t.y, t.z), t.x});
    halfEdges.push_back({key(t.z, t.x), t.y});
  }
  std::sort(halfEdges.begin(), halfEdges.end(), [](const HalfEdge& l, const HalfEdge& r) { return l.key < r.key; });
  auto thirdOf = [&](std::uint32_t from, std::uint32_t to) {
    const std::uint64_t wanted = key(from, to);
    const auto found = std::lower_bound(halfEdges.begin(), halfEdges.end(), wanted,
                                        [](const HalfEdge& h, std::uint64_t k) { return h.key < k; });
    if (found == halfEdges.end() || found->key != wanted || (found + 1 != halfEdges.end() && (found + 1)->key == wanted))
      throw std::invalid_argument("edge " + std::to_string(from) + "-" + std::to_string(to) +
                                  " is not in exactly one triangle each way: the mesh is not closed");
    return found->third;
  };
  std::vector<glm::u32vec2> opposites(edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e)
    opposites[e] = {thirdOf(edges[e].x, edges[e].y), thirdOf(edges[e].y, edges[e].x)};
  return opposites;
}

double fillPressure(double volume, double restVolume, double restPressure, double bulkModulus) {
  return restPressure + bulkModulus * (1.0 - volume / restVolume);
}

}  // namespace slime

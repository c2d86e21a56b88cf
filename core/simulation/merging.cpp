#include "core/simulation/merging.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace slime {
namespace {

// Surface nodes of a body in cubic cells, for the nearest within a distance.
class SurfaceNodeGrid {
 public:
  SurfaceNodeGrid(const BulkBody& body, double cell) : body_(body), cell_(cell) {
    for (std::uint32_t i = 0; i < body.mesh.surfaceNodes; ++i) cells_[key(cellOf(body.state.positions[i]))].push_back(i);
  }
  // The nearest surface node within `distance` of p (the lowest index of equals), or none.
  std::uint32_t nearest(const glm::dvec3& p, double distance) const {
    std::uint32_t best = std::numeric_limits<std::uint32_t>::max();
    double bestDistance = distance * distance;
    const glm::i64vec3 c = cellOf(p);
    for (std::int64_t x = c.x - 1; x <= c.x + 1; ++x)
      for (std::int64_t y = c.y - 1; y <= c.y + 1; ++y)
        for (std::int64_t z = c.z - 1; z <= c.z + 1; ++z) {
          const auto found = cells_.find(key({x, y, z}));
          if (found == cells_.end()) continue;
          for (std::uint32_t i : found->second) {
            const glm::dvec3 d = body_.state.positions[i] - p;
            const double squared = glm::dot(d, d);
            if (squared < bestDistance || (squared == bestDistance && i < best)) {
              bestDistance = squared;
              best = i;
            }
          }
        }
    return best;
  }

 private:
  glm::i64vec3 cellOf(const glm::dvec3& p) const { return glm::i64vec3(glm::floor(p / cell_)); }
  static std::int64_t key(const glm::i64vec3& c) { return ((c.x & 0x1FFFFF) << 42) | ((c.y & 0x1FFFFF) << 21) | (c.z & 0x1FFFFF); }
  const BulkBody& body_;
  double cell_;
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> cells_;
};

bool boxesOverlap(const BulkBody& a, const BulkBody& b, double margin) {
  glm::dvec3 lowA(1e300), highA(-1e300), lowB(1e300), highB(-1e300);
  for (std::size_t i = 0; i < a.mesh.surfaceNodes; ++i) {
    lowA = glm::min(lowA, a.state.positions[i]);
    highA = glm::max(highA, a.state.positions[i]);
  }
  for (std::size_t i = 0; i < b.mesh.surfaceNodes; ++i) {
    lowB = glm::min(lowB, b.state.positions[i]);
    highB = glm::max(highB, b.state.positions[i]);
  }
  return glm::all(glm::lessThanEqual(lowA - margin, highB)) && glm::all(glm::lessThanEqual(lowB - margin, highA));
}

}  // namespace

std::size_t touchingNodes(const BulkBody& a, const BulkBody& b, double distance) {
  if (!boxesOverlap(a, b, distance)) return 0;
  const SurfaceNodeGrid grid(b, distance);
  std::size_t touching = 0;
  for (std::uint32_t i = 0; i < a.mesh.surfaceNodes; ++i)
    touching += grid.nearest(a.state.positions[i], distance) != std::numeric_limits<std::uint32_t>::max();
  return touching;
}

BodyParts weldedParts(const BulkBody& a, const BulkBody& b, double weldDistance, std::vector<std::uint32_t>& bOf) {
  std::vector<std::uint32_t> allA(a.mesh.tetrahedra.size()), allB(b.mesh.tetrahedra.size()), nodesA, nodesB;
  for (std::uint32_t e = 0; e < allA.size(); ++e) allA[e] = e;
  for (std::uint32_t e = 0; e < allB.size(); ++e) allB[e] = e;
  BodyParts parts = partsOf(a, allA, nodesA);  // every node of a is used: part node i is a's node i
  const BodyParts second = partsOf(b, allB, nodesB);
  // Mutual nearest surface nodes within the weld distance.
  const SurfaceNodeGrid gridA(a, weldDistance), gridB(b, weldDistance);
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> weldedTo(b.state.positions.size(), kNone);
  for (std::uint32_t j = 0; j < b.mesh.surfaceNodes; ++j) {
    const std::uint32_t i = gridA.nearest(b.state.positions[j], weldDistance);
    if (i != kNone && gridB.nearest(a.state.positions[i], weldDistance) == j) weldedTo[j] = i;
  }
  bOf.assign(b.state.positions.size(), kNone);
  for (std::uint32_t j = 0; j < nodesB.size(); ++j) {
    const std::uint32_t node = nodesB[j];
    if (weldedTo[node] != kNone) {
      bOf[node] = weldedTo[node];
      continue;
    }
    bOf[node] = static_cast<std::uint32_t>(parts.positions.size());
    parts.restPositions.push_back(second.positions[j]);  // b's rest frame is not a's: its node's place now
    parts.positions.push_back(second.positions[j]);
    parts.velocities.push_back(second.velocities[j]);
    parts.inverseMasses.push_back(second.inverseMasses[j]);
  }
  // Each welded pair meets half-way, with the mass-weighted velocity.
  std::vector<std::uint8_t> moved(parts.positions.size(), 0);
  const std::vector<glm::dvec3> before = parts.positions;  // a's nodes before the weld
  const std::vector<glm::dvec3>& beforeB = second.positions;
  for (std::uint32_t j = 0; j < nodesB.size(); ++j) {
    const std::uint32_t node = nodesB[j];
    if (weldedTo[node] == kNone) continue;
    const std::uint32_t i = weldedTo[node];
    parts.positions[i] = 0.5 * (parts.positions[i] + second.positions[j]);
    parts.velocities[i] = 0.5 * (parts.velocities[i] + second.velocities[j]);
    moved[i] = 1;
  }
  for (const Tetrahedron& t : second.tetrahedra)
    parts.tetrahedra.emplace_back(bOf[nodesB[t.x]], bOf[nodesB[t.y]], bOf[nodesB[t.z]], bOf[nodesB[t.w]]);
  parts.rest.insert(parts.rest.end(), second.rest.begin(), second.rest.end());
  parts.maxwell.insert(parts.maxwell.end(), second.maxwell.begin(), second.maxwell.end());
  parts.plastic.insert(parts.plastic.end(), second.plastic.begin(), second.plastic.end());
  // A tetrahedron with a welded node: its rest shape pulled back through its deformation before the weld.
  for (std::size_t e = 0; e < parts.tetrahedra.size(); ++e) {
    const Tetrahedron& t = parts.tetrahedra[e];
    if (!(moved[t.x] || moved[t.y] || moved[t.z] || moved[t.w])) continue;
    const bool fromB = e >= a.mesh.tetrahedra.size();
    glm::dvec3 old[4];
    for (int corner = 0; corner < 4; ++corner) {
      if (!fromB) old[corner] = before[t[corner]];
      else old[corner] = beforeB[second.tetrahedra[e - a.mesh.tetrahedra.size()][corner]];
    }
    const glm::dmat3 f = glm::dmat3(old[1] - old[0], old[2] - old[0], old[3] - old[0]) * parts.rest[e].restInverse;
    const glm::dvec3& x0 = parts.positions[t.x];
    const glm::dmat3 shape(parts.positions[t.y] - x0, parts.positions[t.z] - x0, parts.positions[t.w] - x0);
    if (glm::determinant(f) <= 0.0 || glm::determinant(shape) <= 0.0) continue;  // keeps its rest shape
    const glm::dmat3 restShape = glm::inverse(f) * shape;
    parts.rest[e] = makeTetRest(glm::dvec3(0.0), restShape[0], restShape[1], restShape[2]);
  }
  // The rest frames of the two bodies differ: the merged body's node frame (its dampers' rest lengths,
  // the frequency estimate's shape) is where its nodes are now; each tetrahedron keeps its own rest data.
  parts.restPositions = parts.positions;
  return parts;
}

}  // namespace slime

#include "core/simulation/tearing.h"

#include "core/bulk/elastic_stretch.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace slime {
namespace {

struct UnionFind {
  std::vector<std::uint32_t> parent;
  explicit UnionFind(std::size_t count) : parent(count) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  void join(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);  // the smaller index leads: a fixed result
  }
};

// Pairs of tetrahedra that share a face, each pair once, in a fixed order.
std::vector<std::array<std::uint32_t, 2>> faceNeighbours(const std::vector<Tetrahedron>& tetrahedra) {
  std::vector<std::pair<std::array<std::uint32_t, 3>, std::uint32_t>> faces;
  faces.reserve(tetrahedra.size() * 4);
  for (std::uint32_t e = 0; e < tetrahedra.size(); ++e)
    for (int skip = 0; skip < 4; ++skip) {
      std::array<std::uint32_t, 3> key;
      int k = 0;
      for (int corner = 0; corner < 4; ++corner)
        if (corner != skip) key[k++] = tetrahedra[e][corner];
      std::sort(key.begin(), key.end());
      faces.emplace_back(key, e);
    }
  std::sort(faces.begin(), faces.end());
  std::vector<std::array<std::uint32_t, 2>> pairs;
  for (std::size_t f = 0; f + 1 < faces.size(); ++f)
    if (faces[f].first == faces[f + 1].first) pairs.push_back({faces[f].second, faces[f + 1].second});
  return pairs;
}

}  // namespace

TearPlan planTear(const BulkBody& body, double tearStretch, double smallestVolume) {
  TearPlan plan;
  const MostStretched most = mostStretchedElement(body, tearStretch);
  const MostTorn torn = mostTornDamagedElement(body, tearStretch);
  plan.stretch = most.stretch;
  if (most.stretch < tearStretch && torn.measure < 1.0) return plan;
  const std::vector<glm::dvec3>& x = body.state.positions;
  const std::vector<Tetrahedron>& tetrahedra = body.mesh.tetrahedra;
  const std::size_t count = tetrahedra.size();
  // The seed: the most stretched element, or a damaged one that tears first (its measure the larger). A
  // damaged seed is cut across its total stretch's principal direction (its elastic stretch, small in a
  // strand drawn out slowly, may point anywhere); an undamaged one across its elastic stretch's.
  const bool damaged = torn.measure >= 1.0 && (most.stretch < tearStretch || torn.measure > (most.stretch - 1.0) / (tearStretch - 1.0));
  const std::size_t seed = damaged ? torn.tetrahedron : most.tetrahedron;
  glm::dvec3 normal;
  if (damaged) {
    const Tetrahedron& t = tetrahedra[seed];
    const glm::dmat3 f = deformationGradient(body.rest[seed], x[t.x], x[t.y], x[t.z], x[t.w]);
    largestSymmetricEigenvalue(f * glm::transpose(f), &normal);
  } else {
    elasticStretchSquared(body, x, seed, &normal);
  }
  const auto centroid = [&](std::size_t e) {
    const Tetrahedron& t = tetrahedra[e];
    return 0.25 * (x[t.x] + x[t.y] + x[t.z] + x[t.w]);
  };
  const glm::dvec3 origin = centroid(seed);
  const auto straddles = [&](std::size_t e) {
    double low = 1e300, high = -1e300;
    for (int corner = 0; corner < 4; ++corner) {
      const double s = glm::dot(x[tetrahedra[e][corner]] - origin, normal);
      low = std::min(low, s);
      high = std::max(high, s);
    }
    return low < 0.0 && high > 0.0;
  };
  // Without damage, tearMeasure ≥ kCrackStretchShare is λ_e ≥ 1 + kCrackStretchShare (λ_tear − 1).
  const bool anyDamage = body.material.damageStretch > 0.0;
  const double crackStretch = 1.0 + kCrackStretchShare * (tearStretch - 1.0);
  const auto joinsCrack = [&](std::size_t e) {
    return anyDamage ? tearMeasure(body, x, e, tearStretch) >= kCrackStretchShare
                     : elasticStretchSquared(body, x, e) >= crackStretch * crackStretch;
  };
  const auto neighbours = faceNeighbours(tetrahedra);
  std::vector<std::uint32_t> start(count + 1, 0), adjacent(neighbours.size() * 2);
  for (const auto& pair : neighbours) {
    ++start[pair[0] + 1];
    ++start[pair[1] + 1];
  }
  for (std::size_t e = 0; e < count; ++e) start[e + 1] += start[e];
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (const auto& pair : neighbours) {
      adjacent[fill[pair[0]]++] = pair[1];
      adjacent[fill[pair[1]]++] = pair[0];
    }
  }
  // The crack: straddling, stretched tetrahedra reached from the seed over shared faces.
  std::vector<std::uint8_t> crack(count, 0);
  std::vector<std::uint32_t> frontier{static_cast<std::uint32_t>(seed)};
  crack[seed] = 1;
  while (!frontier.empty()) {
    const std::uint32_t e = frontier.back();
    frontier.pop_back();
    for (std::uint32_t k = start[e]; k < start[e + 1]; ++k) {
      const std::uint32_t f = adjacent[k];
      if (crack[f] || !straddles(f) || !joinsCrack(f)) continue;
      crack[f] = 1;
      frontier.push_back(f);
    }
  }
  // Cut the faces between a crack tetrahedron and a neighbour on the other side of the plane.
  std::vector<std::uint8_t> above(count);
  for (std::size_t e = 0; e < count; ++e) above[e] = glm::dot(centroid(e) - origin, normal) > 0.0;
  UnionFind components(count);
  std::vector<std::array<std::uint32_t, 2>> cut;
  for (const auto& pair : neighbours) {
    if ((crack[pair[0]] || crack[pair[1]]) && above[pair[0]] != above[pair[1]]) cut.push_back(pair);
    else components.join(pair[0], pair[1]);
  }
  // Tetrahedra that share a node off the cut stay together too (a merged piece's two bodies share only
  // their welded nodes, no faces).
  std::vector<std::uint8_t> onCut(x.size(), 0);
  for (const auto& pair : cut)
    for (int corner = 0; corner < 4; ++corner) {
      const std::uint32_t node = tetrahedra[pair[0]][corner];
      const Tetrahedron& other = tetrahedra[pair[1]];
      if (node == other.x || node == other.y || node == other.z || node == other.w) onCut[node] = 1;
    }
  std::vector<std::uint32_t> firstHolder(x.size(), UINT32_MAX);
  for (std::uint32_t e = 0; e < count; ++e)
    for (int corner = 0; corner < 4; ++corner) {
      const std::uint32_t node = tetrahedra[e][corner];
      if (onCut[node]) continue;
      if (firstHolder[node] == UINT32_MAX) firstHolder[node] = e;
      else components.join(firstHolder[node], e);
    }
  // A component under the smallest piece stays joined to its largest neighbour across the cut.
  for (bool joined = true; joined;) {
    joined = false;
    std::vector<double> volume(count, 0.0);
    for (std::size_t e = 0; e < count; ++e) volume[components.find(static_cast<std::uint32_t>(e))] += body.rest[e].volume;
    for (std::uint32_t root = 0; root < count && !joined; ++root) {
      if (components.find(root) != root || volume[root] >= smallestVolume) continue;
      std::uint32_t best = root;
      for (const auto& pair : cut) {
        const std::uint32_t a = components.find(pair[0]), b = components.find(pair[1]);
        const std::uint32_t other = a == root ? b : b == root ? a : root;
        if (other != root && (best == root || volume[other] > volume[best])) best = other;
      }
      if (best == root) continue;  // no neighbour: a whole body under the smallest size stays one
      components.join(root, best);
      joined = true;
    }
  }
  plan.partOf.assign(count, 0);
  std::vector<std::uint32_t> partOfRoot(count, UINT32_MAX);
  for (std::uint32_t e = 0; e < count; ++e) {
    const std::uint32_t root = components.find(e);
    if (partOfRoot[root] == UINT32_MAX) partOfRoot[root] = plan.parts++;
    plan.partOf[e] = partOfRoot[root];
  }
  if (plan.parts < 2) plan.parts = 0;
  return plan;
}

}  // namespace slime

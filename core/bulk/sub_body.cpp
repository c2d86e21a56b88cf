#include "core/bulk/sub_body.h"

#include "core/bulk/element_pass.h"
#include "core/bulk/tet_lanes.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace slime {
namespace {

void setLane(ElementReal (&entries)[9][kTetLanes], std::size_t lane, const glm::dmat3& m) {
  for (int entry = 0; entry < 9; ++entry) entries[entry][lane] = static_cast<ElementReal>(m[entry / 3][entry % 3]);
}
glm::dmat3 lane(const ElementReal (&entries)[9][kTetLanes], std::size_t lane) {
  glm::dmat3 m;
  for (int entry = 0; entry < 9; ++entry) m[entry / 3][entry % 3] = entries[entry][lane];
  return m;
}

// The point of triangle abc nearest to p, squared distance (by the triangle's plane and edges).
double squaredDistanceToTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
  glm::dvec3 q;
  if (d1 <= 0.0 && d2 <= 0.0) q = a;
  else {
    const glm::dvec3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    const glm::dvec3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
    if (d3 >= 0.0 && d4 <= d3) q = b;
    else if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) q = a + (d1 / (d1 - d3)) * ab;
    else if (d6 >= 0.0 && d5 <= d6) q = c;
    else if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) q = a + (d2 / (d2 - d6)) * ac;
    else if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) q = b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
    else {
      const double denominator = 1.0 / (va + vb + vc);
      q = a + ab * (vb * denominator) + ac * (vc * denominator);
    }
  }
  const glm::dvec3 d = p - q;
  return glm::dot(d, d);
}

}  // namespace

BodyParts partsOf(const BulkBody& body, std::span<const std::uint32_t> tetrahedra, std::vector<std::uint32_t>& partNode) {
  BodyParts parts;
  const std::size_t nodes = body.state.positions.size();
  std::vector<std::uint32_t> partOf(nodes, std::numeric_limits<std::uint32_t>::max());
  for (std::uint32_t e : tetrahedra)
    for (int corner = 0; corner < 4; ++corner) partOf[body.mesh.tetrahedra[e][corner]] = 0;
  partNode.clear();
  for (std::uint32_t i = 0; i < nodes; ++i) {
    if (partOf[i] != 0) continue;
    partOf[i] = static_cast<std::uint32_t>(partNode.size());
    partNode.push_back(i);
    parts.restPositions.push_back(body.mesh.positions[i]);
    parts.positions.push_back(body.state.positions[i]);
    parts.velocities.push_back(body.state.velocities[i]);
    parts.inverseMasses.push_back(body.state.inverseMasses[i]);
  }
  for (std::uint32_t e : tetrahedra) {
    const Tetrahedron& t = body.mesh.tetrahedra[e];
    parts.tetrahedra.emplace_back(partOf[t.x], partOf[t.y], partOf[t.z], partOf[t.w]);
    parts.rest.push_back(body.rest[e]);
    const MaxwellBlock& block = body.maxwell[e / kTetLanes];
    parts.maxwell.push_back({lane(block.metric, e % kTetLanes), lane(block.inverse, e % kTetLanes)});
    parts.plastic.push_back(plasticMetric(body, e));
  }
  return parts;
}

std::vector<std::pair<Triangle, std::uint32_t>> boundaryFaces(const std::vector<Tetrahedron>& tetrahedra) {
  // Faces wound outwards for a positively oriented abcd: acb, abd, adc, bcd.
  struct Face {
    std::array<std::uint32_t, 3> key;
    Triangle wound;
    std::uint32_t tetrahedron;
  };
  std::vector<Face> faces;
  faces.reserve(tetrahedra.size() * 4);
  for (std::uint32_t e = 0; e < tetrahedra.size(); ++e) {
    const Tetrahedron& t = tetrahedra[e];
    for (const Triangle& wound : {Triangle(t.x, t.z, t.y), Triangle(t.x, t.y, t.w), Triangle(t.x, t.w, t.z), Triangle(t.y, t.z, t.w)}) {
      std::array<std::uint32_t, 3> key{wound.x, wound.y, wound.z};
      std::sort(key.begin(), key.end());
      faces.push_back({key, wound, e});
    }
  }
  std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) { return a.key < b.key; });
  std::vector<std::pair<Triangle, std::uint32_t>> boundary;
  for (std::size_t f = 0; f < faces.size();) {
    std::size_t last = f + 1;
    while (last < faces.size() && faces[last].key == faces[f].key) ++last;
    if (last - f == 1) boundary.emplace_back(faces[f].wound, faces[f].tetrahedron);
    f = last;
  }
  return boundary;
}

BulkBody assembleBody(const BodyParts& parts, const SlimeSettings& slime, double density, int shellLevel,
                      std::vector<std::uint32_t>& order) {
  if (parts.tetrahedra.empty()) throw std::invalid_argument("assembleBody: a body needs at least one tetrahedron");
  const std::size_t count = parts.positions.size();
  const auto boundary = boundaryFaces(parts.tetrahedra);
  std::vector<std::uint8_t> onSurface(count, 0);
  for (const auto& face : boundary)
    for (int corner = 0; corner < 3; ++corner) onSurface[face.first[corner]] = 1;
  order.clear();
  for (std::uint32_t i = 0; i < count; ++i)
    if (onSurface[i]) order.push_back(i);
  const std::size_t surfaceNodes = order.size();
  for (std::uint32_t i = 0; i < count; ++i)
    if (!onSurface[i]) order.push_back(i);
  std::vector<std::uint32_t> newIndex(count);
  for (std::uint32_t i = 0; i < count; ++i) newIndex[order[i]] = i;

  BulkBody body;
  TetMesh& mesh = body.mesh;
  mesh.shellLevel = shellLevel;
  mesh.shells = 0;
  mesh.surfaceNodes = surfaceNodes;
  mesh.positions.resize(count);
  body.state.positions.resize(count);
  body.state.velocities.resize(count);
  body.state.inverseMasses.resize(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    mesh.positions[i] = parts.restPositions[order[i]];
    body.state.positions[i] = parts.positions[order[i]];
    body.state.velocities[i] = parts.velocities[order[i]];
    body.state.inverseMasses[i] = parts.inverseMasses[order[i]];
  }
  for (const Tetrahedron& t : parts.tetrahedra)
    mesh.tetrahedra.emplace_back(newIndex[t.x], newIndex[t.y], newIndex[t.z], newIndex[t.w]);
  for (const auto& face : boundary)
    mesh.surface.emplace_back(newIndex[face.first.x], newIndex[face.first.y], newIndex[face.first.z]);

  body.rest = parts.rest;
  for (const TetRest& rest : body.rest) body.restVolume += rest.volume;
  const std::size_t tetrahedra = mesh.tetrahedra.size();
  body.restBlocks.resize((tetrahedra + kTetLanes - 1) / kTetLanes);
  body.maxwell.resize(body.restBlocks.size());
  for (MaxwellBlock& block : body.maxwell)  // identity in the lanes past the last tetrahedron
    for (std::size_t l = 0; l < kTetLanes; ++l) {
      setLane(block.inverse, l, glm::dmat3(1.0));
      setLane(block.metric, l, glm::dmat3(1.0));
      for (int entry = 0; entry < 3; ++entry) block.plastic[entry][l] = 1;
    }
  for (std::size_t e = 0; e < tetrahedra; ++e) {
    TetBlock& block = body.restBlocks[e / kTetLanes];
    setLane(block.restInverse, e % kTetLanes, body.rest[e].restInverse);
    setLane(block.forceMap, e % kTetLanes, body.rest[e].forceMap);
    setLane(body.maxwell[e / kTetLanes].inverse, e % kTetLanes, parts.maxwell[e].inverse);
    setLane(body.maxwell[e / kTetLanes].metric, e % kTetLanes, parts.maxwell[e].metric);
    // G_p's six entries (kSymmetricEntry): a part keeps its long-term branch's flowed rest shape (zeros
    // there made its long-term stiffness vanish: a torn and merged slime lay flat, aspect 0.30 against 0.66).
    for (int c = 0; c < 3; ++c)
      for (int r = c; r < 3; ++r)
        body.maxwell[e / kTetLanes].plastic[kSymmetricEntry[r][c]][e % kTetLanes] =
            static_cast<ElementReal>(parts.plastic[e][c][r]);
  }
  fillElementBlocks(body);
  body.edges = tetrahedronEdges(mesh.tetrahedra);
  body.edgeColours = colourEdges(body.edges, count);
  SlimeSettings own = slime;
  own.mass = density * body.restVolume;
  applyBulkMaterial(body, own);
  return body;
}

void carryDrawnSurface(BulkBody& body, TriangleMesh drawn, double support) {
  const std::vector<glm::dvec3>& x = body.state.positions;
  // The smooth map is fitted from the body now (exact for affine motion from here), a few vertices a
  // step (BulkPiece::endStep); the element map, exact now too, places the surface meanwhile.
  beginSmoothFit(x, drawn.positions, support, body.embedding);

  // The element map: each drawn vertex in the tetrahedron under its nearest surface face, found in
  // cubic cells of the faces' mean edge length.
  const auto boundary = boundaryFaces(body.mesh.tetrahedra);
  double meanEdge = 0.0;
  for (const auto& face : boundary) meanEdge += glm::length(x[face.first.y] - x[face.first.x]);
  const double cell = std::max(meanEdge / static_cast<double>(std::max<std::size_t>(boundary.size(), 1)), 1e-4);
  const auto cellOf = [&](const glm::dvec3& p) { return glm::i64vec3(glm::floor(p / cell)); };
  const auto key = [](const glm::i64vec3& c) {
    return ((c.x & 0x1FFFFF) << 42) | ((c.y & 0x1FFFFF) << 21) | (c.z & 0x1FFFFF);
  };
  std::vector<std::pair<std::int64_t, std::uint32_t>> cells;  // (cell, face), sorted
  for (std::uint32_t f = 0; f < boundary.size(); ++f) {
    const Triangle& t = boundary[f].first;
    const glm::i64vec3 low = cellOf(glm::min(x[t.x], glm::min(x[t.y], x[t.z])));
    const glm::i64vec3 high = cellOf(glm::max(x[t.x], glm::max(x[t.y], x[t.z])));
    for (std::int64_t a = low.x; a <= high.x; ++a)
      for (std::int64_t b = low.y; b <= high.y; ++b)
        for (std::int64_t c = low.z; c <= high.z; ++c) cells.emplace_back(key({a, b, c}), f);
  }
  std::sort(cells.begin(), cells.end());
  body.mesh.surface.clear();
  for (const auto& face : boundary) body.mesh.surface.push_back(face.first);
  SurfaceEmbedding& embedding = body.embedding;
  const std::size_t count = drawn.positions.size();
  embedding.nodes.resize(count);
  embedding.weights.resize(count);
  embedding.verticesOfSurfaceTriangle.assign(boundary.size(), {});
  for (std::uint32_t v = 0; v < count; ++v) {
    const glm::dvec3& p = drawn.positions[v];
    const glm::i64vec3 home = cellOf(p);
    std::uint32_t best = 0;
    double bestDistance = std::numeric_limits<double>::infinity();
    for (std::int64_t ring = 1; ring < (1 << 20); ring *= 2) {
      for (std::int64_t a = home.x - ring; a <= home.x + ring; ++a)
        for (std::int64_t b = home.y - ring; b <= home.y + ring; ++b)
          for (std::int64_t c = home.z - ring; c <= home.z + ring; ++c) {
            const std::int64_t k = key({a, b, c});
            auto it = std::lower_bound(cells.begin(), cells.end(), std::make_pair(k, std::uint32_t{0}));
            for (; it != cells.end() && it->first == k; ++it) {
              const Triangle& t = boundary[it->second].first;
              const double d = squaredDistanceToTriangle(p, x[t.x], x[t.y], x[t.z]);
              if (d < bestDistance || (d == bestDistance && it->second < best)) {
                bestDistance = d;
                best = it->second;
              }
            }
          }
      // Found within the ring's reach: no face outside it is nearer.
      if (bestDistance <= (static_cast<double>(ring) * cell) * (static_cast<double>(ring) * cell)) break;
    }
    const Tetrahedron& t = body.mesh.tetrahedra[boundary[best].second];
    embedding.nodes[v] = t;
    embedding.weights[v] = barycentric(p, x[t.x], x[t.y], x[t.z], x[t.w]);
    embedding.verticesOfSurfaceTriangle[best].push_back(v);
  }
  body.drawn = std::move(drawn);
}

}  // namespace slime

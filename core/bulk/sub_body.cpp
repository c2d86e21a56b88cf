#include "core/bulk/eigen.h"  // first: see its header
#include "core/bulk/sub_body.h"

#include "core/bulk/element_pass.h"
#include "core/bulk/tet_lanes.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

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

// ρ(d) of rebaseRestTowardBall: the farthest node's distance from the centre per cell of a latitude–
// longitude grid (rows of equal z = cos θ, columns of equal φ), empty cells filled from their neighbours,
// smoothed once, interpolated bilinearly between cell centres (φ wraps around; rows clamp at the poles).
class RadiusOfDirection {
 public:
  RadiusOfDirection(const std::vector<glm::dvec3>& offsets) : radius_(kRows * kColumns, 0.0) {
    for (const glm::dvec3& offset : offsets) {
      const double length = glm::length(offset);
      if (length <= 0.0) continue;
      const glm::dvec2 cell = cellOf(offset / length);
      const int row = std::clamp(static_cast<int>(std::floor(cell.x + 0.5)), 0, kRows - 1);
      const int column = (static_cast<int>(std::floor(cell.y + 0.5)) % kColumns + kColumns) % kColumns;
      double& r = radius_[row * kColumns + column];
      r = std::max(r, length);
    }
    for (int pass = 0; pass < kRows + kColumns; ++pass) {  // empty cells: the mean of filled neighbours
      bool empty = false;
      std::vector<double> next = radius_;
      for (int row = 0; row < kRows; ++row)
        for (int column = 0; column < kColumns; ++column) {
          if (radius_[row * kColumns + column] > 0.0) continue;
          double sum = 0.0;
          int count = 0;
          forNeighbours(row, column, [&](double r) {
            if (r > 0.0) sum += r, ++count;
          });
          if (count > 0) next[row * kColumns + column] = sum / count;
          else empty = true;
        }
      radius_.swap(next);
      if (!empty) break;
    }
    std::vector<double> smooth(radius_.size());
    for (int row = 0; row < kRows; ++row)
      for (int column = 0; column < kColumns; ++column) {
        double sum = 0.0;
        int count = 0;
        forNeighbours(row, column, [&](double r) { sum += r, ++count; });
        smooth[row * kColumns + column] = 0.5 * radius_[row * kColumns + column] + 0.5 * sum / count;
      }
    radius_.swap(smooth);
  }

  double operator()(const glm::dvec3& direction) const {
    const glm::dvec2 cell = cellOf(direction);
    const double u = std::clamp(cell.x, 0.0, static_cast<double>(kRows - 1));
    const int row = std::min(static_cast<int>(std::floor(u)), kRows - 2);
    const double fu = u - row;
    const double floorV = std::floor(cell.y), fv = cell.y - floorV;
    const int column = (static_cast<int>(floorV) % kColumns + kColumns) % kColumns, nextColumn = (column + 1) % kColumns;
    const auto at = [&](int r, int c) { return radius_[r * kColumns + c]; };
    return (1.0 - fu) * ((1.0 - fv) * at(row, column) + fv * at(row, nextColumn)) +
           fu * ((1.0 - fv) * at(row + 1, column) + fv * at(row + 1, nextColumn));
  }

 private:
  static constexpr int kRows = 12, kColumns = 24;
  // Continuous cell coordinates (row, column) of a unit direction, cell centres at integers.
  static glm::dvec2 cellOf(const glm::dvec3& d) {
    double phi = std::atan2(d.y, d.x);
    if (phi < 0.0) phi += 2.0 * std::numbers::pi;
    return {(std::clamp(d.z, -1.0, 1.0) + 1.0) * 0.5 * kRows - 0.5, phi / (2.0 * std::numbers::pi) * kColumns - 0.5};
  }
  template <typename Visit>
  void forNeighbours(int row, int column, Visit visit) const {
    for (int r = std::max(row - 1, 0); r <= std::min(row + 1, kRows - 1); ++r)
      for (int c = column - 1; c <= column + 1; ++c)
        if (r != row || c != column) visit(radius_[r * kColumns + (c + kColumns) % kColumns]);
  }
  std::vector<double> radius_;
};

glm::dmat3 unitDeterminant(const glm::dmat3& m) { return m / std::cbrt(glm::determinant(m)); }

}  // namespace

void rebaseRestTowardBall(BodyParts& parts) {
  const std::vector<glm::dvec3>& x = parts.positions;
  glm::dvec3 centre(0.0);
  double volume = 0.0;
  for (const Tetrahedron& t : parts.tetrahedra) {
    const double v = glm::determinant(glm::dmat3(x[t.y] - x[t.x], x[t.z] - x[t.x], x[t.w] - x[t.x]));
    centre += v * (x[t.x] + x[t.y] + x[t.z] + x[t.w]) * 0.25;
    volume += v;
  }
  if (!(volume > 0.0)) return;
  centre /= volume;
  // The affine part first: the map that takes the tetrahedra's second moment about the centre to a
  // multiple of the identity, S^(−1/2) (a slime squashed by a hand or sagging on the floor is a nearly
  // affine image of a ball: a radial map alone would leave each part's squash in its rest shape).
  Eigen::Matrix3d moment = Eigen::Matrix3d::Zero();
  for (const Tetrahedron& t : parts.tetrahedra) {
    const double v = glm::determinant(glm::dmat3(x[t.y] - x[t.x], x[t.z] - x[t.x], x[t.w] - x[t.x]));
    const glm::dvec3 d = (x[t.x] + x[t.y] + x[t.z] + x[t.w]) * 0.25 - centre;
    const Eigen::Vector3d e(d.x, d.y, d.z);
    moment += v * e * e.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> spectrum(moment);
  if (!(spectrum.eigenvalues()(0) > 0.0)) return;
  const Eigen::Matrix3d rounding = spectrum.operatorInverseSqrt();
  std::vector<glm::dvec3> ball(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const glm::dvec3 d = x[i] - centre;
    const Eigen::Vector3d r = rounding * Eigen::Vector3d(d.x, d.y, d.z);
    ball[i] = glm::dvec3(r.x(), r.y(), r.z());
  }
  // Then radially onto a sphere: what is not affine (a piece pressed on as a nub) rounds in.
  const RadiusOfDirection radius(ball);
  for (glm::dvec3& p : ball) {
    const double length = glm::length(p);
    if (length > 0.0) p /= radius(p / length);
  }
  for (std::size_t e = 0; e < parts.tetrahedra.size(); ++e) {
    const Tetrahedron& t = parts.tetrahedra[e];
    const glm::dmat3 image(ball[t.y] - ball[t.x], ball[t.z] - ball[t.x], ball[t.w] - ball[t.x]);
    const double imageDeterminant = glm::determinant(image);
    const glm::dmat3 old = glm::inverse(parts.rest[e].restInverse);
    const double oldDeterminant = glm::determinant(old);
    if (!(imageDeterminant > 0.0) || !(oldDeterminant > 0.0)) continue;
    const glm::dmat3 reference = image * std::cbrt(oldDeterminant / imageDeterminant);
    const glm::dmat3 a = old * glm::inverse(reference);  // the old reference seen from the new one, det 1
    parts.rest[e] = makeTetRest(glm::dvec3(0.0), reference[0], reference[1], reference[2]);
    parts.plastic[e] = unitDeterminant(glm::transpose(a) * parts.plastic[e] * a);
    MaxwellRest& maxwell = parts.maxwell[e];
    maxwell.metric = unitDeterminant(glm::transpose(a) * maxwell.metric * a);
    maxwell.inverse = glm::inverse(maxwell.metric);
  }
}

void relaxLongTermTowardReference(BulkBody& body, double w) {
  for (std::size_t e = 0; e < body.mesh.tetrahedra.size(); ++e) {
    const glm::dmat3 metric = unitDeterminant(plasticMetric(body, e) * (1.0 - w) + glm::dmat3(w));
    for (int c = 0; c < 3; ++c)
      for (int r = c; r < 3; ++r)
        body.maxwell[e / kTetLanes].plastic[kSymmetricEntry[r][c]][e % kTetLanes] = static_cast<ElementReal>(metric[c][r]);
  }
  refreshMaxwellForceMaps(body);
}

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

void carryDrawnSurface(BulkBody& body, TriangleMesh drawn, double support, const std::vector<glm::dvec3>& reference) {
  if (reference.size() != body.state.positions.size())
    throw std::invalid_argument("carryDrawnSurface: " + std::to_string(reference.size()) + " reference positions for " +
                                std::to_string(body.state.positions.size()) + " nodes");
  const std::vector<glm::dvec3>& x = reference;
  // The smooth map is fitted from the reference (exact for affine motion from there), a few vertices a
  // step (BulkPiece::endStep); the element map, exact there too, places the surface meanwhile.
  beginSmoothFit(x, drawn.positions, support, body.embedding);

  // The element map: each drawn vertex in the tetrahedron under its nearest surface face, found in
  // cubic cells of the faces' mean edge length.
  const auto boundary = boundaryFaces(body.mesh.tetrahedra);
  double meanEdge = 0.0;
  for (const auto& face : boundary) meanEdge += glm::length(x[face.first.y] - x[face.first.x]);
  const double cell = std::max(meanEdge / static_cast<double>(std::max<std::size_t>(boundary.size(), 1)), 1e-4);
  const auto cellOf = [&](const glm::dvec3& p) { return glm::i64vec3(glm::floor(p / cell)); };
  // The faces by cell, in a dense grid of cells over the faces' box (a face in every cell its box meets),
  // and each face's box: a face whose box lies farther than the nearest face found so far is not measured.
  std::vector<std::pair<glm::dvec3, glm::dvec3>> boxes(boundary.size());
  glm::dvec3 lowest(std::numeric_limits<double>::infinity()), highest(-std::numeric_limits<double>::infinity());
  for (std::uint32_t f = 0; f < boundary.size(); ++f) {
    const Triangle& t = boundary[f].first;
    boxes[f] = {glm::min(x[t.x], glm::min(x[t.y], x[t.z])), glm::max(x[t.x], glm::max(x[t.y], x[t.z]))};
    lowest = glm::min(lowest, boxes[f].first);
    highest = glm::max(highest, boxes[f].second);
  }
  const glm::i64vec3 first = cellOf(lowest), last = cellOf(highest), span = last - first + glm::i64vec3(1);
  const auto cellIndex = [&](const glm::i64vec3& c) {
    return static_cast<std::size_t>((c.z - first.z) * span.y * span.x + (c.y - first.y) * span.x + (c.x - first.x));
  };
  std::vector<std::uint32_t> cellStart(static_cast<std::size_t>(span.x * span.y * span.z) + 1, 0), cellFaces;
  for (int fill = 0; fill < 2; ++fill) {  // count, then place
    if (fill == 1) {
      for (std::size_t c = 1; c < cellStart.size(); ++c) cellStart[c] += cellStart[c - 1];
      cellFaces.resize(cellStart.back());
    }
    std::vector<std::uint32_t> placed(fill == 1 ? cellStart.size() - 1 : 0);
    for (std::uint32_t f = 0; f < boundary.size(); ++f) {
      const glm::i64vec3 low = cellOf(boxes[f].first), high = cellOf(boxes[f].second);
      for (std::int64_t c = low.z; c <= high.z; ++c)
        for (std::int64_t b = low.y; b <= high.y; ++b)
          for (std::int64_t a = low.x; a <= high.x; ++a) {
            const std::size_t k = cellIndex({a, b, c});
            if (fill == 0) ++cellStart[k + 1];
            else cellFaces[cellStart[k] + placed[k]++] = f;
          }
    }
  }
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
    const auto visit = [&](const glm::i64vec3& c) {
      if (glm::any(glm::lessThan(c, first)) || glm::any(glm::greaterThan(c, last))) return;
      // A cell farther than the nearest face found so far holds no nearer one: a nearer face's nearest
      // point would lie in a cell within that distance, and the face is listed in every cell its box meets.
      const glm::dvec3 cellLow = glm::dvec3(c) * cell;
      const glm::dvec3 away = glm::max(glm::max(cellLow - p, p - (cellLow + glm::dvec3(cell))), glm::dvec3(0.0));
      if (glm::dot(away, away) > bestDistance) return;
      const std::size_t k = cellIndex(c);
      for (std::uint32_t slot = cellStart[k]; slot < cellStart[k + 1]; ++slot) {
        const std::uint32_t f = cellFaces[slot];
        const glm::dvec3 outside = glm::max(glm::max(boxes[f].first - p, p - boxes[f].second), glm::dvec3(0.0));
        if (glm::dot(outside, outside) > bestDistance) continue;
        const Triangle& t = boundary[f].first;
        const double d = squaredDistanceToTriangle(p, x[t.x], x[t.y], x[t.z]);
        if (d < bestDistance || (d == bestDistance && f < best)) {
          bestDistance = d;
          best = f;
        }
      }
    };
    visit(home);  // first, so that the boxes prune most of the faces around it
    for (std::int64_t ring = 1; ring < (1 << 20); ring *= 2) {
      // Only the cells of the grid: a ring past it on every side holds nothing more.
      const glm::i64vec3 from = glm::max(home - glm::i64vec3(ring), first), to = glm::min(home + glm::i64vec3(ring), last);
      for (std::int64_t c = from.z; c <= to.z; ++c)
        for (std::int64_t b = from.y; b <= to.y; ++b)
          for (std::int64_t a = from.x; a <= to.x; ++a) visit({a, b, c});
      // Found within the ring's reach: no face outside it is nearer; or the ring held every cell.
      if (bestDistance <= (static_cast<double>(ring) * cell) * (static_cast<double>(ring) * cell)) break;
      if (glm::all(glm::lessThanEqual(home - glm::i64vec3(ring), first)) && glm::all(glm::greaterThanEqual(home + glm::i64vec3(ring), last))) break;
    }
    const Tetrahedron& t = body.mesh.tetrahedra[boundary[best].second];
    embedding.nodes[v] = t;
    embedding.weights[v] = barycentric(p, x[t.x], x[t.y], x[t.z], x[t.w]);
    embedding.verticesOfSurfaceTriangle[best].push_back(v);
  }
  body.drawn = std::move(drawn);
}

}  // namespace slime

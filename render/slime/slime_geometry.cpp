#include "render/slime/slime_geometry.h"

#include "render/simd/lanes.h"
#include "render/trace/tsan_handoff.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace slime {
namespace {

constexpr std::size_t kClusterSize = 16;  // vertices per cluster at most: two lanes' worth

// Splits vertices [begin, end) of `order` at the median of their longest extent until each part holds
// kClusterSize or fewer, appending each part's start to `begins`.
void splitClusters(const std::vector<glm::vec3>& positions, std::vector<std::uint32_t>& order, std::size_t begin,
                   std::size_t end, std::vector<std::uint32_t>& begins) {
  if (end - begin <= kClusterSize) {
    begins.push_back(static_cast<std::uint32_t>(begin));
    return;
  }
  glm::vec3 low(kInfinity), high(-kInfinity);
  for (std::size_t i = begin; i < end; ++i) {
    low = glm::min(low, positions[order[i]]);
    high = glm::max(high, positions[order[i]]);
  }
  const glm::vec3 extent = high - low;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
  const std::size_t middle = begin + (end - begin) / 2;
  std::nth_element(order.begin() + static_cast<std::ptrdiff_t>(begin), order.begin() + static_cast<std::ptrdiff_t>(middle),
                   order.begin() + static_cast<std::ptrdiff_t>(end),
                   [&](std::uint32_t a, std::uint32_t b) { return positions[a][axis] < positions[b][axis]; });
  splitClusters(positions, order, begin, middle, begins);
  splitClusters(positions, order, middle, end, begins);
}

}  // namespace

bool SlimeGeometry::update(std::span<const SurfaceView> surfaces) {
  std::size_t vertexTotal = 0, triangleTotal = 0;
  for (const SurfaceView& surface : surfaces) {
    vertexTotal += surface.positions.size();
    triangleTotal += surface.triangles.size();
  }
  // The topology is the pieces' triangles, each offset by the vertices before its piece.
  bool topologyChanged = triangleTotal != triangles.size() || vertexTotal != vertexCount();
  for (std::size_t piece = 0, f = 0, offset = 0; !topologyChanged && piece < surfaces.size(); ++piece) {
    const Triangle shift(static_cast<std::uint32_t>(offset));
    for (const Triangle& t : surfaces[piece].triangles)
      if (triangles[f++] != t + shift) {
        topologyChanged = true;
        break;
      }
    offset += surfaces[piece].positions.size();
  }
  if (topologyChanged) {
    triangles.clear();
    triangles.reserve(triangleTotal);
    std::size_t offset = 0;
    for (std::size_t piece = 0; piece < surfaces.size(); ++piece) {
      const std::size_t count = surfaces[piece].positions.size();
      for (const Triangle& t : surfaces[piece].triangles) {
        if (t.x >= count || t.y >= count || t.z >= count)
          throw std::invalid_argument("slime piece " + std::to_string(piece) + ": a triangle indexes vertex " +
                                      std::to_string(std::max({t.x, t.y, t.z})) + " of its " + std::to_string(count) +
                                      " (each piece's triangles index its own vertices, from 0)");
        triangles.push_back(t + Triangle(static_cast<std::uint32_t>(offset)));
      }
      offset += count;
    }
  }
  pieceTriangleStarts.clear();
  for (std::size_t piece = 0, start = 0; piece < surfaces.size(); start += surfaces[piece++].triangles.size())
    pieceTriangleStarts.push_back(static_cast<std::uint32_t>(start));
  positions.resize(vertexTotal + 1);
  glm::vec3 low(kInfinity), high(-kInfinity);
  glm::vec3* vertex = positions.data();
  for (const SurfaceView& surface : surfaces) {
    for (const glm::dvec3& p : surface.positions) {
      *vertex = glm::vec3(p);
      // A non-finite vertex (a diverged simulation) would poison the BVH: pin it to the origin.
      if (!std::isfinite(vertex->x + vertex->y + vertex->z)) *vertex = glm::vec3(0.0f);
      low = glm::min(low, *vertex);
      high = glm::max(high, *vertex);
      ++vertex;
    }
  }
  positions.back() = glm::vec3(0.0f);
  if (topologyChanged) buildClusters();

  // Vertex normals: the sum of the faces' cross products, i.e. area-weighted face normals.
  // The faces' own unit normals are kept too: a hit then costs a lookup, not three vertex loads.
  normals.assign(vertexTotal, glm::vec3(0.0f));
  faceNormals.resize(triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const Triangle& t = triangles[i];
    faceNormals[i] = glm::cross(positions[t.y] - positions[t.x], positions[t.z] - positions[t.x]);
    normals[t.x] += faceNormals[i];
    normals[t.y] += faceNormals[i];
    normals[t.z] += faceNormals[i];
  }
  for (glm::vec3& n : normals) {
    const float length = glm::length(n);
    n = length > 0.0f && std::isfinite(length) ? n / length : glm::vec3(0.0f, 0.0f, 1.0f);
  }
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const Triangle& t = triangles[i];
    const float length = glm::length(faceNormals[i]);
    if (length > 0.0f && std::isfinite(length)) {
      faceNormals[i] /= length;
    } else {
      // A collapsed (zero-area) triangle has no normal of its own: fall back to its vertex normals.
      const glm::vec3 average = normals[t.x] + normals[t.y] + normals[t.z];
      const float averageLength = glm::length(average);
      faceNormals[i] = averageLength > 0.0f ? average / averageLength : glm::vec3(0.0f, 0.0f, 1.0f);
    }
  }

  boundCenter = vertexTotal == 0 ? glm::vec3(0.0f) : 0.5f * (low + high);
  float radius2 = 0.0f;
  glm::vec3 sum(0.0f);
  for (std::size_t i = 0; i < vertexTotal; ++i) {
    const glm::vec3 d = positions[i] - boundCenter;
    radius2 = std::max(radius2, glm::dot(d, d));
    sum += positions[i];
  }
  boundRadius = std::sqrt(radius2);
  meshBoundCenter = boundCenter;
  meshBoundRadius = boundRadius;
  if (vertexTotal > 0) sphereCenter = sum / static_cast<float>(vertexTotal);
  analyticSphere = sphereRequested && vertexTotal > 0;
  if (analyticSphere) {
    boundCenter = sphereCenter;
    boundRadius = sphereRadius;
  }

  findSupportingTriangles();
  return topologyChanged;
}

void SlimeGeometry::buildClusters() {
  const std::size_t count = vertexCount();
  clusterOrder.resize(count);
  for (std::size_t i = 0; i < count; ++i) clusterOrder[i] = static_cast<std::uint32_t>(i);
  clusterBegin.clear();
  if (count > 0) splitClusters(positions, clusterOrder, 0, count, clusterBegin);
  clusterBegin.push_back(static_cast<std::uint32_t>(count));

  // The tree's shape: level 0 the clusters, each level above one node for each 8 consecutive nodes
  // of the level below, up to a top of at most 8. A node holds a run of clusterOrder (its vertices);
  // every level is padded to whole lanes with empty nodes (radius −∞, far below every plane), and the
  // clusters' vertex slots past their vertices are NaN (never above a plane): only the real nodes'
  // bounds and vertices change from frame to frame.
  const std::size_t clusters = clusterBegin.size() - 1;
  nodeLevels.clear();
  nodeRuns.clear();
  for (std::size_t depth = 0, nodes = clusters, span = 1; nodes > 0; ++depth, span *= 8) {
    NodeBounds& level = nodeLevels.emplace_back();
    for (auto& values : level.values) values.assign((nodes + 7) / 8 * 8, 0.0f);
    std::fill(level.values[NodeBounds::kRadius].begin(), level.values[NodeBounds::kRadius].end(), -kInfinity);
    for (std::size_t k = 0; k < nodes; ++k)
      nodeRuns.push_back({static_cast<std::uint32_t>(depth), static_cast<std::uint32_t>(k), clusterBegin[k * span],
                          clusterBegin[std::min(clusters, (k + 1) * span)]});
    if (nodes <= 8) break;
    nodes = (nodes + 7) / 8;
  }
  for (auto& values : clusterVertices) values.assign(clusters * kClusterSize, std::nanf(""));
}

void SlimeGeometry::NodeBounds::set(std::size_t k, const std::vector<std::uint32_t>& order, const std::vector<glm::vec3>& positions,
                                    const std::vector<glm::vec3>& normals, std::size_t begin, std::size_t end) {
  glm::vec3 centre(0.0f), normal(0.0f);
  for (std::size_t i = begin; i < end; ++i) {
    centre += positions[order[i]];
    normal += normals[order[i]];
  }
  centre /= static_cast<float>(end - begin);
  const float length = glm::length(normal);
  normal = length > 1e-6f && std::isfinite(length) ? normal / length : glm::vec3(0.0f, 0.0f, 1.0f);
  float radius2 = 0.0f, across2 = 0.0f, thickness = 0.0f;
  for (std::size_t i = begin; i < end; ++i) {
    const glm::vec3 d = positions[order[i]] - centre;
    const float along = glm::dot(d, normal);
    const glm::vec3 inPlane = d - along * normal;
    radius2 = std::max(radius2, glm::dot(d, d));
    across2 = std::max(across2, glm::dot(inPlane, inPlane));
    thickness = std::max(thickness, std::abs(along));
  }
  // Rounding: each bound must hold its vertices.
  const auto padded = [](float value) { return value * 1.0001f + 1e-7f; };
  for (int c = 0; c < 3; ++c) {
    values[kCentre + c][k] = centre[c];
    values[kNormal + c][k] = normal[c];
  }
  values[kRadius][k] = padded(std::sqrt(radius2));
  values[kAcross][k] = padded(std::sqrt(across2));
  values[kThickness][k] = padded(thickness);
}

// The lower of the sphere's top and the disk's: the disk's top lies radius·sin + thickness·|cos|
// above its centre, for the angle between n and the disk's normal.
unsigned SlimeGeometry::NodeBounds::above(std::size_t k, const glm::vec3& n, float level) const {
  const auto load = [&](int field) { return Lanes::load(&values[field][k]); };
  const Lanes centre = load(kCentre) * n.x + load(kCentre + 1) * n.y + load(kCentre + 2) * n.z;
  const Lanes cosine = load(kNormal) * n.x + load(kNormal + 1) * n.y + load(kNormal + 2) * n.z;
  const Lanes sine = sqrt(max(Lanes(1.0f) - cosine * cosine, Lanes(0.0f)));
  const Lanes disk = load(kAcross) * sine + load(kThickness) * max(cosine, -cosine);
  return (centre + min(load(kRadius), disk) > level).mask();
}

void SlimeGeometry::findSupportingTriangles() {
  supporting.assign(triangles.size(), 0);
  if (vertexCount() == 0 || clusterBegin.size() < 2 || !(boundRadius > 0.0f)) {  // none is known to support it
    listNonSupporting();
    return;
  }
  // Every level passes over all the vertices: the nodes of all levels are bounded side by side.
  handOff(this);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nodeRuns.size(), 32), [&](const tbb::blocked_range<std::size_t>& range) {
    takeOver(this);
    for (std::size_t i = range.begin(); i < range.end(); ++i) {
      const NodeRun& node = nodeRuns[i];
      nodeLevels[node.depth].set(node.index, clusterOrder, positions, normals, node.begin, node.end);
    }
    handOff(this);
  });
  takeOver(this);
  // The vertices cluster by cluster in kClusterSize slots (two lanes' worth).
  for (std::size_t k = 0; k + 1 < clusterBegin.size(); ++k)
    for (std::uint32_t i = clusterBegin[k]; i < clusterBegin[k + 1]; ++i)
      for (int c = 0; c < 3; ++c) clusterVertices[c][k * kClusterSize + (i - clusterBegin[k])] = positions[clusterOrder[i]][c];
  // A triangle supports the slime when no vertex rises more than the tolerance above its plane:
  // nodes wholly below it are passed over with all they hold, eight at a time, from the top down.
  const float tolerance = kConvexTolerance * boundRadius;
  // Whether a vertex under the 8 nodes of `depth` from `first` on rises above the plane n·x = level.
  const auto rises = [&](const auto& self, std::size_t depth, std::size_t first, const glm::vec3& n, float level) -> bool {
    for (unsigned bits = nodeLevels[depth].above(first, n, level); bits != 0; bits &= bits - 1) {
      const std::size_t k = first + static_cast<std::size_t>(__builtin_ctz(bits));
      if (depth > 0) {
        if (self(self, depth - 1, 8 * k, n, level)) return true;
        continue;
      }
      for (std::size_t i = k * kClusterSize; i < (k + 1) * kClusterSize; i += 8) {
        const Lanes height = Lanes::load(&clusterVertices[0][i]) * n.x + Lanes::load(&clusterVertices[1][i]) * n.y +
                             Lanes::load(&clusterVertices[2][i]) * n.z;
        if ((height > level).mask() != 0) return true;
      }
    }
    return false;
  };
  const auto supportsSlime = [&](std::size_t f) {
    const glm::vec3 n = faceNormals[f];
    const float level = glm::dot(n, positions[triangles[f].x]) + tolerance;  // the plane, lifted by the tolerance
    return !rises(rises, nodeLevels.size() - 1, 0, n, level);
  };
  handOff(this);  // the frame's positions and spheres, to the workers (render/trace/tsan_handoff.h)
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles.size(), 256), [&](const tbb::blocked_range<std::size_t>& range) {
    takeOver(this);
    for (std::size_t f = range.begin(); f < range.end(); ++f) supporting[f] = supportsSlime(f) ? 1 : 0;
    handOff(this);  // their marks, back to the caller
  });
  takeOver(this);
  listNonSupporting();
}

void SlimeGeometry::listNonSupporting() {
  nonSupportingTriangles.clear();
  nonSupportingPrimitives.clear();
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    if (supporting[f] != 0) continue;
    nonSupportingTriangles.push_back(triangles[f]);
    nonSupportingPrimitives.push_back(static_cast<std::uint32_t>(f));
  }
  convex = !triangles.empty() && nonSupportingTriangles.empty();
  // Their bounding sphere: the centre of their box, the farthest of their vertices.
  glm::vec3 low(kInfinity), high(-kInfinity);
  for (const Triangle& t : nonSupportingTriangles)
    for (const std::uint32_t v : {t.x, t.y, t.z}) {
      low = glm::min(low, positions[v]);
      high = glm::max(high, positions[v]);
    }
  nonSupportingCenter = nonSupportingTriangles.empty() ? glm::vec3(0.0f) : 0.5f * (low + high);
  float radius2 = 0.0f;
  for (const Triangle& t : nonSupportingTriangles)
    for (const std::uint32_t v : {t.x, t.y, t.z}) {
      const glm::vec3 d = positions[v] - nonSupportingCenter;
      radius2 = std::max(radius2, glm::dot(d, d));
    }
  nonSupportingRadius = std::sqrt(radius2);
}

void SlimeGeometry::setAnalyticSphere(bool enabled, float radius) {
  sphereRequested = enabled;
  analyticSphere = enabled && vertexCount() > 0;
  sphereRadius = radius;
  boundCenter = analyticSphere ? sphereCenter : meshBoundCenter;
  boundRadius = analyticSphere ? sphereRadius : meshBoundRadius;
}

}  // namespace slime

#include "render/slime_geometry.h"

#include "render/lanes.h"
#include "render/tsan_handoff.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

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

bool SlimeGeometry::update(const std::vector<glm::dvec3>& newPositions, const std::vector<Triangle>& newTriangles) {
  const bool topologyChanged = newTriangles != triangles || newPositions.size() != vertexCount();
  if (topologyChanged) triangles = newTriangles;
  positions.resize(newPositions.size() + 1);
  glm::vec3 low(kInfinity), high(-kInfinity);
  for (std::size_t i = 0; i < newPositions.size(); ++i) {
    positions[i] = glm::vec3(newPositions[i]);
    // A non-finite vertex (a diverged simulation) would poison the BVH: pin it to the origin.
    if (!std::isfinite(positions[i].x + positions[i].y + positions[i].z)) positions[i] = glm::vec3(0.0f);
    low = glm::min(low, positions[i]);
    high = glm::max(high, positions[i]);
  }
  positions.back() = glm::vec3(0.0f);
  if (topologyChanged) buildClusters();

  // Vertex normals: the sum of the faces' cross products, i.e. area-weighted face normals.
  // The faces' own unit normals are kept too: a hit then costs a lookup, not three vertex loads.
  normals.assign(newPositions.size(), glm::vec3(0.0f));
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

  boundCenter = newPositions.empty() ? glm::vec3(0.0f) : 0.5f * (low + high);
  float radius2 = 0.0f;
  glm::vec3 sum(0.0f);
  for (std::size_t i = 0; i < newPositions.size(); ++i) {
    const glm::vec3 d = positions[i] - boundCenter;
    radius2 = std::max(radius2, glm::dot(d, d));
    sum += positions[i];
  }
  boundRadius = std::sqrt(radius2);
  meshBoundCenter = boundCenter;
  meshBoundRadius = boundRadius;
  if (!newPositions.empty()) sphereCenter = sum / static_cast<float>(newPositions.size());
  analyticSphere = sphereRequested && !newPositions.empty();
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
}

void SlimeGeometry::findSupportingTriangles() {
  supporting.assign(triangles.size(), 0);
  if (vertexCount() == 0 || clusterBegin.size() < 2 || !(boundRadius > 0.0f)) {  // none is known to support it
    listNonSupporting();
    return;
  }
  // Each cluster's bounding sphere (centroid, farthest member), and each group of 8 consecutive
  // clusters' (neighbours in the median splits), padded with empty spheres far below every plane
  // (radius −∞) to whole lanes.
  const std::size_t clusters = clusterBegin.size() - 1, padded = (clusters + 63) / 64 * 64, groups = padded / 8;
  for (auto& values : clusterSpheres) values.assign(padded, 0.0f);
  for (auto& values : groupSpheres) values.assign((groups + 7) / 8 * 8, 0.0f);
  std::fill(clusterSpheres[3].begin() + static_cast<std::ptrdiff_t>(clusters), clusterSpheres[3].end(), -kInfinity);
  std::fill(groupSpheres[3].begin(), groupSpheres[3].end(), -kInfinity);
  for (std::size_t k = 0; k < clusters; ++k) {
    glm::vec3 centre(0.0f);
    for (std::uint32_t i = clusterBegin[k]; i < clusterBegin[k + 1]; ++i) centre += positions[clusterOrder[i]];
    centre /= static_cast<float>(clusterBegin[k + 1] - clusterBegin[k]);
    float radius2 = 0.0f;
    for (std::uint32_t i = clusterBegin[k]; i < clusterBegin[k + 1]; ++i) {
      const glm::vec3 d = positions[clusterOrder[i]] - centre;
      radius2 = std::max(radius2, glm::dot(d, d));
    }
    for (int c = 0; c < 3; ++c) clusterSpheres[c][k] = centre[c];
    clusterSpheres[3][k] = std::sqrt(radius2);
  }
  // The vertices cluster by cluster in kClusterSize slots (two lanes' worth), the empty slots NaN
  // (never above a plane).
  for (auto& values : clusterVertices) values.assign(clusters * kClusterSize, std::nanf(""));
  for (std::size_t k = 0; k < clusters; ++k)
    for (std::uint32_t i = clusterBegin[k]; i < clusterBegin[k + 1]; ++i)
      for (int c = 0; c < 3; ++c) clusterVertices[c][k * kClusterSize + (i - clusterBegin[k])] = positions[clusterOrder[i]][c];
  for (std::size_t g = 0; g * 8 < clusters; ++g) {
    const std::size_t first = g * 8, last = std::min(clusters, first + 8);
    glm::vec3 centre(0.0f);
    for (std::size_t k = first; k < last; ++k) centre += glm::vec3(clusterSpheres[0][k], clusterSpheres[1][k], clusterSpheres[2][k]);
    centre /= static_cast<float>(last - first);
    float radius = 0.0f;
    for (std::size_t k = first; k < last; ++k)
      radius = std::max(radius, glm::length(glm::vec3(clusterSpheres[0][k], clusterSpheres[1][k], clusterSpheres[2][k]) - centre) +
                                    clusterSpheres[3][k]);
    for (int c = 0; c < 3; ++c) groupSpheres[c][g] = centre[c];
    groupSpheres[3][g] = radius * 1.0001f + 1e-7f;  // rounding: the group's sphere must hold its clusters'
  }
  // A triangle supports the slime when no vertex rises more than the tolerance above its plane:
  // groups, then clusters, whose sphere lies wholly below are passed over, eight at a time.
  const float tolerance = kConvexTolerance * boundRadius;
  const auto above = [](const std::vector<float>* spheres, std::size_t k, const glm::vec3& n, float level) {
    const Lanes height = Lanes::load(&spheres[0][k]) * n.x + Lanes::load(&spheres[1][k]) * n.y +
                         Lanes::load(&spheres[2][k]) * n.z + Lanes::load(&spheres[3][k]);
    return (height > level).mask();
  };
  const auto supportsSlime = [&](std::size_t f) {
    const glm::vec3 n = faceNormals[f];
    const float level = glm::dot(n, positions[triangles[f].x]) + tolerance;  // the plane, lifted by the tolerance
    for (std::size_t g = 0; g < groupSpheres[0].size(); g += 8) {
      for (unsigned groupBits = above(groupSpheres, g, n, level); groupBits != 0; groupBits &= groupBits - 1) {
        const std::size_t group = g + static_cast<std::size_t>(__builtin_ctz(groupBits));
        for (unsigned bits = above(clusterSpheres, 8 * group, n, level); bits != 0; bits &= bits - 1) {
          const std::size_t first = (8 * group + static_cast<std::size_t>(__builtin_ctz(bits))) * kClusterSize;
          for (std::size_t i = first; i < first + kClusterSize; i += 8) {
            const Lanes height = Lanes::load(&clusterVertices[0][i]) * n.x + Lanes::load(&clusterVertices[1][i]) * n.y +
                                 Lanes::load(&clusterVertices[2][i]) * n.z;
            if ((height > level).mask() != 0) return false;
          }
        }
      }
    }
    return true;
  };
  handOff(this);  // the frame's positions and spheres, to the workers (render/tsan_handoff.h)
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

#include "core/geometry/icosphere.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

namespace slime {
namespace {

// The 12 vertices of a regular icosahedron, (0, ±1, ±φ) and its cyclic permutations.
TriangleMesh unitIcosahedron() {
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  TriangleMesh mesh;
  mesh.positions = {{-1, phi, 0}, {1, phi, 0}, {-1, -phi, 0}, {1, -phi, 0},
                    {0, -1, phi}, {0, 1, phi}, {0, -1, -phi}, {0, 1, -phi},
                    {phi, 0, -1}, {phi, 0, 1}, {-phi, 0, -1}, {-phi, 0, 1}};
  for (auto& p : mesh.positions) p = glm::normalize(p);
  mesh.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                    {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                    {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                    {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  return mesh;
}

// Splits every triangle into four; midpoints are shared between the two triangles of an edge.
void subdivide(TriangleMesh& mesh) {
  std::unordered_map<std::uint64_t, std::uint32_t> midpointOf;
  midpointOf.reserve(mesh.triangles.size() * 3 / 2);
  auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
    const std::uint64_t key = (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
    auto [it, inserted] = midpointOf.try_emplace(key, static_cast<std::uint32_t>(mesh.positions.size()));
    if (inserted) mesh.positions.push_back(glm::normalize(mesh.positions[a] + mesh.positions[b]));
    return it->second;
  };
  std::vector<Triangle> finer;
  finer.reserve(mesh.triangles.size() * 4);
  for (const Triangle& t : mesh.triangles) {
    const std::uint32_t ab = midpoint(t.x, t.y), bc = midpoint(t.y, t.z), ca = midpoint(t.z, t.x);
    finer.push_back({t.x, ab, ca});
    finer.push_back({t.y, bc, ab});
    finer.push_back({t.z, ca, bc});
    finer.push_back({ab, bc, ca});
  }
  mesh.triangles = std::move(finer);
}

}  // namespace

TriangleMesh makeIcosphere(int level, double radius, const glm::dvec3& center) {
  if (level < 0 || level > kMaxLevel)
    throw std::invalid_argument("icosphere level " + std::to_string(level) + " is outside 0.." +
                                std::to_string(kMaxLevel));
  TriangleMesh mesh = unitIcosahedron();
  for (int i = 0; i < level; ++i) subdivide(mesh);
  for (auto& p : mesh.positions) p = center + radius * p;
  return mesh;
}

std::vector<glm::u32vec2> uniqueEdges(const std::vector<Triangle>& triangles) {
  std::vector<glm::u32vec2> edges;
  edges.reserve(triangles.size() * 3);
  for (const Triangle& t : triangles) {
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t a = t[i], b = t[(i + 1) % 3];
      edges.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(edges.begin(), edges.end(),
            [](const auto& l, const auto& r) { return l.x != r.x ? l.x < r.x : l.y < r.y; });
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

}  // namespace slime

#include "core/bulk/tet_mesh.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

namespace slime {
namespace {

void addPositive(std::vector<Tetrahedron>& tetrahedra, const std::vector<glm::dvec3>& x, Tetrahedron t) {
  if (tetrahedronVolume(x[t.x], x[t.y], x[t.z], x[t.w]) < 0.0) std::swap(t.z, t.w);
  tetrahedra.push_back(t);
}

}  // namespace

double tetrahedronVolume(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d) {
  return glm::dot(b - a, glm::cross(c - a, d - a)) / 6.0;
}

TetMesh makeBallTetMesh(int resolution, double radius, const glm::dvec3& center) {
  if (resolution < kMinBodyResolution || resolution > kMaxBodyResolution)
    throw std::invalid_argument("body resolution " + std::to_string(resolution) + " is outside " +
                                std::to_string(kMinBodyResolution) + ".." + std::to_string(kMaxBodyResolution));
  const TriangleMesh unit = makeIcosphere(resolution, 1.0, glm::dvec3(0.0));
  const std::size_t perShell = unit.positions.size();
  TetMesh mesh;
  mesh.shellLevel = resolution;
  const int divisions = 1 << resolution;  // K: the radius in K equal steps, as fine as the shell edges
  mesh.surfaceNodes = perShell;
  // K/2 + 1 shells evenly spaced from R down to r_in (the outer part of the radius, where the n = 2
  // modes and the contact deform it most); the centre is coned to the innermost one. r_in was R/2 (the
  // radial step R/K): the innermost shell's triangles then had half the surface's edge, its elements were
  // the thinnest and set ω_max, the explicit step's limit. Even spacing is best once that shell's edge
  // r_in·e_s matches the radial step, r_in ≈ 0.64 R (issue 27, branches mesh2 and mesh3;
  // docs/performance.md): ω_max −20 % at resolutions 3 and 4. Resolutions 1 and 2 keep R/2: there the
  // bigger one-element-deep core cone changed what the tests measure (at 0.6 R the torture's yank and
  // fling with explicit_euler and rk4 rolled back at resolution 1; at 0.55 R a press through to the floor
  // did not come back at resolution 2, at 0.64 R the landing's volume and the pinch's creep failed).
  const double innerRadius[] = {0.5, 0.5, 0.64, 0.64};
  const int steps = std::max(1, divisions / 2);
  std::vector<double> radii;
  for (int k = 0; k <= steps; ++k)
    radii.push_back(radius * (1.0 - (1.0 - innerRadius[resolution - 1]) * k / steps));
  for (double r : radii)
    for (const glm::dvec3& direction : unit.positions) mesh.positions.push_back(center + r * direction);
  const auto centreNode = static_cast<std::uint32_t>(mesh.positions.size());
  mesh.positions.push_back(center);
  mesh.surface = unit.triangles;
  const auto node = [&](std::size_t shell, std::uint32_t vertex) {
    return static_cast<std::uint32_t>(shell * perShell + vertex);
  };

  // Per surface triangle: the outer layer's tetrahedra first (the embedding looks there), then the
  // layers inwards, then the cone to the centre.
  const std::vector<glm::dvec3>& x = mesh.positions;
  for (const Triangle& t : unit.triangles) {
    mesh.outerPrism.push_back(static_cast<std::uint32_t>(mesh.tetrahedra.size()));
    std::array<std::uint32_t, 3> v{t.x, t.y, t.z};
    std::sort(v.begin(), v.end());
    for (std::size_t shell = 0; shell + 1 < radii.size(); ++shell) {
      // Prism between this shell (top) and the next inwards (bottom); each lateral quad is cut from the
      // top of its smaller vertex to the bottom of its larger one, the same in both prisms sharing it.
      const auto top = [&](int i) { return node(shell, v[i]); };
      const auto bottom = [&](int i) { return node(shell + 1, v[i]); };
      addPositive(mesh.tetrahedra, x, {top(0), top(1), top(2), bottom(2)});
      addPositive(mesh.tetrahedra, x, {top(0), top(1), bottom(1), bottom(2)});
      addPositive(mesh.tetrahedra, x, {top(0), bottom(0), bottom(1), bottom(2)});
    }
    const std::size_t inner = radii.size() - 1;
    addPositive(mesh.tetrahedra, x, {node(inner, v[0]), node(inner, v[1]), node(inner, v[2]), centreNode});
  }
  mesh.shells = static_cast<int>(radii.size());
  mesh.outerPrismSize = radii.size() >= 2 ? 3 : 1;
  return mesh;
}

std::vector<glm::u32vec2> tetrahedronEdges(const std::vector<Tetrahedron>& tetrahedra) {
  std::vector<glm::u32vec2> edges;
  edges.reserve(tetrahedra.size() * 6);
  for (const Tetrahedron& t : tetrahedra)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) edges.push_back({std::min(t[i], t[j]), std::max(t[i], t[j])});
  std::sort(edges.begin(), edges.end(),
            [](const auto& l, const auto& r) { return l.x != r.x ? l.x < r.x : l.y < r.y; });
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

}  // namespace slime

#include "core/bulk/surface_embedding.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace slime {

glm::dvec4 barycentric(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                       const glm::dvec3& d) {
  const glm::dvec3 local = glm::inverse(glm::dmat3(b - a, c - a, d - a)) * (p - a);
  return {1.0 - local.x - local.y - local.z, local.x, local.y, local.z};
}

SurfaceEmbedding embedSurface(const TetMesh& body, const TriangleMesh& drawn, int drawnLevel) {
  if (drawnLevel < body.shellLevel)
    throw std::invalid_argument("the drawn level must be at least the body's shell level");
  const int shift = 2 * (drawnLevel - body.shellLevel);
  SurfaceEmbedding embedding;
  const std::size_t count = drawn.positions.size();
  embedding.nodes.assign(count, Tetrahedron(0));
  embedding.weights.assign(count, glm::dvec4(0.0));
  embedding.verticesOfSurfaceTriangle.assign(body.surface.size(), {});
  std::vector<bool> done(count, false);
  for (std::size_t j = 0; j < drawn.triangles.size(); ++j) {
    const std::size_t parent = j >> shift;
    for (int corner = 0; corner < 3; ++corner) {
      const std::uint32_t vertex = drawn.triangles[j][corner];
      if (done[vertex]) continue;
      done[vertex] = true;
      // The outer layer's tetrahedron under this surface triangle that holds the vertex best
      // (largest smallest weight; the vertex may sit just outside all of them).
      double best = -std::numeric_limits<double>::infinity();
      for (int k = 0; k < body.outerPrismSize; ++k) {
        const Tetrahedron& t = body.tetrahedra[body.outerPrism[parent] + k];
        const glm::dvec4 w = barycentric(drawn.positions[vertex], body.positions[t.x], body.positions[t.y],
                                         body.positions[t.z], body.positions[t.w]);
        const double smallest = std::min(std::min(w.x, w.y), std::min(w.z, w.w));
        if (smallest > best) {
          best = smallest;
          embedding.nodes[vertex] = t;
          embedding.weights[vertex] = w;
        }
      }
      embedding.verticesOfSurfaceTriangle[parent].push_back(vertex);
    }
  }
  return embedding;
}

void placeEmbedded(const SurfaceEmbedding& embedding, const std::vector<glm::dvec3>& body,
                   std::vector<glm::dvec3>& drawn) {
  const std::size_t count = embedding.nodes.size();
  drawn.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    const Tetrahedron& t = embedding.nodes[i];
    const glm::dvec4& w = embedding.weights[i];
    drawn[i] = w.x * body[t.x] + w.y * body[t.y] + w.z * body[t.z] + w.w * body[t.w];
  }
}

}  // namespace slime

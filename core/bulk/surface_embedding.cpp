#include "core/bulk/eigen.h"  // first: see its header
#include "core/bulk/surface_embedding.h"

#include <glm/common.hpp>
#include <glm/ext/vector_int3_sized.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace slime {
namespace {

// The body's nodes in cubic cells of side `cell` (m), for the neighbours within a radius.
class NodeGrid {
 public:
  NodeGrid(const std::vector<glm::dvec3>& positions, double cell) : positions_(positions), cell_(cell) {
    for (std::uint32_t i = 0; i < positions.size(); ++i) cells_[key(cellOf(positions[i]))].push_back(i);
  }

  // Every node within `radius` of p, appended to `out` (cleared first).
  void within(const glm::dvec3& p, double radius, std::vector<std::uint32_t>& out) const {
    out.clear();
    const glm::i64vec3 low = cellOf(p - glm::dvec3(radius)), high = cellOf(p + glm::dvec3(radius));
    for (std::int64_t x = low.x; x <= high.x; ++x)
      for (std::int64_t y = low.y; y <= high.y; ++y)
        for (std::int64_t z = low.z; z <= high.z; ++z) {
          const auto found = cells_.find(key({x, y, z}));
          if (found == cells_.end()) continue;
          for (std::uint32_t i : found->second)
            if (glm::length(positions_[i] - p) < radius) out.push_back(i);
        }
    std::sort(out.begin(), out.end());  // node order: the weights' sums run in one order on every machine
  }

 private:
  glm::i64vec3 cellOf(const glm::dvec3& p) const { return glm::i64vec3(glm::floor(p / cell_)); }
  static std::int64_t key(const glm::i64vec3& c) {
    return ((c.x & 0x1FFFFF) << 42) | ((c.y & 0x1FFFFF) << 21) | (c.z & 0x1FFFFF);
  }
  const std::vector<glm::dvec3>& positions_;
  double cell_;
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> cells_;
};

}  // namespace

glm::dvec4 barycentric(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                       const glm::dvec3& d) {
  const glm::dvec3 local = glm::inverse(glm::dmat3(b - a, c - a, d - a)) * (p - a);
  return {1.0 - local.x - local.y - local.z, local.x, local.y, local.z};
}

SurfaceEmbedding embedByElements(const TetMesh& body, const TriangleMesh& drawn, int drawnLevel) {
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

SurfaceEmbedding embedSurface(const TetMesh& body, const TriangleMesh& drawn, int drawnLevel) {
  SurfaceEmbedding embedding = embedByElements(body, drawn, drawnLevel);
  // The radial step R / 2^s: node 0 is on the outer shell, the last node is the centre (tet_mesh.h).
  const double radius = glm::length(body.positions.front() - body.positions.back());
  embedSmoothly(body, drawn.positions, kSmoothSupportSteps * radius / static_cast<double>(1 << body.shellLevel),
                embedding);
  return embedding;
}

namespace {

// Appends the smooth map's terms of the drawn vertex at `x` over the nodes at `nodes` (found in `grid`).
void appendSmoothTerms(const NodeGrid& grid, const std::vector<glm::dvec3>& nodes, const glm::dvec3& x, double support,
                       std::vector<std::uint32_t>& near, SurfaceEmbedding& embedding) {
  for (double h = support;; h *= 1.25) {
    if (h > 64.0 * support) throw std::runtime_error("embedSmoothly: no affine fit around a drawn vertex");
    grid.within(x, h, near);
    if (near.size() < 4) continue;
    // M = Σ W_j p_j p_jᵀ with p_j = (1, (X_j − X)/h) (the 1/h scales the basis, not φ).
    Eigen::Matrix4d moment = Eigen::Matrix4d::Zero();
    std::vector<Eigen::Vector4d> basis(near.size());
    std::vector<double> kernel(near.size());
    for (std::size_t k = 0; k < near.size(); ++k) {
      const glm::dvec3 d = (nodes[near[k]] - x) / h;
      const double q2 = glm::dot(d, d);
      kernel[k] = (1.0 - q2) * (1.0 - q2) * (1.0 - q2);
      basis[k] = Eigen::Vector4d(1.0, d.x, d.y, d.z);
      moment += kernel[k] * basis[k] * basis[k].transpose();
    }
    // A fit the nodes pin down in every direction: M's condition number below 10⁶.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> spectrum(moment, Eigen::EigenvaluesOnly);
    if (!(spectrum.eigenvalues()(0) > 1e-6 * spectrum.eigenvalues()(3))) continue;
    const Eigen::Vector4d a = moment.ldlt().solve(Eigen::Vector4d(1.0, 0.0, 0.0, 0.0));  // M⁻¹ p(X)
    for (std::size_t k = 0; k < near.size(); ++k) {
      const double phi = kernel[k] * a.dot(basis[k]);
      if (phi != 0.0) embedding.smoothTerms.push_back({phi, near[k]});
    }
    break;
  }
  embedding.smoothStart.push_back(static_cast<std::uint32_t>(embedding.smoothTerms.size()));
}

}  // namespace

void embedSmoothly(const TetMesh& body, const std::vector<glm::dvec3>& rest, double support,
                   SurfaceEmbedding& embedding) {
  if (!(support > 0.0)) throw std::invalid_argument("embedSmoothly: support must be positive");
  const NodeGrid grid(body.positions, support);
  embedding.smoothStart.assign(1, 0);
  embedding.smoothTerms.clear();
  embedding.fitNodes.clear();
  embedding.fitRest.clear();
  std::vector<std::uint32_t> near;
  for (const glm::dvec3& x : rest) appendSmoothTerms(grid, body.positions, x, support, near, embedding);
}

void beginSmoothFit(const std::vector<glm::dvec3>& nodes, const std::vector<glm::dvec3>& rest, double support,
                    SurfaceEmbedding& embedding) {
  if (!(support > 0.0)) throw std::invalid_argument("beginSmoothFit: support must be positive");
  embedding.smoothStart.assign(1, 0);
  embedding.smoothTerms.clear();
  embedding.fitNodes = nodes;
  embedding.fitRest = rest;
  embedding.fitSupport = support;
}

bool continueSmoothFit(SurfaceEmbedding& embedding, std::size_t vertices) {
  if (embedding.fitRest.empty()) return true;
  const NodeGrid grid(embedding.fitNodes, embedding.fitSupport);
  std::vector<std::uint32_t> near;
  const std::size_t first = embedding.smoothStart.size() - 1;
  const std::size_t last = std::min(embedding.fitRest.size(), first + vertices);
  for (std::size_t i = first; i < last; ++i)
    appendSmoothTerms(grid, embedding.fitNodes, embedding.fitRest[i], embedding.fitSupport, near, embedding);
  if (last < embedding.fitRest.size()) return false;
  embedding.fitNodes = {};
  embedding.fitRest = {};
  return true;
}

void placeEmbedded(const SurfaceEmbedding& embedding, const std::vector<glm::dvec3>& body,
                   std::vector<glm::dvec3>& drawn) {
  if (embedding.smoothStart.size() < 2 || !embedding.fitRest.empty()) {
    placeByElements(embedding, body, drawn);
    return;
  }
  const std::size_t count = embedding.smoothStart.size() - 1;
  drawn.resize(count);
  const SmoothTerm* terms = embedding.smoothTerms.data();
  const auto place = [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      glm::dvec3 sum(0.0);
      for (std::uint32_t k = embedding.smoothStart[i]; k < embedding.smoothStart[i + 1]; ++k)
        sum += terms[k].weight * body[terms[k].node];
      drawn[i] = sum;
    }
  };
  // On one thread: in TBB blocks ThreadSanitizer reported races inside TBB's own inlined task code
  // (its hand-overs are invisible to it), and on this 2-core machine the blocks gained nothing
  // measurable at level 6 (20–28 ms either way, docs/physics.md); level 4 takes 0.15 ms.
  place(0, count);
}

void placeByElements(const SurfaceEmbedding& embedding, const std::vector<glm::dvec3>& body,
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

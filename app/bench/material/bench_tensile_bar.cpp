#include "app/bench/material/bench_tensile_bar.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <string>

namespace slime {
namespace {

using Triangle3 = std::array<std::uint32_t, 3>;

// The disc's triangles: the centre fanned to ring 1, then each ring zipped to the next by walking both
// in angle (the ring whose next node comes first in angle advances).
std::vector<Triangle3> discTriangles(int rings) {
  std::vector<Triangle3> triangles;
  const auto first = [](int ring) { return ring == 0 ? 0u : static_cast<std::uint32_t>(1 + 3 * ring * (ring - 1)); };
  const auto count = [](int ring) { return ring == 0 ? 1 : 6 * ring; };
  for (int ring = 1; ring <= rings; ++ring) {
    const int na = count(ring - 1), nb = count(ring);
    const std::uint32_t a0 = first(ring - 1), b0 = first(ring);
    const auto a = [&](int i) { return a0 + static_cast<std::uint32_t>(i % na); };
    const auto b = [&](int j) { return b0 + static_cast<std::uint32_t>(j % nb); };
    if (na == 1) {
      for (int j = 0; j < nb; ++j) triangles.push_back({a0, b(j), b(j + 1)});
      continue;
    }
    int i = 0, j = 0;
    while (i < na || j < nb) {
      const double nextA = static_cast<double>(i + 1) / na, nextB = static_cast<double>(j + 1) / nb;
      if (i < na && (j >= nb || nextA <= nextB)) {
        triangles.push_back({a(i), a(i + 1), b(j)});
        ++i;
      } else {
        triangles.push_back({a(i), b(j), b(j + 1)});
        ++j;
      }
    }
  }
  return triangles;
}

void addPositive(std::vector<Tetrahedron>& tetrahedra, const std::vector<glm::dvec3>& x, Tetrahedron t) {
  if (tetrahedronVolume(x[t.x], x[t.y], x[t.z], x[t.w]) < 0.0) std::swap(t.z, t.w);
  tetrahedra.push_back(t);
}

// The directional derivative of firstPiolaStress at F along δF (B_v held):
//   δP = μ∞ δF + λ'(cof F : δF) cof F + λ'(J − α) δcof F + μ1 (δF B_v − δcof F),
//   δcof F's columns δf1×f2 + f1×δf2, δf2×f0 + f2×δf0, δf0×f1 + f0×δf1.
glm::dmat3 stressDerivative(const ViscoelasticMaterial& material, const glm::dmat3& f, const glm::dmat3& cof, double j,
                            const glm::dmat3& maxwellInverse, const glm::dmat3& df) {
  const double lambdaPrime = volumetricModulus(material);
  const glm::dmat3 dcof(glm::cross(df[1], f[2]) + glm::cross(f[1], df[2]),
                        glm::cross(df[2], f[0]) + glm::cross(f[2], df[0]),
                        glm::cross(df[0], f[1]) + glm::cross(f[0], df[1]));
  const double dj = glm::dot(cof[0], df[0]) + glm::dot(cof[1], df[1]) + glm::dot(cof[2], df[2]);
  glm::dmat3 dp = material.longTermShear * df + (lambdaPrime * dj) * cof +
                  (lambdaPrime * (j - restVolumeRatio(material))) * dcof;
  if (material.maxwellShear > 0.0) dp += material.maxwellShear * (df * maxwellInverse - dcof);
  return dp;
}

// A symmetric positive definite band matrix (lower half, `half` diagonals below the main one) and its
// Cholesky factor in place: entry (i, j), i ≥ j, i − j ≤ half, at [i·(half + 1) + i − j].
struct BandMatrix {
  int size = 0, half = 0;
  std::vector<double> values;
  void reset(int n, int h) {
    size = n;
    half = h;
    values.assign(static_cast<std::size_t>(n) * (h + 1), 0.0);
  }
  double& at(int i, int j) { return values[static_cast<std::size_t>(i) * (half + 1) + (i - j)]; }
  // L Lᵀ = A; false if A is not positive definite.
  bool factor() {
    for (int j = 0; j < size; ++j) {
      double diagonal = at(j, j);
      for (int k = std::max(0, j - half); k < j; ++k) diagonal -= at(j, k) * at(j, k);
      if (!(diagonal > 0.0)) return false;
      const double pivot = std::sqrt(diagonal);
      at(j, j) = pivot;
      for (int i = j + 1; i <= std::min(size - 1, j + half); ++i) {
        double sum = at(i, j);
        for (int k = std::max(0, i - half); k < j; ++k) sum -= at(i, k) * at(j, k);
        at(i, j) = sum / pivot;
      }
    }
    return true;
  }
  void solve(std::vector<double>& b) {  // b ← A⁻¹ b with the factor
    for (int i = 0; i < size; ++i) {
      double sum = b[i];
      for (int k = std::max(0, i - half); k < i; ++k) sum -= at(i, k) * b[k];
      b[i] = sum / at(i, i);
    }
    for (int i = size - 1; i >= 0; --i) {
      double sum = b[i];
      for (int k = i + 1; k <= std::min(size - 1, i + half); ++k) sum -= at(k, i) * b[k];
      b[i] = sum / at(i, i);
    }
  }
};

}  // namespace

CylinderMesh makeCylinderTetMesh(double radius, double length, int rings, int segments) {
  if (!(radius > 0.0) || !(length > 0.0) || rings < 1 || segments < 1)
    throw std::invalid_argument("cylinder mesh: radius " + std::to_string(radius) + " m, length " +
                                std::to_string(length) + " m, rings " + std::to_string(rings) + ", segments " +
                                std::to_string(segments) + " (all must be positive)");
  CylinderMesh cylinder;
  cylinder.radius = radius;
  cylinder.length = length;
  cylinder.layers = segments + 1;
  std::vector<glm::dvec2> disc{{0.0, 0.0}};
  for (int ring = 1; ring <= rings; ++ring)
    for (int j = 0; j < 6 * ring; ++j) {
      const double angle = 2.0 * std::numbers::pi * j / (6 * ring);
      disc.push_back(radius * ring / rings * glm::dvec2(std::cos(angle), std::sin(angle)));
    }
  cylinder.nodesPerLayer = static_cast<int>(disc.size());
  const std::vector<Triangle3> triangles = discTriangles(rings);
  for (const Triangle3& t : triangles) {
    const glm::dvec2 u = disc[t[1]] - disc[t[0]], v = disc[t[2]] - disc[t[0]];
    cylinder.crossSection += 0.5 * std::abs(u.x * v.y - u.y * v.x);
  }
  std::vector<glm::dvec3>& x = cylinder.mesh.positions;
  for (int layer = 0; layer <= segments; ++layer)
    for (const glm::dvec2& p : disc) x.push_back({-0.5 * length + length * layer / segments, p.x, p.y});
  const auto node = [&](int layer, std::uint32_t d) {
    return static_cast<std::uint32_t>(layer * cylinder.nodesPerLayer) + d;
  };
  for (int layer = 0; layer < segments; ++layer)
    for (Triangle3 v : triangles) {
      std::sort(v.begin(), v.end());
      const auto top = [&](int i) { return node(layer, v[i]); };
      const auto bottom = [&](int i) { return node(layer + 1, v[i]); };
      addPositive(cylinder.mesh.tetrahedra, x, {top(0), top(1), top(2), bottom(2)});
      addPositive(cylinder.mesh.tetrahedra, x, {top(0), top(1), bottom(1), bottom(2)});
      addPositive(cylinder.mesh.tetrahedra, x, {top(0), bottom(0), bottom(1), bottom(2)});
    }
  cylinder.mesh.surfaceNodes = 0;
  return cylinder;
}

MeshedBarRun stretchMeshedBar(const ViscoelasticMaterial& material, double strainRate, double maxStrain, int steps,
                              const MeshedBarOptions& options) {
  if (!(strainRate > 0.0) || !(maxStrain > 0.0) || steps < 1 || options.segments < 4)
    throw std::invalid_argument("meshed bar: strain rate, largest strain and steps must be positive, segments >= 4");
  const CylinderMesh cylinder = makeCylinderTetMesh(options.radius, options.length, options.rings, options.segments);
  const std::vector<glm::dvec3>& rest = cylinder.mesh.positions;
  const std::vector<Tetrahedron>& tets = cylinder.mesh.tetrahedra;
  const int perLayer = cylinder.nodesPerLayer, layers = cylinder.layers;
  const int nodes = static_cast<int>(rest.size());
  std::vector<TetRest> restData;
  restData.reserve(tets.size());
  for (const Tetrahedron& t : tets) restData.push_back(makeTetRest(rest[t.x], rest[t.y], rest[t.z], rest[t.w]));
  std::vector<MaxwellRest> maxwell(tets.size());

  // Free degrees of freedom: every node but the two end layers', 3 per node, layer by layer.
  const auto freeIndex = [&](int n, int c) {
    const int layer = n / perLayer;
    return layer == 0 || layer == layers - 1 ? -1 : 3 * (n - perLayer) + c;
  };
  const int freeCount = 3 * perLayer * (layers - 2);
  BandMatrix stiffness;
  std::vector<glm::dvec3> x = rest, forces(nodes);
  std::vector<double> residual(freeCount);

  MeshedBarRun run;
  run.nodes = nodes;
  run.tetrahedra = static_cast<int>(tets.size());
  const double decay = std::exp(-(maxStrain / steps / strainRate) / material.relaxationTime);
  const int gaugeLow = (layers - 1) / 4, gaugeHigh = layers - 1 - gaugeLow, middle = (layers - 1) / 2;
  const double gaugeRest = rest[gaugeHigh * perLayer].x - rest[gaugeLow * perLayer].x;

  // Internal forces at x (the bulk body's: the columns of P·(−V0 Dm⁻ᵀ) on nodes 1..3, their negative sum on 0).
  const auto computeForces = [&]() {
    std::fill(forces.begin(), forces.end(), glm::dvec3(0.0));
    for (std::size_t e = 0; e < tets.size(); ++e) {
      const Tetrahedron& t = tets[e];
      const glm::dmat3 f = deformationGradient(restData[e], x[t.x], x[t.y], x[t.z], x[t.w]);
      const glm::dmat3 h = firstPiolaStress(material, f, maxwell[e].inverse) * restData[e].forceMap;
      forces[t.y] += h[0];
      forces[t.z] += h[1];
      forces[t.w] += h[2];
      forces[t.x] -= h[0] + h[1] + h[2];
    }
  };
  // The tangent K = −∂f/∂x over the free nodes, element by element from the stress's derivative.
  const auto assemble = [&]() {
    stiffness.reset(freeCount, 3 * 2 * perLayer);
    for (std::size_t e = 0; e < tets.size(); ++e) {
      const Tetrahedron& t = tets[e];
      const glm::dmat3 f = deformationGradient(restData[e], x[t.x], x[t.y], x[t.z], x[t.w]);
      const glm::dmat3 cof = cofactor(f);
      const double j = glm::dot(f[0], cof[0]);
      for (int a = 0; a < 4; ++a)
        for (int c = 0; c < 3; ++c) {
          const int column = freeIndex(static_cast<int>(t[a]), c);
          if (column < 0) continue;
          glm::dmat3 shape(0.0);  // δDs for a unit move of node a along c
          for (int k = 0; k < 3; ++k) shape[k][c] = a == 0 ? -1.0 : (k == a - 1 ? 1.0 : 0.0);
          const glm::dmat3 df = shape * restData[e].restInverse;
          const glm::dmat3 dh = stressDerivative(material, f, cof, j, maxwell[e].inverse, df) * restData[e].forceMap;
          const std::array<glm::dvec3, 4> dforce{-(dh[0] + dh[1] + dh[2]), dh[0], dh[1], dh[2]};
          for (int b = 0; b < 4; ++b)
            for (int d = 0; d < 3; ++d) {
              const int row = freeIndex(static_cast<int>(t[b]), d);
              if (row >= column) stiffness.at(row, column) -= dforce[b][d];
            }
        }
    }
  };
  const auto reaction = [&]() {  // the grips' pull: the bar's forces on both ends' held nodes, along x
    double pull = 0.0;
    for (int d = 0; d < perLayer; ++d) pull += forces[d].x - forces[(layers - 1) * perLayer + d].x;
    return 0.5 * pull;
  };
  const auto layerMeanX = [&](int layer) {
    double sum = 0.0;
    for (int d = 0; d < perLayer; ++d) sum += x[layer * perLayer + d].x;
    return sum / perLayer;
  };
  const int outerFirst = perLayer - 6 * options.rings;

  double previousStretch = 1.0;
  for (int k = 0; k <= steps; ++k) {
    const double strain = maxStrain * k / steps, stretch = 1.0 + strain;
    // The grips to their place; the free nodes from the last balance, stretched with them.
    for (int n = 0; n < nodes; ++n) {
      const int layer = n / perLayer;
      if (layer == 0 || layer == layers - 1) x[n].x = rest[n].x * stretch;
      else x[n].x *= stretch / previousStretch;
    }
    previousStretch = stretch;
    computeForces();
    // Newton's method, the tangent kept while it still cuts the largest free force tenfold per
    // iteration (it changes little from step to step at these strains) and assembled afresh when not.
    double largest = 0.0, ratio = 0.0;
    for (int iteration = 0; k > 0 && iteration < options.maxNewtonIterations; ++iteration) {
      const double before = largest;
      largest = 0.0;
      for (int n = perLayer; n < (layers - 1) * perLayer; ++n) largest = std::max(largest, glm::length(forces[n]));
      if (iteration > 0) ratio = largest / before;
      if (largest <= options.newtonTolerance * std::abs(reaction())) break;
      if (run.factorisations == 0 || ratio > 0.1) {
        assemble();
        if (!stiffness.factor()) throw std::runtime_error("meshed bar: the tangent stiffness is not positive definite");
        ++run.factorisations;
        ratio = 0.0;
      }
      for (int n = perLayer; n < (layers - 1) * perLayer; ++n)  // the free nodes, in freeIndex's order
        for (int c = 0; c < 3; ++c) residual[3 * (n - perLayer) + c] = forces[n][c];
      stiffness.solve(residual);  // K δ = f
      for (int n = perLayer; n < (layers - 1) * perLayer; ++n)
        for (int c = 0; c < 3; ++c) x[n][c] += residual[3 * (n - perLayer) + c];
      computeForces();
      ++run.newtonIterations;
    }
    run.strains.push_back(strain);
    run.stresses.push_back(reaction() / cylinder.crossSection);
    run.gaugeStrains.push_back((layerMeanX(gaugeHigh) - layerMeanX(gaugeLow)) / gaugeRest - 1.0);
    double width = 0.0;
    for (int d = outerFirst; d < perLayer; ++d) width += glm::length(glm::dvec2(x[middle * perLayer + d].y, x[middle * perLayer + d].z));
    run.middleWidths.push_back(width / (6 * options.rings) / cylinder.radius);
    // The Maxwell branches flow over the step to the next strain, as relaxBulk does once per step.
    for (std::size_t e = 0; e < tets.size(); ++e) {
      const Tetrahedron& t = tets[e];
      const glm::dmat3 f = deformationGradient(restData[e], x[t.x], x[t.y], x[t.z], x[t.w]);
      run.smallestVolumeRatio = std::min(run.smallestVolumeRatio, glm::determinant(f));
      maxwell[e] = relaxMaxwellBranch(f, maxwell[e], decay);
    }
  }
  return run;
}

}  // namespace slime

#include "core/membrane/springs.h"

#include "core/geometry/icosphere.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

namespace slime {

double seriesStiffness(double elementaryStiffness, double elementaryLength, double length) {
  return elementaryStiffness * elementaryLength / length;
}

glm::dvec3 springForce(const glm::dvec3& positionI, const glm::dvec3& positionJ, double restLength,
                       double stiffness) {
  const glm::dvec3 x = positionJ - positionI;
  const double length = glm::length(x);
  return -stiffness * (length - restLength) * (x / length);
}

glm::dvec3 damperForce(const glm::dvec3& positionI, const glm::dvec3& positionJ,
                       const glm::dvec3& velocityI, const glm::dvec3& velocityJ, double damping) {
  const glm::dvec3 x = positionJ - positionI;
  const glm::dvec3 v = velocityJ - velocityI;
  return -damping * (glm::dot(v, x) / glm::dot(x, x)) * x;
}

void addSpringForces(const SpringSet& springs, const std::vector<glm::dvec3>& positions,
                     const std::vector<glm::dvec3>& velocities, double damping,
                     std::vector<glm::dvec3>& forces) {
  const std::size_t count = springs.size();
  for (std::size_t s = 0; s < count; ++s) {
    const std::uint32_t i = springs.ends[s].x, j = springs.ends[s].y;
    const glm::dvec3 x = positions[j] - positions[i];
    const glm::dvec3 v = velocities[j] - velocities[i];
    const double lengthSquared = glm::dot(x, x);
    const double length = std::sqrt(lengthSquared);
    // Hooke plus the damper, both along x̂, folded into one scalar on x.
    const double hooke = springs.stiffnesses[s] * (length - springs.restLengths[s]) / length;
    const double viscous = damping * glm::dot(v, x) / lengthSquared;
    const glm::dvec3 forceOnJ = -(hooke + viscous) * x;
    forces[j] += forceOnJ;
    forces[i] -= forceOnJ;
  }
}

namespace {

// Solves one spring's two-body damper exactly: the relative speed u along x̂ becomes u·decay
// (decay = exp(-k_d (w_i + w_j) h)); the impulse is split by inverse mass, so momentum is kept.
// `factor` = (decay - 1) / (w_i + w_j), precomputed.
inline void dampOneSpring(const SpringSet& springs, std::size_t s, const std::vector<glm::dvec3>& positions,
                          const std::vector<double>& inverseMasses, double factor,
                          std::vector<glm::dvec3>& velocities) {
  const std::uint32_t i = springs.ends[s].x, j = springs.ends[s].y;
  const glm::dvec3 x = positions[j] - positions[i];
  const double relative = glm::dot(velocities[j] - velocities[i], x) / glm::dot(x, x);  // u / |x|
  const double impulse = relative * factor;                                            // per |x|
  velocities[j] += (impulse * inverseMasses[j]) * x;
  velocities[i] -= (impulse * inverseMasses[i]) * x;
}

}  // namespace

std::vector<glm::u32vec2> orderedForIndependence(const std::vector<glm::u32vec2>& edges, std::size_t vertexCount) {
  // Greedy edge colouring: each edge takes the smallest colour not yet used at either end.
  std::vector<std::uint64_t> usedColours(vertexCount, 0);  // bit c set: colour c taken at the vertex
  std::vector<std::pair<int, std::size_t>> keyed(edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const std::uint64_t taken = usedColours[edges[e].x] | usedColours[edges[e].y];
    int colour = 0;
    while (colour < 63 && (taken >> colour & 1u)) ++colour;
    usedColours[edges[e].x] |= std::uint64_t{1} << colour;
    usedColours[edges[e].y] |= std::uint64_t{1} << colour;
    keyed[e] = {colour, e};
  }
  std::sort(keyed.begin(), keyed.end());  // by colour, then by the original (sorted) order
  std::vector<glm::u32vec2> ordered(edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e) ordered[e] = edges[keyed[e].second];
  return ordered;
}

std::vector<std::size_t> independentSpringRuns(const std::vector<glm::u32vec2>& ends, std::size_t vertexCount) {
  std::vector<std::size_t> starts;
  std::vector<std::size_t> lastRunAt(vertexCount, SIZE_MAX);  // the run that last touched each vertex
  for (std::size_t s = 0; s < ends.size(); ++s) {
    const std::size_t current = starts.empty() ? SIZE_MAX : starts.size() - 1;
    if (starts.empty() || lastRunAt[ends[s].x] == current || lastRunAt[ends[s].y] == current) starts.push_back(s);
    lastRunAt[ends[s].x] = lastRunAt[ends[s].y] = starts.size() - 1;
  }
  starts.push_back(ends.size());
  return starts;
}

void springDampingDecays(const SpringSet& springs, const std::vector<double>& inverseMasses, double damping,
                         double h, std::vector<double>& decays) {
  decays.resize(springs.size());
  for (std::size_t s = 0; s < springs.size(); ++s) {
    const double weight = inverseMasses[springs.ends[s].x] + inverseMasses[springs.ends[s].y];
    decays[s] = weight == 0.0 ? 0.0 : (std::exp(-damping * weight * 0.5 * h) - 1.0) / weight;
  }
}

void springDampingShares(const SpringSet& springs, const std::vector<double>& inverseMasses, double damping,
                         double h, std::vector<glm::dvec2>& shares) {
  std::vector<double> decays;
  springDampingDecays(springs, inverseMasses, damping, h, decays);
  shares.resize(springs.size());
  for (std::size_t s = 0; s < springs.size(); ++s)
    shares[s] = decays[s] * glm::dvec2(inverseMasses[springs.ends[s].x], inverseMasses[springs.ends[s].y]);
}

void dampSpringsImplicitly(const SpringSet& springs, const std::vector<glm::dvec3>& positions,
                           const std::vector<double>& inverseMasses, const std::vector<double>& decays,
                           std::vector<glm::dvec3>& velocities) {
  // Symmetric Gauss–Seidel: forward then backward, h/2 each, so the whole pass is a symmetric
  // contraction of the kinetic energy (a one-way sweep is not, and destabilised symplectic Euler).
  const std::size_t count = springs.size();
  for (std::size_t s = 0; s < count; ++s) dampOneSpring(springs, s, positions, inverseMasses, decays[s], velocities);
  for (std::size_t s = count; s-- > 0;) dampOneSpring(springs, s, positions, inverseMasses, decays[s], velocities);
}

void dampSpringsImplicitly(const SpringSet& springs, const std::vector<glm::dvec3>& positions,
                           const std::vector<double>& inverseMasses, double damping, double h,
                           std::vector<glm::dvec3>& velocities) {
  if (damping == 0.0) return;
  std::vector<double> decays;
  springDampingDecays(springs, inverseMasses, damping, h, decays);
  dampSpringsImplicitly(springs, positions, inverseMasses, decays, velocities);
}

SpringSet makeEdgeSprings(const std::vector<glm::dvec3>& positions,
                          const std::vector<glm::u32vec3>& triangles, double elementaryStiffness,
                          double prestrain) {
  SpringSet springs;
  springs.ends = orderedForIndependence(uniqueEdges(triangles), positions.size());
  springs.restLengths.resize(springs.ends.size());
  springs.stiffnesses.resize(springs.ends.size());
  double meanLength = 0.0;
  for (std::size_t s = 0; s < springs.size(); ++s) {
    const double length = glm::length(positions[springs.ends[s].y] - positions[springs.ends[s].x]);
    springs.restLengths[s] = length;
    meanLength += length;
  }
  meanLength /= static_cast<double>(springs.size());
  for (std::size_t s = 0; s < springs.size(); ++s) {
    springs.stiffnesses[s] = seriesStiffness(elementaryStiffness, meanLength, springs.restLengths[s]);
    springs.restLengths[s] /= 1.0 + prestrain;
  }
  return springs;
}

}  // namespace slime

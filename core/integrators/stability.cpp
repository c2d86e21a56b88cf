#include "core/integrators/stability.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace slime {

double highestFrequency(const SpringSet& springs, const std::vector<glm::dvec3>& positions,
                        const std::vector<double>& inverseMasses, int iterations) {
  const std::size_t count = positions.size();
  std::vector<glm::dvec3> u(count), y(count);
  // A fixed, sign-alternating start excites the highest modes of the lattice.
  for (std::size_t i = 0; i < count; ++i)
    u[i] = glm::dvec3((i % 2 ? 1.0 : -1.0), (i % 3 ? 0.5 : -0.7), (i % 5 ? 0.3 : -0.9));
  double eigenvalue = 0.0;
  for (int iteration = 0; iteration < iterations; ++iteration) {
    std::fill(y.begin(), y.end(), glm::dvec3(0.0));
    for (std::size_t s = 0; s < springs.size(); ++s) {
      const std::uint32_t i = springs.ends[s].x, j = springs.ends[s].y;
      const glm::dvec3 x = positions[j] - positions[i];
      const double length = glm::length(x);
      const glm::dvec3 n = x / length;
      const double k = springs.stiffnesses[s];
      const double transverse = k * std::max(0.0, 1.0 - springs.restLengths[s] / length);
      const glm::dvec3 d = u[j] - u[i];
      const glm::dvec3 f = transverse * d + (k - transverse) * glm::dot(n, d) * n;
      y[j] += f;
      y[i] -= f;
    }
    double norm = 0.0, projection = 0.0;
    for (std::size_t i = 0; i < count; ++i) {
      y[i] *= inverseMasses[i];
      projection += glm::dot(u[i], y[i]);
      norm += glm::dot(y[i], y[i]);
    }
    double unitNorm = 0.0;
    for (std::size_t i = 0; i < count; ++i) unitNorm += glm::dot(u[i], u[i]);
    eigenvalue = projection / unitNorm;  // Rayleigh quotient
    norm = std::sqrt(norm);
    if (norm == 0.0) return 0.0;
    for (std::size_t i = 0; i < count; ++i) u[i] = y[i] / norm;
  }
  return std::sqrt(std::max(0.0, eigenvalue));
}

double highestDampingRate(const SpringSet& springs, const std::vector<glm::dvec3>& positions,
                          const std::vector<double>& inverseMasses, double damping) {
  std::vector<double> rowSum(positions.size(), 0.0);
  for (std::size_t s = 0; s < springs.size(); ++s) {
    const std::uint32_t i = springs.ends[s].x, j = springs.ends[s].y;
    const double c = damping;
    rowSum[i] += 2.0 * c;
    rowSum[j] += 2.0 * c;
  }
  double highest = 0.0;
  for (std::size_t i = 0; i < positions.size(); ++i) highest = std::max(highest, inverseMasses[i] * rowSum[i]);
  return highest;
}

double largestStableStep(Integrator integrator, double omega, double dampingRate) {
  const double infinity = std::numeric_limits<double>::infinity();
  switch (integrator) {
    case Integrator::ExplicitEuler:
      return 4.0 / (dampingRate + std::sqrt(dampingRate * dampingRate + 4.0 * omega * omega));
    case Integrator::SymplecticEuler:  // the damper is integrated implicitly (springs.h)
    case Integrator::Xpbd:
      return omega > 0.0 ? 2.0 / omega : infinity;
    case Integrator::Rk4:
      return omega + dampingRate > 0.0 ? 2.78 / (omega + dampingRate) : infinity;
    case Integrator::ImplicitEuler:
    case Integrator::Projective:
    case Integrator::ProjectiveMidpoint:
      return infinity;
  }
  return infinity;
}

}  // namespace slime

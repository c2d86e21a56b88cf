#include "app/bench/material/modal_fit.h"

#include "core/bulk/lamb_sphere.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>

namespace slime {

void removeRigidMotion(const std::vector<double>& masses, const std::vector<glm::dvec3>& rest,
                       std::vector<glm::dvec3>& vectors) {
  double mass = 0.0;
  glm::dvec3 centre(0.0), momentum(0.0);
  for (std::size_t i = 0; i < rest.size(); ++i) {
    mass += masses[i];
    centre += masses[i] * rest[i];
    momentum += masses[i] * vectors[i];
  }
  centre /= mass;
  for (glm::dvec3& u : vectors) u -= momentum / mass;
  glm::dvec3 angular(0.0);
  glm::dmat3 inertia(0.0);
  for (std::size_t i = 0; i < rest.size(); ++i) {
    const glm::dvec3 r = rest[i] - centre;
    angular += masses[i] * glm::cross(r, vectors[i]);
    inertia += masses[i] * (glm::dot(r, r) * glm::dmat3(1.0) - glm::outerProduct(r, r));
  }
  const glm::dvec3 spin = glm::inverse(inertia) * angular;
  for (std::size_t i = 0; i < rest.size(); ++i) vectors[i] -= glm::cross(spin, rest[i] - centre);
}

std::vector<glm::dvec3> lambModeShape(const std::vector<glm::dvec3>& rest, const std::vector<double>& masses,
                                      const glm::dvec3& centre, double radius, bool spheroidal, double eta,
                                      double poisson) {
  std::vector<glm::dvec3> shape(rest.size());
  double largest = 0.0;
  for (std::size_t i = 0; i < rest.size(); ++i) {
    const glm::dvec3 x = rest[i] - centre;
    shape[i] = spheroidal ? spheroidalModeShape(x, radius, eta, poisson) : torsionalModeShape(x, radius, eta);
    largest = std::max(largest, glm::length(shape[i]));
  }
  for (glm::dvec3& s : shape) s /= largest;
  removeRigidMotion(masses, rest, shape);
  return shape;
}

double massProjection(const std::vector<glm::dvec3>& u, const std::vector<glm::dvec3>* origin,
                      const std::vector<glm::dvec3>& shape, const std::vector<double>& masses) {
  double projection = 0.0, norm = 0.0;
  for (std::size_t i = 0; i < u.size(); ++i) {
    const glm::dvec3 d = origin != nullptr ? u[i] - (*origin)[i] : u[i];
    projection += masses[i] * glm::dot(d, shape[i]);
    norm += masses[i] * glm::dot(shape[i], shape[i]);
  }
  return projection / norm;
}

double zeroCrossingFrequency(const std::vector<double>& t, const std::vector<double>& y) {
  std::vector<double> crossings;
  for (std::size_t k = 1; k < t.size(); ++k)
    if ((y[k] < 0.0) != (y[k - 1] < 0.0))
      crossings.push_back(t[k - 1] + (t[k] - t[k - 1]) * y[k - 1] / (y[k - 1] - y[k]));
  if (crossings.size() < 3) return 0.0;
  return static_cast<double>(crossings.size() - 1) / (2.0 * (crossings.back() - crossings.front()));
}

double energyDampingRatio(const std::vector<double>& t, const std::vector<double>& amplitude,
                          const std::vector<double>& rate, double omega) {
  // The fit stops where a strongly damped mode has fallen to round-off (1e-12 of its start's energy).
  constexpr double kLostEnergy = 1e-12;
  const double initial = t.empty() ? 0.0 : omega * omega * amplitude[0] * amplitude[0] + rate[0] * rate[0];
  double n = 0.0, st = 0.0, sy = 0.0, stt = 0.0, sty = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double energy = omega * omega * amplitude[k] * amplitude[k] + rate[k] * rate[k];
    if (energy < kLostEnergy * initial && n >= 2.0) break;
    const double y = std::log(std::max(energy, 1e-300));
    n += 1.0;
    st += t[k];
    sy += y;
    stt += t[k] * t[k];
    sty += t[k] * y;
  }
  const double determinant = n * stt - st * st;
  const double slope = determinant != 0.0 ? (n * sty - st * sy) / determinant : 0.0;
  return -slope / (2.0 * omega);
}

}  // namespace slime

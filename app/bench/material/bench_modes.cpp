#include "app/bench/material/bench_modes.h"

#include "core/bulk/lamb_sphere.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace slime {

Settings elasticBall(const Settings& base, int resolution) {
  Settings settings = base;
  settings.slime.model = "bulk";
  settings.slime.resolution = resolution;
  settings.slime.level = std::max(resolution, 2);  // the drawn surface costs nothing here
  settings.slime.longTerm = 1.0;
  settings.slime.viscosity = 0.0;
  settings.sim.gravity = 0.0;
  settings.slime.position.z = std::max(settings.slime.position.z, 2.0 * settings.slime.radius);
  return settings;
}

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

std::vector<glm::dvec3> modeShape(const Simulation& simulation, bool spheroidal, double eta) {
  const Settings& settings = simulation.settings();
  const std::vector<glm::dvec3>& rest = simulation.bulkBody().mesh.positions;
  std::vector<glm::dvec3> shape(rest.size());
  double largest = 0.0;
  for (std::size_t i = 0; i < rest.size(); ++i) {
    const glm::dvec3 x = rest[i] - settings.slime.position;
    shape[i] = spheroidal ? spheroidalModeShape(x, settings.slime.radius, eta, settings.slime.poisson)
                          : torsionalModeShape(x, settings.slime.radius, eta);
    largest = std::max(largest, glm::length(shape[i]));
  }
  for (glm::dvec3& s : shape) s /= largest;
  std::vector<double> masses(rest.size());
  for (std::size_t i = 0; i < rest.size(); ++i) masses[i] = 1.0 / simulation.bulkBody().freeInverseMasses[i];
  removeRigidMotion(masses, rest, shape);
  return shape;
}

namespace {

// Σ m (u − origin)·ψ / Σ m ψ·ψ over the nodes (origin: none, or the rest positions).
double modeMassProjection(const Simulation& simulation, const std::vector<glm::dvec3>& u,
                      const std::vector<glm::dvec3>* origin, const std::vector<glm::dvec3>& shape) {
  const std::vector<double>& w = simulation.bulkBody().freeInverseMasses;
  double projection = 0.0, norm = 0.0;
  for (std::size_t i = 0; i < u.size(); ++i) {
    const glm::dvec3 d = origin != nullptr ? u[i] - (*origin)[i] : u[i];
    projection += glm::dot(d, shape[i]) / w[i];
    norm += glm::dot(shape[i], shape[i]) / w[i];
  }
  return projection / norm;
}

}  // namespace

double modalAmplitude(const Simulation& simulation, const std::vector<glm::dvec3>& shape) {
  return modeMassProjection(simulation, simulation.state().positions, &simulation.bulkBody().mesh.positions, shape);
}

double modalVelocity(const Simulation& simulation, const std::vector<glm::dvec3>& shape) {
  return modeMassProjection(simulation, simulation.state().velocities, nullptr, shape);
}

double lambTheoryHz(const Simulation& simulation, double eta) {
  const SlimeSettings& slime = simulation.settings().slime;
  const double density = slime.mass / simulation.bulkBody().restVolume;
  return eta * std::sqrt(slime.modulus / density) / (2.0 * std::numbers::pi * slime.radius);
}

}  // namespace slime

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

std::vector<glm::dvec3> modeShape(const Simulation& simulation, bool spheroidal, double eta) {
  const Settings& settings = simulation.settings();
  const std::vector<glm::dvec3>& rest = simulation.bulkBody().mesh.positions;
  std::vector<double> masses(rest.size());
  for (std::size_t i = 0; i < rest.size(); ++i) masses[i] = 1.0 / simulation.bulkBody().freeInverseMasses[i];
  return lambModeShape(rest, masses, settings.slime.position, settings.slime.radius, spheroidal, eta,
                       settings.slime.poisson);
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

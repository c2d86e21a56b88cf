// Helpers shared by the core tests that run a whole Simulation: run it on, and read where its surface is.
#pragma once

#include "core/simulation/simulation.h"

#include <glm/vec3.hpp>

#include <algorithm>
#include <limits>
#include <vector>

namespace slime::fixture {

// Steps the simulation until `seconds` more of simulated time have passed (a whole number of steps).
inline void runFor(Simulation& simulation, double seconds) {
  const double end = simulation.time() + seconds - 1e-9;
  while (simulation.time() < end) simulation.step();
}

// The drawn surface's lowest height (m): below 0 the slime has gone through the floor.
inline double lowestDrawnZ(const Simulation& simulation) {
  double lowest = std::numeric_limits<double>::infinity();
  for (const glm::dvec3& p : simulation.positions()) lowest = std::min(lowest, p.z);
  return lowest;
}

// The drawn surface's highest vertex.
inline glm::dvec3 topOf(const Simulation& simulation) {
  const std::vector<glm::dvec3>& x = simulation.positions();
  return *std::max_element(x.begin(), x.end(), [](const auto& a, const auto& b) { return a.z < b.z; });
}

}  // namespace slime::fixture

// The slime's physics as one object: the mass points of an icosphere joined by springs, with volume
// preservation, floor contact and grab/press, advanced with a fixed time step by the integrator that
// sim.integrator names. A headless run, a test and a viewer reset each make a new Simulation.
//
// CONTRACT used by render/ and app/ (keep these signatures; add whatever else physics needs):
//   Simulation(const Settings&), reload, applySettings, step, time, stepCount, positions, triangles,
//   metrics, divergences, grab, dragTo, release, grabbing, grabTarget, grabbedIndices.
#pragma once

#include "core/icosphere.h"
#include "core/settings.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace slime {

// Shape and energy figures of the current state (what `slime sim` reports).
struct SlimeMetrics {
  double volumeRatio = 1.0;    // enclosed volume / rest volume
  double height = 0.0;         // max z - min z, m
  double width = 0.0;          // largest horizontal extent (max of x and y extents), m
  double aspect = 1.0;         // height / width
  double minZ = 0.0;           // lowest vertex z, m
  double kineticEnergy = 0.0;  // J
  double maxSpeed = 0.0;       // fastest vertex, m/s
};

// A step that produced NaN/inf or an absurd speed; the state was rolled back to the last good one.
struct DivergenceEvent {
  std::int64_t step = 0;
  double time = 0.0;
  std::string integrator;
  std::string what;  // e.g. "NaN position at vertex 17", "speed 3.2e4 m/s at vertex 5"
};

class Simulation {
 public:
  explicit Simulation(const Settings& settings);  // builds the slime at slime.position, at rest

  void reload(const Settings& settings);          // rebuild from the settings (level, radius, ...)
  void applySettings(const Settings& settings);   // live changes: mass, stiffness, damping, dt, integrator, ...
  void step();                                    // advance one fixed step sim.dt

  double time() const;                            // simulated seconds since (re)load
  std::int64_t stepCount() const;
  const std::vector<glm::dvec3>& positions() const;
  const std::vector<Triangle>& triangles() const;
  SlimeMetrics metrics() const;
  const std::vector<DivergenceEvent>& divergences() const;

  // Grab the mass points within `radius` of the surface point nearest to `point`; false if none.
  bool grab(const glm::dvec3& point, double radius);
  void dragTo(const glm::dvec3& target);          // move the grab target (the grabbed points follow)
  void release();
  bool grabbing() const;
  glm::dvec3 grabTarget() const;
  const std::vector<std::uint32_t>& grabbedIndices() const;

 private:
  // Owned by the physics implementation.
};

}  // namespace slime

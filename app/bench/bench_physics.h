// `slime bench physics`: what each integrator costs, where it blows up, and how accurate it is.
//  - cost: ms per step (sim.dt, with the substeps the integrator needs to stay stable) at levels 3..6;
//  - stability map (bench_stability.h): the largest stable dt against stiffness, with theory over it;
//  - accuracy against cost (bench_trajectory_error.h): a drop-and-grab against a small-step RK4 reference;
//  - roundness at rest of the settled ball (compare: the Bullet btSoftBody ball of peers/bullet_ball.cpp).
#pragma once

#include "core/settings.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace slime {

struct PhysicsBenchOptions {
  std::vector<int> levels{3, 4, 5, 6};             // levels of the cost table
  std::vector<std::string> integrators;            // empty: all five
  double secondsPerMeasurement = 1.0;              // wall time spent timing each (integrator, level)
  int stabilityLevel = 4;                          // level of the stability map (none if < 0)
  std::vector<double> stiffnesses{10, 20, 40, 80, 160, 320, 640, 1280};  // k_e, N/m
  int accuracyLevel = 4;                           // level of the accuracy run (none if < 0)
  std::vector<double> steps{5e-5, 1e-4, 2e-4, 5e-4, 1e-3, 2e-3, 5e-3};  // dt of the accuracy run, s
  double settleSeconds = 2.0;                      // roundness at rest after this long (none if <= 0)
  std::string jsonFile;
  std::string csvFile;
};

nlohmann::json runPhysicsBench(const Settings& settings, const PhysicsBenchOptions& options);

// The settings of one physics run: the level, integrator and step given, everything else as `base`.
Settings physicsSettings(const Settings& base, int level, const std::string& integrator, double dt);

}  // namespace slime

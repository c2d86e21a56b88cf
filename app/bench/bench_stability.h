// The stability map: for one integrator and spring stiffness, the largest step dt at which the slime
// does not blow up, found by bisection on log dt.
//
// Blow-up criterion (defined once, used everywhere): the ball starts 1 mm into the floor, so the
// first contact kicks every mode of the lattice, and runs kStabilitySteps steps of exactly dt
// (automatic substeps off). It has blown up when the divergence guard fires (NaN/inf or a speed over
// 50 m/s, core/divergence.h), the kinetic energy passes 1 J (ten times m g R of the whole ball), or
// the volume leaves [0.5, 2] × V0.
//
// Theory over it: ω_max of M⁻¹K by power iteration on the mesh (Simulation::highestFrequency) and
// the stability radius on the imaginary axis: ω dt < 2 for the symplectic Euler and the seed's
// update, ≈ 2.83 (2√2) for RK4; implicit Euler and XPBD have none.
#pragma once

#include "app/bench/bench_progress.h"
#include "core/settings.h"

namespace slime {

constexpr int kStabilitySteps = 400;
constexpr double kStabilityMinStep = 1e-6;   // s, bottom of the bisection bracket
constexpr double kStabilityMaxStep = 0.05;   // s, top: "stable at every step tried"
constexpr int kStabilityBisections = 11;     // bracket ratio 5e4 → about 1 % resolution

struct StabilityResult {
  double largestStableStep = 0.0;  // s; kStabilityMaxStep when it never blew up
  bool boundedAbove = true;        // false: stable even at kStabilityMaxStep
  double omegaMax = 0.0;           // rad/s, power iteration
  double omegaEstimate = 0.0;      // rad/s, SPEC §9: 2.48 √(k/m) with m the mean vertex mass
  int runs = 0;
};

// True when `settings` (integrator, dt, stiffness, level) passes kStabilitySteps steps without blowing up.
bool runsStably(const Settings& settings);

StabilityResult findLargestStableStep(const Settings& settings, BenchProgress& progress);

}  // namespace slime

// The stability map: for one model, integrator and material, the largest step dt at which the slime
// does not blow up, found by bisection on log dt, beside the limit the simulation predicts for itself
// (Simulation::largestStableStep, the one its automatic substeps use).
//
// Blow-up criterion (defined once, used everywhere): the ball starts 1 mm into the floor, so the
// first contact kicks every mode of the mesh, and runs kStabilitySteps steps of exactly dt
// (automatic substeps off, one substep). It has blown up when the divergence guard fires (NaN/inf or
// a speed over 50 m/s, core/integrators/divergence.h), the kinetic energy passes 1 J (ten times m g R of the whole
// ball), or the volume leaves [0.5, 2] × V0.
//
// The prediction: ω_max of the linearised body by power iteration (Simulation::highestFrequency: the
// membrane's M⁻¹K, the bulk body's elastic tetrahedra) and the stability radius of the integrator on
// the test equation x'' + c x' + ω² x = 0 (core/integrators/stability.h): ω dt < 2 for the symplectic Euler
// (dampers exact), h² ω² + 2 h c < 4 for the explicit Euler, (ω + c) dt < 2.78 for RK4.
#pragma once

#include "app/bench/report/bench_progress.h"
#include "core/settings/settings.h"

namespace slime {

constexpr int kStabilitySteps = 400;
constexpr double kStabilityMinStep = 1e-6;   // s, bottom of the bisection bracket
constexpr double kStabilityMaxStep = 0.05;   // s, top: "stable at every step tried"
constexpr int kStabilityBisections = 11;     // bracket ratio 5e4 → about 1 % resolution

struct StabilityResult {
  double largestStableStep = 0.0;  // s; kStabilityMaxStep when it never blew up
  bool boundedAbove = true;        // false: stable even at kStabilityMaxStep
  double omegaMax = 0.0;           // rad/s, power iteration
  double predictedStep = 0.0;      // s, Simulation::largestStableStep (infinite: no limit)
  double omegaEstimate = 0.0;      // rad/s, SPEC §9 for the membrane: 2.48 √(k/m), m the mean vertex mass
  int runs = 0;
};

// True when `settings` (model, integrator, dt, material, level) passes kStabilitySteps steps without blowing up.
bool runsStably(const Settings& settings);

StabilityResult findLargestStableStep(const Settings& settings, BenchProgress& progress);

}  // namespace slime

// `slime bench physics --front` (issue 45): the solver judged at equal accuracy. Every bulk integrator
// of the settings table (sim.integrator; one that steps the bulk body exactly as symplectic_euler does
// is not a bulk method and is left out) × step (1, 2, 4, 8, 16.7 ms, and the program's automatic
// substeps for an integrator with a stability limit) × iterations (1, 2, 4, 8, where sim.iterations
// changes the step) × resolution 1–4. Each point's runs, each on one thread:
//  - cost: thread CPU ms per simulated ms of the scene's slime dropped from its start (landing and at
//    least 0.3 s of floor contact);
//  - Lamb's n = 2 torsional and spheroidal frequencies of the free elastic ball against theory, and the
//    numerical damping ratio of those modes (viscosity 0, longTerm 1: nothing physical dissipates, so
//    all the damping measured is the integrator's; bench_damping.h);
//  - the creep time constant under a constant twist against the standard linear solid's closed form
//    (bench_material.h);
//  - the rest height (the top node's height) of the elastic ball (longTerm 1, frictionless, not sticky,
//    so its equilibrium is unique) dropped onto the floor, against a converged static solve on the same
//    floor: dynamic relaxation (symplectic_euler at its stability limit, the velocities zeroed at each
//    peak of the kinetic energy) until its height stops changing, its force residual reported; one per
//    resolution;
//  - the divergence guard's rollbacks (a fixed-step run stops at the first: unstable at that step).
// Peers (peers/jolt_tets, peers/bullet_tets, when built) print points of their own, whose errors are
// computed here with the same oracles. Charts (gnuplot, PNG): cost against each error, our integrators'
// points, the peers', and the Pareto front of ours.
#pragma once

#include "core/settings/settings.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace slime {

// One point of the front: the step is sim.dt with one substep, or the program's automatic substeps
// on its own sim.dt (stepMs = 0).
struct FrontPoint {
  std::string integrator;
  double stepMs = 1.0;  // 0: automatic substeps
  int iterations = 0;   // sim.iterations; 0 for a method that does not iterate
  int resolution = 2;
};

struct FrontOptions {
  std::vector<int> resolutions{1, 2, 3, 4};
  std::vector<double> stepsMs{1.0, 2.0, 4.0, 8.0, 16.7};
  std::vector<int> iterations{1, 2, 4, 8};
  std::vector<std::string> integrators;  // empty: every bulk integrator of the settings table
  std::vector<FrontPoint> points;        // non-empty: exactly these instead of the grid (--quick)
  double dropSeconds = 0.5;              // the cost run: the fall (about 0.11 s) and the contact
  double restSeconds = 1.0;              // the rest-height run
  double modePeriods = 5.0;              // of Lamb's frequency, each mode
  double modeSpeed = 0.005;              // m/s, the mode's largest initial speed (small: linear)
  double creepSettleSeconds = 0.5;       // frozen Maxwell branch, the twist ramped on
  double creepSeconds = 2.0;             // under the twist (τ_c of the default material: 1.5 s)
  double staticSeconds = 6.0;            // the static solve's run at most (it stops once converged)
  double peerSeconds = 2.0;              // simulated seconds the peers run each point
  int jobs = 2;                          // points measured at once, one thread each
  std::string outputDirectory;           // front.json, front.md, front_*.csv and the charts (empty: none)
  std::vector<std::string> peerPrograms; // empty: peers/jolt_tets and peers/bullet_tets next to slime

  static FrontOptions quick();  // two points at resolution 2 and short runs (CI)
};

nlohmann::json runFront(const Settings& settings, const FrontOptions& options);

// The integrators of the settings table that the bulk body runs as methods of their own, and which of
// them iterate, found by stepping a small ball: {"bulk": [...], "iterating": [...], "not_bulk": [...]}.
nlohmann::json bulkFrontIntegrators(const Settings& settings);

// The Pareto front of (error, cost) pairs, both to be small: the indices of the points no other point
// beats on both (no larger error and no larger cost, one strictly smaller), by cost ascending.
std::vector<std::size_t> paretoFront(const std::vector<std::pair<double, double>>& errorAndCost);

// A peer's front point with its errors, computed with our oracles: Lamb's n = 2 frequencies from its G,
// ρ, R and ν; the rest height against `staticRestHeight` (≤ 0: none). A peer program, run as
// `PROGRAM --front --resolutions 1,2 --steps-ms 1,2,4,8,16.7 --iterations 1,2,4,8 --seconds S --json FILE`,
// writes FILE = {"peer": "jolt" | "bullet", "processor": "...", "points": [{"resolution", "step_ms",
// "iterations", "cost_ms_per_ms", "shear_modulus_pa", "density_kg_m3", "radius_m", "poisson",
// "spheroidal_hz", "torsional_hz" (null: not measured), "damping_ratio", "rest_height_m" (the top of the
// body at rest), "diverged"}]}.
nlohmann::json peerPointErrors(const nlohmann::json& point, double staticRestHeight);

// The guide's accuracy: Lamb's n = 2 modes within 5 %, numerical damping ratio ≤ 0.02, rest height
// within 2 % of the static solve, all at once (errors as runFront writes them; a missing one fails).
bool meetsGuideAccuracy(const nlohmann::json& errors);

}  // namespace slime

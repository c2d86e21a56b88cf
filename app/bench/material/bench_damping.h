// `slime bench material`'s numerical damping (issue 27 item 2): what an integrator's speed costs in
// jiggle. The free elastic ball (no viscosity, no Maxwell branch, no gravity, no floor: nothing in the
// physics dissipates) is started in Lamb's n = 2 torsional or spheroidal mode; its modal energy
// E = ω²a² + ȧ² (a, ȧ: the mode's amplitude and rate, bench_modes.h) decays as exp(−2ζωt) only by
// what the integrator loses, so the damping ratio ζ = −slope(ln E) / (2ω), fitted over the run, is the
// integrator's numerical damping of that mode; its frequency against Lamb's is the other cost. One row
// per method (symplectic_euler, rk4, projective at 1, 3 and 10 iterations), mode and sim.dt.
#pragma once

#include "app/bench/report/bench_report.h"
#include "core/settings/settings.h"

#include <nlohmann/json.hpp>

#include <vector>

namespace slime {

struct DampingOptions {
  int resolution = 2;
  std::vector<double> steps{0.0005, 0.001, 0.002, 0.004, 0.008};  // sim.dt, s
  std::vector<int> projectiveIterations{1, 3, 10};
  double periods = 8.0;   // simulated periods of Lamb's frequency per run
  double speed = 0.005;   // m/s, the largest initial speed (small: linear, as Lamb's runs)
};

// Fills `table` (method, iterations, mode, dt_s, substeps, damping_ratio, frequency_ratio,
// cost_ms_per_sim_ms, backward_euler_damping_ratio: ln(1 + (ωh)²) / (2ωh), the closed form of an
// implicit Euler step's damping at the measured ω and substep h) and returns the same rows as JSON.
nlohmann::json runDampingBench(const Settings& settings, const DampingOptions& options, CsvTable& table);

// One run of the free elastic ball (elasticBall at slime.resolution, settings' integrator, sim.dt,
// sim.iterations) started in Lamb's n = 2 torsional or spheroidal mode at `speed` (m/s at its largest)
// for `periods` of Lamb's frequency: theory_hz, measured_hz (0: fewer than three zero crossings),
// frequency_ratio, damping_ratio, backward_euler_damping_ratio, substeps, rollbacks. With
// automaticSubsteps off the step is exactly sim.dt / sim.substeps (a blow-up shows as a rollback, and
// the run stops at the first).
nlohmann::json measureModeDamping(const Settings& settings, bool spheroidal, double periods, double speed,
                                  bool automaticSubsteps = true);

}  // namespace slime

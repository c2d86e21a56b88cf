#include "app/bench/material/bench_damping.h"

#include "app/bench/material/bench_material.h"
#include "app/bench/material/bench_modes.h"
#include "app/bench/report/bench_timing.h"
#include "core/bulk/lamb_sphere.h"
#include "core/simulation/simulation.h"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

namespace slime {
namespace {

using nlohmann::json;


struct DampingMethod {
  std::string integrator;
  int iterations;  // projective's sim.iterations; 0 for the others
};

json dampingRun(const Settings& base, const DampingOptions& options, const DampingMethod& method, bool spheroidal,
                double dt) {
  Settings settings = base;
  settings.slime.resolution = options.resolution;
  settings.sim.integrator = method.integrator;
  if (method.iterations > 0) settings.sim.iterations = method.iterations;
  settings.sim.dt = dt;
  json run = measureModeDamping(settings, spheroidal, options.periods, options.speed);
  run["method"] = method.integrator;
  run["iterations"] = method.iterations;
  run["dt_s"] = dt;
  return run;
}

}  // namespace

json measureModeDamping(const Settings& base, bool spheroidal, double periods, double speed, bool automaticSubsteps) {
  const Settings settings = elasticBall(base, base.slime.resolution);
  Simulation simulation(settings);
  simulation.setAutomaticSubsteps(automaticSubsteps);
  const double eta = lambRoot(2, spheroidal, settings.slime.poisson);
  const double theory = lambTheoryHz(simulation, eta);
  const std::vector<glm::dvec3> shape = modeShape(simulation, spheroidal, eta);
  std::vector<glm::dvec3> velocities(shape.size());
  for (std::size_t i = 0; i < shape.size(); ++i) velocities[i] = speed * shape[i];
  simulation.setVelocities(velocities);

  std::vector<double> times, amplitudes, rates;
  const double seconds = periods / theory;
  const Stopwatch watch;
  while (simulation.time() < seconds) {
    simulation.step();
    if (!automaticSubsteps && !simulation.divergences().empty()) break;
    times.push_back(simulation.time());
    amplitudes.push_back(modalAmplitude(simulation, shape));
    rates.push_back(modalVelocity(simulation, shape));
  }
  const double wall = watch.milliseconds();
  const double measured = zeroCrossingFrequency(times, amplitudes);
  // A mode damped out within the run has too few crossings for a frequency: its damping is then
  // taken at Lamb's ω (the energy still decays, which is what the ratio is about).
  const double omega = 2.0 * std::numbers::pi * (measured > 0.0 ? measured : theory);
  const double zeta = energyDampingRatio(times, amplitudes, rates, omega);
  // Backward Euler's own damping of an undamped oscillator at ω: each step multiplies its energy by
  // 1 / (1 + (ωh)²), so ζ = ln(1 + (ωh)²) / (2ωh) ≈ ωh/2 — the closed form projective dynamics (an
  // implicit Euler step, Bouaziz et al. 2014) should approach as its iterations converge.
  const double h = settings.sim.dt / simulation.substepsPerStep();
  const double backwardEuler = std::log1p(omega * omega * h * h) / (2.0 * omega * h);
  return {{"mode", spheroidal ? "spheroidal_n2" : "torsional_n2"},
          {"substeps", simulation.substepsPerStep()},
          {"theory_hz", theory},
          {"measured_hz", measured},
          {"frequency_ratio", measured / theory},
          {"damping_ratio", zeta},
          {"backward_euler_damping_ratio", backwardEuler},
          {"periods", periods},
          {"simulated_s", simulation.time()},
          {"rollbacks", simulation.divergences().size()},
          {"cost_ms_per_sim_ms", wall / (1e3 * simulation.time())}};
}

json runDampingBench(const Settings& settings, const DampingOptions& options, CsvTable& table) {
  std::vector<DampingMethod> methods{{"symplectic_euler", 0}, {"rk4", 0}};
  for (int iterations : options.projectiveIterations) methods.push_back({"projective", iterations});
  std::printf("\nNumerical damping of Lamb's n = 2 modes (free elastic ball, resolution %d, nothing physical "
              "dissipates): damping ratio zeta and measured / Lamb's frequency against sim.dt\n",
              options.resolution);
  std::printf("%-17s %4s %-14s %8s %4s %12s %12s %10s %14s\n", "method", "it", "mode", "dt ms", "sub", "zeta",
              "zeta (BE)", "f ratio", "ms per sim ms");
  json rows = json::array();
  table.columns = {"method", "iterations", "mode", "dt_s", "substeps", "damping_ratio", "frequency_ratio",
                   "cost_ms_per_sim_ms", "backward_euler_damping_ratio"};
  for (const DampingMethod& method : methods) {
    for (bool spheroidal : {false, true}) {
      for (double dt : options.steps) {
        json run = dampingRun(settings, options, method, spheroidal, dt);
        std::printf("%-17s %4d %-14s %8.2f %4d %12.3e %12.3e %10.4f %14.4f\n", method.integrator.c_str(),
                    method.iterations, run["mode"].get<std::string>().c_str(), dt * 1e3, run["substeps"].get<int>(),
                    run["damping_ratio"].get<double>(), run["backward_euler_damping_ratio"].get<double>(),
                    run["frequency_ratio"].get<double>(),
                    run["cost_ms_per_sim_ms"].get<double>());
        std::fflush(stdout);
        table.add({method.integrator, method.iterations, run["mode"], dt, run["substeps"], run["damping_ratio"],
                   run["frequency_ratio"], run["cost_ms_per_sim_ms"], run["backward_euler_damping_ratio"]});
        rows.push_back(std::move(run));
      }
    }
  }
  return rows;
}

}  // namespace slime

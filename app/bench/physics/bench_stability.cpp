#include "app/bench/physics/bench_stability.h"

#include "core/simulation/simulation.h"

#include <cmath>

namespace slime {
namespace {

constexpr double kBlowUpEnergy = 1.0;  // J
constexpr double kMinVolumeRatio = 0.5, kMaxVolumeRatio = 2.0;

Settings startingInTheFloor(Settings settings) {
  settings.slime.position.z = settings.slime.radius - 0.001;
  settings.sim.substeps = 1;
  return settings;
}

}  // namespace

bool runsStably(const Settings& settings) {
  Simulation simulation(startingInTheFloor(settings));
  simulation.setAutomaticSubsteps(false);
  for (int step = 0; step < kStabilitySteps; ++step) {
    simulation.step();
    if (!simulation.divergences().empty()) return false;
    // The metrics cost a pass over the mesh: look every 20 steps and at the end.
    if (step % 20 == 19 || step == kStabilitySteps - 1) {
      const SlimeMetrics metrics = simulation.metrics();
      if (!(metrics.kineticEnergy < kBlowUpEnergy)) return false;
      if (!(metrics.volumeRatio > kMinVolumeRatio && metrics.volumeRatio < kMaxVolumeRatio)) return false;
    }
  }
  return true;
}

StabilityResult findLargestStableStep(const Settings& base, BenchProgress& progress) {
  StabilityResult result;
  {
    const Simulation probe(base);
    result.omegaMax = probe.highestFrequency();
    result.predictedStep = probe.largestStableStep();
    const double meanMass = base.slime.mass / static_cast<double>(probe.state().size());
    result.omegaEstimate = 2.48 * std::sqrt(base.slime.stiffness / meanMass);
  }
  Settings settings = base;
  const auto stable = [&](double dt) {
    settings.sim.dt = dt;
    ++result.runs;
    const bool ok = runsStably(settings);
    progress.advance(1.0, base.slime.model + " " + base.sim.integrator + ", dt = " + std::to_string(dt) + " s");
    return ok;
  };
  if (stable(kStabilityMaxStep)) {
    result.largestStableStep = kStabilityMaxStep;
    result.boundedAbove = false;
    return result;
  }
  if (!stable(kStabilityMinStep)) return result;  // unstable everywhere tried: 0
  double low = std::log(kStabilityMinStep), high = std::log(kStabilityMaxStep);
  for (int i = 0; i < kStabilityBisections; ++i) {
    const double middle = 0.5 * (low + high);
    (stable(std::exp(middle)) ? low : high) = middle;
  }
  result.largestStableStep = std::exp(low);
  return result;
}

}  // namespace slime

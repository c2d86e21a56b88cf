// Micro-benchmarks of the physics kernels on the default slime at levels 4 and 6: the spring forces
// alone, the whole force evaluation (springs, damper, fill pressure, gravity), and one full step of
// each integrator (Simulation::step with sim.dt = 1 ms and the substeps it needs).
#include "core/membrane/force_model.h"
#include "core/integrators/integrators.h"
#include "core/settings/settings_io.h"
#include "core/scene/simulation.h"
#include "core/membrane/slime_body.h"
#include "core/membrane/springs.h"

#include <benchmark/benchmark.h>

namespace slime {
namespace {

SlimeBody defaultBody(int level) {
  Settings settings = defaultSettings();
  settings.slime.level = level;
  return buildSlimeBody(settings.slime);
}

void springForces(benchmark::State& state) {
  const SlimeBody body = defaultBody(static_cast<int>(state.range(0)));
  std::vector<glm::dvec3> forces(body.state.size());
  for (auto _ : state) {
    std::fill(forces.begin(), forces.end(), glm::dvec3(0.0));
    addSpringForces(body.springs, body.state.positions, body.state.velocities, 0.02, forces);
    benchmark::DoNotOptimize(forces.data());
  }
  state.counters["springs"] = static_cast<double>(body.springs.size());
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(body.springs.size()));
}
BENCHMARK(springForces)->Arg(4)->Arg(6)->Unit(benchmark::kMicrosecond);

void allForces(benchmark::State& state) {
  const SlimeBody body = defaultBody(static_cast<int>(state.range(0)));
  ForceModel model;
  model.springs = &body.springs;
  model.damping = 0.02;
  model.triangles = &body.triangles;
  model.restVolume = body.restVolume;
  model.restPressure = body.restPressure;
  model.bulkModulus = body.bulkModulus;
  ForceScratch scratch;
  std::vector<glm::dvec3> accelerations(body.state.size());
  for (auto _ : state) {
    computeAccelerations(model, body.state.inverseMasses, body.state.positions, body.state.velocities, scratch, accelerations);
    benchmark::DoNotOptimize(accelerations.data());
  }
}
BENCHMARK(allForces)->Arg(4)->Arg(6)->Unit(benchmark::kMicrosecond);

// One Simulation::step of 1 ms for integrator range(0) at level range(1), the ball in free fall.
void integratorStep(benchmark::State& state) {
  const std::string integrator = integratorNames()[static_cast<std::size_t>(state.range(0))];
  Settings settings = defaultSettings();
  settings.slime.level = static_cast<int>(state.range(1));
  settings.slime.position.z = 10.0;  // far above the floor: the same work every step
  settings.sim.integrator = integrator;
  Simulation simulation(settings);
  for (auto _ : state) simulation.step();
  state.SetLabel(integrator + ", " + std::to_string(simulation.substepsPerStep()) + " substeps");
}
BENCHMARK(integratorStep)->ArgsProduct({{0, 1, 2, 3, 4}, {4}})->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace slime

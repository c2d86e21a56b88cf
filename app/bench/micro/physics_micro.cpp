// Micro-benchmarks of the physics kernels on the default slime at levels 4 and 6: the spring forces
// alone, the whole force evaluation (springs, damper, fill pressure, gravity), and one full step of
// each integrator (Simulation::step with sim.dt = 1 ms and the substeps it needs); the bulk slime's step
// at rest on the floor at drawn levels 4, 6 and 7; and the bulk body's projective local step (its targets
// with the Maxwell flow) at resolutions 2 and 3.
#include "core/bulk/projective_local.h"
#include "core/membrane/force_model.h"
#include "core/integrators/integrators.h"
#include "core/settings/settings_io.h"
#include "core/simulation/simulation.h"
#include "core/membrane/slime_body.h"
#include "core/membrane/springs.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <ctime>

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

// One Simulation::step of the default bulk slime resting on the floor (landed 0.5 s before) at drawn level
// range(0), the drawn surface placed every range(1) steps between them (0: never; `slime sim` places it
// every 10 steps for its series, a viewer once a frame). Timed: the step's own thread CPU time. The floor
// holds up level 4's points at every drawn level (BulkBody::floorPoints), so the step does the same work;
// what a placement at level 6 leaves behind is caches without the body (its 1.8 M smooth-map terms, 30 MB).
void restingStepByLevel(benchmark::State& state) {
  Settings settings = defaultSettings();
  settings.slime.level = static_cast<int>(state.range(0));
  Simulation simulation(settings);
  while (simulation.time() < 0.5) simulation.step();
  const auto threadSeconds = [] {
    timespec now{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
  };
  const std::int64_t placeEvery = state.range(1);
  std::int64_t steps = 0;
  for (auto _ : state) {
    const double start = threadSeconds();
    simulation.step();
    state.SetIterationTime(threadSeconds() - start);
    if (placeEvery > 0 && ++steps % placeEvery == 0) benchmark::DoNotOptimize(simulation.positions().data());
  }
  state.counters["drawn_vertices"] = static_cast<double>(simulation.positions().size());
}
BENCHMARK(restingStepByLevel)->ArgsProduct({{4, 6, 7}, {0, 10}})->UseManualTime()->Unit(benchmark::kMicrosecond);

// projectiveTargets with the flow, on the bulk body of resolution range(0) twisted and squashed a little
// (each element its own F, so the polar decompositions do work), R warm-started from the last call.
void projectiveLocalStep(benchmark::State& state) {
  SlimeSettings slime = defaultSettings().slime;
  slime.resolution = static_cast<int>(state.range(0));
  BulkBody body = buildBulkBody(slime);
  for (glm::dvec3& x : body.state.positions) {
    const glm::dvec3 d = x - slime.position;
    const double angle = 4.0 * d.z;  // radians per metre of height
    x = slime.position + glm::dvec3(d.x * std::cos(angle) - d.y * std::sin(angle),
                                    d.x * std::sin(angle) + d.y * std::cos(angle), 0.9 * d.z);
  }
  std::vector<ProjectiveBlock> blocks(body.restBlocks.size());
  for (ProjectiveBlock& block : blocks)
    for (std::size_t lane = 0; lane < kTetLanes; ++lane) block.rotation[0][lane] = 1;
  NodeQuads quads;
  std::vector<glm::dvec3> targets;
  for (auto _ : state) {
    projectiveTargets(body, true, 0.001, false, blocks, quads, targets);
    benchmark::DoNotOptimize(targets.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(body.mesh.tetrahedra.size()));
}
BENCHMARK(projectiveLocalStep)->Arg(2)->Arg(3)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace slime

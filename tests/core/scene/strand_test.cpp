// Long strands: two hands pull the default slime apart slowly into a strand at least five times its
// rest diameter, with no NaN, no inverted element, no rollback and its volume within 2 %; let go, it
// draws back towards its ball (the standard linear solid's long-term branch). Slow: HandsLong.
#include "core/settings/settings_io.h"
#include "core/scene/simulation.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace slime {
namespace {

// Smallest det F = det(D_s D_m⁻¹) over the body's tetrahedra, as a ratio of rest to now (6V / 6V₀).
double smallestVolumeRatio(const Simulation& simulation) {
  const BulkBody& body = simulation.bulkBody();
  const std::vector<glm::dvec3>& x = body.state.positions;
  const std::vector<glm::dvec3>& x0 = body.mesh.positions;
  double smallest = 1e300;
  for (const Tetrahedron& t : body.mesh.tetrahedra) {
    const auto volume = [&](const std::vector<glm::dvec3>& p) {
      return glm::dot(glm::cross(p[t.y] - p[t.x], p[t.z] - p[t.x]), p[t.w] - p[t.x]);
    };
    smallest = std::min(smallest, volume(x) / volume(x0));
  }
  return smallest;
}

struct StrandRun {
  double restDiameter, strand, smallestElement, volumeMin, volumeMax, released, nan;
  std::size_t rollbacks;
};

StrandRun pullIntoAStrand(const std::string& integrator) {
  Settings settings = defaultSettings();
  settings.sim.integrator = integrator;
  Simulation simulation(settings);
  while (simulation.time() < 1.0 - 1e-9) simulation.step();
  StrandRun run{};
  run.restDiameter = simulation.metrics().width;
  const double r = settings.slime.radius;
  EXPECT_TRUE(simulation.grab(glm::dvec3(-2.0 * r, 0.0, 0.03), 0.5 * r, 0));
  EXPECT_TRUE(simulation.grab(glm::dvec3(2.0 * r, 0.0, 0.03), 0.5 * r, 1));
  const glm::dvec3 left = simulation.grabTarget(0), right = simulation.grabTarget(1);
  // Each hand goes out 22 cm and up 8 cm in 14 s (1.7 cm/s), then holds for 1 s.
  const double t0 = simulation.time(), pull = 14.0, out = 0.22, up = 0.08;
  run.volumeMin = run.volumeMax = 1.0;
  run.smallestElement = 1.0;
  while (simulation.time() < t0 + pull + 1.0 - 1e-9) {
    const double s = std::min(1.0, (simulation.time() - t0) / pull);
    simulation.dragTo(left + glm::dvec3(-out * s, 0.0, up * s), 0);
    simulation.dragTo(right + glm::dvec3(out * s, 0.0, up * s), 1);
    simulation.step();
    if (simulation.stepCount() % 20 == 0) {
      const SlimeMetrics m = simulation.metrics();
      run.volumeMin = std::min(run.volumeMin, m.volumeRatio);
      run.volumeMax = std::max(run.volumeMax, m.volumeRatio);
      run.smallestElement = std::min(run.smallestElement, smallestVolumeRatio(simulation));
      if (!std::isfinite(m.volumeRatio)) run.nan = 1.0;
    }
  }
  run.strand = simulation.metrics().width;
  std::printf("strand (%s): hands at %.1f and %.1f cm, forces %.2f / %.2f N\n", integrator.c_str(),
              simulation.grabbedPoint(0).x * 100, simulation.grabbedPoint(1).x * 100,
              glm::length(simulation.handForce(0)), glm::length(simulation.handForce(1)));
  simulation.releaseAll();
  const double t1 = simulation.time();
  while (simulation.time() < t1 + 3.0 - 1e-9) simulation.step();
  run.released = simulation.metrics().width;
  run.rollbacks = simulation.divergences().size();
  std::printf("strand (%s): rest diameter %.1f cm, strand %.1f cm (%.1f×), smallest element volume ratio %.3f, "
              "volume [%.4f, %.4f], 3 s after release %.1f cm, rollbacks %zu\n",
              integrator.c_str(), run.restDiameter * 100, run.strand * 100, run.strand / run.restDiameter,
              run.smallestElement, run.volumeMin, run.volumeMax, run.released * 100, run.rollbacks);
  return run;
}

void expectAStrandThatComesBack(const StrandRun& run) {
  EXPECT_EQ(run.nan, 0.0);
  EXPECT_GE(run.strand, 5.0 * run.restDiameter);
  EXPECT_GT(run.smallestElement, 0.0);  // no inverted element
  EXPECT_GT(run.volumeMin, 0.98);
  EXPECT_LT(run.volumeMax, 1.02);
  EXPECT_EQ(run.rollbacks, 0u);
  EXPECT_LT(run.released, 0.6 * run.strand);  // draws back towards its ball
}

// Disabled: the goal of issue 29 item 2, not met yet. Measured 2026-11-27 (docs/physics.md, "Long
// strands"): symplectic_euler, hands 20 cm out and 8 cm up in 8 s, reached 5.3× but rolled back 12
// times and inverted elements; sim.integrator=projective reached 4.4× (8 s) and 4.7× (22 cm in 14 s:
// one rollback at 13.7 s) with both hands at their 10 N limit (kMouseMaxForce). Enable it when a
// strand that long fits under the hands' force, or the solver holds it without rollbacks.
TEST(HandsLong, DISABLED_TwoHandsPullTheDefaultSlimeIntoAStrandThatComesBack) {
  expectAStrandThatComesBack(pullIntoAStrand("projective"));
}

}  // namespace
}  // namespace slime

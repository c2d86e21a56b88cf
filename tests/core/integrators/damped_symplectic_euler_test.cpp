// The fused substep of the default integrator against the same mathematics done pass by pass
// (computeAccelerations without the damper → half kick → dampSpringsImplicitly → half kick → drift
// → floor):
// they must agree up to floating-point rounding, with the fill, a kinematic point and the floor in play,
// serially and on threads; threads must not change a bit; and its volume gradient per edge against
// volume.h's per triangle.
#include "core/integrators/damped_symplectic_euler.h"
#include "core/contact/floor_contact.h"
#include "core/membrane/force_model.h"
#include "core/geometry/icosphere.h"
#include "core/integrators/integrators.h"
#include "core/settings/settings_io.h"
#include "core/simulation/simulation.h"
#include "core/membrane/slime_body.h"
#include "core/geometry/volume.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace slime {
namespace {

// Level 3 runs the serial substep, level 6 the one on threads.
class FusedSubstep : public ::testing::TestWithParam<int> {};

TEST_P(FusedSubstep, MatchesThePassByPassOne) {
  Settings settings = defaultSettings();
  settings.slime.level = GetParam();
  const SlimeBody body = buildSlimeBody(settings.slime);
  const double h =
      GetParam() >= 6 ? 1.25e-4 : 5e-4;  // within the stable step (8 substeps of 1 ms at level 6)
  const double friction = 0.6;
  const glm::dvec3 gravity{0.0, 0.0, -9.81};

  // A lively state: a swirl of velocities, the ball half through the floor, one point held.
  ParticleState start = body.state;
  for (std::size_t i = 0; i < start.size(); ++i) {
    const double phase = 0.37 * static_cast<double>(i);
    start.velocities[i] = {0.3 * std::sin(phase), 0.2 * std::cos(1.7 * phase),
                           -0.5 + 0.1 * std::sin(3.1 * phase)};
    start.positions[i].z -= 0.03;
  }
  start.inverseMasses[5] = 0.0;

  std::vector<double> decays;
  springDampingDecays(body.springs, start.inverseMasses, settings.slime.damping, h, decays);

  ForceModel elastic;
  elastic.springs = &body.springs;
  elastic.triangles = &body.triangles;
  elastic.restVolume = body.restVolume;
  elastic.restPressure = body.restPressure;
  elastic.bulkModulus = body.bulkModulus;
  elastic.gravity = gravity;
  ForceScratch forceScratch;
  IntegratorScratch integratorScratch;
  const AccelerationField field = [&](const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& v,
                                      std::vector<glm::dvec3>& a) {
    computeAccelerations(elastic, start.inverseMasses, x, v, forceScratch, a);
  };

  DampedSymplecticEulerModel model;
  model.springs = &body.springs;
  std::vector<glm::dvec2> shares;
  springDampingShares(body.springs, start.inverseMasses, settings.slime.damping, h, shares);
  model.dampingShares = &shares;
  model.springOpposites = &body.springOpposites;
  const std::vector<std::size_t> runs = independentSpringRuns(body.springs.ends, body.state.size());
  model.independentRuns = &runs;
  model.restVolume = body.restVolume;
  model.restPressure = body.restPressure;
  model.bulkModulus = body.bulkModulus;
  model.gravity = gravity;
  model.friction = friction;
  DampedSymplecticEulerScratch scratch;

  ParticleState split = start, fused = start;
  for (int substep = 0; substep < 40; ++substep) {
    symplecticEulerKick(split, 0.5 * h, field, integratorScratch);
    dampSpringsImplicitly(body.springs, split.positions, split.inverseMasses, decays, split.velocities);
    symplecticEulerKick(split, 0.5 * h, field, integratorScratch);
    symplecticEulerDrift(split, h);
    resolveFloorContact(split, friction);
    dampedSymplecticEulerSubstep(fused, h, model, scratch);
  }
  double largestSpeed = 0.0;
  for (const glm::dvec3& v : split.velocities) {
    ASSERT_TRUE(std::isfinite(glm::length(v)));
    largestSpeed = std::max(largestSpeed, glm::length(v));
  }
  ASSERT_GT(largestSpeed, 0.1);  // something did happen
  for (std::size_t i = 0; i < split.size(); ++i) {
    EXPECT_LT(glm::length(fused.positions[i] - split.positions[i]), 1e-12) << "vertex " << i;
    EXPECT_LT(glm::length(fused.velocities[i] - split.velocities[i]), 1e-9 * largestSpeed) << "vertex " << i;
    EXPECT_GE(fused.positions[i].z, 0.0);
  }
}

INSTANTIATE_TEST_SUITE_P(Levels, FusedSubstep, ::testing::Values(3, 6));

TEST(DampedSymplecticEuler, ThreadsDoNotChangeTheResult) {
  Settings settings = defaultSettings();
  settings.slime.level = 6;  // big enough for threads
  auto simulate = [&](int threads) {
    std::vector<glm::dvec3> positions;
    tbb::task_arena arena(threads);
    arena.execute([&] {
      Simulation simulation(settings);
      for (int step = 0; step < 20; ++step) simulation.step();
      positions = simulation.positions();
    });
    return positions;
  };
  ASSERT_GE(Simulation(settings).positions().size(), kParallelPointCount);
  const std::vector<glm::dvec3> one = simulate(1), two = simulate(2), three = simulate(3);
  for (std::size_t i = 0; i < one.size(); ++i) {
    ASSERT_EQ(one[i], two[i]) << "vertex " << i;
    ASSERT_EQ(one[i], three[i]) << "vertex " << i;
  }
}

TEST(DampedSymplecticEuler, IndependentRunsShareNoVertex) {
  const SlimeBody body = buildSlimeBody(defaultSettings().slime);
  const std::vector<std::size_t> runs = independentSpringRuns(body.springs.ends, body.state.size());
  ASSERT_GE(runs.size(), 2u);
  EXPECT_EQ(runs.front(), 0u);
  EXPECT_EQ(runs.back(), body.springs.size());
  EXPECT_LT(runs.size(), 16u);  // about one run per colour
  for (std::size_t run = 0; run + 1 < runs.size(); ++run) {
    std::vector<bool> touched(body.state.size(), false);
    for (std::size_t s = runs[run]; s < runs[run + 1]; ++s) {
      const glm::u32vec2 ends = body.springs.ends[s];
      ASSERT_FALSE(touched[ends.x] || touched[ends.y]) << "spring " << s;
      touched[ends.x] = touched[ends.y] = true;
    }
  }
}

TEST(DampedSymplecticEuler, VolumeGradientPerEdgeMatchesPerTriangle) {
  // A lumpy, off-centre icosphere: ∇V from one cross product per edge (given to the vertices
  // opposite it) equals the per-triangle sum, and Σ p_i · ∇_i V = 3 V.
  TriangleMesh mesh = makeIcosphere(2, 0.05, {0.3, -0.2, 0.1});
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    mesh.positions[i] += 0.004 * glm::dvec3(std::sin(1.3 * i), std::cos(2.1 * i), std::sin(0.7 * i + 1.0));
  std::vector<glm::dvec3> expected;
  const double volume = volumeGradient(mesh.positions, mesh.triangles, expected);
  const std::vector<glm::u32vec2> edges = uniqueEdges(mesh.triangles);
  const std::vector<glm::u32vec2> opposites = edgeOpposites(edges, mesh.triangles);
  std::vector<glm::dvec3> gradient(mesh.positions.size(), glm::dvec3(0.0));
  const glm::dvec3 origin = mesh.positions[0];
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const glm::dvec3 share =
        glm::cross(mesh.positions[edges[e].x] - origin, mesh.positions[edges[e].y] - origin) / 6.0;
    gradient[opposites[e].x] += share;
    gradient[opposites[e].y] -= share;
  }
  double threeVolume = 0.0;
  for (std::size_t i = 0; i < gradient.size(); ++i) {
    EXPECT_LT(glm::length(gradient[i] - expected[i]), 1e-12 * glm::length(expected[i])) << "vertex " << i;
    threeVolume += glm::dot(mesh.positions[i] - origin, gradient[i]);
  }
  EXPECT_NEAR(threeVolume / 3.0, volume, 1e-12 * volume);
  // An open mesh has edges with one triangle: refused.
  std::vector<Triangle> open = mesh.triangles;
  open.pop_back();
  EXPECT_THROW(edgeOpposites(uniqueEdges(open), open), std::invalid_argument);
}

}  // namespace
}  // namespace slime

// Forces against hand-computed values: Hooke, damper, series rule, volume and its gradient, the
// fill pressure and the implicit spring damping.
#include "core/membrane/force_model.h"
#include "core/geometry/icosphere.h"
#include "core/membrane/springs.h"
#include "core/geometry/volume.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace slime {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(Springs, HookeForceByHand) {
  // p_i = 0, p_j = (3, 4, 0): |x| = 5, rest 4, k = 10: F_j = -10 (5 - 4) (0.6, 0.8, 0) = (-6, -8, 0).
  const glm::dvec3 f = springForce({0, 0, 0}, {3, 4, 0}, 4.0, 10.0);
  EXPECT_NEAR(f.x, -6.0, 1e-12);
  EXPECT_NEAR(f.y, -8.0, 1e-12);
  EXPECT_NEAR(f.z, 0.0, 1e-12);
  // Compressed: |x| = 5, rest 6 pushes j away from i.
  EXPECT_NEAR(springForce({0, 0, 0}, {3, 4, 0}, 6.0, 10.0).x, 6.0, 1e-12);
}

TEST(Springs, DamperActsOnRelativeVelocityAlongTheSpring) {
  // x = (2, 0, 0), v_ij = (1, 5, 0): (v·x)/(x·x) x = (1, 0, 0); k_d = 0.5 -> F_j = (-0.5, 0, 0).
  const glm::dvec3 f = damperForce({1, 1, 1}, {3, 1, 1}, {0, 0, 0}, {1, 5, 0}, 0.5);
  EXPECT_NEAR(f.x, -0.5, 1e-12);
  EXPECT_NEAR(f.y, 0.0, 1e-12);
  // A common velocity (rigid translation) is not damped.
  EXPECT_NEAR(glm::length(damperForce({0, 0, 0}, {1, 0, 0}, {2, 3, 4}, {2, 3, 4}, 7.0)), 0.0, 1e-12);
}

TEST(Springs, SeriesRuleMakesLongerSpringsSofter) {
  EXPECT_DOUBLE_EQ(seriesStiffness(40.0, 0.01, 0.01), 40.0);
  EXPECT_DOUBLE_EQ(seriesStiffness(40.0, 0.01, 0.02), 20.0);
  EXPECT_DOUBLE_EQ(seriesStiffness(40.0, 0.01, 0.005), 80.0);
}

TEST(Springs, AddSpringForcesSumsBothEndsAndKeepsMomentum) {
  SpringSet springs;
  springs.ends = {{0, 1}, {1, 2}};
  springs.restLengths = {1.0, 1.0};
  springs.stiffnesses = {10.0, 20.0};
  const std::vector<glm::dvec3> x = {{0, 0, 0}, {2, 0, 0}, {2, 0.5, 0}};
  const std::vector<glm::dvec3> v = {{0, 0, 0}, {0, 0, 0}, {0, 1, 0}};
  std::vector<glm::dvec3> f(3, glm::dvec3(0.0));
  addSpringForces(springs, x, v, 0.3, f);
  // Spring 0 stretched by 1: pulls 0 towards +x with 10 N, 1 towards -x. Spring 1 compressed by
  // 0.5 (k 20 -> 10 N) pushes 2 to +y and 1 to -y; its damper: v_ij = (0, 1, 0) along x̂ = ŷ: 0.3 N.
  EXPECT_NEAR(f[0].x, 10.0, 1e-12);
  EXPECT_NEAR(f[1].x, -10.0, 1e-12);
  EXPECT_NEAR(f[2].y, 10.0 - 0.3, 1e-12);
  EXPECT_NEAR(f[1].y, -(10.0 - 0.3), 1e-12);
  const glm::dvec3 total = f[0] + f[1] + f[2];
  EXPECT_NEAR(glm::length(total), 0.0, 1e-12);
}

TEST(Springs, EdgeSpringsFollowTheSeriesRuleAndPrestrain) {
  const TriangleMesh mesh = makeIcosphere(2, 0.04, {});
  const SpringSet springs = makeEdgeSprings(mesh.positions, mesh.triangles, 50.0, 1.0);
  ASSERT_EQ(springs.size(), 480u);
  double mean = 0.0;
  for (const auto& e : springs.ends) mean += glm::length(mesh.positions[e.y] - mesh.positions[e.x]);
  mean /= static_cast<double>(springs.size());
  for (std::size_t s = 0; s < springs.size(); ++s) {
    const double d = glm::length(mesh.positions[springs.ends[s].y] - mesh.positions[springs.ends[s].x]);
    EXPECT_NEAR(springs.stiffnesses[s], 50.0 * mean / d, 1e-9);
    EXPECT_NEAR(springs.restLengths[s], d / 2.0, 1e-15);
  }
}

TEST(Springs, ImplicitDampingDecaysRelativeSpeedExactly) {
  SpringSet springs;
  springs.ends = {{0, 1}};
  springs.restLengths = {1.0};
  springs.stiffnesses = {1.0};
  const std::vector<glm::dvec3> x = {{0, 0, 0}, {0, 0, 2}};
  const std::vector<double> w = {1.0, 3.0};  // masses 1 and 1/3
  std::vector<glm::dvec3> v = {{0, 0, -1}, {0.5, 0, 1}};
  const glm::dvec3 momentum = v[0] / w[0] + v[1] / w[1];
  dampSpringsImplicitly(springs, x, w, 0.2, 0.5, v);
  // Relative normal speed 2 decays as exp(-k_d (w_i + w_j) h) = exp(-0.2 * 4 * 0.5).
  EXPECT_NEAR(v[1].z - v[0].z, 2.0 * std::exp(-0.4), 1e-12);
  EXPECT_NEAR(v[1].x, 0.5, 1e-15);  // the tangential part is untouched
  const glm::dvec3 after = v[0] / w[0] + v[1] / w[1];
  EXPECT_NEAR(glm::length(after - momentum), 0.0, 1e-12);
}

TEST(Volume, UnitCubeAndTetrahedron) {
  const std::vector<glm::dvec3> tetra = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const std::vector<glm::u32vec3> faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  EXPECT_NEAR(enclosedVolume(tetra, faces), 1.0 / 6.0, 1e-15);
  std::vector<glm::dvec3> moved = tetra;
  for (auto& p : moved) p += glm::dvec3(10, -20, 30);
  EXPECT_NEAR(enclosedVolume(moved, faces), 1.0 / 6.0, 1e-12);
}

TEST(Volume, IcosphereApproachesTheBall) {
  const double ball = 4.0 / 3.0 * kPi * 0.04 * 0.04 * 0.04;
  const TriangleMesh coarse = makeIcosphere(3, 0.04, {0, 0, 0.1});
  const TriangleMesh fine = makeIcosphere(5, 0.04, {0, 0, 0.1});
  const double coarseError = ball - enclosedVolume(coarse.positions, coarse.triangles);
  const double fineError = ball - enclosedVolume(fine.positions, fine.triangles);
  EXPECT_GT(coarseError, 0.0);  // inscribed polyhedra are smaller
  EXPECT_LT(fineError / ball, 1e-3);
  EXPECT_NEAR(coarseError / fineError, 16.0, 1.0);  // second order in the edge length
}

TEST(Volume, GradientMatchesFiniteDifferences) {
  TriangleMesh mesh = makeIcosphere(1, 0.04, {0.01, 0.02, 0.05});
  mesh.positions[3] += glm::dvec3(0.003, -0.002, 0.001);  // not a symmetric shape
  std::vector<glm::dvec3> gradient;
  const double volume = volumeGradient(mesh.positions, mesh.triangles, gradient);
  EXPECT_NEAR(volume, enclosedVolume(mesh.positions, mesh.triangles), 1e-18);
  const double step = 1e-7;
  for (std::size_t i : {0u, 3u, 17u}) {
    for (int axis = 0; axis < 3; ++axis) {
      std::vector<glm::dvec3> plus = mesh.positions, minus = mesh.positions;
      plus[i][axis] += step;
      minus[i][axis] -= step;
      const double numeric =
          (enclosedVolume(plus, mesh.triangles) - enclosedVolume(minus, mesh.triangles)) / (2 * step);
      EXPECT_NEAR(gradient[i][axis], numeric, 1e-10) << "vertex " << i << " axis " << axis;
    }
  }
}

TEST(Volume, FillPressure) {
  EXPECT_DOUBLE_EQ(fillPressure(1.0, 1.0, 300.0, 1e4), 300.0);
  EXPECT_DOUBLE_EQ(fillPressure(0.99, 1.0, 300.0, 1e4), 400.0);  // squeezed 1 % -> +100 Pa
}

TEST(ForceModel, GravityOnlyOnDynamicPoints) {
  ForceModel model;
  model.gravity = {0, 0, -9.81};
  const std::vector<double> w = {2.0, 0.0};
  const std::vector<glm::dvec3> x = {{0, 0, 0}, {1, 0, 0}}, v(2, glm::dvec3(0.0));
  ForceScratch scratch;
  std::vector<glm::dvec3> a;
  computeAccelerations(model, w, x, v, scratch, a);
  EXPECT_DOUBLE_EQ(a[0].z, -9.81);
  EXPECT_DOUBLE_EQ(a[1].z, 0.0);
}

}  // namespace
}  // namespace slime

// Floor contact: nothing stays below z = 0, the normal velocity into the floor is removed, and
// Coulomb friction sticks slow points and slows fast ones by μ |Δv_n|.
#include "core/contact/floor_contact.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace slime {
namespace {

ParticleState onePoint(glm::dvec3 position, glm::dvec3 velocity, double inverseMass = 1.0) {
  ParticleState state;
  state.positions = {position};
  state.velocities = {velocity};
  state.inverseMasses = {inverseMass};
  return state;
}

TEST(FloorContact, LiftsPenetratingPointAndRemovesDownwardSpeed) {
  ParticleState state = onePoint({0.1, 0.2, -0.003}, {0.0, 0.0, -2.0});
  EXPECT_EQ(resolveFloorContact(state, 0.5), 1u);
  EXPECT_EQ(state.positions[0].z, 0.0);
  EXPECT_EQ(state.velocities[0].z, 0.0);
  EXPECT_EQ(state.positions[0].x, 0.1);
}

TEST(FloorContact, StaticFrictionSticksSlowPoints) {
  // |Δv_n| = 2, μ = 0.5: sliding up to 1 m/s is stopped.
  ParticleState state = onePoint({0, 0, -0.001}, {0.6, 0.8, -2.0});
  resolveFloorContact(state, 0.5);
  EXPECT_EQ(state.velocities[0].x, 0.0);
  EXPECT_EQ(state.velocities[0].y, 0.0);
}

TEST(FloorContact, KineticFrictionSlowsFastPointsByMuTimesNormalImpulse) {
  ParticleState state = onePoint({0, 0, -0.001}, {3.0, 4.0, -2.0});
  resolveFloorContact(state, 0.5);
  // Tangential speed 5 loses μ |Δv_n| = 1 along its own direction.
  EXPECT_NEAR(state.velocities[0].x, 3.0 * 4.0 / 5.0, 1e-12);
  EXPECT_NEAR(state.velocities[0].y, 4.0 * 4.0 / 5.0, 1e-12);
}

TEST(FloorContact, LeavesPointsAboveOrLeavingAndKinematicOnesAlone) {
  ParticleState above = onePoint({0, 0, 0.01}, {1.0, 0.0, -1.0});
  EXPECT_EQ(resolveFloorContact(above, 0.5), 0u);
  EXPECT_EQ(above.velocities[0].x, 1.0);
  ParticleState leaving = onePoint({0, 0, 0.0}, {1.0, 0.0, 0.5});
  EXPECT_EQ(resolveFloorContact(leaving, 0.5), 0u);
  ParticleState grabbed = onePoint({0, 0, -0.01}, {0, 0, -1}, 0.0);
  EXPECT_EQ(resolveFloorContact(grabbed, 0.5), 0u);
  EXPECT_EQ(grabbed.positions[0].z, -0.01);
}

TEST(FloorContact, ARestingPointDoesNotJitter) {
  // Symplectic Euler under gravity on the floor: every step ends exactly at rest on z = 0.
  ParticleState state = onePoint({0.01, 0.0, 0.0}, {0.0, 0.0, 0.0});
  const double dt = 0.001;
  for (int step = 0; step < 1000; ++step) {
    state.velocities[0].z -= 9.81 * dt;
    state.positions[0] += state.velocities[0] * dt;
    resolveFloorContact(state, 0.6);
    ASSERT_EQ(state.positions[0].z, 0.0);
    ASSERT_EQ(state.velocities[0], glm::dvec3(0.0));
  }
  EXPECT_EQ(state.positions[0].x, 0.01);
}

// Four points of unequal mass, a tetrahedron standing on the floor with one corner, moving as a
// rigid body: translation u plus turning ω about the centre of mass, plus a breathing stretch.
struct TestTetrahedron {
  ParticleState state;
  glm::dvec3 centre{0.0};
};

TestTetrahedron spinningTetrahedron(glm::dvec3 translation, glm::dvec3 turning, double breathing, double lift) {
  TestTetrahedron t;
  t.state.positions = {{0.0, 0.0, lift}, {0.05, 0.0, lift + 0.04}, {-0.02, 0.04, lift + 0.05}, {0.0, -0.03, lift + 0.06}};
  t.state.inverseMasses = {10.0, 5.0, 20.0, 8.0};
  double mass = 0.0;
  for (std::size_t i = 0; i < 4; ++i) {
    mass += 1.0 / t.state.inverseMasses[i];
    t.centre += t.state.positions[i] / t.state.inverseMasses[i];
  }
  t.centre /= mass;
  for (const glm::dvec3& p : t.state.positions)
    t.state.velocities.push_back(translation + glm::cross(turning, p - t.centre) + breathing * (p - t.centre));
  return t;
}

glm::dvec3 momentum(const ParticleState& s) {
  glm::dvec3 sum(0.0);
  for (std::size_t i = 0; i < s.size(); ++i)
    if (s.inverseMasses[i] != 0.0) sum += s.velocities[i] / s.inverseMasses[i];
  return sum;
}

TEST(RollingResistance, TurningDecaysExactlyOnTheFloor) {
  const glm::dvec3 u{0.3, -0.1, 0.2}, omega{1.0, -2.0, 0.5};
  TestTetrahedron t = spinningTetrahedron(u, omega, 0.0, 0.0);
  const glm::dvec3 before = momentum(t.state);
  ASSERT_TRUE(dampTurningOnFloor(t.state, 5.0, 0.1));
  const double keep = std::exp(-0.5);
  for (std::size_t i = 0; i < 4; ++i) {
    const glm::dvec3 expected = u + keep * glm::cross(omega, t.state.positions[i] - t.centre);
    EXPECT_LT(glm::length(t.state.velocities[i] - expected), 1e-12) << "point " << i;
  }
  EXPECT_LT(glm::length(momentum(t.state) - before), 1e-12);
}

TEST(RollingResistance, LeavesSlidingAndStretchingAlone) {
  TestTetrahedron t = spinningTetrahedron({0.3, -0.1, 0.2}, glm::dvec3(0.0), 0.7, 0.0);
  const std::vector<glm::dvec3> before = t.state.velocities;
  ASSERT_TRUE(dampTurningOnFloor(t.state, 50.0, 0.01));
  for (std::size_t i = 0; i < 4; ++i) EXPECT_LT(glm::length(t.state.velocities[i] - before[i]), 1e-12);
}

TEST(RollingResistance, NothingOffTheFloorOrForKinematicPoints) {
  TestTetrahedron flying = spinningTetrahedron({0.0, 0.0, 0.0}, {1.0, 2.0, 3.0}, 0.0, 0.001);
  const std::vector<glm::dvec3> before = flying.state.velocities;
  EXPECT_FALSE(dampTurningOnFloor(flying.state, 5.0, 0.1));
  EXPECT_EQ(flying.state.velocities, before);
  TestTetrahedron held = spinningTetrahedron({0.0, 0.0, 0.0}, {1.0, 2.0, 3.0}, 0.0, 0.0);
  held.state.inverseMasses[2] = 0.0;  // grabbed: driven, not damped
  const glm::dvec3 driven = held.state.velocities[2];
  dampTurningOnFloor(held.state, 5.0, 0.1);
  EXPECT_EQ(held.state.velocities[2], driven);
  EXPECT_FALSE(dampTurningOnFloor(held.state, 0.0, 0.1));  // rate 0: off
}

}  // namespace
}  // namespace slime

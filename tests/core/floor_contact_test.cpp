// Floor contact: nothing stays below z = 0, the normal velocity into the floor is removed, and
// Coulomb friction sticks slow points and slows fast ones by μ |Δv_n|.
#include "core/floor_contact.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace slime

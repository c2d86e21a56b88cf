// Every integrator against the analytic damped mass–spring oscillator, with the measured order of
// convergence (error ratio when dt halves); the measured stability limit of symplectic Euler on one
// spring against 2/ω; and the unconditionally stable methods at 100× that step.
#include "core/implicit_euler.h"
#include "core/integrators.h"
#include "core/stability.h"
#include "core/xpbd.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace slime {
namespace {

// One point of mass m on a spring of rest length L0 to a pinned point at the origin, moving on the
// x axis: m x'' = -k (x - L0) - c x', which is exactly linear because x̂ stays (1, 0, 0).
constexpr double kMass = 0.01, kStiffness = 100.0, kRestLength = 1.0, kAmplitude = 0.1;
const double kOmega = std::sqrt(kStiffness / kMass);  // 100 rad/s

struct Oscillator {
  SpringSet springs;
  ParticleState state;
  ForceModel forces;
  XpbdModel constraints;

  explicit Oscillator(double damping) {
    springs.ends = {{0, 1}};
    springs.restLengths = {kRestLength};
    springs.stiffnesses = {kStiffness};
    state.positions = {{0, 0, 0}, {kRestLength + kAmplitude, 0, 0}};
    state.velocities = {{0, 0, 0}, {0, 0, 0}};
    state.inverseMasses = {0.0, 1.0 / kMass};
    forces.springs = &springs;
    forces.damping = damping;
    forces.gravity = {0, 0, 0};
    constraints.springs = &springs;
    constraints.damping = damping;
    constraints.gravity = {0, 0, 0};
  }

  // One step of `integrator` with the scratch each one needs.
  void step(Integrator integrator, double dt) {
    const AccelerationField field = [this](const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& v,
                                           std::vector<glm::dvec3>& a) {
      computeAccelerations(forces, state.inverseMasses, x, v, forceScratch, a);
    };
    switch (integrator) {
      case Integrator::ExplicitEuler: explicitEulerStep(state, dt, field, scratch); break;
      case Integrator::SymplecticEuler: symplecticEulerStep(state, dt, field, scratch); break;
      case Integrator::Rk4: rk4Step(state, dt, field, scratch); break;
      case Integrator::ImplicitEuler: implicitEulerStep(state, dt, forces, implicitOptions, implicitScratch); break;
      case Integrator::Xpbd: xpbdSubstep(state, dt, constraints, xpbdScratch); break;
    }
  }

  ImplicitEulerOptions implicitOptions;
  IntegratorScratch scratch;
  ImplicitEulerScratch implicitScratch;
  XpbdScratch xpbdScratch;
  ForceScratch forceScratch;
};

// x(t) - L0 for x(0) - L0 = A, x'(0) = 0, underdamped.
double analyticOffset(double t, double damping) {
  const double decay = damping / (2.0 * kMass);
  const double omegaDamped = std::sqrt(kOmega * kOmega - decay * decay);
  return kAmplitude * std::exp(-decay * t) * (std::cos(omegaDamped * t) + decay / omegaDamped * std::sin(omegaDamped * t));
}

// Runs `integrator` to time T with step dt; returns the largest error of x over the run.
double runError(Integrator integrator, double damping, double dt, double duration) {
  Oscillator o(damping);
  o.implicitOptions.tolerance = 1e-14;
  const int steps = static_cast<int>(std::lround(duration / dt));
  double worst = 0.0;
  for (int n = 1; n <= steps; ++n) {
    o.step(integrator, dt);
    const double error = std::abs(o.state.positions[1].x - kRestLength - analyticOffset(n * dt, damping));
    worst = std::max(worst, error);
  }
  return worst;
}

struct OrderCase {
  Integrator integrator;
  double expectedOrder;
  double dt;  // coarse step; well inside every method's stability region
};

class ConvergenceOrder : public ::testing::TestWithParam<OrderCase> {};

TEST_P(ConvergenceOrder, ErrorRatioWhenHalvingDtMatchesTheOrder) {
  const OrderCase c = GetParam();
  for (double damping : {0.0, 0.2}) {  // undamped and ζ = 0.1
    const double coarse = runError(c.integrator, damping, c.dt, 0.5);
    const double fine = runError(c.integrator, damping, c.dt / 2, 0.5);
    const double finer = runError(c.integrator, damping, c.dt / 4, 0.5);
    const double order = std::log2(fine / finer);
    std::printf("%-16s damping %.1f: error %.3e %.3e %.3e, measured order %.2f\n",
                integratorName(c.integrator).c_str(), damping, coarse, fine, finer, order);
    EXPECT_NEAR(order, c.expectedOrder, 0.25) << integratorName(c.integrator);
    EXPECT_LT(finer, fine);
    EXPECT_LT(finer, 0.2 * kAmplitude);  // and actually close to the analytic solution
  }
}

INSTANTIATE_TEST_SUITE_P(
    AllIntegrators, ConvergenceOrder,
    ::testing::Values(OrderCase{Integrator::ExplicitEuler, 1.0, 2e-4}, OrderCase{Integrator::SymplecticEuler, 1.0, 2e-4},
                      OrderCase{Integrator::Rk4, 4.0, 2e-3}, OrderCase{Integrator::ImplicitEuler, 1.0, 2e-4},
                      OrderCase{Integrator::Xpbd, 1.0, 2e-4}),
    [](const auto& info) { return integratorName(info.param.integrator); });

// True when 4000 steps of dt keep the undamped oscillator bounded (|x - L0| ≤ 10 A).
bool staysBounded(Integrator integrator, double dt, int steps = 4000) {
  Oscillator o(0.0);
  for (int n = 0; n < steps; ++n) {
    o.step(integrator, dt);
    const double offset = std::abs(o.state.positions[1].x - kRestLength);
    if (!(offset <= 10.0 * kAmplitude)) return false;
  }
  return true;
}

// Bisection for the largest stable step between a stable and an unstable one.
double measuredStabilityLimit(Integrator integrator, double stable, double unstable) {
  for (int i = 0; i < 40; ++i) {
    const double middle = 0.5 * (stable + unstable);
    (staysBounded(integrator, middle) ? stable : unstable) = middle;
  }
  return stable;
}

TEST(Stability, SymplecticEulerLimitIsTwoOverOmega) {
  const double predicted = 2.0 / kOmega;
  const double measured = measuredStabilityLimit(Integrator::SymplecticEuler, 0.1 * predicted, 10.0 * predicted);
  std::printf("symplectic_euler: measured dt limit %.6f s, 2/omega = %.6f s (ratio %.4f)\n", measured, predicted,
              measured / predicted);
  EXPECT_NEAR(measured / predicted, 1.0, 0.10);
  EXPECT_DOUBLE_EQ(largestStableStep(Integrator::SymplecticEuler, kOmega, 0.0), predicted);
}

TEST(Stability, Rk4LimitIsAboutTwoPointEightOverOmega) {
  const double measured = measuredStabilityLimit(Integrator::Rk4, 0.1 / kOmega, 10.0 / kOmega);
  std::printf("rk4: measured dt limit %.6f s = %.3f / omega\n", measured, measured * kOmega);
  EXPECT_NEAR(measured * kOmega, 2.83, 0.15);
}

TEST(Stability, ImplicitMethodsStayBoundedAtHundredTimesTheSymplecticLimit) {
  const double step = 100.0 * 2.0 / kOmega;
  EXPECT_TRUE(staysBounded(Integrator::ImplicitEuler, step, 200));
  EXPECT_TRUE(staysBounded(Integrator::Xpbd, step, 200));
  EXPECT_FALSE(staysBounded(Integrator::SymplecticEuler, step, 200));  // the same step breaks it
}

TEST(Stability, SeedUpdateIsSymplecticEuler) {
  // p = p0 + v0 dt + a dt², v = v0 + a dt is algebraically p = p0 + v1 dt: the same map.
  const double a = runError(Integrator::ExplicitEuler, 0.2, 1e-3, 0.3);
  const double b = runError(Integrator::SymplecticEuler, 0.2, 1e-3, 0.3);
  EXPECT_NEAR(a, b, 1e-12);
}

TEST(Stability, PowerIterationFindsTheSpringFrequency) {
  SpringSet springs;
  springs.ends = {{0, 1}};
  springs.restLengths = {1.0};
  springs.stiffnesses = {50.0};
  const std::vector<glm::dvec3> x = {{0, 0, 0}, {1, 0, 0}};
  const std::vector<double> w = {2.0, 3.0};
  EXPECT_NEAR(highestFrequency(springs, x, w), std::sqrt(50.0 * 5.0), 1e-6);
}

}  // namespace
}  // namespace slime

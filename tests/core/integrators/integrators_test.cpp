// Every integrator run exactly as the slime runs it — a Simulation stepping a body, so the default
// symplectic_euler is the fused substep (damped_symplectic_euler.h) with its implicit damper — on
// a body whose motion is known in closed form: one mass on one spring to a pinned point. Against
// that analytic damped oscillator: the measured order of convergence (error ratio when dt halves),
// the measured step at which each explicit method blows up against its theoretical limit, and the
// unconditionally stable methods at 100× that step.
#include "core/integrators/integrators.h"
#include "core/settings/settings_io.h"
#include "core/simulation/simulation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

namespace slime {
namespace {

// One point of mass m on a spring of rest length L0 to a pinned point, moving on the x axis, high
// above the floor, no gravity: m x'' = -k (x - L0) - c x', exactly linear because x̂ stays (1, 0, 0)
// (the damper acts on the relative speed along the spring, springs.h).
constexpr double kMass = 0.01, kStiffness = 100.0, kRestLength = 1.0, kAmplitude = 0.1, kHeight = 1.0;
const double kOmega = std::sqrt(kStiffness / kMass);  // 100 rad/s

SlimeBody oneSpring(double amplitude) {
  SlimeBody body;
  body.state.positions = {{0, 0, kHeight}, {kRestLength + amplitude, 0, kHeight}};
  body.state.velocities = {{0, 0, 0}, {0, 0, 0}};
  body.state.inverseMasses = {0.0, 1.0 / kMass};  // the first end pinned
  body.freeInverseMasses = body.state.inverseMasses;
  body.restPositions = body.state.positions;
  body.springs.ends = {{0, 1}};
  body.springs.restLengths = {kRestLength};
  body.springs.stiffnesses = {kStiffness};
  body.totalMass = kMass;
  return body;
}

// What the slime's settings would say, but for this body: no fill, gravity or rolling resistance,
// exactly one substep of dt (no automatic refinement: the step under test is the step taken).
Simulation oscillator(Integrator integrator, double dt, double damping, double amplitude = kAmplitude) {
  Settings settings = defaultSettings();
  settings.sim.integrator = integratorName(integrator);
  settings.sim.dt = dt;
  settings.sim.substeps = 1;
  settings.sim.gravity = 0.0;
  settings.slime.damping = damping;  // k_d, N·s/m
  settings.slime.pressure = 0.0;
  settings.slime.rolling = 0.0;
  Simulation simulation(settings, oneSpring(amplitude));
  simulation.setAutomaticSubsteps(false);
  return simulation;
}

double offset(const Simulation& simulation) { return simulation.positions()[1].x - kRestLength; }

// x(t) - L0 for x(0) - L0 = A, x'(0) = 0, underdamped.
double analyticOffset(double t, double damping) {
  const double decay = damping / (2.0 * kMass);
  const double omegaDamped = std::sqrt(kOmega * kOmega - decay * decay);
  return kAmplitude * std::exp(-decay * t) * (std::cos(omegaDamped * t) + decay / omegaDamped * std::sin(omegaDamped * t));
}

// Runs `integrator` to time T with step dt; returns the largest error of x over the run.
double runError(Integrator integrator, double damping, double dt, double duration) {
  Simulation simulation = oscillator(integrator, dt, damping);
  const int steps = static_cast<int>(std::lround(duration / dt));
  double worst = 0.0;
  for (int n = 1; n <= steps; ++n) {
    simulation.step();
    worst = std::max(worst, std::abs(offset(simulation) - analyticOffset(simulation.time(), damping)));
  }
  EXPECT_TRUE(simulation.divergences().empty()) << integratorName(integrator) << " at dt " << dt;
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
    EXPECT_NEAR(order, c.expectedOrder, 0.25) << integratorName(c.integrator) << " damping " << damping;
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

// True when `steps` steps of dt keep the oscillator bounded and the simulation's divergence guard
// never had to roll back. A small start (1 mm) and a wide bound (500 times it): just below the limit
// symplectic Euler's orbit is an ellipse stretched by 1/√(1 - (hω/2)²), bounded but long, and that
// must not read as a blow-up (the guard's absurd speed included); just above it grows exponentially.
constexpr double kSmallAmplitude = 1e-3, kBound = 500.0 * kSmallAmplitude;

bool staysBounded(Integrator integrator, double dt, double damping = 0.0, int steps = 4000) {
  Simulation simulation = oscillator(integrator, dt, damping, kSmallAmplitude);
  for (int n = 0; n < steps; ++n) {
    simulation.step();
    if (!simulation.divergences().empty() || !(std::abs(offset(simulation)) <= kBound)) return false;
  }
  return true;
}

// Bisection for the largest stable step between a stable and an unstable one.
double measuredStabilityLimit(Integrator integrator, double damping, double stable, double unstable) {
  EXPECT_TRUE(staysBounded(integrator, stable, damping));
  EXPECT_FALSE(staysBounded(integrator, unstable, damping));
  for (int i = 0; i < 30; ++i) {
    const double middle = 0.5 * (stable + unstable);
    (staysBounded(integrator, middle, damping) ? stable : unstable) = middle;
  }
  return stable;
}

// The theoretical limits on x'' + c x' + ω² x = 0 (c = k_d/m), from the eigenvalues of each step's
// 2×2 amplification matrix (stable while |trace| < 1 + det < 2):
//  - the seed's update (explicit_euler; the symplectic Euler map with an explicit damper):
//    det = 1 - hc, trace = 2 - h²ω² - hc, so h²ω² + 2hc < 4;
//  - the fused substep (half kick, damper decaying exp(-ch), half kick, drift): det = exp(-ch),
//    trace = 1 + det - h²ω²(1 + det)/2, so h < 2/ω whatever the damping;
//  - rk4: its stability polynomial reaches the imaginary axis at |hω| = 2√2.
struct LimitCase {
  Integrator integrator;
  double damping;  // k_d, N·s/m
  double theory;   // the largest stable step, s
};

class StabilityLimit : public ::testing::TestWithParam<LimitCase> {};

TEST_P(StabilityLimit, MeasuredBlowUpStepMatchesTheTheoryAndTheSimulationsPrediction) {
  const LimitCase c = GetParam();
  const double measured = measuredStabilityLimit(c.integrator, c.damping, 0.2 * c.theory, 3.0 * c.theory);
  const double predicted = oscillator(c.integrator, 1e-3, c.damping).largestStableStep();  // what sets substeps
  std::printf("%-16s damping %.1f: blows up above %.6f s; theory %.6f s (ratio %.4f), Simulation predicts %.6f s\n",
              integratorName(c.integrator).c_str(), c.damping, measured, c.theory, measured / c.theory, predicted);
  EXPECT_NEAR(measured / c.theory, 1.0, 0.01);
  // The prediction that sets the slime's substeps may be cautious, never optimistic, and not by much.
  EXPECT_LE(predicted, measured * 1.001);
  EXPECT_GT(predicted, 0.6 * measured);
}

const double kDampingRate = 100.0;                 // c = k_d/m, 1/s: ζ = 0.5
const double kHeavyDamping = kDampingRate * kMass;  // k_d, N·s/m

INSTANTIATE_TEST_SUITE_P(
    ExplicitMethods, StabilityLimit,
    ::testing::Values(
        LimitCase{Integrator::SymplecticEuler, 0.0, 2.0 / kOmega},
        LimitCase{Integrator::SymplecticEuler, kHeavyDamping, 2.0 / kOmega},
        LimitCase{Integrator::ExplicitEuler, 0.0, 2.0 / kOmega},
        LimitCase{Integrator::ExplicitEuler, kHeavyDamping,
                  4.0 / (kDampingRate + std::sqrt(kDampingRate * kDampingRate + 4.0 * kOmega * kOmega))},
        LimitCase{Integrator::Rk4, 0.0, 2.0 * std::sqrt(2.0) / kOmega}),
    [](const auto& info) {
      return integratorName(info.param.integrator) + (info.param.damping > 0.0 ? "_damped" : "_undamped");
    });

TEST(Stability, ImplicitMethodsStayBoundedAtHundredTimesTheSymplecticLimit) {
  const double step = 100.0 * 2.0 / kOmega;
  EXPECT_TRUE(staysBounded(Integrator::ImplicitEuler, step, 0.0, 200));
  EXPECT_TRUE(staysBounded(Integrator::Xpbd, step, 0.0, 200));
  EXPECT_FALSE(staysBounded(Integrator::SymplecticEuler, step, 0.0, 200));  // the same step breaks it
}

TEST(Stability, ExplicitEulerIsTheSeedsUpdate) {
  // SPEC §3: v = v0 + a dt, p = p0 + v0 dt + a dt², with a = (-k (x - L0) - c v0)/m, written out here.
  const double damping = 0.2, dt = 1e-3;
  Simulation simulation = oscillator(Integrator::ExplicitEuler, dt, damping);
  double x = kAmplitude, v = 0.0;
  for (int n = 0; n < 300; ++n) {
    const double a = (-kStiffness * x - damping * v) / kMass;
    x += v * dt + a * dt * dt;
    v += a * dt;
    simulation.step();
    ASSERT_NEAR(offset(simulation), x, 1e-12) << "step " << n;
  }
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

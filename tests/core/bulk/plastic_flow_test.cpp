// The long-term branch's plastic flow (viscoelastic.h, Bingham-like above a yield stretch): its closed
// form under a held stretch, nothing below the yield, the recovery, the stress as the energy's gradient,
// and the vectorised flow (tet_lanes.h's flowLongTermLanes) against the scalar one.
#include "core/bulk/bulk_body.h"
#include "core/bulk/elastic_stretch.h"
#include "core/bulk/element_pass.h"
#include "core/bulk/tet_lanes.h"
#include "core/bulk/viscoelastic.h"

#include <glm/matrix.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace slime {
namespace {

ViscoelasticMaterial plasticMaterial() {
  ViscoelasticMaterial m;
  m.longTermShear = 480.0;
  m.maxwellShear = 0.0;  // the long-term branch alone
  m.lameLambda = lameLambdaFor(480.0, 0.4);
  m.plastic = true;
  m.yieldStretch = 1.8;
  m.plasticFlowTime = 0.6;
  m.recoveryTime = 1.0;
  return m;
}

// An isochoric uniaxial stretch λ along x.
glm::dmat3 uniaxial(double stretch) {
  const double across = 1.0 / std::sqrt(stretch);
  return glm::dmat3(stretch, 0.0, 0.0, 0.0, across, 0.0, 0.0, 0.0, across);
}

// τ_xx − τ_yy of the stress P Fᵀ: the volumetric part cancels, the branch's deviatoric part stays.
double stressDifference(const ViscoelasticMaterial& m, const glm::dmat3& f, const glm::dmat3& plasticInverse) {
  const glm::dmat3 kirchhoff = firstPiolaStress(m, f, glm::dmat3(1.0), plasticInverse) * glm::transpose(f);
  return kirchhoff[0][0] - kirchhoff[1][1];
}

// A bar held at λ = 3 (elastic stretch 3 at first, G_p = I) relaxes to the yield stretch as the closed form
// t(u) = 3 τ_p ∫_u^λ dv/(v³ − s_y v − 1) says (plasticHoldTime), its stress μ∞(u² − 1/u) falling to the
// yield stress μ∞ s_y and no further. The flow is first order in its step: 1 ms steps agree to 1 % of t.
TEST(PlasticFlow, AHeldStretchRelaxesToTheYieldAsTheClosedFormSays) {
  const ViscoelasticMaterial m = plasticMaterial();
  const double held = 3.0, dt = 0.001;
  const glm::dmat3 f = uniaxial(held);
  const PlasticFlow flow = plasticFlowOver(m, dt);
  glm::dmat3 metric(1.0);
  const double yieldStress = m.longTermShear * yieldMeasure(m.yieldStretch);
  int checked = 0;
  for (int k = 1; k * dt <= 4.0; ++k) {
    metric = relaxLongTermBranch(f, metric, flow);
    const glm::dmat3 inverse = plasticInverseOf(metric);
    const double u = equivalentStretch(deviatoricStretchMeasure(f, inverse));
    const double t = k * dt;
    const double stress = stressDifference(m, f, inverse);
    EXPECT_NEAR(stress, m.longTermShear * (u * u - 1.0 / u), 1e-9 * yieldStress) << "t = " << t;
    EXPECT_GE(stress, yieldStress * (1.0 - 1e-9)) << "t = " << t;
    if (k % 50 == 0 && u > m.yieldStretch + 1e-3) {
      EXPECT_NEAR(t, plasticHoldTime(m.yieldStretch, m.plasticFlowTime, held, u), 0.01 * t + 2.0 * dt) << "u = " << u;
      ++checked;
    }
  }
  EXPECT_GE(checked, 25);
  const double u = equivalentStretch(deviatoricStretchMeasure(f, plasticInverseOf(metric)));
  EXPECT_NEAR(u, m.yieldStretch, 2e-3) << "4 s (6.7 τ_p) after: at the yield";
  EXPECT_NEAR(glm::determinant(metric), 1.0, 1e-12);
}

// Below the yield nothing flows: a press's 50 % compression (u = 0.5 is s = 1.75, below s_y = 2.68) and a
// stretch of 1.75 leave G_p the identity, bit for bit in the lanes; so does any shape of a body that never
// yields, which is then the standard linear solid exactly.
TEST(PlasticFlow, NothingFlowsBelowTheYield) {
  const ViscoelasticMaterial m = plasticMaterial();
  const PlasticFlow flow = plasticFlowOver(m, 0.01);
  for (const double stretch : {0.5, 1.0, 1.2, 1.75}) {
    EXPECT_LT(deviatoricStretchMeasure(uniaxial(stretch), glm::dmat3(1.0)), flow.yieldMeasure) << stretch;
    const glm::dmat3 metric = relaxLongTermBranch(uniaxial(stretch), glm::dmat3(1.0), flow);
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) EXPECT_NEAR(metric[c][r], c == r ? 1.0 : 0.0, 1e-15) << stretch;
    alignas(64) double shape[9][kTetLanes] = {}, restInverse[9][kTetLanes] = {}, metrics[6][kTetLanes] = {};
    for (std::size_t lane = 0; lane < kTetLanes; ++lane) {
      const glm::dmat3 rotated = glm::dmat3(std::cos(0.1 * lane), std::sin(0.1 * lane), 0.0, -std::sin(0.1 * lane),
                                            std::cos(0.1 * lane), 0.0, 0.0, 0.0, 1.0) * uniaxial(stretch);
      for (int e = 0; e < 9; ++e) {
        shape[e][lane] = rotated[e / 3][e % 3];
        restInverse[e][lane] = e % 4 == 0 ? 1.0 : 0.0;
      }
      for (int e = 0; e < 3; ++e) metrics[e][lane] = 1.0;
    }
    for (std::size_t o = 0; o < kTetLanes; o += kLanesOf<double>)
      EXPECT_FALSE(flowLongTermLanes<double>(shape, restInverse, flow.yieldMeasure, flow.flow, flow.recovery, o, metrics));
    for (std::size_t lane = 0; lane < kTetLanes; ++lane)
      for (int e = 0; e < 6; ++e) EXPECT_EQ(metrics[e][lane], e < 3 ? 1.0 : 0.0);
  }
}

// Below the yield a flowed rest shape returns to the ball: a small plastic strain ε decays as e^(−t/τ_r).
TEST(PlasticFlow, AFlowedRestShapeRecoversBelowTheYield) {
  const ViscoelasticMaterial m = plasticMaterial();
  const double dt = 0.01, strain = 1e-3;
  const PlasticFlow flow = plasticFlowOver(m, dt);
  glm::dmat3 metric = uniaxial(1.0 + strain) * uniaxial(1.0 + strain);
  for (int k = 1; k * dt <= 2.0 + 1e-9; ++k) {
    metric = relaxLongTermBranch(glm::dmat3(1.0), metric, flow);
    if (k % 50 == 0) {
      EXPECT_NEAR((metric[0][0] - 1.0) / (2.0 * strain), std::exp(-k * dt / m.recoveryTime), 2e-3) << "t = " << k * dt;
    }
  }
  ViscoelasticMaterial never = m;
  never.recoveryTime = 0.0;
  const glm::dmat3 kept = relaxLongTermBranch(glm::dmat3(1.0), uniaxial(1.2) * uniaxial(1.2), plasticFlowOver(never, 1.0));
  EXPECT_NEAR(kept[0][0], 1.44, 1e-12) << "τ_r = 0 keeps the flowed shape";
}

// P is dΨ/dF with a flowed rest shape, and the branch is free of stress at it (F = R U_p, however far it flowed).
TEST(PlasticFlow, TheStressIsTheEnergysGradientAndVanishesAtTheFlowedShape) {
  ViscoelasticMaterial m = plasticMaterial();
  m.maxwellShear = 700.0;
  const glm::dmat3 u(1.6, 0.2, 0.0, 0.2, 0.9, -0.1, 0.0, -0.1, 0.8);
  const glm::dmat3 stretch = u / std::cbrt(glm::determinant(u));
  const glm::dmat3 metric = stretch * stretch, inverse = plasticInverseOf(metric);
  const glm::dmat3 f(1.2, 0.1, -0.3, 0.2, 0.8, 0.1, 0.05, -0.2, 1.1), maxwell(1.0);
  const glm::dmat3 stress = firstPiolaStress(m, f, maxwell, inverse);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      glm::dmat3 up = f, down = f;
      up[i][j] += 1e-6;
      down[i][j] -= 1e-6;
      const double derivative = (energyDensity(m, up, maxwell, inverse) - energyDensity(m, down, maxwell, inverse)) / 2e-6;
      EXPECT_NEAR(stress[i][j], derivative, 1e-4 * m.longTermShear) << i << "," << j;
    }
  ViscoelasticMaterial longTermOnly = m;
  longTermOnly.maxwellShear = 0.0;
  const glm::dmat3 rotation(std::cos(0.3), std::sin(0.3), 0.0, -std::sin(0.3), std::cos(0.3), 0.0, 0.0, 0.0, 1.0);
  const glm::dmat3 p = firstPiolaStress(longTermOnly, rotation * stretch, maxwell, inverse);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(p[i][j], 0.0, 1e-9 * m.longTermShear) << i << "," << j;
}

// The vectorised flow is the scalar one per lane, in double and in the step's ElementReal, over strains
// above and below the yield and rest shapes that have flowed already.
template <class Real>
void expectLanesFlowAsTheScalarBranch(double tolerance) {
  const ViscoelasticMaterial m = plasticMaterial();
  const PlasticFlow flow = plasticFlowOver(m, 0.05);
  alignas(64) Real shape[9][kTetLanes] = {}, restInverse[9][kTetLanes] = {}, metrics[6][kTetLanes] = {};
  glm::dmat3 f[kTetLanes], g[kTetLanes];
  for (std::size_t lane = 0; lane < kTetLanes; ++lane) {
    const double a = 0.37 * static_cast<double>(lane);
    f[lane] = uniaxial(1.0 + 0.04 * static_cast<double>(lane)) *
              glm::dmat3(1.0, 0.1 * std::sin(a), 0.0, 0.05 * std::cos(a), 1.0, 0.1, 0.0, 0.0, 1.0 + 0.05 * std::sin(3 * a));
    const glm::dmat3 u = uniaxial(1.0 + 0.3 * std::abs(std::sin(2 * a)));
    g[lane] = lane % 3 == 0 ? glm::dmat3(1.0) : u * u;
    for (int e = 0; e < 9; ++e) {
      shape[e][lane] = static_cast<Real>(f[lane][e / 3][e % 3]);
      restInverse[e][lane] = e % 4 == 0 ? Real(1) : Real(0);
    }
    for (int r = 0; r < 3; ++r)
      for (int c = r; c < 3; ++c) metrics[kSymmetricEntry[r][c]][lane] = static_cast<Real>(g[lane][c][r]);
    for (int e = 0; e < 9; ++e) f[lane][e / 3][e % 3] = shape[e][lane];  // as stored
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) g[lane][c][r] = metrics[kSymmetricEntry[r][c]][lane];
  }
  for (std::size_t o = 0; o < kTetLanes; o += kLanesOf<Real>)
    flowLongTermLanes<Real>(shape, restInverse, flow.yieldMeasure, flow.flow, flow.recovery, o, metrics);
  int yielded = 0;
  for (std::size_t lane = 0; lane < kTetLanes; ++lane) {
    if (deviatoricStretchMeasure(f[lane], plasticInverseOf(g[lane])) > flow.yieldMeasure) ++yielded;
    const glm::dmat3 expected = relaxLongTermBranch(f[lane], g[lane], flow);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(metrics[kSymmetricEntry[r][c]][lane], expected[c][r], tolerance * std::abs(expected[0][0]))
            << "lane " << lane << " (" << r << "," << c << ")";
  }
  EXPECT_GT(yielded, 10);
  EXPECT_LT(yielded, static_cast<int>(kTetLanes) - 10);
}

TEST(PlasticFlow, TheLanesFlowAsTheScalarBranch) {
  expectLanesFlowAsTheScalarBranch<double>(1e-12);
  expectLanesFlowAsTheScalarBranch<ElementReal>(64.0 * std::numeric_limits<ElementReal>::epsilon());
}

// The closed form itself: its derivative is the flow law, dt/du = −3 τ_p / (u³ − s_y u − 1), on both sides
// of u_y = 4^(1/3), where its arctangent turns into a logarithm.
TEST(PlasticFlow, TheClosedFormsDerivativeIsTheFlowLaw) {
  for (const double yield : {1.3, 1.8, 2.5}) {
    const double s = yieldMeasure(yield);
    for (const double u : {yield + 0.01, yield + 0.3, yield + 2.0}) {
      const double h = 1e-6;
      const double slope = (plasticHoldTime(yield, 0.6, 5.0, u + h) - plasticHoldTime(yield, 0.6, 5.0, u - h)) / (2 * h);
      EXPECT_NEAR(slope, -3.0 * 0.6 / (u * u * u - s * u - 1.0), 1e-5 * std::abs(slope)) << yield << " " << u;
    }
    EXPECT_NEAR(plasticHoldTime(yield, 0.6, 3.0, 3.0), 0.0, 1e-12);
  }
}

// Damage (slime.damage): the plastic stretch of a flowed rest metric, and D from it.
TEST(PlasticDamage, GrowsFromTheDamageStretchToTwiceIt) {
  for (const double stretch : {1.0, 1.5, 4.0, 11.0}) {
    const double trace = stretch * stretch + 2.0 / stretch;  // G_p of an isochoric uniaxial plastic stretch
    EXPECT_NEAR(plasticStretchOfTrace(trace), stretch, 1e-10 * stretch);
  }
  const auto damageAt = [](double stretch, double damageStretch) {
    return damageOfTrace(stretch * stretch + 2.0 / stretch, damageStretch);
  };
  EXPECT_EQ(damageAt(1.0, 3.0), 0.0);
  EXPECT_EQ(damageAt(2.9, 3.0), 0.0);
  EXPECT_NEAR(damageAt(4.5, 3.0), 0.5, 1e-9);
  EXPECT_EQ(damageAt(6.0 + 1e-6, 3.0), 1.0);
  EXPECT_EQ(damageAt(50.0, 3.0), 1.0);
  EXPECT_EQ(damageAt(50.0, 0.0), 0.0) << "λ_d = 0: no damage";
}

// The element pass scales a damaged element's long-term force map K_p by 1 − D, and only when damage is on;
// the tear measure reads D: (λ_e − 1)/((λ_tear − 1)(1 − D)), infinite once broken through.
TEST(PlasticDamage, SoftensTheLongTermBranchAndLowersTheTearStretch) {
  SlimeSettings slime;
  slime.resolution = 1;
  slime.plastic = true;
  slime.damageStretch = 3.0;
  BulkBody intact = buildBulkBody(slime);
  slime.damage = true;
  BulkBody damaged = buildBulkBody(slime);
  ASSERT_EQ(damaged.material.damageStretch, 3.0);
  const std::size_t element = 5, other = 6;
  const double stretch = 4.5;  // D = 0.5
  for (BulkBody* body : {&intact, &damaged}) {
    MaxwellBlock& block = body->maxwell[element / kTetLanes];
    const std::size_t lane = element % kTetLanes;
    block.plastic[0][lane] = static_cast<ElementReal>(stretch * stretch);
    block.plastic[1][lane] = static_cast<ElementReal>(1.0 / stretch);
    block.plastic[2][lane] = static_cast<ElementReal>(1.0 / stretch);
    refreshMaxwellForceMaps(*body, true);
  }
  EXPECT_NEAR(damage(damaged, element), 0.5, 1e-6);
  EXPECT_EQ(damage(intact, element), 0.0);
  EXPECT_EQ(damage(damaged, other), 0.0);
  const TetBlock& a = intact.restBlocks[element / kTetLanes];
  const TetBlock& b = damaged.restBlocks[element / kTetLanes];
  for (int entry = 0; entry < 6; ++entry) {
    EXPECT_NEAR(b.stiffnessMap[entry][element % kTetLanes], 0.5 * a.stiffnessMap[entry][element % kTetLanes],
                1e-6 * std::abs(a.stiffnessMap[0][element % kTetLanes]));
    EXPECT_EQ(b.stiffnessMap[entry][other % kTetLanes], a.stiffnessMap[entry][other % kTetLanes]);
  }
  // Stretch the body 1.3× along x: the intact element is 0.3 / 1.5 = 0.2 of the way to tearing (λ_tear 2.5), the
  // damaged one twice that; broken through it tears.
  std::vector<glm::dvec3> x = damaged.state.positions;
  for (glm::dvec3& p : x) p.x *= 1.3;
  const double measure = tearMeasure(intact, x, element, 2.5);
  EXPECT_NEAR(tearMeasure(damaged, x, element, 2.5), 2.0 * measure, 1e-9);
  EXPECT_NEAR(measure, (std::sqrt(elasticStretchSquared(intact, x, element)) - 1.0) / 1.5, 1e-12);
  MaxwellBlock& block = damaged.maxwell[element / kTetLanes];
  block.plastic[0][element % kTetLanes] = static_cast<ElementReal>(49.0);  // λ_p ≈ 7 > 2 λ_d
  EXPECT_TRUE(std::isinf(tearMeasure(damaged, x, element, 2.5)));
}

}  // namespace
}  // namespace slime

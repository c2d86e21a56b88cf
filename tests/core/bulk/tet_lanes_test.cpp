// The vector-lane element kernels (core/bulk/tet_lanes.h) against the scalar material they spell out
// (viscoelastic.h): per lane, the same nodal forces and the same Maxwell flow to rounding, and the lanes'
// inverse cube root within a few ulp over the range it serves.
#include "core/bulk/bulk_body.h"
#include "core/bulk/cube_root.h"
#include "core/bulk/tet_lanes.h"
#include "core/bulk/viscoelastic.h"

#include <glm/matrix.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace slime {
namespace {

// A distinct, well-conditioned matrix per lane and seed.
glm::dmat3 laneShape(std::size_t lane, double seed) {
  const double a = 0.37 * static_cast<double>(lane) + seed;
  return glm::dmat3(1.0 + 0.3 * std::sin(a), 0.2 * std::cos(2 * a), 0.05 * std::sin(3 * a), 0.1 * std::cos(a),
                    0.8 + 0.1 * std::cos(5 * a), -0.2 * std::sin(a), 0.03, 0.1 * std::sin(7 * a), 1.1 + 0.2 * std::cos(a));
}

// A lane's matrix in and out of a block's [9][kTetLanes] entries, stored as double or ElementReal.
template <typename Real>
void setLane(Real (&entries)[9][kTetLanes], std::size_t lane, const glm::dmat3& m) {
  for (int e = 0; e < 9; ++e) entries[e][lane] = static_cast<Real>(m[e / 3][e % 3]);
}
template <typename Real>
glm::dmat3 getLane(const Real (&entries)[9][kTetLanes], std::size_t lane) {
  glm::dmat3 m;
  for (int e = 0; e < 9; ++e) m[e / 3][e % 3] = entries[e][lane];
  return m;
}

double largestEntry(const glm::dmat3& m) {
  double largest = 0.0;
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) largest = std::max(largest, std::abs(m[c][r]));
  return largest;
}

// The size of the largest term that H = P·forceMap sums before the terms cancel, (λ'(|J| + α) + μ∞ +
// μ1 (1 + 3|B_v|)) · max(|F|, |cof F|) · 3|forceMap|: rounding errors are relative to it, not to H, whose
// entries the terms cancel down to.
double forceTermScale(const ViscoelasticMaterial& material, const glm::dmat3& f, const glm::dmat3& maxwell,
                      const glm::dmat3& forceMap) {
  const double j = glm::determinant(f);
  const glm::dmat3 cofactor = j * glm::transpose(glm::inverse(f));
  const double moduli = volumetricModulus(material) * (std::abs(j) + restVolumeRatio(material)) +
                        material.longTermShear + material.maxwellShear * (1.0 + 3.0 * largestEntry(maxwell));
  return moduli * std::max(largestEntry(f), largestEntry(cofactor)) * 3.0 * largestEntry(forceMap);
}

// stressForceLanes<Real> on data stored as Real, lane by lane against the scalar stress in double from the
// same stored (rounded) data: what is left is the lanes' arithmetic, within 64 ulp of Real of the largest
// term the forces sum (forceTermScale).
template <typename Real>
void expectLanesKeepTheScalarStress() {
  ViscoelasticMaterial material;
  material.longTermShear = 480.0;
  material.maxwellShear = 720.0;
  material.lameLambda = lameLambdaFor(1200.0, 0.4);
  alignas(64) Real shape[9][kTetLanes], restInverse[9][kTetLanes], forceMap[9][kTetLanes], maxwell[9][kTetLanes],
      forces[9][kTetLanes];
  for (std::size_t lane = 0; lane < kTetLanes; ++lane) {
    setLane(shape, lane, laneShape(lane, 0.0) * 0.01);  // Ds of the same size: F = O(1)
    const glm::dmat3 rest = laneShape(lane, 1.0) * 0.01;  // Dm, 1 cm edges
    setLane(restInverse, lane, glm::inverse(rest));
    setLane(forceMap, lane, -glm::determinant(rest) / 6.0 * glm::transpose(glm::inverse(rest)));
    setLane(maxwell, lane, glm::inverse(glm::transpose(laneShape(lane, 2.0)) * laneShape(lane, 2.0)));
  }
  for (std::size_t o = 0; o < kTetLanes; o += kLanesOf<Real>)
    stressForceLanes<Real>(material.longTermShear, material.maxwellShear, volumetricModulus(material),
                           restVolumeRatio(material), shape, restInverse, forceMap, maxwell, o, forces);
  for (std::size_t lane = 0; lane < kTetLanes; ++lane) {
    const glm::dmat3 f = getLane(shape, lane) * getLane(restInverse, lane);
    const glm::dmat3 expected = firstPiolaStress(material, f, getLane(maxwell, lane)) * getLane(forceMap, lane);
    const glm::dmat3 got = getLane(forces, lane);
    const double tolerance = 64.0 * std::numeric_limits<Real>::epsilon() *
                             forceTermScale(material, f, getLane(maxwell, lane), getLane(forceMap, lane));
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r)
        EXPECT_NEAR(got[c][r], expected[c][r], tolerance) << "lane " << lane << " entry " << c << "," << r;
  }
}

TEST(TetLanes, ForcesMatchTheScalarStressLaneByLane) { expectLanesKeepTheScalarStress<double>(); }

// The step's own precision (element_real.h): float on AVX-512, where it is not the test above again.
TEST(TetLanes, ForcesInElementRealKeepTheScalarStressToItsRounding) { expectLanesKeepTheScalarStress<ElementReal>(); }

TEST(TetLanes, FlowMatchesTheScalarFlowAndKeepsACollapsedElement) {
  alignas(64) double shape[9][kTetLanes], restInverse[9][kTetLanes], metric[9][kTetLanes], inverse[9][kTetLanes];
  MaxwellRest rests[kTetLanes];
  for (std::size_t lane = 0; lane < kTetLanes; ++lane) {
    glm::dmat3 ds = laneShape(lane, 3.0);
    if (lane == 5) ds = glm::dmat3(0.0);  // a collapsed element
    setLane(shape, lane, ds);
    setLane(restInverse, lane, glm::dmat3(1.0));
    const glm::dmat3 g = glm::transpose(laneShape(lane, 4.0)) * laneShape(lane, 4.0);
    rests[lane].metric = g / std::cbrt(glm::determinant(g));
    rests[lane].inverse = glm::inverse(rests[lane].metric);
    setLane(metric, lane, rests[lane].metric);
    setLane(inverse, lane, rests[lane].inverse);
  }
  const double decay = std::exp(-0.004 / 0.6);
  for (std::size_t o = 0; o < kTetLanes; o += kLanesOf<double>) relaxLanes<double>(shape, restInverse, decay, o, metric, inverse);
  for (std::size_t lane = 0; lane < kTetLanes; ++lane) {
    const MaxwellRest expected = relaxMaxwellBranch(getLane(shape, lane), rests[lane], decay);
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) {
        EXPECT_NEAR(getLane(metric, lane)[c][r], expected.metric[c][r], 1e-14) << "lane " << lane;
        EXPECT_NEAR(getLane(inverse, lane)[c][r], expected.inverse[c][r], 1e-14) << "lane " << lane;
      }
  }
  // With no memory (decay 0) the collapsed element's blend C = 0 has det 0: it keeps its rest state.
  const glm::dmat3 before = getLane(metric, 5);
  for (std::size_t o = 0; o < kTetLanes; o += kLanesOf<double>) relaxLanes<double>(shape, restInverse, 0.0, o, metric, inverse);
  EXPECT_EQ(getLane(metric, 5), before);
  EXPECT_NEAR(glm::determinant(getLane(metric, 4)), 1.0, 1e-13);
}

// The flow in ElementReal lanes on ElementReal storage: G_v and B_v to that type's rounding (entries O(1)),
// and det G_v = 1 to it (the cube root's two steps in float).
TEST(TetLanes, FlowInElementRealKeepsTheScalarFlowToItsRounding) {
  alignas(64) ElementReal shape[9][kTetLanes], restInverse[9][kTetLanes], metric[9][kTetLanes], inverse[9][kTetLanes];
  MaxwellRest rests[kTetLanes];
  for (std::size_t lane = 0; lane < kTetLanes; ++lane) {
    setLane(shape, lane, laneShape(lane, 3.0));
    setLane(restInverse, lane, glm::dmat3(1.0));
    const glm::dmat3 g = glm::transpose(laneShape(lane, 4.0)) * laneShape(lane, 4.0);
    setLane(metric, lane, g / std::cbrt(glm::determinant(g)));
    setLane(inverse, lane, glm::inverse(g / std::cbrt(glm::determinant(g))));
    rests[lane].metric = getLane(metric, lane);  // the stored, rounded state
    rests[lane].inverse = getLane(inverse, lane);
  }
  const double decay = std::exp(-0.004 / 0.6);
  for (std::size_t o = 0; o < kTetLanes; o += kLaneWidth) relaxLanes<ElementReal>(shape, restInverse, decay, o, metric, inverse);
  const double tolerance = 64.0 * std::numeric_limits<ElementReal>::epsilon();
  for (std::size_t lane = 0; lane < kTetLanes; ++lane) {
    const MaxwellRest expected = relaxMaxwellBranch(getLane(shape, lane), rests[lane], decay);
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) {
        EXPECT_NEAR(getLane(metric, lane)[c][r], expected.metric[c][r], tolerance) << "lane " << lane;
        EXPECT_NEAR(getLane(inverse, lane)[c][r], expected.inverse[c][r], tolerance) << "lane " << lane;
      }
    EXPECT_NEAR(glm::determinant(getLane(metric, lane)), 1.0, tolerance) << "lane " << lane;
  }
}

TEST(TetLanes, InverseCubeRootWithinAFewUlpOverItsRange) {
  alignas(64) double x[kLanesOf<double>], root[kLanesOf<double>];
  for (double exponent = -120.0; exponent <= 120.0; exponent += 0.37) {
    for (std::size_t lane = 0; lane < kLanesOf<double>; ++lane) x[lane] = std::exp2(exponent + 0.05 * lane);
    LanesOf<double> r;
    inverseCubeRootLanes<double>(loadLanes<double>(x), r);
    storeLanes<double>(root, r);
    for (std::size_t lane = 0; lane < kLanesOf<double>; ++lane) {
      const double expected = inverseCubeRootOfPositive(x[lane]);
      EXPECT_NEAR(root[lane], expected, 1e-15 * expected) << x[lane];  // ~4.5 ulp
    }
  }
}

}  // namespace
}  // namespace slime

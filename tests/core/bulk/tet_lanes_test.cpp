// The vector-lane element kernels (core/bulk/tet_lanes.h) against the scalar material they spell out
// (viscoelastic.h): per lane, the same nodal forces and the same Maxwell flow to rounding, and the lanes'
// inverse cube root within a few ulp over the range it serves.
#include "core/bulk/bulk_body.h"
#include "core/bulk/cube_root.h"
#include "core/bulk/tet_lanes.h"
#include "core/bulk/viscoelastic.h"

#include <glm/matrix.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace slime {
namespace {

// A distinct, well-conditioned matrix per lane and seed.
glm::dmat3 laneShape(std::size_t lane, double seed) {
  const double a = 0.37 * static_cast<double>(lane) + seed;
  return glm::dmat3(1.0 + 0.3 * std::sin(a), 0.2 * std::cos(2 * a), 0.05 * std::sin(3 * a), 0.1 * std::cos(a),
                    0.8 + 0.1 * std::cos(5 * a), -0.2 * std::sin(a), 0.03, 0.1 * std::sin(7 * a), 1.1 + 0.2 * std::cos(a));
}

void setLane(double (&entries)[9][kTetLanes], std::size_t lane, const glm::dmat3& m) {
  for (int e = 0; e < 9; ++e) entries[e][lane] = m[e / 3][e % 3];
}
glm::dmat3 getLane(const double (&entries)[9][kTetLanes], std::size_t lane) {
  glm::dmat3 m;
  for (int e = 0; e < 9; ++e) m[e / 3][e % 3] = entries[e][lane];
  return m;
}

TEST(TetLanes, ForcesMatchTheScalarStressLaneByLane) {
  ViscoelasticMaterial material;
  material.longTermShear = 480.0;
  material.maxwellShear = 720.0;
  material.lameLambda = lameLambdaFor(1200.0, 0.4);
  alignas(64) double shape[9][kTetLanes], restInverse[9][kTetLanes], forceMap[9][kTetLanes], maxwell[9][kTetLanes],
      forces[9][kTetLanes];
  for (std::size_t lane = 0; lane < kTetLanes; ++lane) {
    setLane(shape, lane, laneShape(lane, 0.0));
    const glm::dmat3 rest = laneShape(lane, 1.0) * 0.01;  // Dm, 1 cm edges
    setLane(restInverse, lane, glm::inverse(rest));
    setLane(forceMap, lane, -glm::determinant(rest) / 6.0 * glm::transpose(glm::inverse(rest)));
    setLane(maxwell, lane, glm::inverse(glm::transpose(laneShape(lane, 2.0)) * laneShape(lane, 2.0)));
  }
  for (std::size_t o = 0; o < kTetLanes; o += kLaneWidth)
    stressForceLanes(material.longTermShear, material.maxwellShear, volumetricModulus(material),
                     restVolumeRatio(material), shape, restInverse, forceMap, maxwell, o, forces);
  for (std::size_t lane = 0; lane < kTetLanes; ++lane) {
    const glm::dmat3 f = getLane(shape, lane) * getLane(restInverse, lane);
    const glm::dmat3 expected = firstPiolaStress(material, f, getLane(maxwell, lane)) * getLane(forceMap, lane);
    const glm::dmat3 got = getLane(forces, lane);
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r)
        EXPECT_NEAR(got[c][r], expected[c][r], 1e-12 * (1.0 + std::abs(expected[c][r])) + 1e-9 * 1e-3)
            << "lane " << lane << " entry " << c << "," << r;
  }
}

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
  for (std::size_t o = 0; o < kTetLanes; o += kLaneWidth) relaxLanes(shape, restInverse, decay, o, metric, inverse);
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
  for (std::size_t o = 0; o < kTetLanes; o += kLaneWidth) relaxLanes(shape, restInverse, 0.0, o, metric, inverse);
  EXPECT_EQ(getLane(metric, 5), before);
  EXPECT_NEAR(glm::determinant(getLane(metric, 4)), 1.0, 1e-13);
}

TEST(TetLanes, InverseCubeRootWithinAFewUlpOverItsRange) {
  alignas(64) double x[kLaneWidth], root[kLaneWidth];
  for (double exponent = -120.0; exponent <= 120.0; exponent += 0.37) {
    for (std::size_t lane = 0; lane < kLaneWidth; ++lane) x[lane] = std::exp2(exponent + 0.05 * lane);
    Lanes r;
    inverseCubeRootLanes(loadLanes(x), r);
    storeLanes(root, r);
    for (std::size_t lane = 0; lane < kLaneWidth; ++lane) {
      const double expected = inverseCubeRootOfPositive(x[lane]);
      EXPECT_NEAR(root[lane], expected, 1e-15 * expected) << x[lane];  // ~4.5 ulp
    }
  }
}

}  // namespace
}  // namespace slime

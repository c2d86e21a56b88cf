// The element pass (core/bulk/element_pass.h): the forces from Ds (tet_lanes.h's shapeForceLanes, with
// the maps K0 and M) equal viscoelastic.h's P·(−V0 Dm⁻ᵀ) summed over the tetrahedra, to rounding, on
// a body deformed by a non-affine map whose Maxwell branches have flowed (B_v ≠ I), at resolutions 1–2.
#include "core/bulk/bulk_body.h"
#include "core/bulk/element_pass.h"
#include "core/bulk/viscoelastic.h"
#include "core/settings/settings_io.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace slime {
namespace {

// A smooth non-affine deformation (so that every element has its own F) about the body's centre.
std::vector<glm::dvec3> deformed(const std::vector<glm::dvec3>& rest, double amount) {
  glm::dvec3 centre(0.0);
  for (const glm::dvec3& x : rest) centre += x;
  centre /= static_cast<double>(rest.size());
  std::vector<glm::dvec3> out(rest.size());
  for (std::size_t i = 0; i < rest.size(); ++i) {
    const glm::dvec3 d = (rest[i] - centre) / 0.04;
    out[i] = rest[i] + 0.04 * amount * glm::dvec3(0.3 * d.y + 0.2 * std::sin(3.0 * d.z), -0.25 * d.x * d.x,
                                                 0.15 * d.z + 0.1 * std::cos(2.0 * d.x + d.y));
  }
  return out;
}

// f = −V0 P Dm⁻ᵀ per tetrahedron with glm's scalar matrices (bulk_body.cpp's loop before issue 27).
std::vector<glm::dvec3> scalarForces(const BulkBody& body, const std::vector<glm::dvec3>& x) {
  std::vector<glm::dvec3> forces(x.size(), glm::dvec3(0.0));
  for (std::size_t e = 0; e < body.mesh.tetrahedra.size(); ++e) {
    const Tetrahedron& t = body.mesh.tetrahedra[e];
    const glm::dmat3 f = deformationGradient(body.rest[e], x[t.x], x[t.y], x[t.z], x[t.w]);
    const glm::dmat3 h =
        firstPiolaStress(body.material, f, maxwellInverse(body, e), plasticInverse(body, e)) * body.rest[e].forceMap;
    forces[t.y] += h[0];
    forces[t.z] += h[1];
    forces[t.w] += h[2];
    forces[t.x] -= h[0] + h[1] + h[2];
  }
  return forces;
}

void expectSameForces(const BulkBody& body, const std::vector<glm::dvec3>& x) {
  std::vector<glm::dvec3> lanes;
  elementForces(body, x, lanes);
  const std::vector<glm::dvec3> scalar = scalarForces(body, x);
  ASSERT_EQ(lanes.size(), scalar.size());
  // Rounding is relative to one element's force scale (λ' + μ1) V0^(2/3), which the terms cancel down
  // from (at rest the forces are rounding alone), or to the largest force if that is larger.
  double largest = (volumetricModulus(body.material) + body.material.maxwellShear) *
                   std::pow(body.restVolume / static_cast<double>(body.mesh.tetrahedra.size()), 2.0 / 3.0);
  for (const glm::dvec3& f : scalar) largest = std::max(largest, glm::length(f));
  // In double lanes and storage the forces agree to 1e-11 of that scale; in float (element_real.h) to
  // float's rounding of it: an error of ε in an element's force scale is a strain error of ε (6e-8
  // × 64 here, far below any strain the oracles look at).
  const double tolerance = std::max(1e-11, 64.0 * std::numeric_limits<ElementReal>::epsilon());
  for (std::size_t i = 0; i < x.size(); ++i)
    EXPECT_LT(glm::length(lanes[i] - scalar[i]), tolerance * largest) << "node " << i;
}

class ElementPass : public ::testing::TestWithParam<int> {};

TEST_P(ElementPass, ForcesFromDsEqualTheScalarStressBeforeAndAfterTheFlow) {
  SlimeSettings slime = defaultSettings().slime;
  slime.resolution = GetParam();
  BulkBody body = buildBulkBody(slime);
  ASSERT_GT(body.material.maxwellShear, 0.0);
  expectSameForces(body, body.state.positions);  // at rest: all but zero, still the same
  const std::vector<glm::dvec3> rest = body.state.positions;
  body.state.positions = deformed(rest, 0.3);
  relaxBulk(body, 0.2);  // the branches flow towards this shape: B_v ≠ I, M follows
  body.state.positions = deformed(rest, 0.5);
  relaxBulk(body, 0.05);
  expectSameForces(body, deformed(rest, 0.4));
  // A purely elastic body (μ1 = 0) leaves M out.
  slime.longTerm = 1.0;
  applyBulkMaterial(body, slime);
  expectSameForces(body, deformed(rest, 0.4));
}

// With the long-term branches yielded (a low yield: G_p ≠ I, K_p follows), the forces are still the scalar
// stress's, and a body whose flowing rest states are put back (the guard's rollback) and refreshed gives
// the forces it gave before the flow, bit for bit.
TEST_P(ElementPass, ForcesFollowTheLongTermBranchesFlowAndItsRollback) {
  SlimeSettings slime = defaultSettings().slime;
  slime.resolution = GetParam();
  slime.plastic = true;
  slime.yieldStretch = 1.1;
  slime.flowTime = 0.1;
  BulkBody body = buildBulkBody(slime);
  const std::vector<glm::dvec3> rest = body.state.positions;
  body.state.positions = deformed(rest, 0.6);
  std::vector<glm::dvec3> before;
  elementForces(body, body.state.positions, before);
  const std::vector<MaxwellBlock> saved = body.maxwell;
  relaxBulk(body, 0.1);
  std::size_t yielded = 0;
  for (std::size_t e = 0; e < body.mesh.tetrahedra.size(); ++e)
    if (std::abs(plasticMetric(body, e)[0][0] - 1.0) > 1e-3) ++yielded;
  EXPECT_GT(yielded, body.mesh.tetrahedra.size() / 10) << "the deformation should pass this yield";
  expectSameForces(body, deformed(rest, 0.5));
  body.maxwell = saved;
  refreshMaxwellForceMaps(body);
  std::vector<glm::dvec3> after;
  elementForces(body, body.state.positions, after);
  for (std::size_t i = 0; i < after.size(); ++i) EXPECT_EQ(after[i], before[i]) << "node " << i;
}

// The frequency estimate differences the forces over moves of ~1e-8 m spread over all nodes (bulk_body.h's
// bulkHighestFrequencyAt), below float's rounding of an element's edge: its forces in double lanes give the
// same directional stiffness K·u over a 10× smaller move (to the curvature's 1e-3 here), which float lanes
// could not (their rounding noise over 1e-9 m is larger than K·u itself).
TEST_P(ElementPass, ForcesInDoubleLanesDifferenceSmoothlyOverTheEstimatesMoves) {
  SlimeSettings slime = defaultSettings().slime;
  slime.resolution = GetParam();
  BulkBody body = buildBulkBody(slime);
  const std::vector<glm::dvec3> at = deformed(body.state.positions, 0.2);
  const std::size_t n = at.size();
  std::vector<glm::dvec3> direction(n);
  double norm = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    direction[i] = glm::dvec3(std::sin(1.0 + 3.0 * i), std::cos(2.0 + 5.0 * i), std::sin(3.0 + 7.0 * i));
    norm += glm::dot(direction[i], direction[i]);
  }
  for (glm::dvec3& d : direction) d /= std::sqrt(norm);
  std::vector<glm::dvec3> base, probe, moved(n);
  elementForcesInDouble(body, at, base);
  const auto stiffness = [&](double epsilon) {
    for (std::size_t i = 0; i < n; ++i) moved[i] = at[i] + epsilon * direction[i];
    elementForcesInDouble(body, moved, probe);
    std::vector<glm::dvec3> ku(n);
    for (std::size_t i = 0; i < n; ++i) ku[i] = (probe[i] - base[i]) / epsilon;
    return ku;
  };
  const std::vector<glm::dvec3> coarse = stiffness(1e-8), fine = stiffness(1e-9);
  double size = 0.0, difference = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    size += glm::dot(coarse[i], coarse[i]);
    difference += glm::dot(fine[i] - coarse[i], fine[i] - coarse[i]);
  }
  ASSERT_GT(size, 0.0);
  EXPECT_LT(std::sqrt(difference / size), 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Resolutions, ElementPass, ::testing::Values(1, 2));

}  // namespace
}  // namespace slime

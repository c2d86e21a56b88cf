// The projective local step in float lanes (core/bulk/projective_local.h) against the same step
// written per tetrahedron in double with glm (the loop of main f661e65, before the lanes): the targets
// Σ w_e D_eᵀ p_e, the rotations and the flowed Maxwell stretches agree to float's rounding, on a twisted,
// non-affine shape with a few elements inverted, from R = I and again warm-started, at resolutions 1–2.
#include "core/bulk/bulk_body.h"
#include "core/bulk/projective_local.h"
#include "core/settings/settings_io.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace slime {
namespace {

// Per tetrahedron: R as a unit quaternion (w, x, y, z) and U_v (00, 11, 22, 01, 02, 12).
struct ReferenceState {
  double q[4] = {1.0, 0.0, 0.0, 0.0};
  double u[6] = {1.0, 1.0, 1.0, 0.0, 0.0, 0.0};
};

glm::dmat3 rotationOf(const double (&q)[4]) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  return glm::dmat3(1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y),  //
                    2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x),  //
                    2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y));
}

glm::dmat3 stretchOf(const double (&u)[6]) { return glm::dmat3(u[0], u[3], u[4], u[3], u[1], u[5], u[4], u[5], u[2]); }

// Two warm-started sweeps of Müller et al. 2016, the flow of U_v towards sym(RᵀF) renormalised to det 1,
// p = (μ∞ R + μ1 R U_v + (3λ/2) p_V)/(μ + 3λ/2) and w_e p Dm⁻ᵀ on nodes 1..3, minus their sum on node 0.
std::vector<glm::dvec3> referenceTargets(const BulkBody& body, double flow, std::vector<ReferenceState>& states) {
  const ViscoelasticMaterial& m = body.material;
  const double mu = m.longTermShear + m.maxwellShear, volumeWeight = 1.5 * m.lameLambda;
  std::vector<glm::dvec3> targets(body.state.size(), glm::dvec3(0.0));
  for (std::size_t e = 0; e < body.mesh.tetrahedra.size(); ++e) {
    const Tetrahedron& t = body.mesh.tetrahedra[e];
    const std::vector<glm::dvec3>& x = body.state.positions;
    const glm::dmat3 f = deformationGradient(body.rest[e], x[t.x], x[t.y], x[t.z], x[t.w]);
    ReferenceState& s = states[e];
    for (int sweep = 0; sweep < 2; ++sweep) {
      const glm::dmat3 r = rotationOf(s.q);
      glm::dvec3 omega(0.0);
      double dot = 0.0;
      for (int c = 0; c < 3; ++c) {
        omega += glm::cross(r[c], f[c]);
        dot += glm::dot(r[c], f[c]);
      }
      omega *= 0.5 / (std::abs(dot) + 1e-12);
      const double n[4] = {s.q[0] - glm::dot(omega, glm::dvec3(s.q[1], s.q[2], s.q[3])),
                           s.q[1] + omega.x * s.q[0] + omega.y * s.q[3] - omega.z * s.q[2],
                           s.q[2] + omega.y * s.q[0] + omega.z * s.q[1] - omega.x * s.q[3],
                           s.q[3] + omega.z * s.q[0] + omega.x * s.q[2] - omega.y * s.q[1]};
      const double norm = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2] + n[3] * n[3]);
      for (int k = 0; k < 4; ++k) s.q[k] = n[k] / norm;
    }
    const glm::dmat3 r = rotationOf(s.q);
    const glm::dmat3 stretch = glm::transpose(r) * f;
    const glm::dmat3 u = stretchOf(s.u) + flow * (0.5 * (stretch + glm::transpose(stretch)) - stretchOf(s.u));
    const double det = glm::determinant(u);
    if (det > 0.0) {
      const glm::dmat3 normalised = u / std::cbrt(det);
      const double entries[6] = {normalised[0][0], normalised[1][1], normalised[2][2],
                                 normalised[1][0], normalised[2][0], normalised[2][1]};
      std::copy(entries, entries + 6, s.u);
    }
    const glm::dmat3 cofactor = glm::transpose(glm::inverse(f)) * glm::determinant(f);
    const double j = glm::determinant(f);
    double cofSquared = 0.0, toRotation = 0.0;
    for (int c = 0; c < 3; ++c) {
      cofSquared += glm::dot(cofactor[c], cofactor[c]);
      toRotation += glm::dot(f[c] - r[c], f[c] - r[c]);
    }
    const double delta = (1.0 - j) / cofSquared;
    const bool newton = j > 0.0 && delta * delta * cofSquared <= toRotation;
    const glm::dmat3 volumeTarget = newton ? f + delta * cofactor : r;
    const glm::dmat3 p = (m.longTermShear * r + m.maxwellShear * r * stretchOf(s.u) + volumeWeight * volumeTarget) /
                         (mu + volumeWeight);
    const glm::dmat3 h = body.rest[e].volume * (2.0 * mu + 3.0 * m.lameLambda) * p * glm::transpose(body.rest[e].restInverse);
    targets[t.y] += h[0];
    targets[t.z] += h[1];
    targets[t.w] += h[2];
    targets[t.x] -= h[0] + h[1] + h[2];
  }
  return targets;
}

// A twist about the vertical (0.8 rad across the ball), a squash and a smooth shear, and one node moved
// through the centre (its elements inverted, whose target is R).
std::vector<glm::dvec3> twisted(const std::vector<glm::dvec3>& rest, double amount) {
  glm::dvec3 centre(0.0);
  for (const glm::dvec3& x : rest) centre += x;
  centre /= static_cast<double>(rest.size());
  std::vector<glm::dvec3> out(rest.size());
  for (std::size_t i = 0; i < rest.size(); ++i) {
    const glm::dvec3 d = rest[i] - centre;
    const double angle = amount * 20.0 * d.z, height = d.z / 0.04;
    out[i] = centre + glm::dvec3(d.x * std::cos(angle) - d.y * std::sin(angle) + 0.004 * amount * std::sin(3.0 * height),
                                 d.x * std::sin(angle) + d.y * std::cos(angle), (1.0 - 0.3 * amount) * d.z);
  }
  std::size_t farthest = 0;
  for (std::size_t i = 0; i < rest.size(); ++i)
    if (glm::length(rest[i] - centre) > glm::length(rest[farthest] - centre)) farthest = i;
  out[farthest] = centre - 0.5 * (rest[farthest] - centre);
  return out;
}

std::size_t invertedElements(const BulkBody& body) {
  std::size_t count = 0;
  for (std::size_t e = 0; e < body.mesh.tetrahedra.size(); ++e) {
    const Tetrahedron& t = body.mesh.tetrahedra[e];
    const std::vector<glm::dvec3>& x = body.state.positions;
    if (glm::determinant(deformationGradient(body.rest[e], x[t.x], x[t.y], x[t.z], x[t.w])) <= 0.0) ++count;
  }
  return count;
}

class ProjectiveLocal : public ::testing::TestWithParam<int> {};

TEST_P(ProjectiveLocal, TargetsRotationsAndFlowEqualTheScalarStepInDouble) {
  SlimeSettings slime = defaultSettings().slime;
  slime.resolution = GetParam();
  BulkBody body = buildBulkBody(slime);
  ASSERT_GT(body.material.maxwellShear, 0.0);
  const std::vector<glm::dvec3> rest = body.state.positions;
  const std::size_t tetrahedra = body.mesh.tetrahedra.size();
  std::vector<ProjectiveBlock> blocks(body.restBlocks.size());
  for (ProjectiveBlock& block : blocks)
    for (std::size_t lane = 0; lane < kTetLanes; ++lane) block.rotation[0][lane] = 1;
  std::vector<ReferenceState> states(tetrahedra);
  NodeQuads quads;
  std::vector<glm::dvec3> lanes;
  // An element's force scale w_e |Dm⁻¹| ≈ (2μ + 3λ) V0^(2/3); float rounds it at 6e-8 (element_pass_test).
  const ViscoelasticMaterial& m = body.material;
  const double scale = (2.0 * (m.longTermShear + m.maxwellShear) + 3.0 * m.lameLambda) *
                       std::pow(body.restVolume / static_cast<double>(tetrahedra), 2.0 / 3.0);
  // Float rounding, amplified by the polar decomposition of the twisted, partly inverted elements: the worst node
  // is 0.36 × 64 ε of the scale at -O3 but 5.8 × 64 ε in the -O1 sanitizer build (other rounding, same code);
  // 1024 ε (1.2e-4) holds both. A dropped term of the target is off by orders more (testing.md).
  const double tolerance = std::max(1e-11, 1024.0 * std::numeric_limits<ProjectiveReal>::epsilon());
  // The rotation and the Maxwell stretch, unit-sized: 1e-5 held at -O3, but the -O1 sanitizer build put one
  // quaternion of the twist's most deformed element 1.8e-5 off; one polar sweep instead of two is off by more.
  const double kStateTolerance = 1e-4;
  for (const double amount : {0.6, 0.7, 0.75}) {  // from R = I, then warm-started twice
    body.state.positions = twisted(rest, amount);
    ASSERT_GT(invertedElements(body), 0u);
    projectiveTargets(body, true, 0.05, false, blocks, quads, lanes);
    const std::vector<glm::dvec3> reference = referenceTargets(body, 0.05, states);
    ASSERT_EQ(lanes.size(), reference.size());
    for (std::size_t i = 0; i < lanes.size(); ++i)
      EXPECT_LT(glm::length(lanes[i] - reference[i]), tolerance * scale) << "node " << i << ", twist " << amount;
    for (std::size_t e = 0; e < tetrahedra; ++e) {
      const ProjectiveBlock& block = blocks[e / kTetLanes];
      const std::size_t lane = e % kTetLanes;
      for (int k = 0; k < 4; ++k)
        EXPECT_NEAR(block.rotation[k][lane], states[e].q[k], kStateTolerance) << "tetrahedron " << e << ", twist " << amount;
      for (int k = 0; k < 6; ++k)
        EXPECT_NEAR(block.maxwellStretch[k][lane] + (k < 3 ? 1.0 : 0.0), states[e].u[k], kStateTolerance) << "tetrahedron " << e << ", twist " << amount;
    }
  }
}

// A step's flow moves U_v by flow × (U − U_v), ~1e-6 for a small strain: at the rest shape a Maxwell
// stretch of 1e-4 decays by (1 − flow) a step down to F's own rounding (~1e-7), where float storage
// of U_v itself stopped it at ulp/flow ≈ 1e-5 (bench material's recovery ended at 0.1 % of the twist).
TEST(ProjectiveLocal, ARelaxedStretchFlowsBackToRest) {
  SlimeSettings slime = defaultSettings().slime;
  slime.resolution = 1;
  const BulkBody body = buildBulkBody(slime);
  std::vector<ProjectiveBlock> blocks(body.restBlocks.size());
  const std::size_t tetrahedra = body.mesh.tetrahedra.size();
  for (std::size_t e = 0; e < tetrahedra; ++e) {
    ProjectiveBlock& block = blocks[e / kTetLanes];
    const std::size_t lane = e % kTetLanes;
    block.rotation[0][lane] = 1;
    const ProjectiveReal stretch[6] = {1e-4f, -1e-4f, 0.0f, 5e-5f, 0.0f, -5e-5f};  // U_v − I, volume kept to 1e-8
    for (int k = 0; k < 6; ++k) block.maxwellStretch[k][lane] = stretch[k];
  }
  NodeQuads quads;
  std::vector<glm::dvec3> targets;
  for (int step = 0; step < 2000; ++step) projectiveTargets(body, true, 0.01, false, blocks, quads, targets);
  double largest = 0.0;  // 1e-4 × 0.99^2000 = 2e-13 in exact arithmetic
  for (std::size_t e = 0; e < tetrahedra; ++e)
    for (int k = 0; k < 6; ++k) largest = std::max(largest, std::abs(double(blocks[e / kTetLanes].maxwellStretch[k][e % kTetLanes])));
  EXPECT_LT(largest, 1e-6);
}

INSTANTIATE_TEST_SUITE_P(Resolutions, ProjectiveLocal, ::testing::Values(1, 2));

}  // namespace
}  // namespace slime

// The bulk slime's pieces: the tetrahedral ball, the embedded drawn surface, the material's stress,
// and the standard linear solid's flow against its closed-form relaxation and creep.
#include "core/bulk/bulk_body.h"
#include "core/geometry/icosphere.h"
#include "core/settings/settings_io.h"
#include "core/bulk/surface_embedding.h"
#include "core/bulk/tet_mesh.h"
#include "core/bulk/viscoelastic.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace slime {
namespace {

constexpr double kRadius = 0.04;
const glm::dvec3 kCentre{0.0, 0.0, 0.1};

class BallMesh : public ::testing::TestWithParam<int> {};

// Every element positive, the elements fill the polyhedron the outer shell bounds, and the mesh is
// conforming: each face is shared by two elements, except the outer shell's, which have one.
TEST_P(BallMesh, PositiveConformingAndFillsTheBall) {
  const int resolution = GetParam();
  const TetMesh mesh = makeBallTetMesh(resolution, kRadius, kCentre);
  const std::size_t perShell = 10 * (std::size_t{1} << (2 * resolution)) + 2;
  EXPECT_EQ(mesh.surfaceNodes, perShell);
  EXPECT_EQ(mesh.surface.size(), 20u << (2 * resolution));
  double volume = 0.0;
  std::map<std::array<std::uint32_t, 3>, int> faces;
  for (const Tetrahedron& t : mesh.tetrahedra) {
    const double v = tetrahedronVolume(mesh.positions[t.x], mesh.positions[t.y], mesh.positions[t.z], mesh.positions[t.w]);
    ASSERT_GT(v, 0.0);
    volume += v;
    for (int skip = 0; skip < 4; ++skip) {
      std::array<std::uint32_t, 3> face{};
      for (int i = 0, k = 0; i < 4; ++i)
        if (i != skip) face[k++] = t[i];
      std::sort(face.begin(), face.end());
      ++faces[face];
    }
  }
  std::size_t boundary = 0;
  for (const auto& [face, count] : faces) {
    ASSERT_LE(count, 2);
    if (count == 1) {
      ++boundary;
      EXPECT_TRUE(face[2] < mesh.surfaceNodes) << "a boundary face inside the ball";
    }
  }
  EXPECT_EQ(boundary, mesh.surface.size());
  // The inscribed polyhedron: its volume is that of the triangles' outer shell.
  const TriangleMesh shell = makeIcosphere(resolution, kRadius, kCentre);
  double shellVolume = 0.0;
  for (const Triangle& t : shell.triangles)
    shellVolume += tetrahedronVolume(kCentre, shell.positions[t.x], shell.positions[t.y], shell.positions[t.z]);
  EXPECT_NEAR(volume, shellVolume, 1e-12);
  EXPECT_GT(volume / (4.0 / 3.0 * std::numbers::pi * std::pow(kRadius, 3)), resolution == 1 ? 0.85 : 0.95);
}

INSTANTIATE_TEST_SUITE_P(Resolutions, BallMesh, ::testing::Values(1, 2, 3));

// At rest the embedding gives back the drawn icosphere exactly, with weights that sum to one, for
// drawn levels finer than, equal to and coarser than the body's shells.
TEST(SurfaceEmbedding, RestShapeIsTheDrawnIcosphere) {
  for (int level : {1, 2, 4, 5}) {
    SlimeSettings slime = defaultSettings().slime;
    slime.level = level;
    slime.resolution = 2;
    const BulkBody body = buildBulkBody(slime);
    std::vector<glm::dvec3> drawn;
    placeEmbedded(body.embedding, body.state.positions, drawn);
    ASSERT_EQ(drawn.size(), body.drawn.positions.size());
    double worst = 0.0;
    for (std::size_t i = 0; i < drawn.size(); ++i) {
      worst = std::max(worst, glm::length(drawn[i] - body.drawn.positions[i]));
      const glm::dvec4& w = body.embedding.weights[i];
      EXPECT_NEAR(w.x + w.y + w.z + w.w, 1.0, 1e-12);
      // A drawn vertex sits at most just outside its element (the sphere bulges past the flat face).
      EXPECT_GT(std::min({w.x, w.y, w.z, w.w}), -0.1) << "level " << level << " vertex " << i;
    }
    EXPECT_LT(worst, 1e-12 * kRadius) << "level " << level;
  }
}

// An affine motion of the body moves the drawn surface by the same affine map.
TEST(SurfaceEmbedding, FollowsAnAffineDeformation) {
  SlimeSettings slime = defaultSettings().slime;
  const BulkBody body = buildBulkBody(slime);
  const glm::dmat3 map(1.3, 0.1, 0.0, -0.2, 0.7, 0.05, 0.0, 0.3, 1.1);
  const glm::dvec3 shift(0.01, -0.02, 0.03);
  std::vector<glm::dvec3> moved = body.state.positions, drawn;
  for (glm::dvec3& x : moved) x = map * x + shift;
  placeEmbedded(body.embedding, moved, drawn);
  for (std::size_t i = 0; i < drawn.size(); ++i)
    EXPECT_LT(glm::length(drawn[i] - (map * body.drawn.positions[i] + shift)), 1e-12);
}

ViscoelasticMaterial testMaterial() {
  ViscoelasticMaterial m;
  m.longTermShear = 400.0;
  m.maxwellShear = 800.0;
  m.lameLambda = lameLambdaFor(1200.0, 0.4);
  m.relaxationTime = 0.5;
  return m;
}

// No stress at rest; at a small strain the stress is linear elasticity's 2μ ε + λ tr(ε) I with
// μ = μ∞ + μ1 (hand-computed Lamé form), and P is the derivative of the energy density.
TEST(Viscoelastic, RestFreeLinearAtSmallStrainAndTheEnergysDerivative) {
  const ViscoelasticMaterial m = testMaterial();
  const glm::dmat3 identity(1.0);
  const glm::dmat3 atRest = firstPiolaStress(m, identity, identity);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(atRest[i][j], 0.0, 1e-9);
  const double e = 1e-6;
  const glm::dmat3 gradient(e * 0.3, e * 0.7, -e * 0.2, e * 0.1, -e * 0.5, e * 0.4, e * 0.9, e * 0.2, e * 0.6);
  const glm::dmat3 strain = 0.5 * (gradient + glm::transpose(gradient));
  const double trace = strain[0][0] + strain[1][1] + strain[2][2];
  const glm::dmat3 p = firstPiolaStress(m, identity + gradient, identity);
  const double mu = m.longTermShear + m.maxwellShear;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double expected = 2.0 * mu * strain[i][j] + (i == j ? m.lameLambda * trace : 0.0);
      EXPECT_NEAR(p[i][j], expected, 1e-3 * std::abs(mu * e)) << i << "," << j;
    }
  // dΨ/dF by central differences at a large, sheared and flowed state.
  const glm::dmat3 f(1.2, 0.1, -0.3, 0.2, 0.8, 0.1, 0.05, -0.2, 1.1);
  const glm::dmat3 flowed =
      relaxMaxwellBranch(glm::dmat3(1.1, 0.0, 0.1, 0.0, 0.95, 0.0, 0.1, 0.0, 0.97), MaxwellRest{}, 0.0).inverse;
  const glm::dmat3 stress = firstPiolaStress(m, f, flowed);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      glm::dmat3 up = f, down = f;
      up[i][j] += 1e-6;
      down[i][j] -= 1e-6;
      const double derivative = (energyDensity(m, up, flowed) - energyDensity(m, down, flowed)) / 2e-6;
      EXPECT_NEAR(stress[i][j], derivative, 1e-4 * mu) << i << "," << j;
    }
}

// The Maxwell branch alone is free of stress at its flowed rest shape, however far it flowed (a
// branch that kept a stress there would hold a pressed slime flat for good).
TEST(Viscoelastic, TheMaxwellBranchIsStressFreeWhereItFlowed) {
  ViscoelasticMaterial maxwellOnly;
  maxwellOnly.maxwellShear = 800.0;
  const glm::dmat3 u(1.6, 0.2, 0.0, 0.2, 0.9, -0.1, 0.0, -0.1, 0.8);  // symmetric, det 1 after scaling
  const glm::dmat3 stretch = u / std::cbrt(glm::determinant(u));
  const glm::dmat3 flowed = relaxMaxwellBranch(stretch, MaxwellRest{}, 0.0).inverse;  // fully flowed: B_v = U⁻²
  const glm::dmat3 rotation = glm::dmat3(std::cos(0.3), std::sin(0.3), 0.0, -std::sin(0.3), std::cos(0.3), 0.0, 0.0, 0.0, 1.0);
  const glm::dmat3 p = firstPiolaStress(maxwellOnly, rotation * stretch, flowed);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(p[i][j], 0.0, 1e-9 * maxwellOnly.maxwellShear) << i << "," << j;
}

// The flow carries G_v and B_v together: after many steps of a changing strain they are still each
// other's inverse, det G_v = 1, and B_v is what blending inverse(B_v) and inverting twice gave.
TEST(Viscoelastic, TheFlowKeepsTheMetricAndItsInverseTogether) {
  MaxwellRest rest;
  glm::dmat3 twoInverses(1.0);
  const double decay = std::exp(-0.004 / 0.05);
  for (int k = 0; k < 200; ++k) {
    const double phase = 0.1 * k;
    const glm::dmat3 f(1.0 + 0.3 * std::sin(phase), 0.2 * std::cos(phase), 0.05, 0.1, 0.8 + 0.1 * std::cos(phase),
                       -0.2 * std::sin(phase), 0.03, 0.1, 1.1);
    rest = relaxMaxwellBranch(f, rest, decay);
    const glm::dmat3 c = glm::transpose(f) * f;
    const glm::dmat3 metric = c + (glm::inverse(twoInverses) - c) * decay;
    twoInverses = glm::inverse(metric / std::cbrt(glm::determinant(metric)));
  }
  EXPECT_NEAR(glm::determinant(rest.metric), 1.0, 1e-13);
  const glm::dmat3 product = rest.metric * rest.inverse;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(product[i][j], i == j ? 1.0 : 0.0, 1e-13) << i << "," << j;
      EXPECT_NEAR(rest.inverse[i][j], twoInverses[i][j], 1e-13) << i << "," << j;
      EXPECT_EQ(rest.metric[i][j], rest.metric[j][i]);
      EXPECT_EQ(rest.inverse[i][j], rest.inverse[j][i]);
    }
}

// Shear stress of the element at a shear strain γ held from t = 0: σ(t) = (μ∞ + μ1 e^(−t/τ)) γ,
// the standard linear solid's relaxation; the flow is exact for a held strain, so any step gives it.
TEST(Viscoelastic, RelaxationUnderAHeldShearMatchesTheClosedForm) {
  const ViscoelasticMaterial m = testMaterial();
  const double gamma = 1e-4;
  glm::dmat3 f(1.0);
  f[1][0] = gamma;  // F = I + γ e_x e_yᵀ (column 1, row 0)
  MaxwellRest maxwell;
  const double dt = 0.01;
  for (int k = 1; k <= 100; ++k) {
    maxwell = relaxMaxwellBranch(f, maxwell, std::exp(-dt / m.relaxationTime));
    const double t = k * dt;
    const double shear = firstPiolaStress(m, f, maxwell.inverse)[1][0];
    const double expected = (m.longTermShear + m.maxwellShear * std::exp(-t / m.relaxationTime)) * gamma;
    EXPECT_NEAR(shear, expected, 1e-3 * m.maxwellShear * gamma) << "t = " << t;
  }
}

// Creep: the shear strain under a held shear stress σ is γ(t) = σ/μ∞ − σ(1/μ∞ − 1/μ0) e^(−t/τ_c),
// τ_c = τ μ0/μ∞. The element's strain is solved for the stress each step (quasi-static) and the
// flow updated with the strain at the step's end, so the error is first order in the step: halving
// the step halves it.
TEST(Viscoelastic, CreepUnderAHeldShearStressConvergesAtFirstOrder) {
  const ViscoelasticMaterial m = testMaterial();
  const double mu0 = m.longTermShear + m.maxwellShear;
  const double stress = 0.05;  // Pa: a strain of 1e-4, linear
  const double tauC = creepTimeConstant(m);
  EXPECT_NEAR(tauC, m.relaxationTime * mu0 / m.longTermShear, 1e-12);
  auto error = [&](double dt) {
    MaxwellRest maxwell;
    double worst = 0.0;
    for (int k = 1; k * dt <= 2.0 * tauC + 1e-12; ++k) {
      // The shear γ at which this element carries `stress` now (Newton on P_xy(γ), linear here).
      double gamma = stress / mu0;
      for (int it = 0; it < 4; ++it) {
        glm::dmat3 f(1.0);
        f[1][0] = gamma;
        glm::dmat3 g = f;
        g[1][0] += 1e-7;
        const double p = firstPiolaStress(m, f, maxwell.inverse)[1][0];
        const double slope = (firstPiolaStress(m, g, maxwell.inverse)[1][0] - p) / 1e-7;
        gamma -= (p - stress) / slope;
      }
      glm::dmat3 f(1.0);
      f[1][0] = gamma;
      maxwell = relaxMaxwellBranch(f, maxwell, std::exp(-dt / m.relaxationTime));
      const double t = k * dt;
      const double expected =
          stress / m.longTermShear - stress * (1.0 / m.longTermShear - 1.0 / mu0) * std::exp(-(t - dt) / tauC);
      worst = std::max(worst, std::abs(gamma - expected) / (stress / m.longTermShear));
    }
    return worst;
  };
  const double coarse = error(0.02), fine = error(0.01), finer = error(0.005);
  std::printf("creep error %.3e %.3e %.3e (order %.2f, %.2f)\n", coarse, fine, finer, std::log2(coarse / fine),
              std::log2(fine / finer));
  EXPECT_LT(finer, 0.01);
  EXPECT_NEAR(std::log2(coarse / fine), 1.0, 0.15);
  EXPECT_NEAR(std::log2(fine / finer), 1.0, 0.15);
}

// The element map's height of drawn vertex v.
double drawnHeight(const BulkBody& body, std::size_t v) {
  const Tetrahedron& t = body.embedding.nodes[v];
  const glm::dvec4& w = body.embedding.weights[v];
  const std::vector<glm::dvec3>& x = body.state.positions;
  return w.x * x[t.x].z + w.y * x[t.y].z + w.z * x[t.z].z + w.w * x[t.w].z;
}

// The drawn surface's floor under the nodes (for the projective solve): nothing while the body is in
// the air; turned onto a face of its outer shell and set down until its lowest drawn vertex touches,
// that vertex holds the node it follows most right where it is (above the floor: the drawn surface
// bulges below the face), and no node is held above itself or below the floor.
TEST(DrawnFloorHeights, TheLowestDrawnVertexHoldsItsMainNodeWhereItIs) {
  BulkBody body = buildBulkBody(defaultSettings().slime);
  std::vector<double> heights;
  drawnFloorHeights(body, heights);
  ASSERT_EQ(heights.size(), body.state.size());
  for (double f : heights) EXPECT_EQ(f, 0.0);
  // Rodrigues' rotation about the centre taking the first outer face's direction c to straight down.
  std::vector<glm::dvec3>& x = body.state.positions;
  glm::dvec3 centre(0.0);
  for (const glm::dvec3& p : x) centre += p / static_cast<double>(x.size());
  const Triangle& face = body.mesh.surface.front();
  const glm::dvec3 c = glm::normalize((x[face.x] + x[face.y] + x[face.z]) / 3.0 - centre), down(0.0, 0.0, -1.0);
  const glm::dvec3 axis = glm::normalize(glm::cross(c, down));
  const double angle = std::acos(glm::dot(c, down));
  for (glm::dvec3& p : x) {
    const glm::dvec3 r = p - centre;
    p = centre + r * std::cos(angle) + glm::cross(axis, r) * std::sin(angle) +
        axis * glm::dot(axis, r) * (1.0 - std::cos(angle));
  }
  std::size_t lowest = 0;
  for (std::size_t v = 1; v < body.embedding.nodes.size(); ++v)
    if (drawnHeight(body, v) < drawnHeight(body, lowest)) lowest = v;
  const double drop = drawnHeight(body, lowest);
  for (glm::dvec3& p : x) p.z -= drop;
  drawnFloorHeights(body, heights);
  const glm::dvec4& w = body.embedding.weights[lowest];
  int owner = 0;
  for (int j = 1; j < 4; ++j)
    if (w[j] > w[owner]) owner = j;
  const std::uint32_t node = body.embedding.nodes[lowest][owner];
  EXPECT_GT(body.state.positions[node].z, 1e-5);  // the drawn surface bulges below the node
  EXPECT_NEAR(heights[node], body.state.positions[node].z, 1e-12);
  for (std::size_t i = 0; i < heights.size(); ++i) {
    EXPECT_GE(heights[i], 0.0);
    EXPECT_LE(heights[i], std::max(body.state.positions[i].z, 0.0) + 1e-12);
  }
}

// A floor of the wrong length is refused, not read past its end.
TEST(ProjectBulkVolume, RefusesAFloorOfTheWrongSize) {
  BulkBody body = buildBulkBody(defaultSettings().slime);
  BulkScratch scratch;
  const std::vector<double> floor(body.state.size() - 1, 0.0);
  EXPECT_THROW(projectBulkVolume(body, 0.001, scratch, body.state, &floor), std::invalid_argument);
}

}  // namespace
}  // namespace slime

// The modal oracles' arithmetic that the material bench and the peers (bullet_tets, jolt_tets --front)
// share: a damped oscillation's ratio comes back from its energy's decay, and a mode's amplitude from
// its mass-weighted projection whatever rigid motion rides on it.
#include "app/bench/material/modal_fit.h"

#include "core/bulk/lamb_sphere.h"
#include "core/bulk/tet_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace slime {
namespace {

TEST(ModalFit, EnergyDecayGivesTheDampingRatio) {
  const double zeta = 0.03, omega = 2.0 * std::numbers::pi * 9.0, damped = omega * std::sqrt(1.0 - zeta * zeta);
  std::vector<double> t, a, rate;
  for (int k = 1; k <= 2000; ++k) {
    t.push_back(5e-4 * k);
    const double envelope = std::exp(-zeta * omega * t.back());
    a.push_back(envelope * std::cos(damped * t.back()));
    rate.push_back(envelope * (-zeta * omega * std::cos(damped * t.back()) - damped * std::sin(damped * t.back())));
  }
  EXPECT_NEAR(energyDampingRatio(t, a, rate, omega), zeta, 0.002);
  // An undamped one has none.
  for (std::size_t k = 0; k < t.size(); ++k) {
    a[k] = std::cos(omega * t[k]);
    rate[k] = -omega * std::sin(omega * t[k]);
  }
  EXPECT_NEAR(energyDampingRatio(t, a, rate, omega), 0.0, 1e-9);
}

TEST(ModalFit, ProjectionRecoversTheAmplitudeUnderRigidMotion) {
  const TetMesh mesh = makeBallTetMesh(1, 0.04, glm::dvec3(0.0));
  std::vector<double> masses(mesh.positions.size());
  for (std::size_t i = 0; i < masses.size(); ++i) masses[i] = 1.0 + 0.1 * static_cast<double>(i % 7);  // unequal
  for (bool spheroidal : {false, true}) {
    const double eta = lambRoot(2, spheroidal, 0.4);
    const std::vector<glm::dvec3> shape = lambModeShape(mesh.positions, masses, glm::dvec3(0.0), 0.04, spheroidal, eta, 0.4);
    double largest = 0.0;
    for (const glm::dvec3& s : shape) largest = std::max(largest, std::sqrt(s.x * s.x + s.y * s.y + s.z * s.z));
    EXPECT_GT(largest, 0.9);  // about 1: the rigid part taken out after the scaling is small
    // 0.7 mm of the mode, carried 3 cm sideways: the translation is orthogonal to ψ in the mass norm.
    std::vector<glm::dvec3> moved(mesh.positions.size());
    for (std::size_t i = 0; i < moved.size(); ++i) moved[i] = mesh.positions[i] + 7e-4 * shape[i] + glm::dvec3(0.03, -0.01, 0.02);
    EXPECT_NEAR(massProjection(moved, &mesh.positions, shape, masses), 7e-4, 1e-9) << (spheroidal ? "spheroidal" : "torsional");
  }
}

}  // namespace
}  // namespace slime

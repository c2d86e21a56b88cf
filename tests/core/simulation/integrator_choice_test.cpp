// sim.integrator=auto (integrator_choice.h): symplectic_euler where the slime's slowest jiggle can be
// seen at 60 frames a second or the sticky floor could be, projective where neither can.
#include "simulation_fixture.h"
#include "core/simulation/integrator_choice.h"
#include "core/simulation/simulation.h"
#include "core/settings/settings_io.h"

#include <gtest/gtest.h>

#include <cmath>

namespace slime {
namespace {

using fixture::runFor;

// The default ball: G = 1200 Pa, 0.268 kg in a 4 cm radius (1000 kg/m³), so c_s = 1.095 m/s and
// f = 2.5011 c_s / (2π R) = 10.9 Hz; the bulk body itself rings at 10.7 Hz, 0.97 % under Lamb's
// (docs/material.md). The frequency goes as √G and as 1/√m.
TEST(IntegratorChoice, SlowestJiggleIsLambsTorsionalModeOfTheRestBall) {
  SlimeSettings slime = defaultSettings().slime;
  EXPECT_NEAR(slowestJiggleHz(slime), 10.90, 0.02);
  const double base = slowestJiggleHz(slime);
  slime.modulus *= 4.0;
  EXPECT_NEAR(slowestJiggleHz(slime), 2.0 * base, 1e-9 * base);
  slime.modulus /= 4.0;
  slime.mass /= 4.0;
  EXPECT_NEAR(slowestJiggleHz(slime), 2.0 * base, 1e-9 * base);
}

Integrator autoFor(double modulus, double mass, const char* model = "bulk", double adhesion = 0.0) {
  Settings settings = defaultSettings();
  EXPECT_EQ(settings.sim.integrator, "auto");
  settings.slime.modulus = modulus;
  settings.slime.mass = mass;
  settings.slime.adhesion = adhesion;
  settings.slime.model = model;
  return chooseIntegrator(settings);
}

TEST(IntegratorChoice, AutoTakesProjectiveOnlyWhereNeitherTheJiggleNorTheStickyFloorShows) {
  EXPECT_EQ(autoFor(1200.0, 0.268), Integrator::SymplecticEuler);   // 10.9 Hz
  EXPECT_EQ(autoFor(8000.0, 0.268), Integrator::SymplecticEuler);   // 28.1 Hz
  EXPECT_EQ(autoFor(10000.0, 0.268), Integrator::Projective);       // 31.5 Hz
  EXPECT_EQ(autoFor(100000.0, 0.268), Integrator::Projective);      // 99.5 Hz
  EXPECT_EQ(autoFor(1200.0, 0.04), Integrator::SymplecticEuler);    // 28.2 Hz
  EXPECT_EQ(autoFor(1200.0, 0.01), Integrator::Projective);         // 56.4 Hz
  EXPECT_EQ(autoFor(100000.0, 0.268, "membrane"), Integrator::SymplecticEuler);  // projective is the bulk body's only
  // The default sticky floor (8,000 Pa) stays where it strains the body by more than a tenth.
  EXPECT_EQ(autoFor(1200.0, 0.01, "bulk", 8000.0), Integrator::SymplecticEuler);   // 6.7
  EXPECT_EQ(autoFor(60000.0, 0.268, "bulk", 8000.0), Integrator::SymplecticEuler); // 0.13
  EXPECT_EQ(autoFor(100000.0, 0.268, "bulk", 8000.0), Integrator::Projective);     // 0.08
  Settings named = defaultSettings();
  named.slime.modulus = 100000.0;
  named.sim.integrator = "rk4";  // a name is taken as it is, whatever the material
  EXPECT_EQ(chooseIntegrator(named), Integrator::Rk4);
}

// The panel's modulus slider crosses 30 Hz both ways on a running slime: the integrator follows, the
// Maxwell state moves between them, and the guard never fires.
TEST(IntegratorChoice, ASimulationFollowsTheMaterialAcrossTheThreshold) {
  Settings settings = defaultSettings();
  settings.slime.level = 2;
  Simulation simulation(settings);
  EXPECT_EQ(simulation.integrator(), Integrator::SymplecticEuler);
  runFor(simulation, 0.5);
  settings.slime.modulus = 100000.0;
  simulation.applySettings(settings);
  EXPECT_EQ(simulation.integrator(), Integrator::Projective);
  EXPECT_EQ(simulation.substepsPerStep(), 1);
  runFor(simulation, 0.5);
  settings.slime.modulus = 1200.0;
  simulation.applySettings(settings);
  EXPECT_EQ(simulation.integrator(), Integrator::SymplecticEuler);
  runFor(simulation, 0.5);
  EXPECT_TRUE(simulation.divergences().empty());
  const SlimeMetrics metrics = simulation.metrics();
  EXPECT_TRUE(std::isfinite(metrics.kineticEnergy));
  EXPECT_NEAR(metrics.volumeRatio, 1.0, 0.02);
}

}  // namespace
}  // namespace slime

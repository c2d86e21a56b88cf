// `slime bench physics --front` (bench_front.h): its two-point quick run end to end, with oracles that
// must hold for those two points (symplectic Euler at 1 ms keeps the jiggle and meets the guide's
// accuracy at resolution 1; projective dynamics at 16.7 ms damps it as backward Euler does), and the
// pieces that judge points: the Pareto front, the peers' errors from their own fields.
#include "app/bench/physics/bench_front.h"
#include "app/bench/physics/bench_front_report.h"
#include "core/settings/settings_io.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

namespace slime {
namespace {

using nlohmann::json;

bool contains(const json& list, const std::string& name) {
  return std::find(list.begin(), list.end(), name) != list.end();
}

TEST(BenchFront, ParetoFrontKeepsThePointsNoneBeats) {
  // (error, cost): 0 and 2 are beaten by 1 (cheaper and more accurate than 2; as cheap, more accurate than 0).
  const std::vector<std::pair<double, double>> points{{0.5, 1.0}, {0.1, 1.0}, {0.3, 2.0}, {0.01, 5.0}, {0.2, 0.5}};
  const std::vector<std::size_t> front = paretoFront(points);
  EXPECT_EQ(front, (std::vector<std::size_t>{4, 1, 3}));
}

TEST(BenchFront, PeerErrorsComeFromLambsTheoryOfTheirOwnMaterial) {
  // Lamb's torsional n = 2 root is 2.5011 whatever ν (Lamb 1882): f = η √(G/ρ) / (2πR).
  const double modulus = 1200.0, density = 1000.0, radius = 0.04;
  const double torsional = 2.5011 * std::sqrt(modulus / density) / (2.0 * std::numbers::pi * radius);
  const json point = {{"resolution", 2}, {"step_ms", 16.7}, {"iterations", 4}, {"cost_ms_per_ms", 0.07},
                      {"shear_modulus_pa", modulus}, {"density_kg_m3", density}, {"radius_m", radius},
                      {"poisson", 0.4}, {"torsional_hz", 1.02 * torsional}, {"spheroidal_hz", nullptr},
                      {"damping_ratio", -0.3}, {"rest_height_m", 0.0612}, {"diverged", false}};
  const json judged = peerPointErrors(point, 0.06);
  EXPECT_NEAR(judged["errors"]["torsional"].get<double>(), 0.02, 1e-3);
  EXPECT_TRUE(judged["errors"]["spheroidal"].is_null());  // not measured: no error, and not at the guide's accuracy
  EXPECT_NEAR(judged["errors"]["damping"].get<double>(), 0.3, 1e-12);
  EXPECT_NEAR(judged["errors"]["rest_height"].get<double>(), 0.02, 1e-9);
  EXPECT_TRUE(judged["errors"]["creep"].is_null());  // no peer models the Maxwell branch
  EXPECT_FALSE(judged["guide"].get<bool>());

  json diverged = point;
  diverged["diverged"] = true;
  EXPECT_TRUE(peerPointErrors(diverged, 0.06)["errors"]["torsional"].is_null());
}

// Issue 45's test of a peer point: the cheapest of our points at its resolution no worse on any of the
// four oracles it shares, and that point's cost as a share of the peer's.
TEST(BenchFront, APeerPointIsBeatenOnlyByAPointNoWorseOnEveryOracle) {
  const auto point = [](int resolution, double cost, double torsional, double spheroidal, double damping, double rest) {
    return json{{"resolution", resolution}, {"stable", true}, {"cost_ms_per_ms", cost}, {"step_ms", 1.0}, {"iterations", 1},
                {"integrator", "x"},
                {"errors", {{"torsional", torsional}, {"spheroidal", spheroidal}, {"damping", damping}, {"rest_height", rest},
                            {"creep", 0.5}}}};
  };
  const json ours = json::array({point(2, 0.01, 0.02, 0.02, 0.001, 0.001),    // cheap, worse damping than the peer
                                 point(2, 0.04, 0.01, 0.01, 0.0001, 0.001),   // no worse on all four
                                 point(2, 0.03, 0.01, 0.01, 0.0001, 0.5),     // cheaper, but its rest height worse
                                 point(1, 0.001, 0.0, 0.0, 0.0, 0.0)});       // another resolution
  json peerPoint = point(2, 0.1, 0.02, 0.02, 0.0005, 0.01);
  peerPoint.erase("integrator");
  const json peers = json::array({{{"peer", "jolt"}, {"points", json::array({peerPoint})}}});
  const json dominance = peerDominance(ours, peers);
  ASSERT_EQ(dominance["points"].size(), 1u);
  EXPECT_EQ(dominance["stable_peer_points"], 1);
  EXPECT_DOUBLE_EQ(dominance["points"][0]["ours"]["cost_ms_per_ms"].get<double>(), 0.04);
  EXPECT_DOUBLE_EQ(dominance["points"][0]["share"].get<double>(), 0.4);
  EXPECT_EQ(dominance["beaten_at_half_cost"], 1);
}

TEST(BenchFront, GuideAccuracyNeedsEveryCondition) {
  const json good = {{"torsional", 0.04}, {"spheroidal", 0.01}, {"damping", 0.019}, {"creep", 0.5}, {"rest_height", 0.01}};
  EXPECT_TRUE(meetsGuideAccuracy(good));
  for (const char* key : {"torsional", "spheroidal", "damping", "rest_height"}) {
    json bad = good;
    bad[key] = 0.06;
    EXPECT_FALSE(meetsGuideAccuracy(bad)) << key;
    bad[key] = nullptr;
    EXPECT_FALSE(meetsGuideAccuracy(bad)) << key;
  }
}

TEST(BenchFront, IntegratorsComeFromTheSettingsTable) {
  const json integrators = bulkFrontIntegrators(defaultSettings());
  for (const char* name : {"symplectic_euler", "explicit_euler", "rk4", "projective"})
    EXPECT_TRUE(contains(integrators["bulk"], name)) << name << " in " << integrators.dump();
  // The membrane's implicit methods step the bulk body as symplectic_euler does.
  for (const char* name : {"implicit_euler", "xpbd"})
    EXPECT_TRUE(contains(integrators["not_bulk"], name)) << name << " in " << integrators.dump();
  EXPECT_TRUE(contains(integrators["iterating"], "projective"));
  EXPECT_FALSE(contains(integrators["iterating"], "symplectic_euler"));
}

TEST(BenchFront, QuickFrontMeasuresBothPointsAgainstTheOracles) {
  FrontOptions options = FrontOptions::quick();
  options.outputDirectory = std::string(SLIME_TEST_OUTPUT_DIR) + "/front_quick";
  options.peerPrograms = {"/nonexistent/jolt_tets"};
  const json report = runFront(defaultSettings(), options);
  ASSERT_EQ(report["points"].size(), 2u);

  // The static solve has come to rest: its force residual is small against the weight.
  ASSERT_EQ(report["static_solves"].size(), 1u);
  const json& solve = report["static_solves"][0];
  EXPECT_LT(solve["residual"]["rms_residual_over_weight"].get<double>(), 0.02) << solve.dump();
  EXPECT_TRUE(solve["converged"].get<bool>()) << solve.dump();
  EXPECT_GT(solve["rest_height_m"].get<double>(), 0.03);  // sagged below the 8 cm ball, not flattened
  EXPECT_LT(solve["rest_height_m"].get<double>(), 0.08);

  const json& explicitPoint = report["points"][0];
  ASSERT_EQ(explicitPoint["integrator"], "symplectic_euler") << explicitPoint.dump();
  ASSERT_TRUE(explicitPoint["stable"].get<bool>()) << explicitPoint.dump();
  const json& errors = explicitPoint["errors"];
  EXPECT_LT(errors["torsional"].get<double>(), 0.05) << errors.dump();
  EXPECT_LT(errors["spheroidal"].get<double>(), 0.05) << errors.dump();
  EXPECT_LT(errors["damping"].get<double>(), 2e-3) << errors.dump();  // symplectic Euler keeps the jiggle
  EXPECT_LT(errors["rest_height"].get<double>(), 0.02) << errors.dump();
  EXPECT_LT(errors["creep"].get<double>(), 0.2) << errors.dump();
  EXPECT_TRUE(explicitPoint["guide"].get<bool>());
  EXPECT_GT(explicitPoint["drop"]["contact_s"].get<double>(), 0.3 - 1e-9);  // cost with the landing and contact
  EXPECT_GT(explicitPoint["cost_ms_per_ms"].get<double>(), 0.0);

  // Backward Euler by projective dynamics at 16.7 ms (ωh ≈ 1.2) damps the jiggle hard, as its closed form
  // ln(1 + (ωh)²) / (2ωh) says (within what four iterations leave of the implicit step).
  const json& implicitPoint = report["points"][1];
  ASSERT_EQ(implicitPoint["integrator"], "projective");
  ASSERT_TRUE(implicitPoint["stable"].get<bool>()) << implicitPoint.dump();
  const double closedForm = implicitPoint["modes"]["spheroidal"]["backward_euler_damping_ratio"];
  const double zeta = implicitPoint["damping_ratio"]["spheroidal"];
  EXPECT_GT(zeta, 0.5 * closedForm) << implicitPoint.dump();
  EXPECT_LT(zeta, 2.5 * closedForm) << implicitPoint.dump();
  EXPECT_GT(implicitPoint["errors"]["damping"].get<double>(), 0.1);
  EXPECT_FALSE(implicitPoint["guide"].get<bool>());

  // The peer that is not there says so; the guide names the symplectic point; the files are written.
  ASSERT_EQ(report["peers"].size(), 1u);
  EXPECT_EQ(report["peers"][0]["status"], "not built");
  ASSERT_EQ(report["guide"].size(), 1u);
  ASSERT_FALSE(report["guide"][0]["cheapest"].is_null()) << report["guide"].dump();
  EXPECT_EQ(report["guide"][0]["cheapest"]["integrator"], "symplectic_euler");
  EXPECT_TRUE(std::filesystem::exists(options.outputDirectory + "/front.json"));
  EXPECT_TRUE(std::filesystem::exists(options.outputDirectory + "/front.md"));
  EXPECT_TRUE(std::filesystem::exists(options.outputDirectory + "/front_damping.gp"));
}

}  // namespace
}  // namespace slime

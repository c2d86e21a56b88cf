// The tensile test (app/bench/material/bench_tensile.h) against oracles written here, not by the bench:
//  - the standard linear solid's constant-strain-rate response, σ = E∞ε + E₁ε̇τ(1 − e^{−ε/(ε̇τ)})
//    with E = 2G(1 + ν) (issue 29, item 5), within 5 % at small strain, at three rates;
//  - the limits that closed form has: a purely elastic material (no Maxwell branch) at any rate is
//    E∞ε, and a rate far above 1/τ is the instantaneous modulus 2(μ∞ + μ₁)(1 + ν)·ε;
//  - the bar's sides are free (the lateral stress is zero), so its lateral stretch is 1 − νε at small strain;
//  - the slime pulled by two hands: a faster pull needs more force, nothing diverges, the volume holds
//    (BenchTensileLong: seconds of physics).
#include "app/bench/material/bench_tensile.h"
#include "core/settings/settings_io.h"
#include "sls_oracle.h"

#include <gtest/gtest.h>

#include <cmath>

namespace slime {
namespace {

TEST(BenchTensile, BarFollowsTheStandardLinearSolidAtSmallStrainAtThreeRates) {
  const SlimeSettings slime = defaultSettings().slime;
  for (double rate : {0.05, 0.5, 5.0}) {
    const BarRun run = stretchBar(materialOf(slime), rate, 0.05, 500);
    ASSERT_EQ(run.strains.size(), 501u);
    EXPECT_NEAR(run.stresses.front(), 0.0, 1e-9);  // free of stress at rest
    for (std::size_t k = 50; k < run.strains.size(); k += 50) {
      const double oracle = fixture::standardLinearSolidStress(slime, run.strains[k], rate);
      EXPECT_NEAR(run.stresses[k], oracle, 0.05 * oracle) << "rate " << rate << " strain " << run.strains[k];
    }
  }
}

TEST(BenchTensile, BarLimitsAreTheElasticAndTheInstantaneousModuli) {
  SlimeSettings elastic = defaultSettings().slime;
  elastic.longTerm = 1.0;  // no Maxwell branch: E∞ε at every rate
  for (double rate : {0.01, 10.0}) {
    const BarRun run = stretchBar(materialOf(elastic), rate, 0.01, 200);
    const double young = 2.0 * elastic.modulus * (1.0 + elastic.poisson);
    EXPECT_NEAR(run.stresses.back(), young * 0.01, 0.02 * young * 0.01) << rate;
    EXPECT_NEAR(run.lateralStretches.back(), 1.0 - elastic.poisson * 0.01, 0.002) << rate;
  }
  const SlimeSettings slime = defaultSettings().slime;
  const BarRun fast = stretchBar(materialOf(slime), 1000.0, 0.01, 200);  // ε̇τ = 600: nothing relaxes
  const double instantaneous = 2.0 * slime.modulus * (1.0 + slime.poisson);
  EXPECT_NEAR(fast.stresses.back(), instantaneous * 0.01, 0.03 * instantaneous * 0.01);
  const BarRun slow = stretchBar(materialOf(slime), 1e-4, 0.01, 200);  // ε̇τ = 6e-5: all relaxed
  const double longTerm = 2.0 * slime.modulus * slime.longTerm * (1.0 + slime.poisson);
  EXPECT_NEAR(slow.stresses.back(), longTerm * 0.01, 0.05 * longTerm * 0.01);
}

// 0.5-2.5 s in release on the shared machine (1.5 s of physics at resolution 2), 10-20× that under the
// sanitizers: Long, so they leave it out.
TEST(BenchTensileLong, FasterPullsOfTheSlimeNeedMoreForce) {
  Settings settings = defaultSettings();
  // The material's rate dependence, on the floor the chart was measured on (docs/material.md): on the
  // sticky default (8000 Pa) the contact's creep adds to both pulls and the fast one needs only 6 %
  // more at half the extension (0.929 against 0.876 N), under the 10 % asked.
  settings.slime.adhesion = 0.0;
  TensileOptions options;
  options.strainRates = {0.5};
  options.barSteps = 100;
  options.pullSpeeds = {0.05, 0.2};
  options.pullExtension = 0.04;
  options.settleSeconds = 0.5;
  options.meshedSteps = 20;
  options.maxStrain = 0.1;
  CsvTable bar = tensilePointTable(), meshed = tensileMeshedTable(), pull = tensilePullTable();
  const nlohmann::json report = runTensileBench(settings, options, bar, meshed, pull);
  ASSERT_EQ(report["bar"].size(), 1u);
  EXPECT_LT(std::abs(report["bar"][0]["meshed_max_relative_error"].get<double>()), 0.05);
  EXPECT_EQ(meshed.rows.size(), 21u);
  ASSERT_EQ(report["pulls"].size(), 2u);
  const nlohmann::json& slow = report["pulls"][0];
  const nlohmann::json& fast = report["pulls"][1];
  for (const nlohmann::json& run : report["pulls"]) {
    EXPECT_EQ(run["divergences"].get<std::size_t>(), 0u);
    EXPECT_GT(run["final_extension_m"].get<double>(), 0.005);
    EXPECT_GT(run["volume_ratio"]["min"].get<double>(), 0.98);
    EXPECT_LT(run["volume_ratio"]["max"].get<double>(), 1.02);
  }
  // The body rings and slips while it is pulled (docs/material.md), so compare where the pulls are
  // well under way: at half the shorter extension, and at the end.
  EXPECT_GT(slow["force_at_common_extension_n"].get<double>(), 0.5);
  EXPECT_GT(fast["force_at_common_extension_n"].get<double>(), 1.1 * slow["force_at_common_extension_n"].get<double>());
  EXPECT_GT(fast["final_force_n"].get<double>(), 1.1 * slow["final_force_n"].get<double>());
  EXPECT_GT(pull.rows.size(), 20u);
}

}  // namespace
}  // namespace slime

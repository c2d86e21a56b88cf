// The benchmarks run end to end at a tiny size so their code cannot rot: every JSON field the charts
// and the README read is there and sane. Nothing about timing is asserted beyond "positive" and the
// ratios being the quotients of the times they name.
#include "app/bench/render/bench_accuracy.h"
#include "app/bench/material/bench_material.h"
#include "app/bench/physics/bench_physics.h"
#include "app/bench/render/bench_render.h"
#include "core/settings/settings_io.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <numbers>
#include <string>

namespace slime {
namespace {

using nlohmann::json;

std::string outputPath(const std::string& name) { return std::string(SLIME_TEST_OUTPUT_DIR) + "/" + name; }

// The render bench's fields and labels, not the light: without caustics (on by default since issue
// 30), whose photons the brute-force rows would trace on one thread (these tests 5-30 s, not 1-6 s).
Settings withoutCaustics() {
  Settings settings = defaultSettings();
  settings.render.caustics = false;
  return settings;
}

json readJson(const std::string& path) {
  std::ifstream file(path);
  return json::parse(file);
}

// Every bench report says which machine measured it: figures from two machines are not comparable.
void expectMachine(const json& report) {
  ASSERT_TRUE(report.contains("machine"));
  const json& machine = report["machine"];
  const std::string cpu = machine["cpu"].get<std::string>();
  EXPECT_FALSE(cpu.empty());
  EXPECT_NE(cpu.front(), ' ') << cpu;
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);)
    if (line.rfind("model name", 0) == 0) {
      EXPECT_EQ(cpu.rfind(line.substr(line.find(": ") + 2), 0), 0u) << cpu << " does not start with " << line;
      break;
    }
  EXPECT_GE(machine["cores"].get<int>(), 1);
  const std::string vectors = machine["compiled_for"].get<std::string>();
  EXPECT_TRUE(vectors == "AVX-512" || vectors == "AVX2" || vectors == "AVX" || vectors == "SSE2") << vectors;
  EXPECT_EQ(machine["date"].get<std::string>().size(), 20u);
  EXPECT_EQ(machine["load_average"].size(), 3u);
}

TEST(BenchRender, OneTinyLevelHasEveryField) {
  RenderBenchOptions options;
  options.levels = {1};
  options.threads = {1};
  options.frames = 1;
  options.warmup = 0;
  options.width = 64;
  options.height = 48;
  options.bruteMaxLevel = 1;
  options.bvhLevels = {1};
  options.jsonFile = outputPath("bench_render.json");
  options.csvFile = outputPath("bench_render.csv");
  runRenderBench(withoutCaustics(), options);

  const json report = readJson(options.jsonFile);
  expectMachine(report);
  ASSERT_EQ(report["configurations"].size(), 1u);
  const json& c = report["configurations"][0];
  EXPECT_EQ(c["level"], 1);
  EXPECT_EQ(c["faces"], 80);
  EXPECT_EQ(c["width"], 64);
  EXPECT_EQ(c["height"], 48);
  EXPECT_EQ(c["depth"], 3);
  EXPECT_EQ(c["threads"], 1);
  for (const char* frame : {"still_camera", "moving_camera"}) {
    EXPECT_GT(c[std::string(frame) + "_frame_ms"].get<double>(), 0.0) << frame;
    EXPECT_EQ(c[std::string(frame) + "_frame_ms"], c[frame]["ms"]["median"]) << frame;
    EXPECT_GT(c[frame]["all_mrays_per_s"].get<double>(), 0.0) << frame;
    for (const char* kind : {"primary", "shadow", "reflection", "refraction", "total", "slime_queries"})
      EXPECT_TRUE(c[frame]["rays"].contains(kind)) << frame << " " << kind;
  }
  // The moving-camera frame and the brute force's frame trace every pixel: nothing reused or cached.
  EXPECT_EQ(c["moving_camera"]["rays"]["primary"], 64 * 48);
  EXPECT_EQ(c["moving_camera"]["reused_pixels"], 0);
  EXPECT_EQ(c["moving_camera"]["cached_floor_pixels"], 0);
  EXPECT_EQ(c["brute_force"]["rays"]["primary"], 64 * 48);
  EXPECT_EQ(c["brute_force"]["reused_pixels"], 0);
  EXPECT_EQ(c["brute_force"]["cached_floor_pixels"], 0);
  // The still camera's first (here its only) frame traces every pixel too; later ones reuse.
  EXPECT_EQ(c["still_camera"]["rays"]["primary"], 64 * 48);
  EXPECT_GT(c["limit_ms_per_frame"].get<double>(), 0.0);
  EXPECT_GT(c["brute_force_frame_ms"].get<double>(), 0.0);
  // Throughput under names that cannot be mixed up: queries that reach Embree, and all rays.
  EXPECT_FALSE(c.contains("mrays_per_s"));
  EXPECT_FALSE(c.contains("ms_per_frame"));
  EXPECT_FALSE(c.contains("speedup_over_brute"));
  const double queries = c["limit"]["queries"]["total"].get<double>();
  EXPECT_NEAR(c["embree_mqueries_per_s"].get<double>(), queries / (c["limit_ms_per_frame"].get<double>() * 1e3),
              1e-9 * queries);
  EXPECT_NEAR(c["all_mrays_per_s"].get<double>(), c["moving_camera"]["all_mrays_per_s"].get<double>(), 1e-12);
  EXPECT_LT(queries, c["moving_camera"]["rays"]["total"].get<double>());  // floor and sky rays never query Embree
  // The replayed queries are the frame's own as Embree alone would be asked them: the renderer makes
  // the same primary and secondary ones (the primaries answered by its eye grid), and answers each
  // shadow ray in one query of its light grid where Embree needs one or two (crossFromBothEnds8).
  const json& kinds = c["limit"]["queries"];
  const auto asked = c["still_camera"]["rays"]["slime_queries"].get<std::uint64_t>();
  const auto primaryAndSecondary = kinds["primary"].get<std::uint64_t>() + kinds["secondary"].get<std::uint64_t>();
  EXPECT_EQ(kinds["total"].get<std::uint64_t>(), primaryAndSecondary + kinds["shadow"].get<std::uint64_t>());
  EXPECT_GT(asked, primaryAndSecondary) << "the shadow rays' queries";
  EXPECT_LT(asked, kinds["total"].get<std::uint64_t>()) << "a shadow ray that enters the slime costs Embree two";

  // The headline: brute force over the same full frame, medians, at least 3 brute samples after a warm-up.
  ASSERT_TRUE(report.contains("headline"));
  const json& headline = report["headline"];
  EXPECT_EQ(headline["level"], 1);
  EXPECT_EQ(headline["embree_mqueries_per_s"], c["embree_mqueries_per_s"]);
  EXPECT_EQ(headline["all_mrays_per_s"], c["all_mrays_per_s"]);
  EXPECT_EQ(headline["still_camera_frame_ms"], c["still_camera_frame_ms"]);
  EXPECT_EQ(headline["moving_camera_frame_ms"], c["moving_camera_frame_ms"]);
  EXPECT_TRUE(headline["all_mrays_per_s_counts"].is_string());
  const json& speedup = headline["speedup_over_brute_full_frame"];
  const double bruteMs = speedup["brute_force_frame_ms"].get<double>();
  const double embreeMs = speedup["embree_frame_ms"].get<double>();
  EXPECT_GT(bruteMs, 0.0);
  EXPECT_EQ(embreeMs, c["moving_camera_frame_ms"].get<double>());
  EXPECT_EQ(bruteMs, c["brute_force"]["ms"]["median"].get<double>());
  EXPECT_NEAR(speedup["ratio"].get<double>(), bruteMs / embreeMs, 1e-9 * bruteMs / embreeMs);
  EXPECT_EQ(speedup["ratio"], c["full_frame_speedup_over_brute"]);
  EXPECT_GE(speedup["brute_force_samples"].get<int>(), 3);
  EXPECT_EQ(speedup["brute_force_samples"], c["brute_force"]["ms"]["samples"]);
  EXPECT_GE(speedup["brute_force_warmup_frames"].get<int>(), 1);
  EXPECT_EQ(speedup["embree_frame_samples"], 1);
  EXPECT_EQ(speedup["mode"], "full");
  ASSERT_EQ(report["bvh"].size(), 4u);
  for (const json& b : report["bvh"]) {
    EXPECT_GT(b["update_ms"].get<double>(), 0.0);
    EXPECT_GT(b["trace_deformed_ms"].get<double>(), 0.0);
  }
  EXPECT_GT(report["seed"].size(), 0u);
  EXPECT_TRUE(std::ifstream(outputPath("bench_render_bvh.csv")).good());
  EXPECT_TRUE(std::ifstream(outputPath("bench_render_seed.csv")).good());
}

// Issue 28: each headline row has the handled frame (camera still, the slime pulled frame after
// frame, traced as the viewer does with its reuse) beside the every-pixel deforming frame.
TEST(BenchRender, TheHeadlineHasTheHandledFrame) {
  RenderBenchOptions options;
  options.levels = {1};
  options.threads = {1};
  options.frames = 3;
  options.warmup = 1;
  options.width = 32;
  options.height = 24;
  options.bruteMaxLevel = -1;
  options.bvhLevels = {};
  options.headlineSizes = {{120, 90}};
  options.headlineLevel = 2;
  const json report = runRenderBench(withoutCaustics(), options);
  ASSERT_EQ(report["interactive_headline"].size(), 1u);
  const json& row = report["interactive_headline"][0];
  const double handled = row["handled_frame_ms"].get<double>(), deforming = row["deforming_frame_ms"].get<double>();
  EXPECT_GT(handled, 0.0);
  EXPECT_EQ(handled, row["handled_frame"]["ms"]["median"].get<double>());
  EXPECT_NEAR(row["handled_over_deforming"].get<double>(), handled / deforming, 1e-12);
  // The slime moved every frame, so some pixels were traced; the floor away from it was kept.
  const auto reused = row["handled_frame"]["reused_pixels"].get<std::uint64_t>();
  EXPECT_GT(reused, 0u);
  EXPECT_LT(reused, 120u * 90u);
  EXPECT_GT(row["handled_frame"]["rays"]["slime_queries"].get<std::uint64_t>(), 0u);
}

// Fewer brute-force samples than 3 are allowed (a quick run) but the headline says so.
TEST(BenchRender, QuickBruteForceIsLabelled) {
  RenderBenchOptions options;
  options.levels = {0};
  options.threads = {1};
  options.frames = 1;
  options.warmup = 0;
  options.width = 32;
  options.height = 24;
  options.bruteMaxLevel = 0;
  options.bruteSamples = 1;
  options.bvhLevels = {};
  const json report = runRenderBench(withoutCaustics(), options);
  const json& speedup = report["headline"]["speedup_over_brute_full_frame"];
  EXPECT_EQ(speedup["brute_force_samples"], 1);
  EXPECT_NE(speedup["mode"].get<std::string>().find("quick"), std::string::npos);
}

// The bulk body at its coarsest resolution and the membrane at level 1: every section the charts and
// docs read (cost with the quoted Jolt rows, both stability maps with the prediction beside them, both
// accuracy runs with the integrator choice), and sane values.
TEST(BenchPhysics, OneTinyLevelHasEveryField) {
  PhysicsBenchOptions options;
  options.levels = {1};
  options.resolutions = {1};
  options.integrators = {"symplectic_euler", "implicit_euler"};  // the bulk body runs only the first
  options.secondsPerMeasurement = 0.01;
  options.stabilityLevel = 1;
  options.moduli = {1000.0};
  options.stiffnesses = {40.0};
  options.accuracyLevel = 1;
  options.steps = {1e-3};
  options.settleSeconds = 0.05;
  options.bulletProgram = "/nonexistent/bullet_ball";  // a peer that is not there is left out, not an error
  options.jsonFile = outputPath("bench_physics.json");
  options.csvFile = outputPath("bench_physics.csv");
  Settings settings = defaultSettings();
  settings.slime.level = 1;  // the drawn level of the resolution rows
  settings.slime.resolution = 1;
  runPhysicsBench(settings, options);

  const json report = readJson(options.jsonFile);
  expectMachine(report);
  EXPECT_FALSE(report["date"].get<std::string>().empty());
  int measured = 0, jolt = 0;
  for (const json& row : report["cost"]) {
    EXPECT_GT(row["cpu_ms_per_simulated_s"]["median"].get<double>(), 0.0) << row.dump();
    if (row["source"] == "measured") {
      ++measured;
      EXPECT_TRUE(row["stable"].get<bool>()) << row.dump();
      EXPECT_GT(row["simulated_points"].get<int>(), 0);
      EXPECT_EQ(row["drawn_vertices"].get<int>(), 42);  // level 1
    }
    if (row["series"] == "jolt") ++jolt;
  }
  EXPECT_EQ(measured, 3);  // bulk at level 1, bulk at resolution 1 (the same run, listed twice), membrane
  EXPECT_EQ(jolt, 4);
  ASSERT_EQ(report["stability"]["bulk"].size(), 1u);
  const json& point = report["stability"]["bulk"][0];
  EXPECT_EQ(point["modulus"], 1000.0);
  // (0 is a finding, not a failure: resolution 1 started 1 mm into the floor trips the guard even at 1 µs.)
  EXPECT_GE(point["largest_stable_dt"].get<double>(), 0.0);
  EXPECT_GT(point["runs"].get<int>(), 0);
  EXPECT_GT(point["predicted_dt"].get<double>(), 0.0);
  EXPECT_GT(point["omega_max"].get<double>(), 0.0);
  ASSERT_EQ(report["stability"]["membrane"].size(), 2u);
  EXPECT_TRUE(report["stability"]["membrane"][1]["predicted_dt"].is_null());  // implicit Euler: no limit
  for (const char* model : {"bulk", "membrane"}) {
    const json& accuracy = report["accuracy"][model];
    ASSERT_EQ(accuracy["runs"].size(), std::string(model) == "bulk" ? 2u : 4u) << model;  // h and automatic
    for (const json& run : accuracy["runs"]) {
      ASSERT_TRUE(run["stable"].get<bool>()) << run.dump();
      EXPECT_TRUE(std::isfinite(run["rms_error_mm"].get<double>()));
      EXPECT_GE(run["rms_error_mm"].get<double>(), 0.0);
      EXPECT_LE(run["rms_error_mm"].get<double>(), run["max_error_mm"].get<double>());
      EXPECT_GT(run["cpu_s_per_simulated_s"].get<double>(), 0.0);
    }
    EXPECT_LT(accuracy["reference"]["rms_error_mm_of_the_check"].get<double>(), 0.1) << model;
    EXPECT_GE(accuracy["landing"]["rms_apart_mm"].get<double>(), 0.0) << model;
    EXPECT_FALSE(accuracy["choice"].empty());
  }
  const std::string outcome = report["accuracy"]["bulk"]["default_integrator"]["outcome"];
  EXPECT_TRUE(outcome == "confirmed" || outcome == "overturned") << outcome;
  EXPECT_GT(report["rest"]["aspect"].get<double>(), 0.0);
  for (const char* table : {"bench_physics.csv", "bench_physics_stability.csv", "bench_physics_accuracy.csv"})
    EXPECT_TRUE(std::ifstream(outputPath(table)).good()) << table;
}

// The choice reads the cheapest run that meets each error target, whatever its integrator.
TEST(BenchPhysics, CheapestForAccuracyPicksTheCheapestRunWithinEachTarget) {
  const json runs = json::array({
      {{"integrator", "rk4"}, {"stable", true}, {"finished", true}, {"rms_error_mm", 0.001}, {"cpu_s_per_simulated_s", 2.0}, {"h", 1e-4}, {"automatic", false}},
      {{"integrator", "symplectic_euler"}, {"stable", true}, {"finished", true}, {"rms_error_mm", 0.05}, {"cpu_s_per_simulated_s", 0.2}, {"h", 1e-3}, {"automatic", true}},
      {{"integrator", "explicit_euler"}, {"stable", false}, {"finished", true}, {"cpu_s_per_simulated_s", 0.01}, {"h", 5e-3}, {"automatic", false}}});
  const json choice = cheapestForAccuracy(runs, {0.01, 0.1});
  ASSERT_EQ(choice.size(), 2u);
  EXPECT_EQ(choice[0]["cheapest"]["integrator"], "rk4");
  EXPECT_EQ(choice[1]["cheapest"]["integrator"], "symplectic_euler");
  EXPECT_FALSE(choice[1]["by_integrator"].contains("explicit_euler"));  // unstable runs never count
  EXPECT_EQ(bulkIntegrators({"xpbd", "rk4", "implicit_euler", "symplectic_euler"}),
            (std::vector<std::string>{"rk4", "symplectic_euler"}));
}

TEST(BenchAccuracy, OneTinyLevelHasEveryField) {
  AccuracyBenchOptions options;
  options.levels = {1};
  options.depths = {1, 2};
  options.frames = 1;
  options.width = 64;
  options.height = 48;
  options.jsonFile = outputPath("bench_accuracy.json");
  runAccuracyBench(defaultSettings(), options);

  const json report = readJson(options.jsonFile);
  expectMachine(report);
  ASSERT_EQ(report["runs"].size(), 4u);  // 1 level × {flat, smooth} × 2 depths
  for (const json& run : report["runs"]) {
    EXPECT_GT(run["ms_per_frame"].get<double>(), 0.0);
    EXPECT_GE(run["rmse"].get<double>(), 0.0);
    EXPECT_GT(run["psnr"].get<double>(), 0.0);
    EXPECT_GE(run["visible_fraction"].get<double>(), 0.0);
    EXPECT_LE(run["visible_fraction"].get<double>(), 1.0);
    EXPECT_GT(run["sagitta_px"].get<double>(), 0.0);
  }
}

TEST(BenchAccuracy, IdenticalImagesHaveNoError) {
  Image image;
  image.resize(4, 3);
  for (auto& pixel : image.pixels) pixel = glm::vec3(0.3f, 0.5f, 0.7f);
  const ImageError error = compareImages(image, image);
  EXPECT_EQ(error.rmse, 0.0);
  EXPECT_EQ(error.maxError, 0.0);
  EXPECT_EQ(error.visibleFraction, 0.0);
  Image other = image;
  other.at(0, 0) = glm::vec3(1.0f);
  const ImageError one = compareImages(other, image);
  EXPECT_GT(one.maxError, 2.0);
  EXPECT_NEAR(one.visibleFraction, 1.0 / 12.0, 1e-12);
}

// `slime bench material --quick`: every field docs/material.md and the charts read, and the oracles
// within their bounds (Lamb at the default resolution 2 within 5 %, the creep time within 10 % of the
// material's, energy drift under 1 %, volume within 1 %).
TEST(BenchMaterial, QuickRunHasEveryFieldAndMeetsItsOracles) {
  MaterialBenchOptions options = MaterialBenchOptions::quick();
  options.jsonFile = outputPath("bench_material.json");
  options.csvFile = outputPath("bench_material.csv");
  runMaterialBench(defaultSettings(), options);

  const json report = readJson(options.jsonFile);
  expectMachine(report);
  auto expectVolumeWithinOnePercent = [](const json& run, const char* what) {
    EXPECT_GT(run["volume_ratio"]["min"].get<double>(), 0.99) << what;
    EXPECT_LT(run["volume_ratio"]["max"].get<double>(), 1.01) << what;
  };
  ASSERT_EQ(report["lamb"].size(), 4u);  // resolutions 1, 2 × torsional, spheroidal
  for (const json& run : report["lamb"]) {
    const std::string mode = run["mode"];
    EXPECT_TRUE(mode == "torsional_n2" || mode == "spheroidal_n2") << mode;
    EXPECT_GT(run["nodes"].get<int>(), 0);
    const double theory = run["theory_hz"], measured = run["measured_hz"];
    EXPECT_GT(theory, 5.0);
    EXPECT_LT(theory, 20.0);
    EXPECT_NEAR(run["error"].get<double>(), measured / theory - 1.0, 1e-12);
    EXPECT_LT(std::abs(run["error"].get<double>()), run["resolution"] == 2 ? 0.05 : 0.12) << mode;
    expectVolumeWithinOnePercent(run, "lamb");
  }
  const json& creep = report["creep"];
  const double material = creep["material_tau_s"];
  EXPECT_NEAR(material, 0.6 * 1200.0 / (0.4 * 1200.0), 1e-9);  // τ (μ∞ + μ1)/μ∞ at the defaults
  EXPECT_NEAR(creep["measured_tau_s"].get<double>(), material, 0.1 * material);
  EXPECT_GT(creep["series"].size(), 10u);
  expectVolumeWithinOnePercent(creep, "creep");
  const json& recovery = report["recovery"];
  EXPECT_NEAR(recovery["measured_tau_s"].get<double>(), material, 0.1 * material);
  EXPECT_GT(recovery["series"].size(), 10u);
  const json& energy = report["energy_drift"];
  EXPECT_GT(energy["initial_energy_j"].get<double>(), 0.0);
  EXPECT_LT(std::abs(energy["drift"].get<double>()), 0.01);
  EXPECT_LT(energy["max_deviation"].get<double>(), 0.01);
  expectVolumeWithinOnePercent(energy, "energy");
  EXPECT_TRUE(std::ifstream(outputPath("bench_material_creep.csv")).good());
}

// The numerical damping (issue 27 item 2) against an oracle: projective dynamics is an implicit Euler
// step, whose damping of an undamped oscillator at ω is ζ = ln(1 + (ωh)²)/(2ωh); converged (10
// iterations) it must add that much to Lamb's torsional mode, within 10 % (measured 1 % at 1 ms and
// 4 % at 4 ms, resolution 1), and the default symplectic_euler, which conserves energy, nearly none
// (measured 4e-4 and 5e-4: energy leaking to other modes of the tetrahedral ball, not lost).
TEST(BenchMaterial, DampingRatiosMatchBackwardEulersClosedForm) {
  DampingOptions options;
  options.resolution = 1;
  options.steps = {0.001, 0.004};
  options.projectiveIterations = {10};
  options.periods = 3.0;
  CsvTable table;
  const json rows = runDampingBench(defaultSettings(), options, table);
  ASSERT_EQ(rows.size(), 12u);  // symplectic_euler, rk4, projective × 2 modes × 2 steps
  ASSERT_EQ(table.rows.size(), 12u);
  int checked = 0;
  for (const json& row : rows) {
    if (row["mode"] != "torsional_n2") continue;
    const double zeta = row["damping_ratio"], closedForm = row["backward_euler_damping_ratio"];
    EXPECT_EQ(row["rollbacks"].get<int>(), 0);
    if (row["method"] == "projective") {
      EXPECT_NEAR(zeta, closedForm, 0.1 * closedForm) << "dt " << row["dt_s"];
      ++checked;
    }
    if (row["method"] == "symplectic_euler") {
      EXPECT_LT(std::abs(zeta), 1e-3) << "dt " << row["dt_s"];
      ++checked;
    }
  }
  EXPECT_EQ(checked, 4);
}

TEST(BenchMaterial, ExponentialFitRecoversItsParameters) {
  std::vector<double> t, y;
  for (int k = 0; k <= 200; ++k) {
    t.push_back(0.04 * k);
    y.push_back(2.5 - 1.5 * std::exp(-t.back() / 1.5) + 1e-4 * std::sin(37.0 * k));
  }
  const ExponentialFit fit = fitExponential(t, y, 0.01, 100.0);
  EXPECT_NEAR(fit.tau, 1.5, 1e-3);
  EXPECT_NEAR(fit.asymptote, 2.5, 1e-3);
  EXPECT_NEAR(fit.initial, 1.0, 1e-3);
  EXPECT_LT(fit.rms, 2e-4);
}

TEST(BenchMaterial, ZeroCrossingsGiveTheFrequency) {
  std::vector<double> t, y;
  for (int k = 1; k <= 1000; ++k) {
    t.push_back(1e-3 * k);
    y.push_back(std::sin(2.0 * std::numbers::pi * 10.7 * t.back()));
  }
  EXPECT_NEAR(zeroCrossingFrequency(t, y), 10.7, 1e-3);
}

}  // namespace
}  // namespace slime

// Torture runs for every integrator (issue 6): drags at 100 m/s, stretching to ten times the radius,
// pressing flat against the floor, the stiffest material at the largest step, a tiny mass. Each run must
// end with no NaN ever reported and no vertex below the floor, and within 5 s of release the rest shape
// must be back (aspect within 5 % and volume within 2 % of an untouched run's) — or the run reports a
// recovered divergence.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <fstream>
#include <map>
#include <string>

namespace {

using nlohmann::json;

json simReport(const std::string& name, const std::string& arguments) {
  const std::string report = std::string(SLIME_TEST_OUTPUT_DIR) + "/torture_" + name + ".json";
  const std::string command = std::string(SLIME_BINARY) + " sim " + arguments + " --report " + report + " > /dev/null";
  const int status = std::system(command.c_str());
  EXPECT_EQ(status, 0) << command;
  std::ifstream file(report);
  if (!file) return json::object();
  return json::parse(file);
}

std::string scenario(const std::string& name) {
  return std::string(SLIME_SOURCE_DIR) + "/tests/scenarios/" + name + ".json";
}

struct Torture {
  const char* name;
  const char* scenario;   // tests/scenarios/<scenario>.json
  const char* arguments;  // besides --seconds and the integrator
};

class TortureRun : public testing::TestWithParam<std::tuple<std::string, Torture>> {};

// The untouched run each torture is compared with, once per set of arguments.
const json& restReport(const std::string& name, const std::string& arguments) {
  static std::map<std::string, json> reports;
  auto found = reports.find(arguments);
  if (found == reports.end()) found = reports.emplace(arguments, simReport(name, arguments)).first;
  return found->second;
}

TEST_P(TortureRun, RecoversItsRestShapeOrReportsARecoveredDivergence) {
  const auto& [integrator, torture] = GetParam();
  // Level 3 (642 vertices) keeps the 25 runs quick; the torture is in the motion, not the mesh size.
  const std::string base = "--set sim.integrator=" + integrator + " --set slime.level=3 --seconds 7";
  const json& rest = restReport(integrator + "_rest_" + torture.name, base + " " + torture.arguments);
  const json run = simReport(integrator + "_" + torture.name,
                             base + " " + torture.arguments + " --scenario " + scenario(torture.scenario));
  ASSERT_TRUE(run.contains("final") && rest.contains("final")) << run.dump();
  EXPECT_FALSE(run["nan"].get<bool>());
  EXPECT_GE(run["range"]["min_z"].get<double>(), 0.0);
  const bool diverged = run["rollbacks"].get<int>() > 0;
  if (!diverged && rest["rollbacks"].get<int>() == 0) {
    const double restAspect = rest["final"]["aspect"].get<double>();
    EXPECT_NEAR(run["final"]["aspect"].get<double>(), restAspect, 0.05 * restAspect);
    // "Volume within 2 %" of the untouched run's rest volume: the rest state itself is the defaults
    // test's business (core tests), and implicit Euler at the largest step rests 6 % low (noted).
    const double restVolume = rest["final"]["volume_ratio"].get<double>();
    EXPECT_NEAR(run["final"]["volume_ratio"].get<double>(), restVolume, 0.02 * restVolume);
  }
}

const Torture kTortures[] = {
    {"drag_100ms", "drag_100ms", ""},
    {"stretch_10x", "stretch_10x", ""},
    {"press_flat", "press_flat", ""},
    {"stiffest_largest_step", "grab_and_stretch", "--set slime.stiffness=1000 --set sim.dt=0.01"},
    {"tiny_mass", "grab_and_stretch", "--set slime.mass=0.01"},
};

INSTANTIATE_TEST_SUITE_P(
    Integrators, TortureRun,
    testing::Combine(testing::Values("explicit_euler", "symplectic_euler", "rk4", "implicit_euler", "xpbd"),
                     testing::ValuesIn(kTortures)),
    [](const auto& info) {
      return std::get<0>(info.param) + "_" + std::get<1>(info.param).name;
    });

}  // namespace

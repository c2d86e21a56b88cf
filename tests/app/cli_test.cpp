// The command line as a user meets it: every bad input gives a clear message naming what is wrong and
// what is allowed, exit code 2, and no output file left behind.
#include "core/settings_io.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>
#include <sys/wait.h>

namespace {

struct CommandResult {
  int exitCode = -1;
  std::string output;  // stdout and stderr together
};

CommandResult runSlime(const std::string& arguments) {
  const std::string command = std::string(SLIME_BINARY) + " " + arguments + " 2>&1";
  CommandResult run;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return run;
  std::array<char, 4096> buffer;
  while (std::fgets(buffer.data(), buffer.size(), pipe)) run.output += buffer.data();
  const int status = pclose(pipe);
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

std::string outputPath(const std::string& name) { return std::string(SLIME_TEST_OUTPUT_DIR) + "/" + name; }

struct BadInput {
  const char* arguments;
  const char* mentions;  // what the message must name
};

class RejectsBadInput : public testing::TestWithParam<BadInput> {};

TEST_P(RejectsBadInput, WithExitCodeTwoAndAMessageNamingTheProblem) {
  const BadInput& bad = GetParam();
  const CommandResult run = runSlime(bad.arguments);
  EXPECT_EQ(run.exitCode, 2) << bad.arguments << "\n" << run.output;
  EXPECT_NE(run.output.find(bad.mentions), std::string::npos) << bad.arguments << "\n" << run.output;
}

INSTANTIATE_TEST_SUITE_P(
    Cli, RejectsBadInput,
    testing::Values(
        BadInput{"sim --seconds 0.1 --set slime.level=12", "slime.level"},
        BadInput{"sim --seconds 0.1 --set slime.level=12", "0 to 7"},
        BadInput{"sim --seconds 0.1 --set slime.mass=nan", "slime.mass"},
        BadInput{"sim --seconds 0.1 --set slime.mass=-1", "slime.mass"},
        BadInput{"sim --seconds 0.1 --set slime.stifness=3", "did you mean 'slime.stiffness'"},
        BadInput{"sim --seconds 0.1 --set sim.integrator=verlet", "symplectic_euler"},
        BadInput{"sim --seconds 0.1 --set render.depth=abc", "render.depth"},
        BadInput{"sim --seconds 0.1 --scene /nonexistent/scene.json", "cannot open"},
        BadInput{"sim --seconds 0.1 --scenario /nonexistent/scenario.json", "scenario"},
        BadInput{"sim --seconds -1", "seconds"},
        BadInput{"sim --seconds nan", "seconds"},
        BadInput{"snapshot -o " SLIME_TEST_OUTPUT_DIR "/bad.png --size 0x0", "size"},
        BadInput{"snapshot -o " SLIME_TEST_OUTPUT_DIR "/bad.png --size 100000x100000", "size"},
        BadInput{"snapshot -o " SLIME_TEST_OUTPUT_DIR "/bad.png --size -5x10", "size"},
        BadInput{"snapshot -o " SLIME_TEST_OUTPUT_DIR "/bad.png --size wide", "size"},
        BadInput{"snapshot -o " SLIME_TEST_OUTPUT_DIR "/bad.png --set floor.pattern=image "
                 "--set floor.image=" SLIME_SOURCE_DIR "/CMakeLists.txt", "floor.image"},
        BadInput{"snapshot -o " SLIME_TEST_OUTPUT_DIR "/bad.png --set floor.pattern=image "
                 "--set floor.image=/nonexistent.png", "floor.image"},
        BadInput{"frobnicate", "frobnicate"}));

TEST(Cli, RejectedSnapshotLeavesNoFileBehind) {
  const std::string path = outputPath("bad.png");
  std::filesystem::remove(path);
  for (const char* arguments : {"--size 0x0", "--set slime.level=12", "--set floor.pattern=image --set floor.image=/nonexistent.png"}) {
    const CommandResult run = runSlime("snapshot -o " + path + " " + arguments);
    EXPECT_EQ(run.exitCode, 2) << arguments << "\n" << run.output;
    EXPECT_FALSE(std::filesystem::exists(path)) << arguments;
  }
}

TEST(Cli, HelpNamesEverySubcommandAndExitsZero) {
  const CommandResult run = runSlime("--help");
  EXPECT_EQ(run.exitCode, 0);
  for (const char* name : {"view", "snapshot", "sim", "bench", "settings"}) EXPECT_NE(run.output.find(name), std::string::npos) << name;
}

TEST(Cli, SimHelpNamesEveryIntegrator) {
  const CommandResult run = runSlime("sim --help");
  EXPECT_EQ(run.exitCode, 0);
  for (const char* name : {"explicit_euler", "symplectic_euler", "rk4", "implicit_euler", "xpbd"})
    EXPECT_NE(run.output.find(name), std::string::npos) << name << "\n" << run.output;
}

// `slime settings` lists every key of the table with its meaning; the JSON form parses and says the same.
TEST(Cli, SettingsListsEveryKey) {
  const CommandResult run = runSlime("settings");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  for (const std::string& key : slime::settingKeys())
    EXPECT_NE(run.output.find("\n" + key + " "), std::string::npos) << key << " missing from `slime settings`";
  EXPECT_NE(run.output.find("1, 4, 9, 16, 25, 36, 49, 64"), std::string::npos) << "render.spp's values";
  EXPECT_NE(run.output.find("icosphere subdivision level"), std::string::npos) << "slime.level's meaning";
}

TEST(Cli, SettingsJsonParsesAndHasEveryKeyWithItsMeaning) {
  const std::string path = outputPath("settings.json");
  const CommandResult run = runSlime("settings --json > " + path);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  std::FILE* file = std::fopen(path.c_str(), "r");
  ASSERT_NE(file, nullptr);
  nlohmann::json list;
  EXPECT_NO_THROW(list = nlohmann::json::parse(file)) << "slime settings --json is not JSON";
  std::fclose(file);
  std::vector<std::string> keys;
  for (const auto& entry : list) {
    keys.push_back(entry.at("key").get<std::string>());
    EXPECT_FALSE(entry.at("help").get<std::string>().empty()) << entry.at("key");
    EXPECT_TRUE(entry.contains("default")) << entry.at("key");
  }
  EXPECT_EQ(keys, slime::settingKeys());
}

}  // namespace

// The command line as a user meets it: every bad input gives a clear message naming what is wrong and
// what is allowed, exit code 2, and no output file left behind.
#include "core/settings/settings_io.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <sys/wait.h>
#include <vector>

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
        BadInput{"snapshot -o " SLIME_TEST_OUTPUT_DIR "/bad.png --eye 0 0 0.1 --look-at 0 0 0.1", "--look-at"},
        BadInput{"view --frame-log /nonexistent-directory/frames.csv", "--frame-log"},
        BadInput{"view --frame-log /nonexistent-directory/frames.csv", "does not exist"},
        BadInput{"view --frame-log " SLIME_TEST_OUTPUT_DIR, "is a directory"},
        BadInput{"view --report /nonexistent-directory/report.json", "--report"},
        BadInput{"view --target-fps 500", "--target-fps"},
        BadInput{"view --target-fps -1", "--target-fps"},
        BadInput{"view --target-fps fast", "--target-fps"},
        BadInput{"view --screenshot-at 2 1", "ascending"},
        BadInput{"view --screenshot-at -1", "0.000000 to 3600"},
        BadInput{"frobnicate", "frobnicate"}));

// --eye and --look-at are readable names of --vp and --vi: the same picture.
TEST(Cli, EyeAndLookAtAreVpAndVi) {
  const std::string named = outputPath("eye.png"), seed = outputPath("vp.png");
  const std::string common = " --size 64x48 --settle 0 ";
  ASSERT_EQ(runSlime("snapshot -o " + named + common + "--eye 0.15 -0.15 0.08 --look-at 0 0 0.03").exitCode, 0);
  ASSERT_EQ(runSlime("snapshot -o " + seed + common + "--vp 0.15 -0.15 0.08 --vi 0 0 0.03").exitCode, 0);
  ASSERT_EQ(runSlime("snapshot -o " + outputPath("default_view.png") + common).exitCode, 0);
  const auto bytes = [](const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  };
  EXPECT_FALSE(bytes(named).empty());
  EXPECT_TRUE(bytes(named) == bytes(seed)) << "--eye/--look-at and --vp/--vi drew different pictures";
  EXPECT_FALSE(bytes(named) == bytes(outputPath("default_view.png"))) << "--eye/--look-at did not move the camera";
}

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
  for (const char* name : {"view", "snapshot", "sim", "bench", "settings", "record"}) EXPECT_NE(run.output.find(name), std::string::npos) << name;
}

TEST(Cli, SimHelpNamesEveryIntegrator) {
  const CommandResult run = runSlime("sim --help");
  EXPECT_EQ(run.exitCode, 0);
  for (const char* name : {"explicit_euler", "symplectic_euler", "rk4", "implicit_euler", "xpbd"})
    EXPECT_NE(run.output.find(name), std::string::npos) << name << "\n" << run.output;
}

// `slime sim --report`'s "pieces", at the end and in every sample of the series: the count, the total
// volume and each piece's volume and centroid (docs/usage.md). One piece today: its drawn volume is
// the default ball's, 4/3 π (4 cm)³ to a few percent, and its centroid lies inside the reported shape.
TEST(Cli, SimReportCarriesThePieces) {
  const std::string path = outputPath("pieces_report.json");
  std::filesystem::remove(path);
  const CommandResult run = runSlime("sim --seconds 0.2 --set slime.level=2 --report " + path);
  ASSERT_EQ(run.exitCode, 0) << run.output;
  std::ifstream in(path);
  const nlohmann::json report = nlohmann::json::parse(in);
  const double ball = 4.0 / 3.0 * 3.14159265358979 * 0.04 * 0.04 * 0.04;
  const auto checkPieces = [&](const nlohmann::json& pieces, const std::string& where) {
    ASSERT_EQ(pieces.at("count"), 1) << where;
    ASSERT_EQ(pieces.at("each").size(), 1u) << where;
    const nlohmann::json& piece = pieces.at("each")[0];
    EXPECT_EQ(pieces.at("total_volume").get<double>(), piece.at("volume").get<double>()) << where;
    EXPECT_NEAR(piece.at("volume").get<double>(), ball, 0.08 * ball) << where;  // level 2: 4 % under the ball
    ASSERT_EQ(piece.at("centroid").size(), 3u) << where;
  };
  const nlohmann::json& final = report.at("final");
  checkPieces(final.at("pieces"), "final");
  const nlohmann::json& centroid = final.at("pieces").at("each")[0].at("centroid");
  EXPECT_NEAR(centroid[0].get<double>(), 0.0, 1e-3);
  EXPECT_NEAR(centroid[1].get<double>(), 0.0, 1e-3);
  EXPECT_GT(centroid[2].get<double>(), final.at("min_z").get<double>());
  EXPECT_LT(centroid[2].get<double>(), final.at("min_z").get<double>() + final.at("height").get<double>());
  ASSERT_GT(report.at("series").size(), 10u);
  for (const nlohmann::json& sample : report.at("series"))
    checkPieces(sample.at("pieces"), "t = " + std::to_string(sample.at("t").get<double>()));
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

// --- slime record ----------------------------------------------------------------------------------

std::string runShell(const std::string& command) {
  std::string output;
  FILE* pipe = popen(("( " + command + " ) 2>&1").c_str(), "r");
  if (!pipe) return output;
  std::array<char, 4096> buffer;
  while (std::fgets(buffer.data(), buffer.size(), pipe)) output += buffer.data();
  pclose(pipe);
  return output;
}

std::string fileBytes(const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) return "";
  std::string bytes;
  std::array<char, 65536> buffer;
  std::size_t count;
  while ((count = std::fread(buffer.data(), 1, buffer.size(), file)) > 0) bytes.append(buffer.data(), count);
  std::fclose(file);
  return bytes;
}

// Temporary files beside `output` (a clip is written to ".<name>.partial-XXXXXX" and renamed): only
// this output's, since tests running beside it (ctest -j) write their own clips in the same directory.
std::vector<std::filesystem::path> partialFilesOf(const std::string& output) {
  const std::filesystem::path path(output);
  const std::filesystem::path directory = path.has_parent_path() ? path.parent_path() : ".";
  std::vector<std::filesystem::path> found;
  if (!std::filesystem::is_directory(directory)) return found;
  const std::string prefix = "." + path.filename().string() + ".partial";
  for (const auto& entry : std::filesystem::directory_iterator(directory))
    if (entry.path().filename().string().rfind(prefix, 0) == 0) found.push_back(entry.path());
  return found;
}

// Before a run: no clip and no temporary file left by an earlier run (a failed one may have left them).
void removeClipAndItsPartials(const std::string& output) {
  std::error_code ignored;
  std::filesystem::remove(output, ignored);
  for (const auto& partial : partialFilesOf(output)) std::filesystem::remove(partial, ignored);
}

const std::string kRecordScenario = " --scenario " SLIME_SOURCE_DIR "/tests/scenarios/grab_and_stretch.json";

class Record : public testing::Test {
 protected:
  void SetUp() override {
    if (runShell("command -v ffmpeg && command -v ffprobe").find("ffprobe") == std::string::npos)
      FAIL() << "ffmpeg and ffprobe are needed (scripts/setup.sh installs them)";
  }
};

TEST_F(Record, Mp4HasTheFramesAndSizeAskedForAndIsTheSameBytesWhenRepeated) {
  const std::string first = outputPath("clip1.mp4"), second = outputPath("clip2.mp4");
  for (const std::string& path : {first, second}) {
    removeClipAndItsPartials(path);
    const CommandResult run = runSlime("record -o " + path + kRecordScenario + " --seconds 1.2 --fps 10 --size 96x64"
                                       " --set render.caustics=false");  // the clip, not the light: 4 s, not 24
    ASSERT_EQ(run.exitCode, 0) << run.output;
  }
  const std::string probe = runShell("ffprobe -v error -count_frames -select_streams v:0 -show_entries "
                                     "stream=nb_read_frames,width,height -of csv=p=0 " + first);
  EXPECT_EQ(probe, "96,64,12\n") << "width,height,frames";
  const std::string bytes = fileBytes(first);
  EXPECT_FALSE(bytes.empty());
  EXPECT_TRUE(bytes == fileBytes(second)) << "two recordings of the same scenario differ";
  EXPECT_EQ(partialFilesOf(first).size() + partialFilesOf(second).size(), 0u);
}

TEST_F(Record, GifAndWebpHaveEveryFrame) {
  const std::string gif = outputPath("clip.gif"), webp = outputPath("clip.webp");
  for (const std::string& path : {gif, webp}) {
    std::filesystem::remove(path);
    const CommandResult run = runSlime("record -o " + path + kRecordScenario + " --seconds 0.5 --fps 8 --size 64x48");
    ASSERT_EQ(run.exitCode, 0) << run.output;
  }
  EXPECT_EQ(runShell("ffprobe -v error -count_frames -show_entries stream=nb_read_frames,width,height -of csv=p=0 " + gif),
            "64,48,4\n");
  // FFmpeg 5.1 cannot decode animated WebP: count its frame chunks (ANMF) instead.
  const std::string bytes = fileBytes(webp);
  ASSERT_GT(bytes.size(), 12u);
  EXPECT_EQ(bytes.substr(0, 4), "RIFF");
  EXPECT_EQ(bytes.substr(8, 4), "WEBP");
  int frames = 0;
  for (std::size_t at = bytes.find("ANMF"); at != std::string::npos; at = bytes.find("ANMF", at + 4)) ++frames;
  EXPECT_EQ(frames, 4);
}

struct BadRecord {
  const char* arguments;  // after `record -o <output>`
  const char* output;
  const char* mentions;
};

void PrintTo(const BadRecord& bad, std::ostream* out) { *out << bad.arguments << " -> " << bad.output; }

// Each case writes its own file name: ctest runs the cases side by side.
class RecordRejects : public testing::TestWithParam<BadRecord> {};

TEST_P(RecordRejects, WithExitCodeTwoAndNoFile) {
  const BadRecord& bad = GetParam();
  removeClipAndItsPartials(bad.output);
  const CommandResult run = runSlime("record -o " + std::string(bad.output) + kRecordScenario + " " + bad.arguments);
  EXPECT_EQ(run.exitCode, 2) << bad.arguments << "\n" << run.output;
  EXPECT_NE(run.output.find(bad.mentions), std::string::npos) << bad.arguments << "\n" << run.output;
  EXPECT_FALSE(std::filesystem::exists(bad.output)) << bad.output;
  EXPECT_EQ(partialFilesOf(bad.output).size(), 0u);
}

INSTANTIATE_TEST_SUITE_P(
    Cli, RecordRejects,
    testing::Values(BadRecord{"--seconds 1", SLIME_TEST_OUTPUT_DIR "/bad.avi", ".mp4, .gif or .webp"},
                    BadRecord{"--seconds 0", SLIME_TEST_OUTPUT_DIR "/bad_seconds_zero.mp4", "--seconds"},
                    BadRecord{"--seconds -2", SLIME_TEST_OUTPUT_DIR "/bad_seconds_negative.mp4", "--seconds"},
                    BadRecord{"--seconds 1 --fps 0", SLIME_TEST_OUTPUT_DIR "/bad_fps.mp4", "--fps"},
                    BadRecord{"--seconds 1 --size 95x64", SLIME_TEST_OUTPUT_DIR "/bad_size.mp4", "even"},
                    BadRecord{"--seconds 1", "/nonexistent/dir/bad.mp4", "does not exist"},
                    BadRecord{"--seconds 1", "/proc/bad.mp4", "cannot write in /proc"},
                    BadRecord{"--seconds 1 --set slime.level=12", SLIME_TEST_OUTPUT_DIR "/bad_level.mp4", "slime.level"},
                    // Found once ffmpeg runs: the clip's temporary file must go too.
                    BadRecord{"--seconds 1 --set floor.pattern=image --set floor.image=/nonexistent.png",
                              SLIME_TEST_OUTPUT_DIR "/bad_floor_image.mp4", "floor.image"}),
    // Named by their place in the list and what they expect to be named (not the pointers' bytes).
    [](const testing::TestParamInfo<BadRecord>& info) {
      std::string name = std::to_string(info.index) + "_";
      for (const char* c = info.param.mentions; *c; ++c) name += std::isalnum(static_cast<unsigned char>(*c)) ? *c : '_';
      return name;
    });

TEST(Cli, RecordWithoutFfmpegSaysSoAndLeavesNoFile) {
  const std::string path = outputPath("no_ffmpeg.mp4");
  removeClipAndItsPartials(path);
  const std::string output =
      runShell("env PATH=/nonexistent " + std::string(SLIME_BINARY) + " record -o " + path + " --seconds 1; echo exit=$?");
  EXPECT_NE(output.find("ffmpeg"), std::string::npos) << output;
  EXPECT_NE(output.find("exit=2"), std::string::npos) << output;
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_EQ(partialFilesOf(path).size(), 0u);
}

}  // namespace

// `slime view --check-every K` run headless (issue 28): the viewer measures what it shows against the
// full trace of the same physics state and camera, and the exit report carries the figures.
#include "viewer_fixture.h"
#include "app/viewer/headless_gl.h"
#include "app/viewer/viewer.h"
#include "core/geometry/camera.h"
#include "core/settings/settings_io.h"
#include "core/simulation/scenario.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>

namespace slime {
namespace {

nlohmann::json runAndReport(const Settings& settings, int frames, int every, const std::string& name,
                            ViewerOptions options = {}) {
  const std::filesystem::path report = std::filesystem::path(SLIME_TEST_OUTPUT_DIR) / name;
  std::filesystem::remove(report);
  options.checkEvery = every;
  options.maxFrames = frames;
  options.reportPath = report.string();
  options.refineBandMs = 1e9;  // bands of half the image, whatever the machine's speed: 2 frames a sample
  fixture::SteppingHeadlessGl backend(320, 240, 1.0 / 30.0);
  Viewer viewer(backend, settings, options);
  EXPECT_EQ(viewer.run(), 0);
  std::ifstream file(report);
  return nlohmann::json::parse(file);
}

// The falling, landing slime: every frame traces anew, reusing the floor's pixels outside the slime's
// footprint; each checked frame must match the full trace.
TEST(ViewerCheck, TheFallingSlimeShowsTheFullTracesImage) {
  const nlohmann::json check = runAndReport(fixture::smallViewerScene(), 12, 3, "viewer_check_falling.json")["check"];
  EXPECT_EQ(check["every"], 3);
  EXPECT_EQ(check["frames"], 4);  // frames 0, 3, 6 and 9 of 0..11
  EXPECT_GE(check["psnr_db"]["mean"].get<double>(), 38.0);
  EXPECT_GE(check["psnr_db"]["min"].get<double>(), 32.0);
  EXPECT_EQ(check["while_handled"]["frames"], 0);  // nobody held it
}

// A still slime: the first frame's one-sample image is checked against the one-sample trace, the
// refining frames are skipped, and the fully refined image against the 16-sample trace (render.spp = 16).
TEST(ViewerCheck, AStillImageRefinesToTheSixteenSampleTrace) {
  Settings settings = fixture::smallViewerScene();
  settings.sim.gravity = 0.0;  // nothing moves
  const nlohmann::json check = runAndReport(settings, 40, 1, "viewer_check_still.json")["check"];
  EXPECT_GT(check["skipped_refining_frames"].get<int>(), 5);
  EXPECT_GE(check["frames"].get<int>(), 10);  // before refining starts, and once it has converged
  EXPECT_GE(check["psnr_db"]["min"].get<double>(), 40.0);
}

// slime.tearing: a piece torn off and carried by one hand while the other pins the rest must be drawn
// where it is, in every checked frame (the viewer judging motion by the first piece alone left the
// carried piece where it was last drawn), and the full trace draws every piece too.
TEST(ViewerCheck, ATornPieceCarriedAloneIsDrawnWhereItIs) {
  Settings settings = fixture::smallViewerScene();
  settings.slime.tearing = true;
  settings.slime.level = 4;  // the default: the scenario's pinch tears at it (not at level 2's)
  settings.render.caustics = false;  // each check traces the full image afresh: the photons would double it
  lookAt(settings.camera, {0.06, -0.36, 0.15}, {0.06, 0.0, 0.02});  // the carried piece stays in the picture
  ViewerOptions options;
  options.scenario = loadScenario(std::string(SLIME_SOURCE_DIR) + "/tests/scenarios/tear_off_and_press_back.json");
  // Frames of 1/30 s (less the checks' time) to 2.6 s simulated: past the tear (1.29 s) and while the piece
  // is carried back (2.0-2.6 s); at most 400 frames.
  options.quitAtSimulatedSeconds = 2.6;
  const nlohmann::json report = runAndReport(settings, 400, 2, "viewer_check_torn.json", options);
  EXPECT_GE(report["simulated_seconds"].get<double>(), 2.6 - 1e-6);
  EXPECT_EQ(report["peak_pieces"], 2);
  const nlohmann::json& check = report["check"];
  EXPECT_GE(check["while_handled"]["frames"].get<int>(), 20);
  EXPECT_GE(check["while_handled"]["psnr_db"]["mean"].get<double>(), 38.0);
  EXPECT_GE(check["while_handled"]["psnr_db"]["min"].get<double>(), 32.0);
}

}  // namespace
}  // namespace slime

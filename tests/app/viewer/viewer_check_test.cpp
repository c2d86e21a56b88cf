// `slime view --check-every K` run headless (issue 28): the viewer measures what it shows against the
// full trace of the same physics state and camera, and the exit report carries the figures.
#include "viewer_fixture.h"
#include "app/viewer/headless_gl.h"
#include "app/viewer/viewer.h"
#include "core/settings/settings_io.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

namespace slime {
namespace {

nlohmann::json runAndReport(const Settings& settings, int frames, int every, const std::string& name) {
  const std::filesystem::path report = std::filesystem::path(SLIME_TEST_OUTPUT_DIR) / name;
  std::filesystem::remove(report);
  ViewerOptions options;
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

}  // namespace
}  // namespace slime

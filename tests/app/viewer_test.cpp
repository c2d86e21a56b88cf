// The viewer's frame code, run headless (EGL surfaceless, no display): the same code as the window.
#include "app/viewer/headless_gl.h"
#include "app/viewer/panels.h"
#include "app/viewer/ui_snapshot.h"
#include "app/viewer/viewer.h"
#include "core/settings_io.h"
#include "render/image_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

namespace slime {
namespace {

Settings smallScene() {
  Settings settings = defaultSettings();
  settings.camera.width = 320;
  settings.camera.height = 240;
  settings.slime.level = 2;
  return settings;
}

TEST(HeadlessViewer, RunsFramesWithoutAdvancingThePhysicsClock) {
  HeadlessGl backend(320, 240);
  Viewer viewer(backend, smallScene(), ViewerOptions{});
  for (int frame = 0; frame < 3; ++frame) EXPECT_TRUE(viewer.frame());
  EXPECT_EQ(viewer.stats().frames, 3);
  EXPECT_EQ(viewer.simulation().stepCount(), 0);  // headless time stands still: a snapshot is reproducible
  // Nobody is interacting: the full-resolution image, filling the window right of the panel column.
  EXPECT_EQ(viewer.stats().imageWidth, 320 - static_cast<int>(std::lround(panelColumnWidth(320.0f))));
  EXPECT_EQ(viewer.stats().imageHeight, 240);
  EXPECT_GT(viewer.stats().rays, 0u);
}

TEST(HeadlessViewer, StopsAfterTheRequestedNumberOfFrames) {
  HeadlessGl backend(64, 48);
  ViewerOptions options;
  options.maxFrames = 2;
  Viewer viewer(backend, smallScene(), options);
  EXPECT_TRUE(viewer.frame());
  EXPECT_FALSE(viewer.frame());
}

// Progressive anti-aliasing (issue 15): a still view refines frame after frame up to 16 samples per
// pixel at full resolution, and a change (here the slime moved) starts it again from one sample.
TEST(HeadlessViewer, AStillImageRefinesToSixteenSamplesAndAChangeResetsIt) {
  HeadlessGl backend(320, 240);  // room for the image beside the panel column
  Settings settings = smallScene();
  Viewer viewer(backend, settings, ViewerOptions{});
  ASSERT_TRUE(viewer.frame());
  EXPECT_EQ(viewer.stats().samplesPerPixel, 1);
  for (int frame = 0; frame < ViewerOptions{}.refineSamples + 2; ++frame) ASSERT_TRUE(viewer.frame());
  EXPECT_EQ(viewer.stats().samplesPerPixel, ViewerOptions{}.refineSamples);
  EXPECT_EQ(viewer.stats().imageWidth, 320 - static_cast<int>(std::lround(panelColumnWidth(320.0f))));
  for (int step = 0; step < 50; ++step) viewer.simulation().step();  // the slime falls a visible distance
  viewer.simulationAdvanced();
  ASSERT_TRUE(viewer.frame());
  EXPECT_EQ(viewer.stats().samplesPerPixel, 1);
}

TEST(UiSnapshot, WritesTheWindowWithItsPanelsAtTheCameraSize) {
  const std::filesystem::path path = std::filesystem::path(SLIME_TEST_OUTPUT_DIR) / "ui_snapshot_test.png";
  std::filesystem::remove(path);
  int settleCalls = 0;
  writeUiSnapshot(smallScene(), path.string(), [&](Simulation& simulation) {
    ++settleCalls;
    for (int step = 0; step < 100; ++step) simulation.step();
  });
  EXPECT_EQ(settleCalls, 1);
  const Image image = readPng(path.string());
  EXPECT_EQ(image.width, 320);
  EXPECT_EQ(image.height, 240);
  // The Controls window's title bar is at the top left: ImGui's dark title colour, not the scene.
  const glm::vec3 title = image.at(20, 10);
  EXPECT_LT(title.r + title.g + title.b, 0.3f) << "no panel title bar at (20, 10)";
}

}  // namespace
}  // namespace slime

// The viewer's frame code, run headless (EGL surfaceless, no display): the same code as the window.
#include "viewer_fixture.h"
#include "app/viewer/headless_gl.h"
#include "app/viewer/panels.h"
#include "app/viewer/ui_snapshot.h"
#include "app/viewer/viewer.h"
#include "core/geometry/level_of_detail.h"
#include "core/simulation/scenario.h"
#include "core/settings/settings_io.h"
#include "render/image/image_io.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace slime {
namespace {

using fixture::SteppingHeadlessGl;

nlohmann::json readJson(const std::filesystem::path& path) {
  std::ifstream file(path);
  return nlohmann::json::parse(file);
}

TEST(HeadlessViewer, RunsFramesWithoutAdvancingThePhysicsClock) {
  HeadlessGl backend(320, 240);
  Viewer viewer(backend, fixture::smallViewerScene(), ViewerOptions{});
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
  Viewer viewer(backend, fixture::smallViewerScene(), options);
  EXPECT_TRUE(viewer.frame());
  EXPECT_FALSE(viewer.frame());
}

// Progressive anti-aliasing (issue 15): a still view refines frame after frame up to 16 samples per
// pixel at full resolution, and a change (here the slime moved) starts it again from one sample.
TEST(HeadlessViewer, AStillImageRefinesToSixteenSamplesAndAChangeResetsIt) {
  HeadlessGl backend(320, 240);  // room for the image beside the panel column
  Settings settings = fixture::smallViewerScene();
  Viewer viewer(backend, settings, ViewerOptions{});
  ASSERT_TRUE(viewer.frame());
  EXPECT_EQ(viewer.stats().samplesPerPixel, 1);
  // Each sample is traced a band of rows a frame (Viewer::kRefineBandMs): a few frames a sample.
  for (int frame = 0; frame < 600 && viewer.stats().samplesPerPixel < ViewerOptions{}.refineSamples; ++frame)
    ASSERT_TRUE(viewer.frame());
  EXPECT_EQ(viewer.stats().samplesPerPixel, ViewerOptions{}.refineSamples);
  EXPECT_EQ(viewer.stats().imageWidth, 320 - static_cast<int>(std::lround(panelColumnWidth(320.0f))));
  for (int step = 0; step < 50; ++step) viewer.simulation().step();  // the slime falls a visible distance
  viewer.simulationAdvanced();
  ASSERT_TRUE(viewer.frame());
  EXPECT_EQ(viewer.stats().samplesPerPixel, 1);
}

// render.spp above the refinement's 16 samples: each frame still traces one sample a pixel, and the
// still image refines to render.spp's (tracing all 64 in a frame took seconds).
TEST(HeadlessViewer, SupersamplingIsReachedByRefiningNotInOneFrame) {
  HeadlessGl backend(320, 240);  // room for the image beside the panel column
  Settings settings = fixture::smallViewerScene();
  settings.render.spp = 25;
  Viewer viewer(backend, settings, ViewerOptions{});
  ASSERT_TRUE(viewer.frame());
  EXPECT_EQ(viewer.stats().samplesPerPixel, 1);
  // One sample a pixel: a few rays each (primary, shadow, the slime's refraction), not 25 of them.
  const double pixels = static_cast<double>(viewer.stats().imageWidth) * viewer.stats().imageHeight;
  EXPECT_LT(static_cast<double>(viewer.stats().rays), 10.0 * pixels);
  for (int frame = 0; frame < 900 && viewer.stats().samplesPerPixel < 25; ++frame) ASSERT_TRUE(viewer.frame());
  EXPECT_EQ(viewer.stats().samplesPerPixel, 25);
}

// A slime that moves every third frame (creeping past the redraw threshold) is redrawn when it moves
// and not refined between its moves: the bands of a refinement sample would be thrown away by the next
// move. Once still, it refines within a few frames.
TEST(HeadlessViewer, ASlimeMovingEveryFewFramesIsNotRefinedBetweenItsMoves) {
  SteppingHeadlessGl backend(320, 240, 0.0);  // no physics inside the frames: the test moves the slime
  Viewer viewer(backend, fixture::smallViewerScene(), ViewerOptions{});
  ASSERT_TRUE(viewer.frame());
  for (int move = 0; move < 3; ++move) {
    for (int step = 0; step < 100; ++step) viewer.simulation().step();  // the slime falls a visible distance
    viewer.simulationAdvanced();
    ASSERT_TRUE(viewer.frame());
    EXPECT_EQ(viewer.stats().samplesPerPixel, 1) << "move " << move;
    for (int frame = 0; frame < 2; ++frame) {
      ASSERT_TRUE(viewer.frame());
      EXPECT_EQ(viewer.stats().tracedRows, 0) << "refined between two moves, after move " << move;
    }
  }
  // Still, it refines within a few frames: the first band of the first sample is traced at the
  // kStillFramesBeforeRefining-th frame after the move.
  ASSERT_TRUE(viewer.frame());
  EXPECT_GT(viewer.stats().tracedRows, 0) << "still for " << Viewer::kStillFramesBeforeRefining << " frames";
}

// Moves the floating slime (no gravity) up by about `pixels` as the viewer measures motion
// (largestMotionPixels at the image's height), in one step at the speed that covers it, then stops it.
void creepUp(Viewer& viewer, double pixels) {
  Simulation& simulation = viewer.simulation();
  const Settings& settings = viewer.settings();
  const std::vector<glm::dvec3> before = simulation.positions();
  std::vector<glm::dvec3> shifted = before;
  for (glm::dvec3& p : shifted) p.z += 1e-6;
  const double pixelsPerMetre = 1e6 * largestMotionPixels(before, shifted, settings.camera.position, settings.camera.fov,
                                                          viewer.stats().imageHeight);
  const double speed = pixels / pixelsPerMetre / settings.sim.dt;
  simulation.setVelocities(std::vector<glm::dvec3>(simulation.state().size(), glm::dvec3(0.0, 0.0, speed)));
  simulation.step();
  simulation.setVelocities(std::vector<glm::dvec3>(simulation.state().size(), glm::dvec3(0.0)));
  viewer.simulationAdvanced();
}

// Issue 43: a slime that has crept less than kStillMotionPixels from where the image's refinement
// started is not traced again: the refinement keeps counting to its 16 samples. The creep is measured
// from that start, not from the last frame: creeping on in moves each under the threshold, past it in
// all, traces the slime again and restarts the refinement.
TEST(HeadlessViewer, ASlimeStillEnoughKeepsRefiningUntilItsCreepFromTheStartShows) {
  Settings settings = fixture::smallViewerScene();
  settings.sim.gravity = 0.0;  // the slime floats: only the test moves it
  SteppingHeadlessGl backend(320, 240, 0.0);
  ViewerOptions options;
  Viewer viewer(backend, settings, options);
  ASSERT_TRUE(viewer.frame());
  const std::vector<glm::dvec3> start = viewer.simulation().positions();
  const auto creptPixels = [&] {
    return largestMotionPixels(start, viewer.simulation().positions(), settings.camera.position, settings.camera.fov,
                               viewer.stats().imageHeight);
  };
  // Refining: a few samples in, the slime creeps 0.3 of the threshold, twice.
  int frames = 0;
  while (viewer.stats().samplesPerPixel < 4 && frames++ < 300) ASSERT_TRUE(viewer.frame());
  ASSERT_GE(viewer.stats().samplesPerPixel, 4);
  for (int move = 0; move < 2; ++move) {
    creepUp(viewer, 0.3 * kStillMotionPixels);
    ASSERT_LT(creptPixels(), kStillMotionPixels) << "the test crept too far";
    int samples = viewer.stats().samplesPerPixel;
    for (int frame = 0; frame < 10; ++frame) {
      ASSERT_TRUE(viewer.frame());
      EXPECT_LT(viewer.stats().tracedRows, viewer.stats().imageHeight) << "traced anew after a creep of " << creptPixels() << " px";
      EXPECT_GE(viewer.stats().samplesPerPixel, samples) << "the refinement restarted after a creep of " << creptPixels() << " px";
      samples = viewer.stats().samplesPerPixel;
    }
  }
  frames = 0;
  while (viewer.stats().samplesPerPixel < options.refineSamples && frames++ < 600) ASSERT_TRUE(viewer.frame());
  EXPECT_EQ(viewer.stats().samplesPerPixel, options.refineSamples) << "still enough, it refines to the end";
  // Once more 0.6 of the threshold: under it since the last move, over it since the start.
  creepUp(viewer, 0.6 * kStillMotionPixels);
  ASSERT_GT(creptPixels(), kStillMotionPixels);
  ASSERT_TRUE(viewer.frame());
  EXPECT_EQ(viewer.stats().tracedRows, viewer.stats().imageHeight) << "crept " << creptPixels() << " px, not traced anew";
  EXPECT_EQ(viewer.stats().samplesPerPixel, 1);
}

// Issue 43: a refinement sample is never traced in one frame. It is traced a band of rows a frame, at
// most half the image, so the frames of a still, refining image stay within their budget.
TEST(HeadlessViewer, ARefinementSampleIsTracedOverSeveralFrames) {
  Settings settings = fixture::smallViewerScene();
  settings.sim.gravity = 0.0;
  SteppingHeadlessGl backend(320, 240, 1.0 / 60.0);
  ViewerOptions options;
  Viewer viewer(backend, settings, options);
  ASSERT_TRUE(viewer.frame());
  const int height = viewer.stats().imageHeight;
  ASSERT_EQ(viewer.stats().tracedRows, height);  // the first image: whole
  int frames = 0, bands = 0, rows = 0;
  while (viewer.stats().samplesPerPixel < options.refineSamples && frames++ < 600) {
    ASSERT_TRUE(viewer.frame());
    const int band = viewer.stats().tracedRows;
    if (band == 0) continue;
    ++bands;
    rows += band;
    EXPECT_LE(band, height / 2) << "frame " << frames << " traced " << band << " of " << height << " rows";
  }
  EXPECT_EQ(viewer.stats().samplesPerPixel, options.refineSamples);
  EXPECT_EQ(rows, options.refineSamples * height) << "the samples' bands do not add up to their images";
  EXPECT_GE(bands, 2 * options.refineSamples);
}

// A still scene: the frames that trace (the first image, then its 16 refining samples) never wait;
// every other frame (waiting for stillness before refining, and after the image has its samples) has
// nothing new to trace and waits for input up to the idle frame time (the rest of 1/60 s after its
// own work), so a still window does not spin a core.
TEST(HeadlessViewer, FramesWithNothingNewToTraceWaitForInput) {
  Settings settings = fixture::smallViewerScene();
  settings.sim.gravity = 0.0;  // the slime floats where it starts: nothing moves
  SteppingHeadlessGl backend(320, 240, 1.0 / 30.0);
  ViewerOptions options;
  Viewer viewer(backend, settings, options);
  int frames = 0, tracing = 0;  // frames, and those that traced (the first image, then its samples' bands)
  while (viewer.stats().samplesPerPixel < options.refineSamples && frames < 600) {
    ASSERT_TRUE(viewer.frame());
    ++frames;
    tracing += viewer.stats().tracedRows > 0;
  }
  ASSERT_EQ(viewer.stats().samplesPerPixel, options.refineSamples);
  EXPECT_GT(tracing, 1 + options.refineSamples) << "a sample was traced in one frame";
  EXPECT_EQ(static_cast<int>(backend.waits.size()), frames - tracing) << "over " << frames << " frames";
  const std::size_t before = backend.waits.size();
  for (int frame = 0; frame < 5; ++frame) ASSERT_TRUE(viewer.frame());
  ASSERT_EQ(backend.waits.size(), before + 5) << "a frame of a still, refined image did not wait for input";
  for (std::size_t i = before; i < backend.waits.size(); ++i) EXPECT_LE(backend.waits[i], Viewer::kIdleFrameSeconds);
}

// `slime view --scenario` (issue 15's scripted drag): the scenario's grab takes hold of the resting
// slime and its drags pull it up, and the exit report says so, as it does for a grab with the mouse.
// The bench's own scenario, run until half a second after its grab, at 60 frames a second (few steps
// a frame, so that a sanitizer build's slow physics stays within the viewer's physics budget).
TEST(HeadlessViewer, AScenarioGrabTakesHoldAndTheReportCountsIt) {
  const Scenario scenario = loadScenario(SLIME_SOURCE_DIR "/tests/scenarios/drag_top_in_circles_6s.json");
  const auto grab = std::find_if(scenario.events.begin(), scenario.events.end(), [](const ScenarioEvent& event) {
    return event.kind == ScenarioEvent::Kind::Grab;
  });
  ASSERT_NE(grab, scenario.events.end());
  const std::filesystem::path report =
      std::filesystem::path(SLIME_TEST_OUTPUT_DIR) / "viewer_scenario_report.json";
  const std::filesystem::path frameLog =
      std::filesystem::path(SLIME_TEST_OUTPUT_DIR) / "viewer_scenario_frames.csv";
  std::filesystem::remove(report);
  std::filesystem::remove(frameLog);
  constexpr double kSecondsPerFrame = 1.0 / 60.0;
  ViewerOptions options;
  options.scenario = scenario;
  options.reportPath = report.string();
  options.frameLogPath = frameLog.string();
  // Half as many frames again: a sanitizer build's physics may not keep up with every frame (the
  // clock then drops what it cannot step), and the checks below need only half a second past the grab.
  options.maxFrames = static_cast<int>(std::ceil(1.5 * (grab->time + 0.5) / kSecondsPerFrame));
  SteppingHeadlessGl backend(320, 240, kSecondsPerFrame);
  Viewer viewer(backend, fixture::smallViewerScene(), options);
  ASSERT_EQ(viewer.run(), 0);
  ASSERT_GT(viewer.simulation().time(), grab->time + 0.3) << "the physics fell behind the frames";

  const nlohmann::json result = readJson(report);
  ASSERT_TRUE(result.contains("machine")) << "the report does not say which machine measured it";
  EXPECT_FALSE(result["machine"]["cpu"].get<std::string>().empty());
  EXPECT_GE(result["machine"]["cores"].get<int>(), 1);
  EXPECT_EQ(result["grabs"], 1);
  EXPECT_EQ(result["grabbing"], true);
  const double restingHeight = result["height_at_grab"];
  EXPECT_GT(restingHeight, 0.05);  // the settled bun (5.9 cm at the default radius), not 0
  EXPECT_LT(restingHeight, 0.065);
  EXPECT_GT(result["peak_height_while_grabbing"].get<double>(), 1.15 * restingHeight);

  // No target frame rate (the default): every traced frame at full resolution, the drag included.
  EXPECT_EQ(result["traced_reduced_resolution_frames"], 0);
  EXPECT_EQ(result["traced_full_resolution_frames"], result["traced_frames"]);
  const nlohmann::json& grabbed = result["while_grabbed"];
  EXPECT_GE(grabbed["frames"].get<int>(), 25);  // the last half second, at 60 frames a second
  EXPECT_GT(grabbed["mean_fps"].get<double>(), 0.0);
  EXPECT_GT(grabbed["mean_stage_ms"]["trace"].get<double>(), 0.0);

  // The frame log: a header, then one line per frame; the slime is held in the last ones.
  std::ifstream log(frameLog);
  std::string line, last;
  int lines = 0;
  while (std::getline(log, line)) ++lines, last = line;
  EXPECT_EQ(lines, 1 + options.maxFrames);
  // grabbed is the 14th of the 18 columns (simulated_s, check_psnr_db, caustics_ms, caustic_photons follow it).
  std::vector<std::string> columns;
  std::stringstream fields(last);
  for (std::string field; std::getline(fields, field, ',');) columns.push_back(field);
  ASSERT_GE(columns.size(), 14u) << last;
  EXPECT_EQ(columns[13], "1") << "the last frame is not marked grabbed: " << last;
}

// With a target frame rate the frames cannot meet (240 fps), the falling slime's frames go over budget
// while it moves: the image is traced smaller, and the report counts those frames. Once a frame needs
// no new image (the slime rests, or creeps too little to show) it is traced at full resolution again.
TEST(HeadlessViewer, FramesOverTheTargetWhileTheSlimeMovesAreTracedSmaller) {
  ViewerOptions options;
  const std::filesystem::path report =
      std::filesystem::path(SLIME_TEST_OUTPUT_DIR) / "viewer_adaptive_report.json";
  options.reportPath = report.string();
  // 640×480, a 390-pixel image beside the panels: at 320×240 the image is 70 pixels wide, which an AVX-512
  // F26 traced within the 4.2 ms budget, so whether a frame went over depended on the load (2026-11-28).
  const int width = 640, height = 480;
  SteppingHeadlessGl backend(width, height, 1.0 / 30.0);
  Settings settings = fixture::smallViewerScene();
  settings.render.targetFps = 240.0;  // a scene file's or --set's, as --target-fps sets it
  Viewer viewer(backend, settings, options);
  const int fullWidth = width - static_cast<int>(std::lround(panelColumnWidth(static_cast<float>(width))));
  int smallest = fullWidth;
  for (int frame = 0; frame < 30; ++frame) {  // the first second: it falls, lands and jiggles
    ASSERT_TRUE(viewer.frame());
    smallest = std::min(smallest, viewer.stats().imageWidth);
  }
  EXPECT_LT(smallest, fullWidth);
  EXPECT_GE(smallest, static_cast<int>(AdaptiveResolution::kMinimumScale * fullWidth) - 1);
  EXPECT_GT(viewer.stats().reducedResolutionFrames, 0);
  for (int frame = 0; frame < 300 && viewer.stats().renderScale < 1.0; ++frame) ASSERT_TRUE(viewer.frame());
  EXPECT_EQ(viewer.stats().renderScale, 1.0) << "still reduced after 10 s: the slime rests by then";
  EXPECT_EQ(viewer.stats().imageWidth, fullWidth);
}

// A scenario's "set" event edits the settings the trace reads: it is applied, and the frame it fires
// in traces the scene anew. Without gravity the slime hangs still, so until then the image refines.
TEST(HeadlessViewer, AScenarioSetEventIsAppliedAndDrawnAtOnce) {
  ViewerOptions options;
  const char* kSetColour = R"({"events": [{"t": 1.0, "set": {"slime.color": [0.9, 0.2, 0.2]}}]})";
  options.scenario = parseScenario(nlohmann::json::parse(kSetColour), "inline");
  Settings settings = fixture::smallViewerScene();
  settings.sim.gravity = 0.0;
  SteppingHeadlessGl backend(320, 240, 1.0 / 60.0);
  Viewer viewer(backend, settings, options);
  int frames = 0, samples = 1;
  while (viewer.settings().slime.color == settings.slime.color && frames++ < 120) {
    EXPECT_GE(viewer.stats().samplesPerPixel, samples) << "a still image stopped refining";
    samples = viewer.stats().samplesPerPixel;
    ASSERT_TRUE(viewer.frame());
  }
  EXPECT_GT(samples, 1) << "a still image did not refine in " << frames << " frames";
  EXPECT_EQ(viewer.settings().slime.color, glm::dvec3(0.9, 0.2, 0.2));
  EXPECT_EQ(viewer.stats().samplesPerPixel, 1) << "the new colour was not traced in the frame it was set";
}

TEST(HeadlessViewer, AScenarioOrbitTurnsTheCameraAboutTheSlimeAndItsFramesAreOrbiting) {
  ViewerOptions options;
  options.scenario = parseScenario(nlohmann::json::parse(R"({"events": [
    {"t": 0.1, "orbit": {"yaw": 90, "duration": 0.2}},
    {"t": 0.5, "set": {"slime.color": [0.9, 0.2, 0.2]}}]})"), "inline");
  options.frameLogPath = (std::filesystem::path(SLIME_TEST_OUTPUT_DIR) / "viewer_orbit_frames.csv").string();
  Settings settings = fixture::smallViewerScene();
  settings.sim.gravity = 0.0;
  SteppingHeadlessGl backend(160, 120, 1.0 / 60.0);
  Viewer viewer(backend, settings, options);
  const glm::dvec3 centre = settings.slime.position;
  const double distance = glm::length(settings.camera.position - centre);
  for (int frame = 0; frame < 50; ++frame) ASSERT_TRUE(viewer.frame());
  // A quarter turn about +z at the same distance (the slime, weightless, stays where it started).
  const glm::dvec3 before = settings.camera.position - centre, after = viewer.settings().camera.position - centre;
  EXPECT_NEAR(glm::length(after), distance, 1e-3 * distance);
  EXPECT_NEAR(std::atan2(after.y, after.x) - std::atan2(before.y, before.x), M_PI / 2.0, 0.02);
  int orbiting = 0, editing = 0;
  for (const FrameRecord& record : viewer.frameRecords()) {
    orbiting += record.phase == FramePhase::Orbiting;
    editing += record.phase == FramePhase::Editing;
  }
  EXPECT_GE(orbiting, 10) << "0.2 s of orbit at 60 frames a second";
  EXPECT_LE(orbiting, 14);
  EXPECT_EQ(editing, 1) << "a set event fires before its frame's trace, which draws it";
}

TEST(HeadlessViewer, AnOrbitOverItsBudgetIsTracedSmallerAndTheFrameAfterItInFull) {
  ViewerOptions options;
  options.scenario = parseScenario(nlohmann::json::parse(R"({"events": [
    {"t": 0.1, "orbit": {"yaw": 90, "duration": 0.3}}]})"), "inline");
  options.frameLogPath = (std::filesystem::path(SLIME_TEST_OUTPUT_DIR) / "viewer_orbit_budget_frames.csv").string();
  Settings settings = fixture::smallViewerScene();
  settings.sim.gravity = 0.0;
  settings.render.orbitFps = 240.0;  // 4.2 ms a frame: more than a headless frame with panels can meet
  SteppingHeadlessGl backend(320, 240, 1.0 / 60.0);
  Viewer viewer(backend, settings, options);
  for (int frame = 0; frame < 40; ++frame) ASSERT_TRUE(viewer.frame());
  const std::vector<FrameRecord>& records = viewer.frameRecords();
  int smaller = 0;
  std::size_t last = 0;
  for (std::size_t i = 0; i < records.size(); ++i) {
    if (records[i].phase != FramePhase::Orbiting) continue;
    smaller += records[i].scale < 1.0;
    last = i;
  }
  EXPECT_GE(smaller, 5) << "orbiting frames over render.orbitFps's budget stayed at full size";
  ASSERT_LT(last + 1, records.size());
  EXPECT_EQ(records[last + 1].scale, 1.0) << "the frame after the camera stopped was not traced in full";
  EXPECT_TRUE(records[last + 1].fullResolution);
  for (std::size_t i = 0; i < records.size(); ++i) {
    if (records[i].phase == FramePhase::Orbiting) continue;
    EXPECT_EQ(records[i].scale, 1.0) << "frame " << i;
  }
}

TEST(UiSnapshot, WritesTheWindowWithItsPanelsAtTheCameraSize) {
  const std::filesystem::path path = std::filesystem::path(SLIME_TEST_OUTPUT_DIR) / "ui_snapshot_test.png";
  std::filesystem::remove(path);
  int settleCalls = 0;
  writeUiSnapshot(fixture::smallViewerScene(), path.string(), [&](Simulation& simulation) {
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

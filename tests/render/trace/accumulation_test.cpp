// Progressive anti-aliasing (render/trace/accumulation_buffer.h): frames traced at the sequence's points of
// each pixel and averaged give the image that render.spp traces at once; the sequence keeps the
// shown average centred; a new start (what the viewer does when the camera moves) forgets the sum.
#include "render/trace/accumulation_buffer.h"
#include "render_fixture.h"

#include <gtest/gtest.h>

#include <set>
#include <utility>

namespace slime::testing {
namespace {

TEST(AccumulationBuffer, OffsetsAreTheSupersamplingGridInMirroredPairs) {
  const AccumulationBuffer buffer(16);
  std::set<std::pair<float, float>> points;
  for (int k = 0; k < 16; ++k) {
    const glm::vec2 offset = buffer.offset(k);
    points.insert({offset.x, offset.y});
    if (k % 2 == 1) {  // each pair averages to the pixel's centre
      EXPECT_FLOAT_EQ(0.5f * (offset.x + buffer.offset(k - 1).x), 0.5f);
      EXPECT_FLOAT_EQ(0.5f * (offset.y + buffer.offset(k - 1).y), 0.5f);
    }
  }
  std::set<std::pair<float, float>> grid;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) grid.insert({(x + 0.5f) / 4, (y + 0.5f) / 4});
  EXPECT_EQ(points, grid);
  EXPECT_EQ(AccumulationBuffer(1).offset(0), glm::vec2(0.5f));
}

TEST(AccumulationBuffer, SixteenOffsetFramesOfAStillSceneEqualTheSixteenSampleSnapshot) {
  Settings settings = smallScene(96, 72);
  settings.slime.level = 3;
  Settings supersampled = settings;
  supersampled.render.spp = 16;
  const Image expected = renderScene(supersampled);

  const TriangleMesh mesh = restingMesh(settings);
  Renderer renderer(settings);
  renderer.updateSlime({mesh});
  AccumulationBuffer buffer(16);
  Image frame, average;
  frame.resize(settings.camera.width, settings.camera.height);
  int shown = 0;
  while (!buffer.converged()) {
    renderer.render(settings, frame, nullptr, false, buffer.nextOffset());
    shown += buffer.add(frame, average) ? 1 : 0;
  }
  EXPECT_EQ(buffer.samples(), 16);
  EXPECT_EQ(shown, 8);  // after every completed pair
  const ImageDifference d = compareImages(average, expected, 1.0);
  EXPECT_EQ(d.fractionAbove, 0.0) << "largest " << d.largest << "/255";
  if (d.fractionAbove > 0.0) {
    writePng(average, outputPath("accumulated_16_actual.png"));
    writePng(expected, outputPath("accumulated_16_expected.png"));
  }
  // Anti-aliasing changed something: the one-sample frame differs at the slime's edges.
  const ImageDifference fromOneSample = compareImages(renderScene(settings), expected, 2.0);
  EXPECT_GT(fromOneSample.fractionAbove, 0.0);
}

TEST(AccumulationBuffer, AMovedCameraStartsAgainFromItsFirstFrame) {
  Settings settings = smallScene(48, 36);
  const TriangleMesh mesh = restingMesh(settings);
  Renderer renderer(settings);
  renderer.updateSlime({mesh});
  AccumulationBuffer buffer(16);
  Image frame, average;
  frame.resize(settings.camera.width, settings.camera.height);
  for (int k = 0; k < 6; ++k) {
    renderer.render(settings, frame, nullptr, false, buffer.nextOffset());
    buffer.add(frame, average);
  }
  ASSERT_EQ(buffer.samples(), 6);

  settings.camera.yaw += 5.0;  // the camera turns: the caller resets
  buffer.reset();
  EXPECT_EQ(buffer.samples(), 0);
  EXPECT_EQ(buffer.nextOffset(), buffer.offset(0));
  renderer.render(settings, frame, nullptr, false, buffer.nextOffset());
  EXPECT_FALSE(buffer.add(frame, average));  // half a pair: the caller keeps its centred frame
  renderer.render(settings, frame, nullptr, false, buffer.nextOffset());
  ASSERT_TRUE(buffer.add(frame, average));
  // The average holds the new view's two frames only, nothing of the old view.
  Image first, second;
  first.resize(frame.width, frame.height);
  second.resize(frame.width, frame.height);
  renderer.render(settings, first, nullptr, false, buffer.offset(0));
  renderer.render(settings, second, nullptr, false, buffer.offset(1));
  for (std::size_t i = 0; i < average.pixels.size(); ++i) {
    const glm::vec3 expected = (first.pixels[i] + second.pixels[i]) * 0.5f;
    ASSERT_NEAR(average.pixels[i].x, expected.x, 1e-6f);
    ASSERT_NEAR(average.pixels[i].y, expected.y, 1e-6f);
    ASSERT_NEAR(average.pixels[i].z, expected.z, 1e-6f);
  }
}

TEST(AccumulationBuffer, AFrameOfAnotherSizeRestartsTheSum) {
  AccumulationBuffer buffer(4);
  Image a, b, average;
  a.resize(4, 2);
  b.resize(2, 2);
  for (auto& p : a.pixels) p = glm::vec3(1.0f);
  for (auto& p : b.pixels) p = glm::vec3(0.25f);
  buffer.add(a, average);
  EXPECT_TRUE(buffer.add(a, average));
  EXPECT_EQ(buffer.samples(), 2);
  EXPECT_FALSE(buffer.add(b, average));
  EXPECT_EQ(buffer.samples(), 1);
  EXPECT_TRUE(buffer.add(b, average));
  EXPECT_EQ(average.width, 2);
  EXPECT_FLOAT_EQ(average.pixels[0].x, 0.25f);
}

}  // namespace
}  // namespace slime::testing

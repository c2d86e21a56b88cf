// Checkerboard tracing while things move (render/trace/checkerboard.h, issue 28): the fill-in rule,
// and frames traced that way against the full trace (the viewer's --check-every aims: ≥ 38 dB).
#include "render_fixture.h"

#include "core/geometry/camera.h"
#include "render/slime/screen_footprint.h"
#include "render/trace/checkerboard.h"
#include "render/trace/shading_parameters.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace slime::testing {
namespace {

TEST(Checkerboard, AlikeNeighboursAreAveraged) {
  const glm::vec3 a(0.20f), b(0.22f), c(0.20f), d(0.20f);
  const glm::vec3* const all[4] = {&a, &b, &c, &d};
  glm::vec3 color;
  ASSERT_TRUE(fillFromNeighbours(all, color));
  EXPECT_NEAR(color.x, 0.20f, 1e-6f);  // up–down agree exactly: their average
  const glm::vec3* const edge[4] = {&a, nullptr, &c, nullptr};  // the image's corner: the two there
  ASSERT_TRUE(fillFromNeighbours(edge, color));
  EXPECT_NEAR(color.y, 0.20f, 1e-6f);
}

TEST(Checkerboard, DisagreeingNeighboursAskForARay) {
  const glm::vec3 dark(0.05f), bright(0.6f);
  const glm::vec3* const edge[4] = {&dark, &dark, &bright, &bright};
  glm::vec3 color;
  EXPECT_FALSE(fillFromNeighbours(edge, color));
  const glm::vec3 red(0.5f, 0.05f, 0.05f), grey(0.5f);  // one channel alone differs
  const glm::vec3* const hue[4] = {&red, &grey, &grey, &grey};
  EXPECT_FALSE(fillFromNeighbours(hue, color));
  const glm::vec3 nan(NAN);
  const glm::vec3* const broken[4] = {&grey, &grey, &grey, &nan};
  EXPECT_FALSE(fillFromNeighbours(broken, color));
  const glm::vec3* const none[4] = {nullptr, nullptr, nullptr, nullptr};
  EXPECT_FALSE(fillFromNeighbours(none, color));
}

double psnrDb(const Image& a, const Image& b) {
  const auto bytesA = toSrgb8(a), bytesB = toSrgb8(b);
  double sum = 0.0;
  for (std::size_t i = 0; i < bytesA.size(); ++i) {
    const double d = static_cast<double>(bytesA[i]) - bytesB[i];
    sum += d * d;
  }
  const double mse = sum / static_cast<double>(bytesA.size());
  return mse == 0.0 ? 100.0 : 10.0 * std::log10(255.0 * 255.0 / mse);
}

// A window's frames while the slime moves: half the footprint's pixels or fewer traced (a quarter with
// render.checkerboardQuarter, a sixteenth with render.checkerboardSixteenth), the image within the
// check's aims of the full trace, and nothing of the fill left behind once it stops.
void expectMovingFramesCloseToTheFullTrace(bool quarter, bool sixteenth = false) {
  Settings settings = withoutCaustics(smallScene(320, 240));
  settings.slime.level = 3;
  settings.render.checkerboardQuarter = quarter;
  settings.render.checkerboardSixteenth = sixteenth;
  const TriangleMesh resting = restingMesh(settings);
  Renderer renderer(settings);
  Image image;
  image.resize(settings.camera.width, settings.camera.height);
  std::vector<std::uint8_t> bytes;
  renderer.updateSlime({resting});
  renderer.render(settings, image, &bytes, /*buffersKept=*/true);
  for (int frame = 1; frame <= 4; ++frame) {
    TriangleMesh moved = resting;
    for (auto& p : moved.positions) p += glm::dvec3(0.006 * frame, 0.004 * frame, 0.0);
    renderer.updateSlime({moved});
    const RenderStats stats = renderer.render(settings, image, &bytes, /*buffersKept=*/true);
    const std::string what = "frame " + std::to_string(frame);
    EXPECT_EQ(stats.nonFinitePixels, 0u) << what;
    EXPECT_GT(stats.filledPixels, 0u) << what << ": nothing filled in";
    const Image full = renderMesh(settings, moved);
    const double psnr = psnrDb(image, full);
    EXPECT_GE(psnr, 38.0) << what;
    // The fill's contrast threshold (kCheckerboardContrast 0.12, issue 28) traces at most a fifth of the
    // skipped pixels after all here (12-16 %; 0.06 traced 19-26 %, each a whole Whitted tree), at the PSNR above.
    EXPECT_LE(5 * stats.tracedFillPixels, stats.filledPixels + stats.tracedFillPixels) << what << ": too many skipped pixels traced";
    std::vector<std::uint8_t> encoded;
    toSrgb8(image, 4, encoded);
    EXPECT_TRUE(bytes == encoded) << what << ": the bytes are not the image's";
    // Every pixel outside the footprint is the full trace's, bit for bit.
    SlimeGeometry geometry;
    geometry.update(moved.positions, moved.triangles);
    const ScreenFootprint footprint =
        slimeFootprint(makeCamera(settings.camera, image.width, image.height), geometry,
                       makeShadingParameters(settings, image.height), image.width, image.height);
    int differingOutside = 0, footprintPixels = 0;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        if (footprint.contains(x, y)) ++footprintPixels;
        else differingOutside += image.at(x, y) != full.at(x, y);
      }
    EXPECT_EQ(differingOutside, 0) << what;
    EXPECT_GE(2 * stats.filledPixels + 2 * stats.tracedFillPixels + 4 * image.width, static_cast<std::uint64_t>(footprintPixels))
        << what << ": about half the footprint is left to the fill";
    if (quarter) {  // three quarters of it, less a row of the image at each span's ends
      EXPECT_GE(4 * (stats.filledPixels + stats.tracedFillPixels) + 8 * image.width, 3u * static_cast<std::uint64_t>(footprintPixels))
          << what << ": about three quarters of the footprint are left to the fill";
    }
    if (sixteenth) {  // fifteen sixteenths of it, less four rows of the image at each span's ends
      EXPECT_GE(16 * (stats.filledPixels + stats.tracedFillPixels) + 64 * image.width, 15u * static_cast<std::uint64_t>(footprintPixels))
          << what << ": about fifteen sixteenths of the footprint are left to the fill";
    }
  }
  // Still again, traced in full: the very image of a fresh renderer.
  settings.render.checkerboard = false;
  TriangleMesh last = resting;
  for (auto& p : last.positions) p += glm::dvec3(0.024, 0.016, 0.0);
  const RenderStats stats = renderer.render(settings, image, &bytes, /*buffersKept=*/true);
  EXPECT_EQ(stats.filledPixels, 0u);
  const Image full = renderMesh(settings, last);
  std::size_t differing = 0;
  for (std::size_t i = 0; i < image.pixels.size(); ++i) differing += image.pixels[i] != full.pixels[i];
  EXPECT_EQ(differing, 0u) << "a filled-in pixel outlived the checkerboard";
}

TEST(Checkerboard, MovingFramesStayCloseToTheFullTrace) { expectMovingFramesCloseToTheFullTrace(false); }

TEST(Checkerboard, QuarterTracedFramesStayCloseToTheFullTrace) { expectMovingFramesCloseToTheFullTrace(true); }

TEST(Checkerboard, SixteenthTracedFramesStayCloseToTheFullTrace) { expectMovingFramesCloseToTheFullTrace(true, true); }

// Every pixel of a 4 × 4 block has one pass, the block's traced pixel moves over all 16 in turn,
// and each fill pass's neighbours come from earlier passes (the traced pixel, or a pass filled before).
TEST(Checkerboard, SixteenthPassesReadOnlyFinishedPixels) {
  const auto order = [](CheckerboardPass pass) {  // the order the passes run in
    switch (pass) {
      case CheckerboardPass::Traced: return 0;
      case CheckerboardPass::FromDiagonalsWide: return 1;
      case CheckerboardPass::FromBesideWide: return 2;
      case CheckerboardPass::FromDiagonals: return 3;
      case CheckerboardPass::FromBeside: return 4;
    }
    return 5;
  };
  for (int oy = 0; oy < 4; ++oy)
    for (int ox = 0; ox < 4; ++ox) {
      int traced = 0;
      for (int y = 8; y < 12; ++y)
        for (int x = 8; x < 12; ++x) {
          const CheckerboardPass pass = checkerboardSixteenthPass(x, y, ox, oy);
          traced += pass == CheckerboardPass::Traced;
          if (pass == CheckerboardPass::Traced) continue;
          const int step = checkerboardStep(pass);
          const bool diagonal = pass == CheckerboardPass::FromDiagonals || pass == CheckerboardPass::FromDiagonalsWide;
          const int offsets[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};
          const int diagonals[4][2] = {{-1, -1}, {1, 1}, {1, -1}, {-1, 1}};
          for (int i = 0; i < 4; ++i) {
            const int* d = diagonal ? diagonals[i] : offsets[i];
            const CheckerboardPass neighbour = checkerboardSixteenthPass(x + step * d[0], y + step * d[1], ox, oy);
            EXPECT_LT(order(neighbour), order(pass)) << "pixel " << x << "," << y << " offset " << ox << "," << oy;
          }
        }
      EXPECT_EQ(traced, 1);
    }
}

// Without the window's promise (a snapshot, the check's reference) nothing is filled in.
TEST(Checkerboard, OnlyAWindowsFramesAreHalved) {
  Settings settings = smallScene(160, 120);
  RenderStats stats;
  renderScene(settings, &stats);
  EXPECT_EQ(stats.filledPixels + stats.tracedFillPixels, 0u);
}

}  // namespace
}  // namespace slime::testing

// Physical invariants and oracles of the renderer: an invisible slime, Beer–Lambert through the centre,
// Embree against the seed's brute-force algorithm, the mesh against the exact sphere, and no NaN.
#include "render_fixture.h"

#include "core/geometry/camera.h"
#include "core/geometry/level_of_detail.h"
#include "render/trace/optics.h"
#include "render/slime/screen_footprint.h"
#include "render/trace/shading_parameters.h"
#include "render/slime/slime_geometry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>

namespace slime::testing {
namespace {

// The invisible slime (render_fixture.h) leaves the image as if it were not there.
TEST(Invariant, InvisibleSlimeLeavesTheImageUnchanged) {
  Settings settings = invisibleSlimeScene();
  RenderStats stats;
  const Image withSlime = renderScene(settings, &stats);
  const Image without = renderMesh(settings, TriangleMesh{});
  EXPECT_GT(stats.slimeQueries, 1000u);  // the slime is in view and was traced
  const ImageDifference d = compareImages(withSlime, without, 1.0);
  EXPECT_EQ(d.fractionAbove, 0.0) << "largest difference " << d.largest << "/255";
  if (d.fractionAbove > 0.0) writePng(differenceImage(withSlime, without), outputPath("invisible_slime_diff.png"));
}

// With ior 1 the ray through the centre crosses a chord of 2R: the sky behind is dimmed by exp(−2σR).
void expectCentreAttenuation(const std::string& shape, int level, float tolerance) {
  Settings settings = smallScene(33, 33);
  settings.slime.shape = shape;
  settings.slime.level = level;
  settings.slime.ior = 1.0;
  settings.slime.transmission = 1.0;
  settings.slime.absorption = 15.0;
  settings.slime.specular = settings.slime.diffuse = settings.slime.ambient = 0.0;
  settings.camera.position = {0.0, -0.2, settings.slime.radius};
  settings.camera.yaw = 90.0;
  settings.camera.pitch = 0.0;
  const Image withSlime = renderScene(settings);
  const Image without = renderMesh(settings, TriangleMesh{});
  const glm::vec3 sigma = absorptionCoefficients(glm::vec3(settings.slime.color), static_cast<float>(settings.slime.absorption));
  const glm::vec3 expected = without.at(16, 16) * beerLambert(sigma, 2.0f * static_cast<float>(settings.slime.radius));
  const glm::vec3 seen = withSlime.at(16, 16);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(seen[c], expected[c], tolerance * expected[c]) << shape << " channel " << c;
}

TEST(Invariant, CentreRayIsAttenuatedByBeerLambertOverTheDiameter) {
  expectCentreAttenuation("sphere", 4, 1e-3f);
  expectCentreAttenuation("mesh", 5, 5e-3f);  // the inscribed mesh's chord is a little shorter
}

// A frame the renderer drew from its caches: the bytes must be the image's own encoding and the
// image must be, bit for bit, the one a fresh renderer draws.
void expectFrameEquals(const Image& image, const std::vector<std::uint8_t>& bytes, const Image& fresh,
                       const std::string& what) {
  std::vector<std::uint8_t> encoded;
  toSrgb8(image, 4, encoded);
  EXPECT_TRUE(bytes == encoded) << what << ": the tiles' bytes are not the image's";
  ASSERT_EQ(image.pixels.size(), fresh.pixels.size()) << what;
  std::size_t differing = 0;
  for (std::size_t i = 0; i < image.pixels.size(); ++i) differing += image.pixels[i] != fresh.pixels[i];
  EXPECT_EQ(differing, 0u) << what;
}

// The renderer keeps the floor its primary rays saw while the view stays still, and copies the pixels
// outside the slime's footprint; a frame drawn from those caches must be exactly the frame a fresh
// renderer draws, after the slime moved (uncovering floor the first frame never shaded, covering
// pixels it copied before) and after the camera or the light changed (the caches are dropped).
// With the window's byte output on, the bytes the tiles write must be the image's own encoding.
TEST(Invariant, FramesFromTheFloorCacheEqualFreshFrames) {
  Settings settings = withoutCaustics(smallScene(160, 120));
  settings.slime.level = 3;
  settings.render.checkerboard = false;  // exact frames; checkerboard_test.cpp holds the halved ones
  const TriangleMesh resting = restingMesh(settings);
  TriangleMesh moved = resting;
  for (auto& p : moved.positions) p += glm::dvec3(0.03, 0.02, 0.0);
  Renderer renderer(settings);
  Image image;
  image.resize(settings.camera.width, settings.camera.height);
  std::vector<std::uint8_t> bytes;  // the window's sRGB bytes, written by the tiles as they go
  renderer.updateSlime({resting});
  renderer.render(settings, image, &bytes);
  auto expectFresh = [&](const Settings& s, const TriangleMesh& mesh, const char* what) {
    renderer.updateSlime({mesh});
    const std::vector<std::uint8_t> before = bytes;
    const RenderStats stats = renderer.render(s, image, &bytes, /*buffersKept=*/true);
    expectFrameEquals(image, bytes, renderMesh(s, mesh), what);
    // A window uploads and draws again only the rectangle the renderer says it wrote: every pixel
    // whose bytes changed must lie in it.
    std::size_t changedOutside = 0;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        const std::size_t at = 4 * (static_cast<std::size_t>(y) * image.width + x);
        const bool inside = x >= stats.bytesWritten.x0 && x < stats.bytesWritten.x1 && y >= stats.bytesWritten.y0 &&
                            y < stats.bytesWritten.y1;
        changedOutside += !inside && !std::equal(&before[at], &before[at] + 4, &bytes[at]);
      }
    EXPECT_EQ(changedOutside, 0u) << what << ": pixels changed outside the written rectangle";
    return stats;
  };
  const RenderStats movedStats = expectFresh(settings, moved, "slime moved");
  EXPECT_GT(movedStats.reusedPixels, image.pixels.size() / 2) << "a still view copies most of the floor";
  const PixelRect written = movedStats.bytesWritten;
  EXPECT_LT(static_cast<std::size_t>(written.x1 - written.x0) * (written.y1 - written.y0), image.pixels.size() * 3 / 4)
      << "the moved slime's frame wrote bytes all over the image";
  expectFresh(settings, resting, "slime moved back");
  TriangleMesh raised = resting;
  for (auto& p : raised.positions) p += glm::dvec3(-0.02, 0.0, 0.05);  // its shadow moves away from it
  expectFresh(settings, raised, "slime lifted");
  settings.camera.yaw += 4.0;
  expectFresh(settings, moved, "camera turned");
  settings.light.position.x -= 0.1;
  expectFresh(settings, resting, "light moved");
  settings.floor.specular = 0.1;
  expectFresh(settings, resting, "floor varnished");
  expectFresh(settings, moved, "slime moved under the varnish");
  settings.render.depth = 1;  // no mirror rays: the copied floor must lose its reflections
  expectFresh(settings, resting, "depth 1");
  settings.render.depth = 3;
  settings.render.shadows = false;
  expectFresh(settings, moved, "shadows off");
}

// Without the promise that the buffers were kept, every pixel is written, even when a new zeroed
// image lands where the last one was (as a loop's local image often does).
TEST(Invariant, FreshBuffersAreWrittenWhole) {
  Settings settings = smallScene(160, 120);
  settings.render.checkerboard = false;  // exact frames
  const TriangleMesh mesh = restingMesh(settings);
  const Image expected = renderMesh(settings, mesh);
  Renderer renderer(settings);
  renderer.updateSlime({mesh});
  Image image;
  image.resize(settings.camera.width, settings.camera.height);
  std::vector<std::uint8_t> bytes;
  renderer.render(settings, image, &bytes, /*buffersKept=*/true);
  for (int frame = 0; frame < 2; ++frame) {
    std::fill(image.pixels.begin(), image.pixels.end(), glm::vec3(0.0f));  // same buffers, new contents
    std::fill(bytes.begin(), bytes.end(), std::uint8_t{0});
    const RenderStats stats = renderer.render(settings, image, &bytes);
    EXPECT_GT(stats.reusedPixels, image.pixels.size() / 2) << "the floor is still copied from the cache";
    EXPECT_EQ(stats.bytesWritten, (PixelRect{0, 0, image.width, image.height})) << "every pixel's bytes are written";
    expectFrameEquals(image, bytes, expected, "frame " + std::to_string(frame) + " on cleared buffers");
  }
}

// The footprint (render/slime/screen_footprint.h) must hold every pixel the slime changes: the difference
// between the scene with the slime and without it, for slimes on the floor, in the air, stretched,
// under a low light, on a varnished floor, near the eye and under a light below the slime's top.
TEST(Invariant, FootprintHoldsEveryPixelTheSlimeChanges) {
  struct Case {
    const char* what;
    glm::dvec3 offset;
    glm::dvec3 stretch;
    double lightHeight;
    double floorSpecular;
    double maxAreaPerChange;  // how much larger than the changed pixels the footprint may be
  };
  // The footprint follows the bounding sphere, its mirror image and its shadow row by row, so it
  // stays close to what changes; only a light below the sphere's top (a shadow without bounds)
  // makes it every row that sees the floor.
  const Case cases[] = {{"resting", {0, 0, 0}, {1, 1, 1}, 0.35, 0.0, 1.5},
                        {"in the air", {0.02, 0.01, 0.06}, {1, 1, 1}, 0.35, 0.0, 1.5},
                        {"stretched", {0, 0, 0}, {1.5, 0.8, 1.2}, 0.35, 0.0, 2.0},
                        {"low light", {0, 0, 0}, {1, 1, 1}, 0.12, 0.0, 1.5},
                        {"varnished floor", {0, 0.02, 0.03}, {1, 1, 1}, 0.35, 0.2, 1.5},
                        {"near the eye", {0, -0.12, 0.02}, {1, 1, 1}, 0.35, 0.0, 1.5},
                        {"light below the top", {0, 0, 0}, {1, 1, 1}, 0.05, 0.0, 8.0}};
  for (const Case& c : cases) {
    Settings settings = smallScene(160, 120);
    settings.slime.level = 3;
    settings.light.position.z = c.lightHeight;
    settings.floor.specular = c.floorSpecular;
    TriangleMesh mesh = restingMesh(settings);
    const glm::dvec3 base = settings.slime.position;
    for (auto& p : mesh.positions) p = base + (p - base) * c.stretch + c.offset;
    const Image with = renderMesh(settings, mesh);
    const Image without = renderMesh(settings, TriangleMesh{});
    SlimeGeometry geometry;
    geometry.update(mesh.positions, mesh.triangles);
    const ScreenFootprint footprint =
        slimeFootprint(makeCamera(settings.camera, with.width, with.height), geometry,
                       makeShadingParameters(settings, with.height), with.width, with.height);
    int changed = 0, outside = 0;
    for (int y = 0; y < with.height; ++y) {
      for (int x = 0; x < with.width; ++x) {
        if (with.at(x, y) == without.at(x, y)) continue;
        ++changed;
        outside += !footprint.contains(x, y);
      }
    }
    EXPECT_GT(changed, 0) << c.what;
    EXPECT_EQ(outside, 0) << c.what << ": " << outside << " changed pixels outside the footprint";
    EXPECT_LE(footprint.area(), c.maxAreaPerChange * changed)
        << c.what << ": " << footprint.area() << " footprint pixels for " << changed << " changed";
  }
}

// A refinement sample traced in bands of rows (Renderer::renderRows, the later bands reusing the
// first one's setup) is, pixel for pixel, the image one render() traces at the same offset; so is
// the next sample, at another offset, and a band after the slime moved. The bands leave the floor
// caches and the last frame's pixels to the window's next frame: it is the frame drawn without them.
TEST(Invariant, BandsOfRowsMakeTheWholeImage) {
  Settings settings = smallScene(160, 120);  // caustics on: the bands share the first one's map
  const TriangleMesh mesh = restingMesh(settings);
  Renderer renderer(settings);
  renderer.updateSlime({mesh});
  Image frame;  // the window's frame, with its bytes: its caches are made
  frame.resize(160, 120);
  std::vector<std::uint8_t> bytes;
  renderer.render(settings, frame, &bytes, true);
  const auto banded = [&](glm::vec2 offset) {
    Image image;
    image.resize(160, 120);
    for (int row = 0; row < 120; row += 24) renderer.renderRows(settings, image, offset, row, row + 24);
    return image;
  };
  const auto whole = [&](glm::vec2 offset, const TriangleMesh& slime) {
    Renderer fresh(settings);
    fresh.updateSlime({slime});
    Image image;
    image.resize(160, 120);
    fresh.render(settings, image, nullptr, false, offset);
    return image;
  };
  for (const glm::vec2 offset : {glm::vec2(0.125f, 0.375f), glm::vec2(0.875f, 0.625f)}) {
    const ImageDifference d = compareImages(banded(offset), whole(offset, mesh), 0.0);
    EXPECT_EQ(d.fractionAbove, 0.0) << "offset " << offset.x << ", " << offset.y << ": largest " << d.largest;
  }
  TriangleMesh moved = mesh;
  for (glm::dvec3& p : moved.positions) p.x += 0.2 * settings.slime.radius;
  renderer.updateSlime({moved});
  const ImageDifference afterMove = compareImages(banded({0.125f, 0.375f}), whole({0.125f, 0.375f}, moved), 0.0);
  EXPECT_EQ(afterMove.fractionAbove, 0.0) << "after the slime moved: largest " << afterMove.largest;
  renderer.render(settings, frame, &bytes, true);  // the window's next frame, from its caches
  // ... is the frame a window draws with no bands between its two frames.
  Renderer window(settings);
  window.updateSlime({mesh});
  Image unbanded;
  unbanded.resize(160, 120);
  std::vector<std::uint8_t> unbandedBytes;
  window.render(settings, unbanded, &unbandedBytes, true);
  window.updateSlime({moved});
  const RenderStats kept = window.render(settings, unbanded, &unbandedBytes, true);
  EXPECT_GT(kept.reusedPixels, 0u);
  const ImageDifference next = compareImages(frame, unbanded, 0.0);
  EXPECT_EQ(next.fractionAbove, 0.0) << "the window's frame after the bands: largest " << next.largest;
  EXPECT_TRUE(bytes == unbandedBytes);
}

// The viewer skips tracing a slime whose vertices moved less than kInvisibleMotionPixels since it was
// last drawn (core/geometry/level_of_detail.h). Every vertex moved that far, each in its own random direction
// (the worst for the normals), must be invisible by the rule the level of detail rests on
// (app/bench/render/bench_accuracy.h: at most 1 % of the pixels off by more than 2 steps of 8-bit sRGB; with one
// sample a pixel, the pixels whose centre a silhouette or a refracted plank edge crosses flip
// whatever the move). A move of one pixel must show by the same rule.
TEST(Invariant, MotionBelowTheRedrawThresholdDoesNotShow) {
  Settings settings = withoutCaustics(smallScene(367, 282));  // the default view at half size
  const TriangleMesh mesh = restingMesh(settings);
  auto movedBy = [&](double pixels) {
    std::mt19937 random(7);
    std::normal_distribution<double> gaussian;
    TriangleMesh moved = mesh;
    for (glm::dvec3& p : moved.positions)
      p += 1e-6 * glm::normalize(glm::dvec3(gaussian(random), gaussian(random), gaussian(random)));
    // The vertices moved by a micrometre each: scale the moves to `pixels` as the viewer measures them.
    const double pixelsPerUnitMove = largestMotionPixels(mesh.positions, moved.positions, settings.camera.position,
                                                         settings.camera.fov, settings.camera.height);
    for (std::size_t i = 0; i < moved.positions.size(); ++i)
      moved.positions[i] = mesh.positions[i] + (moved.positions[i] - mesh.positions[i]) * (pixels / pixelsPerUnitMove);
    EXPECT_NEAR(largestMotionPixels(mesh.positions, moved.positions, settings.camera.position, settings.camera.fov,
                                    settings.camera.height),
                pixels, 0.05 * pixels);
    return moved;
  };
  const Image drawn = renderMesh(settings, mesh);
  const Image invisible = renderMesh(settings, movedBy(kInvisibleMotionPixels));
  constexpr double kStep = 2.0, kFraction = 0.01;
  const ImageDifference d = compareImages(drawn, invisible, kStep);
  EXPECT_LE(d.fractionAbove, kFraction) << d.fractionAbove * 100 << " % of pixels over 2 steps";
  // The rule allows 1 %; a 0.01 px move of this scene flips 0.056 % (58 of 103,494 pixels, measured
  // 2026-11 on the default view at half size: silhouette and plank-edge pixels whose centre the move
  // crosses). The bound sits at 1.5× that, so a change that makes sub-threshold motion show (a larger
  // kInvisibleMotionPixels, a noisier normal) fails here long before it reaches the rule's 1 %.
  constexpr double kMeasuredFraction = 58.0 / (367.0 * 282.0);
  EXPECT_LE(d.fractionAbove, 1.5 * kMeasuredFraction)
      << d.fractionAbove * 100 << " % of pixels over 2 steps, measured " << kMeasuredFraction * 100 << " %";
  if (d.fractionAbove > kFraction) writePng(differenceImage(drawn, invisible), outputPath("motion_below_threshold_diff.png"));
  const ImageDifference visible = compareImages(drawn, renderMesh(settings, movedBy(1.0)), kStep);
  EXPECT_GT(visible.fractionAbove, kFraction) << "a one-pixel move must show, or this test proves nothing";
  std::printf("motion %.2f px: %.3f %% of pixels (%.0f) over 2 steps; 1 px: %.2f %%\n", kInvisibleMotionPixels,
              100 * d.fractionAbove, d.fractionAbove * drawn.width * drawn.height, 100 * visible.fractionAbove);
}

// The creeps a resting slime makes, for the still threshold's tests: a slide along the floor and a
// spreading (wider by ε, lower by 2ε about the floor: its volume kept), moved `pixels` as the viewer
// measures motion (largestMotionPixels: the vertex that moved most, seen at the slime's nearest depth).
struct Creep {
  const char* what;
  std::function<glm::dvec3(const glm::dvec3&)> field;
};

std::vector<Creep> restingCreeps(const Settings& settings) {
  const glm::dvec3 centre = settings.slime.position;
  return {Creep{"slide", [](const glm::dvec3&) { return glm::dvec3(1.0, 0.3, 0.0); }},
          Creep{"spread", [centre](const glm::dvec3& p) { return glm::dvec3(p.x - centre.x, p.y - centre.y, -2.0 * p.z); }}};
}

TriangleMesh creptBy(const Settings& settings, const TriangleMesh& mesh, const Creep& creep, double pixels) {
  TriangleMesh moved = mesh;
  for (glm::dvec3& p : moved.positions) p += 1e-6 * creep.field(p);
  const double perUnit = largestMotionPixels(mesh.positions, moved.positions, settings.camera.position, settings.camera.fov,
                                             settings.camera.height);
  for (std::size_t i = 0; i < moved.positions.size(); ++i)
    moved.positions[i] = mesh.positions[i] + (moved.positions[i] - mesh.positions[i]) * (pixels / perUnit);
  return moved;
}

// The refined image the viewer keeps while the slime creeps: 16 samples a pixel, the caustic map
// finished, the default view at half size (the fraction of pixels a creep changes halves at full size:
// the slime's outline doubles, the image's area quadruples).
Settings refinedScene() {
  Settings settings = smallScene(367, 282);
  settings.render.spp = 16;
  return settings;
}

// The viewer keeps refining a still image while the slime has crept less than kStillMotionPixels
// from where the refinement started (core/geometry/level_of_detail.h). No threshold keeps every pixel
// within 2 steps: a refined pixel averages 16 fixed points, and one of them crossing an edge of 150
// steps moves it by 9 (so does a creep of 0.01 px, the one-sample redraw threshold). The rule is the
// level of detail's (app/bench/bench_accuracy.h: at most 1 % of the pixels off by more than 2 steps of
// 8-bit sRGB is invisible), with a margin of two: a creep to the threshold changes at most 0.5 % of the
// refined image's pixels by more than 2 steps, the lens, the floor seen through it, the shadow's edge
// and the caustic included, and a creep four times as far shows (over 1 %).
TEST(Invariant, CreepBelowTheStillThresholdDoesNotShowInTheRefinedImage) {
  const Settings settings = refinedScene();
  const TriangleMesh mesh = restingMesh(settings);
  const Image drawn = renderMesh(settings, mesh);
  for (const Creep& creep : restingCreeps(settings)) {
    const Image still = renderMesh(settings, creptBy(settings, mesh, creep, kStillMotionPixels));
    const ImageDifference d = compareImages(drawn, still, 2.0);
    EXPECT_LE(d.fractionAbove, 0.005) << creep.what << " by " << kStillMotionPixels << " px: " << 100 * d.fractionAbove
                                      << " % of pixels over 2 steps";
    if (d.fractionAbove > 0.005) writePng(differenceImage(drawn, still), outputPath(std::string("creep_") + creep.what + "_diff.png"));
    const ImageDifference shows =
        compareImages(drawn, renderMesh(settings, creptBy(settings, mesh, creep, 4.0 * kStillMotionPixels)), 2.0);
    EXPECT_GT(shows.fractionAbove, 0.01) << creep.what << ": four times the threshold must show, or this test proves nothing";
    std::printf("%s %.2f px: %.3f %% of pixels over 2 steps (mean %.3f steps); %.2f px: %.3f %%\n", creep.what,
                kStillMotionPixels, 100 * d.fractionAbove, d.mean, 4.0 * kStillMotionPixels, 100 * shows.fractionAbove);
  }
}

// The figures behind kStillMotionPixels (docs/rendering.md), run on demand:
//   render_tests --gtest_also_run_disabled_tests --gtest_filter='Invariant.DISABLED_CreepTable'
TEST(Invariant, DISABLED_CreepTable) {
  const Settings settings = refinedScene();
  const TriangleMesh mesh = restingMesh(settings);
  const Image drawn = renderMesh(settings, mesh);
  std::printf("creep | pixels | largest change, steps | pixels over 2 steps, %% | mean change, steps\n");
  for (const Creep& creep : restingCreeps(settings)) {
    for (const double pixels : {0.01, 0.025, 0.05, 0.1, 0.2, 0.4}) {
      const Image moved = renderMesh(settings, creptBy(settings, mesh, creep, pixels));
      const ImageDifference d = compareImages(drawn, moved, 2.0);
      std::printf("%s | %.3f | %.0f | %.3f | %.4f\n", creep.what, pixels, d.largest, 100.0 * d.fractionAbove, d.mean);
      writePng(differenceImage(drawn, moved), outputPath("creep_" + std::string(creep.what) + "_" + std::to_string(pixels) + "_diff.png"));
    }
  }
}

// The seed's algorithm (bounding sphere, then every triangle) and Embree must agree.
TEST(Oracle, EmbreeMatchesBruteForce) {
  for (const char* optics : {"fresnel", "seed"}) {
    Settings settings = withoutCaustics(smallScene(160, 120));
    settings.slime.level = 3;
    settings.render.optics = optics;
    const Image embree = renderScene(settings);
    settings.render.backend = "brute";
    const Image brute = renderScene(settings);
    const ImageDifference d = compareImages(embree, brute, 1.0);
    EXPECT_LE(d.fractionAbove, 0.001) << optics << ": largest difference " << d.largest << "/255";
    if (d.fractionAbove > 0.001) writePng(differenceImage(embree, brute), outputPath(std::string("embree_vs_brute_") + optics + ".png"));
  }
}

// The subdivided mesh against the exact sphere it approximates: at level 4 the two images differ only
// along the silhouette and in a few refracted details.
TEST(Oracle, MeshAtLevelFourAgreesWithTheAnalyticSphere) {
  Settings settings = smallScene(160, 120);
  settings.slime.level = 4;
  const Image mesh = renderScene(settings);
  settings.slime.shape = "sphere";
  const Image sphere = renderScene(settings);
  const ImageDifference d = compareImages(mesh, sphere, 8.0);
  EXPECT_LT(d.fractionAbove, 0.02) << "largest " << d.largest << "/255, mean " << d.mean;
  EXPECT_LT(d.mean, 1.0);
  if (d.fractionAbove >= 0.02) writePng(differenceImage(mesh, sphere), outputPath("mesh_vs_sphere.png"));
}

void expectFinite(const Settings& settings, const TriangleMesh& mesh, const char* what) {
  for (const char* backend : {"embree", "brute"}) {
    Settings s = settings;
    s.render.backend = backend;
    RenderStats stats;
    const Image image = renderMesh(s, mesh, &stats);
    EXPECT_EQ(stats.nonFinitePixels, 0u) << what << " (" << backend << ")";
    for (const glm::vec3& p : image.pixels)
      ASSERT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) << what << " (" << backend << ")";
  }
}

TEST(Robustness, NoNanPixelForDegenerateMeshes) {
  Settings settings = withoutCaustics(smallScene(48, 36));
  settings.slime.level = 2;
  const TriangleMesh ball = restingMesh(settings);

  TriangleMesh collapsed = ball;  // every vertex at one point: zero-area triangles only
  for (auto& p : collapsed.positions) p = {0.0, 0.0, 0.04};
  expectFinite(settings, collapsed, "collapsed to a point");

  TriangleMesh pancake = ball;  // squashed flat onto the floor
  for (auto& p : pancake.positions) p.z = 1e-4;
  expectFinite(settings, pancake, "flattened");

  TriangleMesh line = ball;  // collapsed onto a segment
  for (auto& p : line.positions) p = {p.x, 0.0, 0.04};
  expectFinite(settings, line, "collapsed to a line");

  TriangleMesh crumpled = ball;  // random vertices: self-intersecting, inside out
  std::mt19937 random(3);
  std::uniform_real_distribution<double> jitter(-0.04, 0.04);
  for (auto& p : crumpled.positions) p = {jitter(random), jitter(random), 0.04 + jitter(random)};
  expectFinite(settings, crumpled, "crumpled");

  TriangleMesh diverged = ball;  // a diverged simulation
  diverged.positions[3] = {std::nan(""), 0.0, 0.0};
  diverged.positions[5] = {1e30, -1e30, 1e30};
  expectFinite(settings, diverged, "NaN and huge vertices");

  Settings extreme = settings;  // extreme optics
  extreme.slime.ior = 3.0;
  extreme.slime.absorption = 10000.0;
  extreme.slime.color = {0.0, 0.0, 0.0};
  extreme.render.depth = 16;
  expectFinite(extreme, ball, "extreme optics");
}

}  // namespace
}  // namespace slime::testing

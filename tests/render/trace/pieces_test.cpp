// The slime as several pieces (Renderer::updateSlime takes one closed surface per piece): two separate
// balls drawn through Embree's shortcuts (supporting triangles, the exit walk, the grids, the footprint)
// against Beer–Lambert through both and against the brute force given the balls as one mesh.
#include "render_fixture.h"

#include "render/trace/optics.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace slime::testing {
namespace {

TriangleMesh ballAt(const Settings& settings, int level, const glm::dvec3& center) {
  return makeIcosphere(level, settings.slime.radius, center);
}

// The two pieces as one mesh, joined here and not by the renderer: the brute force's reference.
TriangleMesh joined(const TriangleMesh& a, const TriangleMesh& b) {
  TriangleMesh both = a;
  const auto offset = static_cast<std::uint32_t>(a.positions.size());
  both.positions.insert(both.positions.end(), b.positions.begin(), b.positions.end());
  for (const Triangle& t : b.triangles) both.triangles.push_back(t + Triangle(offset));
  return both;
}

// Two balls one behind the other on the eye's line of sight, with ior 1: the ray through both centres
// crosses two chords of 2R, so the sky behind is dimmed by exp(−4σR). A ray that left the first ball
// as if nothing lay beyond it (its exit judged against its own piece alone) would cross one.
TEST(Pieces, RayThroughTwoPiecesIsAttenuatedByBothChords) {
  Settings settings = withoutCaustics(smallScene(33, 33));
  settings.slime.ior = 1.0;
  settings.slime.transmission = 1.0;
  settings.slime.absorption = 15.0;
  settings.slime.specular = settings.slime.diffuse = settings.slime.ambient = 0.0;
  settings.render.depth = 6;  // eye, in, between, in, out to the sky
  const double r = settings.slime.radius;
  settings.camera.position = {0.0, -0.2, r};
  settings.camera.yaw = 90.0;
  settings.camera.pitch = 0.0;
  const TriangleMesh front = ballAt(settings, 5, {0.0, 0.0, r}), back = ballAt(settings, 5, {0.0, 3.0 * r, r});
  const glm::vec3 sigma = absorptionCoefficients(glm::vec3(settings.slime.color), static_cast<float>(settings.slime.absorption));
  Image without;
  without.resize(33, 33);
  Renderer empty(settings);
  empty.updateSlime({});
  empty.render(settings, without);
  const glm::vec3 expected = without.at(16, 16) * beerLambert(sigma, 4.0f * static_cast<float>(r));
  for (const char* backend : {"embree", "brute"}) {
    Settings s = settings;
    s.render.backend = backend;
    Renderer renderer(s);
    renderer.updateSlime({front, back});
    Image image;
    image.resize(33, 33);
    renderer.render(s, image);
    const glm::vec3 seen = image.at(16, 16);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(seen[c], expected[c], 5e-3f * expected[c]) << backend << " channel " << c;
  }
}

// Two balls side by side in the default view, refracting and reflecting each other: Embree given the
// two pieces against the brute force given them joined into one mesh by the test.
TEST(Pieces, TwoPiecesMatchTheBruteForceOnTheJoinedMesh) {
  for (const char* optics : {"fresnel", "seed"}) {
    Settings settings = withoutCaustics(smallScene(160, 120));
    settings.render.optics = optics;
    // No ambient: the sky each piece hides from the floor is reckoned piece by piece (a ball of the
    // piece's volume at its centroid, render/floor/sky_occlusion.h), so the joined mesh, one piece
    // centred between the balls, rightly dims other floor than the two pieces do.
    settings.light.ambient = {0.0, 0.0, 0.0};
    const double r = settings.slime.radius;
    const TriangleMesh left = ballAt(settings, 3, {-1.3 * r, 0.0, r}), right = ballAt(settings, 3, {1.3 * r, 0.5 * r, r});
    Renderer renderer(settings);
    renderer.updateSlime({left, right});
    Image embree;
    embree.resize(settings.camera.width, settings.camera.height);
    const RenderStats stats = renderer.render(settings, embree);
    EXPECT_GT(stats.slimeQueries, 1000u);
    settings.render.backend = "brute";
    const Image brute = renderMesh(settings, joined(left, right));
    const ImageDifference d = compareImages(embree, brute, 1.0);
    EXPECT_LE(d.fractionAbove, 0.001) << optics << ": largest difference " << d.largest << "/255";
    if (d.fractionAbove > 0.001) writePng(differenceImage(embree, brute), outputPath(std::string("pieces_vs_brute_") + optics + ".png"));
    // And the pieces must both be there: each alone draws a different image.
    const ImageDifference leftAlone = compareImages(embree, renderMesh(settings, left), 1.0);
    EXPECT_GT(leftAlone.fractionAbove, 0.02) << optics;
  }
}

// A piece added (or taken away) changes the topology: the renderer rebuilds, and draws what a fresh
// renderer draws. A moved piece is refitted.
TEST(Pieces, AddingMovingAndRemovingAPieceDrawsAsAFreshRenderer) {
  const Settings settings = withoutCaustics(smallScene(96, 72));
  const double r = settings.slime.radius;
  const TriangleMesh left = ballAt(settings, 3, {-1.3 * r, 0.0, r}), right = ballAt(settings, 3, {1.3 * r, 0.0, r});
  TriangleMesh moved = right;
  for (glm::dvec3& p : moved.positions) p += glm::dvec3(0.0, 0.3 * r, 0.2 * r);
  Renderer renderer(settings);
  Image image;
  image.resize(settings.camera.width, settings.camera.height);
  const std::vector<std::vector<SurfaceView>> frames = {{left}, {left, right}, {left, moved}, {moved}};
  for (std::size_t frame = 0; frame < frames.size(); ++frame) {
    renderer.updateSlime(frames[frame]);
    renderer.render(settings, image);
    Renderer fresh(settings);
    fresh.updateSlime(frames[frame]);
    Image expected;
    expected.resize(settings.camera.width, settings.camera.height);
    fresh.render(settings, expected);
    const ImageDifference d = compareImages(image, expected, 0.0);
    EXPECT_EQ(d.fractionAbove, 0.0) << "frame " << frame << ": largest " << d.largest << "/255";
  }
}

// Each piece's triangles index its own vertices: a piece given already offset (as if joined by the
// caller) is refused, naming the piece.
TEST(Pieces, ATriangleOutsideItsPieceIsRefused) {
  const Settings settings = withoutCaustics(smallScene(32, 24));
  const double r = settings.slime.radius;
  const TriangleMesh left = ballAt(settings, 1, {-1.3 * r, 0.0, r});
  const TriangleMesh both = joined(left, ballAt(settings, 1, {1.3 * r, 0.0, r}));
  TriangleMesh offsetRight;
  offsetRight.positions.assign(both.positions.begin() + static_cast<std::ptrdiff_t>(left.positions.size()), both.positions.end());
  offsetRight.triangles.assign(both.triangles.begin() + static_cast<std::ptrdiff_t>(left.triangles.size()), both.triangles.end());
  Renderer renderer(settings);
  try {
    renderer.updateSlime({left, offsetRight});
    FAIL() << "an out-of-piece index was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("piece 1"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace slime::testing

// Golden images: fixed small scenes compared with PNGs stored in tests/render/reference/. On failure
// the rendered image and an 8×-amplified difference are written to SLIME_TEST_OUTPUT_DIR.
// Regenerate the references after an intended change of the picture (and look at them!):
//   SLIME_UPDATE_REFERENCES=1 build/render/tests/render_tests --gtest_filter='Golden.*'
#include "render_fixture.h"

#include "core/geometry/camera.h"
#include "render/trace/brute_tracer.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

namespace slime::testing {
namespace {

// Pixels may differ by 2/255 (compilers, float contraction); at most 0.5 % of them by more.
constexpr double kTolerance = 2.0;
constexpr double kAllowedFraction = 0.005;

void expectImageMatchesReference(const std::string& name, const Image& image) {
  const std::string reference = std::string(SLIME_SOURCE_DIR) + "/tests/render/reference/" + name + ".png";
  const char* update = std::getenv("SLIME_UPDATE_REFERENCES");
  if (update && std::string(update) == "1") {
    writePng(image, reference);
    GTEST_SKIP() << "wrote " << reference;
  }
  ASSERT_TRUE(std::filesystem::exists(reference)) << reference << " is missing; see the top of golden_test.cpp";
  const Image expected = readPng(reference);
  const ImageDifference d = compareImages(image, expected, kTolerance);
  EXPECT_LE(d.fractionAbove, kAllowedFraction) << name << ": largest difference " << d.largest << "/255, mean " << d.mean;
  if (d.fractionAbove > kAllowedFraction) {
    writePng(image, outputPath(name + "_actual.png"));
    writePng(differenceImage(image, expected), outputPath(name + "_diff.png"));
  }
}

void expectMatchesReference(const std::string& name, const Settings& settings) {
  expectImageMatchesReference(name, renderScene(settings));
}

TEST(Golden, DefaultScene) {
  Settings settings = smallScene(96, 72);
  settings.slime.level = 3;
  expectMatchesReference("default_96x72", settings);
}

TEST(Golden, CheckerSeedOpticsFlatNormals) {
  Settings settings = smallScene(96, 72);
  settings.slime.level = 2;
  settings.floor.pattern = "checker";
  settings.floor.colorA = {0.8, 0.8, 0.8};
  settings.floor.colorB = {0.1, 0.1, 0.12};
  settings.render.optics = "seed";
  settings.render.normals = "flat";
  expectMatchesReference("checker_seed_flat_96x72", settings);
}

TEST(Golden, TilesAnalyticSphereSupersampled) {
  Settings settings = smallScene(96, 72);
  settings.slime.shape = "sphere";
  settings.floor.pattern = "tiles";
  settings.floor.colorA = {0.7, 0.7, 0.65};
  settings.floor.colorB = {0.25, 0.25, 0.25};
  settings.slime.color = {0.9, 0.3, 0.6};
  settings.render.spp = 4;
  expectMatchesReference("tiles_sphere_spp4_96x72", settings);
}

// The clear slime of docs/rendering.md (clear, lit from low at the side), small, with paths of up to
// 16 segments (`render.depth=16`; the default cap is 3, rendering.md says why).
Settings clearSlimeScene() {
  Settings settings = smallScene(128, 96);
  settings.render.depth = 16;
  settings.slime.level = 4;
  settings.slime.color = {1.0, 1.0, 1.0};
  settings.slime.absorption = 0.0;
  settings.slime.transmission = 1.0;
  settings.light.position = {0.25, -0.05, 0.12};
  settings.light.ambient = {0.08, 0.08, 0.09};
  return settings;
}

// What the pixels of the lower half of the slime's outline on screen hold (pixels whose primary ray
// and its four neighbours' meet the mesh, by brute force: clear of the silhouette).
struct LowerHalf {
  double mean = 0.0;       // mean linear radiance (mean of the channels)
  int pixels = 0;
};
LowerHalf lowerHalf(const Settings& settings, const TriangleMesh& mesh, const Image& image) {
  const Camera camera = makeCamera(settings.camera, image.width, image.height);
  const int w = image.width, h = image.height;
  std::vector<char> hits(static_cast<std::size_t>(w) * h, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Ray ray{glm::vec3(camera.position), glm::vec3(camera.rayDirection((x + 0.5) / w, (y + 0.5) / h)), 0.0f, kInfinity};
      for (const Triangle& t : mesh.triangles) {
        float u = 0.0f, v = 0.0f;
        if (intersectTriangle(ray, glm::vec3(mesh.positions[t.x]), glm::vec3(mesh.positions[t.y]), glm::vec3(mesh.positions[t.z]), u, v) <
            kInfinity) {
          hits[static_cast<std::size_t>(y) * w + x] = 1;
          break;
        }
      }
    }
  const auto hit = [&](int x, int y) { return x >= 0 && y >= 0 && x < w && y < h && hits[static_cast<std::size_t>(y) * w + x]; };
  int top = h, bottom = -1;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (hit(x, y)) top = std::min(top, y), bottom = std::max(bottom, y);
  LowerHalf half;
  for (int y = (top + bottom) / 2 + 1; y <= bottom; ++y)
    for (int x = 0; x < w; ++x) {
      if (!(hit(x, y) && hit(x - 1, y) && hit(x + 1, y) && hit(x, y - 1) && hit(x, y + 1))) continue;
      const glm::vec3 p = image.at(x, y);
      half.mean += (p.x + p.y + p.z) / 3.0;
      ++half.pixels;
    }
  if (half.pixels > 0) half.mean /= half.pixels;
  return half;
}

// Seen from above, the clear (settled) jelly's lower half shows the sky and the floor after several
// total internal reflections, which lose nothing: depth 3 cut those paths off and left it black
// (mean radiance 0.20 there, against 0.37). The paths now go on while they carry visible light, so
// that half holds within 3 % of the light it holds when paths may have four times as many segments;
// and the image matches its reference.
TEST(Golden, ClearSlimeLowerHalfShowsTotalInternalReflection) {
  Settings settings = clearSlimeScene();
  settings.slime.position = defaultSettings().slime.position;  // dropped and settled, as the snapshot
  const TriangleMesh mesh = settledMesh(settings);
  const Image image = renderMesh(settings, mesh);
  Settings deeper = settings;
  deeper.render.depth = 4 * settings.render.depth;
  const LowerHalf half = lowerHalf(settings, mesh, image), converged = lowerHalf(deeper, mesh, renderMesh(deeper, mesh));
  ASSERT_GT(half.pixels, 100);
  EXPECT_GT(half.mean, 0.97 * converged.mean) << "the clear slime's lower half is dark: mean radiance " << half.mean
                                               << " over " << half.pixels << " pixels, " << converged.mean
                                               << " with paths of up to " << deeper.render.depth << " segments";
  if (half.mean <= 0.97 * converged.mean) writePng(image, outputPath("clear_slime_lower_half_actual.png"));
  expectImageMatchesReference("clear_slime_128x96", image);
}

// At the cap, a ray still totally reflected inside the jelly takes the floor or sky along its
// reflection: the clear slime at depth 3 (what a moving frame shows) is not black in its lower half,
// but within 20 % of the converged light there (without that lookup it held 56 % of it).
TEST(Golden, ClearSlimeAtTheCapTakesTheSkyNotBlack) {
  Settings settings = clearSlimeScene();
  settings.slime.position = defaultSettings().slime.position;
  const TriangleMesh mesh = settledMesh(settings);
  Settings capped = settings;
  capped.render.depth = 3;
  const LowerHalf half = lowerHalf(capped, mesh, renderMesh(capped, mesh)), converged = lowerHalf(settings, mesh, renderMesh(settings, mesh));
  EXPECT_GT(half.mean, 0.8 * converged.mean) << "depth 3: mean radiance " << half.mean << " in the lower half, "
                                              << converged.mean << " at the cap of " << settings.render.depth;
  EXPECT_LT(half.mean, 1.2 * converged.mean);
}

TEST(Golden, DefaultScenePhysical) {
  Settings settings = smallScene(96, 72);
  settings.slime.level = 3;
  settings.render.shading = "physical";
  settings.render.depth = 16;  // as its reference was made: the paths totally reflected in the bun's base
  expectMatchesReference("default_physical_96x72", settings);
}

}  // namespace
}  // namespace slime::testing

// Golden images: fixed small scenes compared with PNGs stored in tests/render/reference/. On failure
// the rendered image and an 8×-amplified difference are written to SLIME_TEST_OUTPUT_DIR.
// Regenerate the references after an intended change of the picture (and look at them!):
//   SLIME_UPDATE_REFERENCES=1 build/render/tests/render_tests --gtest_filter='Golden.*'
#include "render_fixture.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

namespace slime::testing {
namespace {

// Pixels may differ by 2/255 (compilers, float contraction); at most 0.5 % of them by more.
constexpr double kTolerance = 2.0;
constexpr double kAllowedFraction = 0.005;

void expectMatchesReference(const std::string& name, const Settings& settings) {
  const Image image = renderScene(settings);
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

}  // namespace
}  // namespace slime::testing

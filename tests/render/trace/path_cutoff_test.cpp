// Where a path stops (shading_parameters.h): kInvisibleRadiance is the largest light that cannot move
// an 8-bit sRGB pixel by half a step, whatever the pixel holds; visibleThroughput scales it by the
// scene's brightest radiance; brightestRadiance bounds what the sky, the floor and the jelly return.
#include "render_fixture.h"

#include "render/image/image_io.h"
#include "render/trace/shading_parameters.h"

#include <gtest/gtest.h>

namespace slime::testing {
namespace {

// The change, in 8-bit steps, of a pixel's unrounded encoded value when `added` light joins `pixel`.
double encodedSteps(double pixel, double added) {
  return 255.0 * (linearToSrgb(static_cast<float>(pixel + added)) - linearToSrgb(static_cast<float>(pixel)));
}

TEST(PathCutoff, InvisibleRadianceMovesNoPixelByHalfAStep) {
  // Just below the threshold: under half a step on every pixel value, black to white (the curve's
  // steepest point is black, where the linear segment holds).
  for (int k = 0; k <= 10000; ++k) {
    const double pixel = k < 5000 ? k * 1e-6 : (k - 5000) / 5000.0;
    EXPECT_LT(encodedSteps(pixel, 0.999 * kInvisibleRadiance), 0.5) << "pixel " << pixel;
  }
  // Just above it, a black pixel moves by more: the threshold is tight, not merely safe.
  EXPECT_GT(encodedSteps(0.0, 1.01 * kInvisibleRadiance), 0.5);
  // A linear half step (0.5/255), the old cut, moves a black pixel by 6.5 half steps.
  EXPECT_GT(encodedSteps(0.0, 0.5 / 255.0), 3.0);
}

TEST(PathCutoff, ABrighterPixelToleratesMoreLight) {
  // Light that visibleLight calls invisible for a pixel holding `pixel` so far moves it (or anything
  // brighter it ends at) by under half a step; light just over the line moves it by more.
  for (int k = 1; k <= 400; ++k) {
    const float pixel = 1e-4f * std::pow(1.025f, static_cast<float>(k));  // 1e-4 … 2
    if (pixel >= 1.0f) break;
    const float limit = 0.5f / 255.0f / srgbSlope(pixel);
    EXPECT_FALSE(visibleLight(glm::vec3(0.999f * limit), glm::vec3(pixel)));
    EXPECT_TRUE(visibleLight(glm::vec3(1.001f * limit), glm::vec3(pixel)));
    for (const float later : {pixel, 1.5f * pixel, 4.0f * pixel})
      EXPECT_LT(encodedSteps(later, 0.999 * limit), 0.5) << "pixel " << pixel << " ending at " << later;
    if (pixel > 0.004f && pixel < 0.9f) {
      EXPECT_GT(encodedSteps(pixel, 1.1 * limit), 0.5) << "pixel " << pixel;
    }
  }
  // Grey 0.2 takes 12 times the light black does; a white channel takes any.
  EXPECT_TRUE(visibleLight(glm::vec3(2.0f * kInvisibleRadiance), glm::vec3(0.0f)));
  EXPECT_FALSE(visibleLight(glm::vec3(2.0f * kInvisibleRadiance), glm::vec3(0.2f)));
  EXPECT_FALSE(visibleLight(glm::vec3(0.5f, 0.0f, 0.0f), glm::vec3(1.0f, 0.2f, 0.2f)));
}

TEST(PathCutoff, ThroughputIsComparedChannelByChannelWithTheBrightestRadiance) {
  const glm::vec3 brightest{0.5f, 1.0f, 2.0f};
  // The blue channel carries most: its product decides.
  EXPECT_TRUE(visibleThroughput(glm::vec3(0.0f, 0.0f, 0.51f * kInvisibleRadiance), brightest));
  EXPECT_FALSE(visibleThroughput(glm::vec3(0.0f, 0.0f, 0.49f * kInvisibleRadiance), brightest));
  // Red needs twice as much throughput as at unit radiance.
  EXPECT_TRUE(visibleThroughput(glm::vec3(2.01f * kInvisibleRadiance, 0.0f, 0.0f), brightest));
  EXPECT_FALSE(visibleThroughput(glm::vec3(1.99f * kInvisibleRadiance, 0.0f, 0.0f), brightest));
  // A totally reflected path keeps its throughput: visible at any depth.
  EXPECT_TRUE(visibleThroughput(glm::vec3(1.0f), brightest));
  // Three partial reflections at normal incidence (F = 0.022 for n = 1.35) are 1.1e-5: invisible.
  EXPECT_FALSE(visibleThroughput(glm::vec3(0.022f * 0.022f * 0.022f), brightest));
}

TEST(PathCutoff, BrightestRadianceBoundsSkyFloorAndTheJellysOwnLight) {
  Settings settings = defaultSettings();
  const ShadingParameters classic = makeShadingParameters(settings, 100);
  const glm::vec3 albedo = brightestFloorAlbedo(settings.floor);
  for (int c = 0; c < 3; ++c) {
    // The sky's colours and the floor's brightest lit albedo lie below the bound.
    EXPECT_GE(classic.brightest[c], classic.skyHorizon[c]);
    EXPECT_GE(classic.brightest[c], classic.skyZenith[c]);
    EXPECT_GE(classic.brightest[c], albedo[c] * (classic.ambientLight[c] + classic.floorDiffuse * classic.lightColor[c]));
    EXPECT_GE(albedo[c], std::max(settings.floor.colorA[c], settings.floor.colorB[c]));
  }
  // Physical shading has no light of the jelly's own: a lower bound, paths that stop sooner.
  settings.render.shading = "physical";
  const ShadingParameters physical = makeShadingParameters(settings, 100);
  EXPECT_LT(largest(physical.brightest), largest(classic.brightest));
  // A light ten times as bright raises the floor's part of the bound tenfold.
  settings.light.color = {10.0, 10.0, 10.0};
  const ShadingParameters bright = makeShadingParameters(settings, 100);
  EXPECT_NEAR(bright.brightest.x, albedo.x * (bright.ambientLight.x + 10.0f * bright.floorDiffuse), 1e-5f);
  // An image floor may be white anywhere.
  settings.floor.pattern = "image";
  EXPECT_EQ(brightestFloorAlbedo(settings.floor), glm::vec3(1.0f));
}

TEST(PathCutoff, PhysicalShadingFoldsColourAndTransmissionIntoAbsorption) {
  Settings settings = defaultSettings();
  settings.render.shading = "physical";
  settings.render.optics = "seed";
  const ShadingParameters p = makeShadingParameters(settings, 100);
  EXPECT_EQ(p.optics, OpticsMode::Fresnel);
  EXPECT_EQ(p.transmission, 1.0f);
  EXPECT_EQ(p.ambient + p.diffuse + p.specular, 0.0f);
  // 1/k metres transmit colour × k_t.
  const double k = settings.slime.absorption;
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(std::exp(-p.slimeAbsorption[c] / k), settings.slime.color[c] * settings.slime.transmission, 1e-5);
}

}  // namespace
}  // namespace slime::testing

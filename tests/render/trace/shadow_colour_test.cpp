// The shadow's colour against a path tracer: the sky light that reaches the floor under and beside the
// green slime, in Cycles (stored floats) and here. Only the ambient lights the scene (light.color = 0):
// Cycles cannot bring a point light's light through the jelly (scripts/reference/cycles_scene.py), but
// the sky it path-traces, through and around the jelly. Without the slime's dimming of the floor's
// ambient (render/floor/sky_occlusion.h) the shadow's gain here is 1 in every channel, against
// Cycles' 0.7–0.8.
//
// The stored reference (tests/render/reference/shadow_sky_*.pfm): the resting level-4 ball of the
// small scene, 96×72, physical shading, the light off. To make it again:
//   SLIME_UPDATE_REFERENCES=1 build/release/tests/render_tests --gtest_filter='ShadowColour.*'
// writes the ball as build/test_output/shadow_sky_ball.glb; then
//   build/release/app/slime snapshot --size 96x72 -o /tmp/s.png --reference-scene /tmp/sky
//       --set slime.position=0,0,0.04 --set light.color=0,0,0 --set render.shading=physical
//   blender -b --factory-startup -P scripts/reference/cycles_scene.py -- --scene /tmp/sky/scene.json
//       --mesh build/release/tests/output/shadow_sky_ball.glb --out /tmp/sky/ref --samples 2048 --seed 1
//       --masks /tmp/sky/masks.pfm
//   (the same with --out /tmp/sky/bare --samples 64 --no-slime)
// and copy ref.pfm, bare.pfm, masks.pfm and masks_haze.pfm to tests/render/reference/ as
// shadow_sky_cycles.pfm, shadow_sky_cycles_bare.pfm, shadow_sky_masks.pfm and shadow_sky_haze.pfm.
#include "render_fixture.h"

#include "core/export/export_material.h"
#include "core/export/mesh_exporter.h"

#include <gtest/gtest.h>

#include <cstdlib>

namespace slime::testing {
namespace {

Image storedReference(const std::string& name) {
  return readPfm(std::string(SLIME_SOURCE_DIR) + "/tests/render/reference/shadow_sky_" + name + ".pfm");
}

// The mean over the shadow's pixels (masks' green) of (lit − haze) / (bare − haze), per channel.
glm::dvec3 shadowGain(const Image& lit, const Image& bare, const Image& masks, const Image& haze, int& pixels) {
  glm::dvec3 sum(0.0);
  pixels = 0;
  for (std::size_t i = 0; i < lit.pixels.size(); ++i) {
    if (!(masks.pixels[i].y > 0.5f)) continue;
    ++pixels;
    for (int c = 0; c < 3; ++c) sum[c] += (lit.pixels[i][c] - haze.pixels[i][c]) / (bare.pixels[i][c] - haze.pixels[i][c]);
  }
  return pixels > 0 ? sum / static_cast<double>(pixels) : glm::dvec3(0.0);
}

TEST(ShadowColour, SkyLightUnderTheSlimeMatchesThePathTracer) {
  Settings settings = smallScene(96, 72);
  settings.light.color = {0.0, 0.0, 0.0};
  settings.render.shading = "physical";
  const TriangleMesh ball = restingMesh(settings);
  const char* update = std::getenv("SLIME_UPDATE_REFERENCES");
  if (update && std::string(update) == "1") {
    writeSurfaceMesh(outputPath("shadow_sky_ball.glb"), surfaceMeshOf(0.0, ball.positions, ball.triangles),
                     exportMaterialOf(settings.slime));
    GTEST_SKIP() << "wrote " << outputPath("shadow_sky_ball.glb") << "; render the reference as the top of this file says";
  }
  const Image ours = renderMesh(settings, ball), oursBare = renderMesh(settings, {});
  const Image cycles = storedReference("cycles"), cyclesBare = storedReference("cycles_bare");
  const Image masks = storedReference("masks"), haze = storedReference("haze");
  ASSERT_EQ(cycles.width, ours.width);
  ASSERT_EQ(cycles.height, ours.height);
  int pixels = 0;
  const glm::dvec3 expected = shadowGain(cycles, cyclesBare, masks, haze, pixels);
  const glm::dvec3 gain = shadowGain(ours, oursBare, masks, haze, pixels);
  ASSERT_GT(pixels, 40) << "the shadow's mask is nearly empty";
  std::printf("shadow gain (%.3f, %.3f, %.3f), Cycles (%.3f, %.3f, %.3f), %d pixels\n", gain.x, gain.y, gain.z, expected.x, expected.y, expected.z, pixels);
  bool close = true;
  for (int c = 0; c < 3; ++c) {
    // Within 10 % of the path tracer's, each channel (its own noise over these pixels is below 1 %).
    EXPECT_NEAR(gain[c] / expected[c], 1.0, 0.10) << "channel " << c << ": gain " << gain[c] << " against Cycles' "
                                                  << expected[c] << " over " << pixels << " shadow pixels";
    close = close && std::abs(gain[c] / expected[c] - 1.0) <= 0.10;
  }
  if (!close) {
    writePng(ours, outputPath("shadow_sky_actual.png"));
    writePng(differenceImage(ours, cycles), outputPath("shadow_sky_diff.png"));
  }
}

}  // namespace
}  // namespace slime::testing

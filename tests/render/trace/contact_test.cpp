// Where the slime rests on the floor: no speckles over the contact patch. The settled slime's
// drawn surface lies in the plane z = 0 there, and a ray inside the jelly met the triangle or the
// floor by a rounding's toss (optics.h, kContactHeight). Two oracles at every level 0–4: no isolated
// outlier pixel (far from its eight neighbours while they agree), and Embree against the brute force
// on ≥ 99.9 % of the pixels within 1/255. Broken on purpose (meetsFloorInContact returning false):
// level 2 had 13 outliers under Embree, 16 under the brute force, and 0.50 % of pixels differing.
#include "render_fixture.h"

#include "core/simulation/simulation.h"

#include <gtest/gtest.h>

#include <cstdlib>

namespace slime::testing {
namespace {

// Pixels whose 8 neighbours agree within `agree` steps of 1/255 in every channel (a uniform patch, as
// the floor seen through the contact is) while the pixel is more than `far` steps from their mean in
// one channel (sRGB bytes, the border left out). Agreement in one channel alone is a coincidence at
// edges: on the settled level-2 slime the jelly's rim above and the shadowed floor below it share
// their red (79–90) once the floor's ambient is dimmed by the slime (render/floor/sky_occlusion.h),
// and the lit floor seen through the rim between them (133, 157, 107) read as a stray pixel.
int isolatedOutliers(const Image& image, int agree = 12, double far = 30.0) {
  const std::vector<std::uint8_t> bytes = toSrgb8(image);
  const int w = image.width, h = image.height;
  int count = 0;
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      bool uniform = true, off = false;
      for (int c = 0; c < 3; ++c) {
        int lowest = 255, highest = 0, sum = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            if (dx == 0 && dy == 0) continue;
            const int v = bytes[3 * ((y + dy) * w + x + dx) + c];
            lowest = std::min(lowest, v), highest = std::max(highest, v), sum += v;
          }
        const int v = bytes[3 * (y * w + x) + c];
        uniform = uniform && highest - lowest <= agree;
        off = off || std::abs(v - sum / 8.0) > far;
      }
      count += uniform && off;
    }
  return count;
}

void expectCleanContact(int level) {
  Settings settings = withoutCaustics(smallScene(200, 150));  // the camera's rays at the contact
  settings.slime.position = defaultSettings().slime.position;  // dropped and settled, as the snapshot
  settings.slime.level = level;
  // Levels 0 and 1 settle without adhesion. On the sticky default (8000 Pa) their 20- and 80-face
  // shapes keep a facet seen almost edge-on where the base meets the floor: one pixel apart from its
  // neighbours at each level (level 0 at the tip of the base, level 1 at the end of a one-pixel ledge),
  // the same in Embree and the brute force, so the geometry's, not a rounding's toss, which is what
  // this oracle is for. Levels 2–4 (the default and finer) settle on the sticky default.
  if (level < 2) settings.slime.adhesion = 0.0;
  const TriangleMesh mesh = settledMesh(settings);
  const Image embree = renderMesh(settings, mesh);
  settings.render.backend = "brute";
  const Image brute = renderMesh(settings, mesh);
  EXPECT_EQ(isolatedOutliers(embree), 0) << "level " << level << ", Embree";
  EXPECT_EQ(isolatedOutliers(brute), 0) << "level " << level << ", brute force";
  const ImageDifference d = compareImages(embree, brute, 1.0);
  EXPECT_LE(d.fractionAbove, 0.001) << "level " << level << ": largest " << d.largest << "/255";
  if (::testing::Test::HasFailure()) writePng(embree, outputPath("contact_level" + std::to_string(level) + ".png"));
}

TEST(Contact, OutlierCountFindsASpeckle) {
  Image image;
  image.resize(5, 5);
  for (glm::vec3& p : image.pixels) p = glm::vec3(0.2f);
  EXPECT_EQ(isolatedOutliers(image), 0);
  image.at(2, 2) = glm::vec3(0.2f, 0.6f, 0.2f);
  EXPECT_EQ(isolatedOutliers(image), 1);
}

TEST(Contact, SettledLevelTwoIsCleanAndMatchesTheBruteForce) { expectCleanContact(2); }

TEST(ContactLong, SettledLevelsZeroToFourAreCleanAndMatchTheBruteForce) {
  for (const int level : {0, 1, 3, 4}) expectCleanContact(level);
}

}  // namespace
}  // namespace slime::testing

// `slime view --check-every` (issue 28): the PSNR of the shown image against the full trace.
#include "app/viewer/image_check.h"

#include <gtest/gtest.h>

#include <cmath>

namespace slime {
namespace {

std::vector<std::uint8_t> uniform(int width, int height, std::uint8_t value) {
  std::vector<std::uint8_t> bytes(4 * static_cast<std::size_t>(width) * height, value);
  for (std::size_t i = 3; i < bytes.size(); i += 4) bytes[i] = 255;  // alpha: never compared
  return bytes;
}

TEST(ImageCheck, IdenticalImagesGiveTheCap) {
  const std::vector<std::uint8_t> image = uniform(4, 3, 90);
  EXPECT_EQ(psnrDb(image, 4, 3, image, 4, 3), kIdenticalPsnrDb);
}

TEST(ImageCheck, PsnrIsTenLogOfPeakOverMeanSquare) {
  // Every channel one step off: MSE 1, 20·log10(255) = 48.13 dB.
  EXPECT_NEAR(psnrDb(uniform(5, 2, 100), 5, 2, uniform(5, 2, 101), 5, 2), 20.0 * std::log10(255.0), 1e-9);
  // One channel of one pixel of two off by 255: MSE 255²/6.
  std::vector<std::uint8_t> shown = uniform(2, 1, 0);
  shown[1] = 255;
  EXPECT_NEAR(psnrDb(shown, 2, 1, uniform(2, 1, 0), 2, 1), 10.0 * std::log10(6.0), 1e-9);
  // Alpha differs only: not compared.
  std::vector<std::uint8_t> alpha = uniform(2, 1, 7);
  alpha[3] = 0;
  EXPECT_EQ(psnrDb(alpha, 2, 1, uniform(2, 1, 7), 2, 1), kIdenticalPsnrDb);
}

TEST(ImageCheck, ASmallerShownImageIsEnlargedBilinearly) {
  // A 2×1 image (0 | 200) shown over 4×1: centres at 0.125 .. 0.875 sample 0, 50, 150, 200.
  std::vector<std::uint8_t> shown = uniform(2, 1, 0);
  for (int c = 0; c < 3; ++c) shown[4 + c] = 200;
  std::vector<std::uint8_t> reference = uniform(4, 1, 0);
  const std::uint8_t expected[4] = {0, 50, 150, 200};
  for (int x = 0; x < 4; ++x)
    for (int c = 0; c < 3; ++c) reference[4 * x + c] = expected[x];
  EXPECT_EQ(psnrDb(shown, 2, 1, reference, 4, 1), kIdenticalPsnrDb);
  reference[4] = 60;  // one channel 10 off: MSE 100/12
  EXPECT_NEAR(psnrDb(shown, 2, 1, reference, 4, 1), 10.0 * std::log10(255.0 * 255.0 * 12.0 / 100.0), 1e-9);
}

TEST(ImageCheck, FiguresKeepMeanAndMinimumAndEveryKthFrameIsDue) {
  PsnrFigures figures;
  EXPECT_EQ(figures.meanDb(), 0.0);
  EXPECT_EQ(figures.minimumDb(), 0.0);
  figures.add(40.0);
  figures.add(34.0);
  EXPECT_EQ(figures.frames, 2);
  EXPECT_DOUBLE_EQ(figures.meanDb(), 37.0);
  EXPECT_DOUBLE_EQ(figures.minimumDb(), 34.0);
  const ImageCheck every3(3), never(0);
  EXPECT_TRUE(every3.due(0));
  EXPECT_FALSE(every3.due(1));
  EXPECT_TRUE(every3.due(6));
  EXPECT_FALSE(never.due(0));
}

}  // namespace
}  // namespace slime

// PNG output and input, and the floor texture: sRGB round trip, atomic writes, clear errors, and a
// footprint filter that matches the true average of the pattern (no aliasing towards the horizon).
#include "render_fixture.h"

#include "render/floor/floor_texture.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <filesystem>
#include <fstream>

namespace slime::testing {
namespace {

TEST(ImageIo, SrgbRoundTripIsExactInEightBits) {
  Image image;
  image.resize(16, 16);
  for (int i = 0; i < 256; ++i) image.pixels[i] = glm::vec3(srgbToLinear(i / 255.0f), srgbToLinear((255 - i) / 255.0f), 0.5f);
  const std::string path = outputPath("roundtrip.png");
  writePng(image, path);
  const Image back = readPng(path);
  ASSERT_EQ(back.width, 16);
  EXPECT_EQ(compareImages(image, back, 0.0).fractionAbove, 0.0);
  EXPECT_NEAR(linearToSrgb(0.5f), 0.735357f, 1e-5f);  // IEC 61966-2-1
}

// The table encoder against the curve it stands for, lround(linearToSrgb(x) · 255): at every float
// near each of the 255 points where the code steps (found by scanning, not by the encoder's own
// bisection), on a sweep of a million floats over [0, 1], and for what lies outside.
TEST(ImageIo, TableEncoderIsExactlyTheCurve) {
  const auto curve = [](float x) { return static_cast<int>(std::lround(linearToSrgb(x) * 255.0f)); };
  const std::uint32_t one = std::bit_cast<std::uint32_t>(1.0f);
  int mismatches = 0, steps = 0;
  std::vector<float> checked;  // for the encoder of whole pixels, below
  const auto check = [&](std::uint32_t bits) {
    const float x = std::bit_cast<float>(bits);
    checked.push_back(x);
    if (encodeSrgb8(x) != curve(x) && ++mismatches <= 5)
      ADD_FAILURE() << "x = " << x << ": table " << int(encodeSrgb8(x)) << ", curve " << curve(x);
  };
  for (std::uint32_t bits = 0; bits <= one; bits += 997) check(bits);
  // Each step of the code, located by bisection on the curve between neighbouring sweep points.
  for (std::uint32_t bits = 0; bits + 4096 <= one; bits += 4096) {
    if (curve(std::bit_cast<float>(bits)) == curve(std::bit_cast<float>(bits + 4096))) continue;
    std::uint32_t low = bits, high = bits + 4096;
    while (high - low > 1) {
      const std::uint32_t middle = low + (high - low) / 2;
      (curve(std::bit_cast<float>(middle)) == curve(std::bit_cast<float>(low)) ? low : high) = middle;
    }
    ++steps;
    for (std::uint32_t near = high - 3; near <= high + 3; ++near) check(near);
  }
  EXPECT_EQ(steps, 255);
  EXPECT_EQ(mismatches, 0);
  EXPECT_EQ(encodeSrgb8(-0.5f), 0);
  EXPECT_EQ(encodeSrgb8(std::numeric_limits<float>::quiet_NaN()), 0);
  EXPECT_EQ(encodeSrgb8(7.0f), 255);
  EXPECT_EQ(encodeSrgb8(std::numeric_limits<float>::infinity()), 255);
  Image image;
  image.resize(3, 2);
  image.pixels[4] = glm::vec3(0.2f, 0.5f, 0.9f);
  std::vector<std::uint8_t> rgba;
  toSrgb8(image, 4, rgba);
  ASSERT_EQ(rgba.size(), 24u);
  EXPECT_EQ(rgba[16], curve(0.2f));
  EXPECT_EQ(rgba[17], curve(0.5f));
  EXPECT_EQ(rgba[18], curve(0.9f));
  EXPECT_EQ(rgba[19], 255);

  // Whole pixels (8 at a time in AVX2 builds, with gathers) give every value's own code, NaN,
  // infinities and negatives included, with 3 channels and with 4.
  for (float special : {-0.5f, -0.0f, 7.0f, std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(),
                        -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::denorm_min()})
    checked.push_back(special);
  Image values;
  values.resize(static_cast<int>((checked.size() + 2) / 3), 1);
  for (std::size_t k = 0; k < checked.size(); ++k) values.pixels[k / 3][static_cast<int>(k % 3)] = checked[k];
  for (int channels : {3, 4}) {
    std::vector<std::uint8_t> bytes;
    toSrgb8(values, channels, bytes);
    int wrong = 0;
    for (std::size_t k = 0; k < checked.size(); ++k) {
      const std::size_t at = (k / 3) * static_cast<std::size_t>(channels) + k % 3;
      if (bytes[at] != encodeSrgb8(checked[k]) && ++wrong <= 5)
        ADD_FAILURE() << channels << " channels, x = " << checked[k] << ": " << int(bytes[at]) << ", alone "
                      << int(encodeSrgb8(checked[k]));
    }
    EXPECT_EQ(wrong, 0) << channels << " channels";
    if (channels == 4) {
      for (std::size_t pixel = 0; pixel < values.pixels.size(); ++pixel) ASSERT_EQ(bytes[4 * pixel + 3], 255) << pixel;
    }
  }
}

TEST(ImageIo, PfmKeepsEveryFloatAndTheRowOrder) {
  // A float image compared with a path tracer's must come back bit for bit: values above 1, tiny ones,
  // and the top row on top (PFM stores rows bottom to top).
  Image image;
  image.resize(5, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) image.at(x, y) = glm::vec3(x + 10.0f * y, 1e-7f * (x + 1), 3.75f - y);
  const std::string path = outputPath("float.pfm");
  writePfm(image, path);
  const Image back = readPfm(path);
  ASSERT_EQ(back.width, 5);
  ASSERT_EQ(back.height, 3);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) EXPECT_EQ(back.pixels[i], image.pixels[i]) << "pixel " << i;
  std::ofstream(outputPath("not.pfm")) << "P6\n2 2\n255\n";
  EXPECT_THROW(readPfm(outputPath("not.pfm")), std::runtime_error);
  std::ofstream(outputPath("short.pfm")) << "PF\n4 4\n-1.0\n" << std::string(20, '\0');
  EXPECT_THROW(readPfm(outputPath("short.pfm")), std::runtime_error);
}

TEST(ImageIo, FailedWriteLeavesNoFile) {
  Image image;
  image.resize(4, 4);
  const std::string path = outputPath("no_such_dir/out.png");
  EXPECT_THROW(writePng(image, path), std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_FALSE(std::filesystem::exists(outputPath("no_such_dir")));
}

TEST(ImageIo, NonPngIsAClearSettingsError) {
  const std::string path = outputPath("not_a_png.png");
  std::ofstream(path) << "hello";
  FloorSettings floor;
  floor.pattern = "image";
  floor.image = path;
  try {
    FloorTexture texture(floor);
    FAIL() << "a text file was accepted as a PNG";
  } catch (const SettingsError& e) {
    EXPECT_NE(std::string(e.what()).find("floor.image"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not a PNG"), std::string::npos) << e.what();
  }
  floor.image = "/nonexistent/wood.png";
  EXPECT_THROW(FloorTexture{floor}, SettingsError);
}

TEST(ImageIo, ImageFloorUsesTheMipmapAverageFarAway) {
  Image checker;
  checker.resize(64, 64);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) checker.at(x, y) = glm::vec3(((x + y) % 2) ? 1.0f : 0.0f);
  const std::string path = outputPath("pixel_checker.png");
  writePng(checker, path);
  FloorSettings floor;
  floor.pattern = "image";
  floor.image = path;
  floor.scale = 0.64;  // 1 cm texels
  const FloorTexture texture(floor);
  const glm::vec3 far = texture.albedo({0.123f, 0.456f}, {0.2f, 0.2f});
  EXPECT_NEAR(far.x, 0.5f, 0.02f);
}

// The analytic box filter against brute-force averaging of point samples over the same box.
TEST(FloorTexture, FilteredPatternsEqualTheirBoxAverage) {
  for (const char* pattern : {"checker", "tiles", "planks"}) {
    FloorSettings floor;
    floor.pattern = pattern;
    const FloorTexture texture(floor);
    for (const float halfWidth : {0.004f, 0.03f, 0.3f}) {
      const glm::vec2 centre{0.237f, -0.412f};
      glm::vec3 sum(0.0f);
      constexpr int kSamples = 200;
      for (int j = 0; j < kSamples; ++j)
        for (int i = 0; i < kSamples; ++i)
          sum += texture.albedo(centre + halfWidth * glm::vec2((i + 0.5f) / kSamples * 2 - 1, (j + 0.5f) / kSamples * 2 - 1), {0.0f, 0.0f});
      const glm::vec3 average = sum / float(kSamples * kSamples);
      const glm::vec3 filtered = texture.albedo(centre, {halfWidth, halfWidth});
      // Checker and grout lines are filtered exactly; planks fade per-board detail towards the mean.
      const float tolerance = std::string(pattern) == "planks" ? 0.06f : 0.01f;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(filtered[c], average[c], tolerance) << pattern << " half width " << halfWidth;
    }
  }
}

}  // namespace
}  // namespace slime::testing

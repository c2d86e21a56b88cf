// inverseCubeRoot against the library's cube root, from the smallest normal double to the largest
// and densely near 1, where the Maxwell branch's determinants lie.
#include "core/bulk/cube_root.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>

namespace slime {
namespace {

// Distance in units in the last place between two positive doubles.
std::int64_t ulpsApart(double a, double b) {
  const std::int64_t difference = std::bit_cast<std::int64_t>(a) - std::bit_cast<std::int64_t>(b);
  return difference < 0 ? -difference : difference;
}

// 1/std::cbrt is itself up to 5 ulps off (glibc's cbrt up to 3, the division half of one), and
// 1/cbrtl rounded to double within one: ours must be within 1 ulp of that and 6 of the former.
// Returns whether ours is 1/cbrtl rounded.
bool expectInverseCubeRoot(double x) {
  const double ours = inverseCubeRoot(x);
  const double reference = static_cast<double>(1.0L / std::cbrt(static_cast<long double>(x)));
  EXPECT_LE(ulpsApart(ours, 1.0 / std::cbrt(x)), 6) << "x = " << x;
  EXPECT_LE(ulpsApart(ours, reference), 1) << "x = " << x;
  return ours == reference;
}

// The last Newton step leaves only the final rounding: 0.03 % of the arguments were 1 ulp away
// from 1/cbrtl rounded (12 % without that step).
constexpr double kRoundedAwayFraction = 0.002;

TEST(InverseCubeRoot, MatchesTheLibraryFromTinyToHuge) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> exponent(std::log(std::numeric_limits<double>::min()),
                                                  std::log(std::numeric_limits<double>::max()));
  int roundedAway = 0;
  for (int i = 0; i < 200000; ++i) roundedAway += !expectInverseCubeRoot(std::exp(exponent(random)));
  EXPECT_LE(roundedAway, kRoundedAwayFraction * 200000);
  expectInverseCubeRoot(std::numeric_limits<double>::min());
  expectInverseCubeRoot(std::numeric_limits<double>::max());
  expectInverseCubeRoot(1e-300);
  expectInverseCubeRoot(1e300);
}

TEST(InverseCubeRoot, MatchesTheLibraryNearOne) {
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> near(0.5, 2.0);
  int roundedAway = 0;
  for (int i = 0; i < 200000; ++i) roundedAway += !expectInverseCubeRoot(near(random));
  EXPECT_LE(roundedAway, kRoundedAwayFraction * 200000);
  for (int k = -1000; k <= 1000; ++k) expectInverseCubeRoot(1.0 + k * 1e-12);
  EXPECT_EQ(inverseCubeRoot(1.0), 1.0);
  EXPECT_EQ(inverseCubeRoot(8.0), 0.5);
  EXPECT_EQ(inverseCubeRoot(0.125), 2.0);
}

TEST(InverseCubeRoot, MatchesTheLibraryOnSubnormals) {
  const double smallest = std::numeric_limits<double>::denorm_min();
  for (double x = smallest; x < std::numeric_limits<double>::min(); x = std::nextafter(1.37 * x, 1.0))
    expectInverseCubeRoot(x);
  std::mt19937_64 random(13);
  std::uniform_real_distribution<double> below(0.0, std::numeric_limits<double>::min());
  for (int i = 0; i < 10000; ++i) expectInverseCubeRoot(std::max(below(random), smallest));
}

// Outside the positive doubles it is the library's 1/cbrt.
TEST(InverseCubeRoot, LeavesTheRestToTheLibrary) {
  EXPECT_EQ(inverseCubeRoot(0.0), std::numeric_limits<double>::infinity());
  EXPECT_EQ(inverseCubeRoot(std::numeric_limits<double>::infinity()), 0.0);
  EXPECT_TRUE(std::isnan(inverseCubeRoot(std::numeric_limits<double>::quiet_NaN())));
  EXPECT_EQ(inverseCubeRoot(-8.0), -0.5);
}

}  // namespace
}  // namespace slime

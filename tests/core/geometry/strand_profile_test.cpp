// strandThickness: the thickness across a strand at a fraction of the way between the hands.
#include "core/geometry/strand_profile.h"

#include <gtest/gtest.h>

#include <cmath>

namespace slime {
namespace {

// Rings of 32 points about the x axis at 1 mm steps, radius r(x); the hands at ±0.2 m.
std::vector<glm::dvec3> spindle(double (*radius)(double)) {
  std::vector<glm::dvec3> points;
  for (int i = -200; i <= 200; ++i) {
    const double x = 0.001 * i, r = radius(x);
    for (int k = 0; k < 32; ++k) {
      const double angle = 2.0 * M_PI * k / 32.0;
      points.emplace_back(x, r * std::cos(angle), 0.1 + r * std::sin(angle));
    }
  }
  return points;
}

double thinMiddle(double x) { return 0.01 + 0.05 * x * x / 0.04; }  // 1 cm in the middle, 6 cm at the hands

TEST(StrandProfile, MeasuresTheThicknessAcrossAtAFractionOfTheWay) {
  const std::vector<glm::dvec3> points = spindle(thinMiddle);
  const glm::dvec3 a(-0.2, 0.0, 0.1), b(0.2, 0.0, 0.1);
  // Within 0.5 mm of the plane lies one ring: its diameter.
  for (double s : {0.25, 0.5, 0.75}) {
    const double x = -0.2 + 0.4 * s;
    EXPECT_NEAR(strandThickness(points, a, b, s, 0.0005), 2.0 * thinMiddle(x), 1e-9) << s;
  }
  EXPECT_LT(strandThickness(points, a, b, 0.5), strandThickness(points, a, b, 0.25));
  // The hands' order does not matter.
  EXPECT_NEAR(strandThickness(points, b, a, 0.5, 0.0005), 0.02, 1e-9);
  // Nothing near the plane, or no line: 0.
  EXPECT_EQ(strandThickness(points, a, b, 2.0), 0.0);
  EXPECT_EQ(strandThickness(points, a, a, 0.5), 0.0);
  EXPECT_EQ(strandThickness(points, a, a + glm::dvec3(0.0, 0.0, 0.3), 0.5), 0.0);
}

}  // namespace
}  // namespace slime

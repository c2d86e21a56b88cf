// Optics free functions against values computed by hand.
#include "render/trace/optics.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>

namespace slime {
namespace {

TEST(Optics, ReflectMirrorsAboutTheNormal) {
  // v = (1, −1, 0)/√2 onto the floor n = (0, 0, 1)... use n = (0, 1, 0): v_r = v − 2 (n·v) n = (1, 1, 0)/√2.
  const glm::vec3 v = glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f));
  const glm::vec3 r = reflect(v, {0.0f, 1.0f, 0.0f});
  EXPECT_NEAR(r.x, 1.0f / std::sqrt(2.0f), 1e-6f);
  EXPECT_NEAR(r.y, 1.0f / std::sqrt(2.0f), 1e-6f);
  EXPECT_NEAR(r.z, 0.0f, 1e-6f);
}

TEST(Optics, RefractFollowsSnell) {
  // 45° from air into n = 1.5: sin θt = sin 45° / 1.5 = 0.47140, θt = 28.1255°.
  const glm::vec3 v = glm::normalize(glm::vec3(1.0f, 0.0f, -1.0f));
  const auto t = refract(v, {0.0f, 0.0f, 1.0f}, 1.0f, 1.5f);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(glm::length(*t), 1.0f, 1e-6f);
  EXPECT_NEAR(t->x, 0.47140f, 1e-5f);          // sin θt
  EXPECT_NEAR(t->z, -0.88192f, 1e-5f);         // −cos θt
  EXPECT_NEAR(t->y, 0.0f, 1e-7f);
}

TEST(Optics, RefractAtNormalIncidenceGoesStraight) {
  const auto t = refract({0.0f, 0.0f, -1.0f}, {0.0f, 0.0f, 1.0f}, 1.0f, 1.35f);
  ASSERT_TRUE(t.has_value());
  EXPECT_NEAR(t->z, -1.0f, 1e-7f);
}

TEST(Optics, TotalInternalReflectionBeyondTheCriticalAngle) {
  // From n = 1.5 into air the critical angle is asin(1/1.5) = 41.81°: 40° passes, 45° does not.
  const glm::vec3 n{0.0f, 0.0f, 1.0f};
  const float degree = 3.14159265f / 180.0f;
  const glm::vec3 at40{std::sin(40 * degree), 0.0f, -std::cos(40 * degree)};
  const glm::vec3 at45{std::sin(45 * degree), 0.0f, -std::cos(45 * degree)};
  EXPECT_TRUE(refract(at40, n, 1.5f, 1.0f).has_value());
  EXPECT_FALSE(refract(at45, n, 1.5f, 1.0f).has_value());
  EXPECT_FLOAT_EQ(fresnelDielectric(std::cos(45 * degree), 1.5f, 1.0f), 1.0f);
}

TEST(Optics, FresnelAtNormalIncidenceIsTheSquaredRatio) {
  // F(0) = ((n1 − n2)/(n1 + n2))²: 0.04 for glass, 0.022 for n = 1.35, the same from either side.
  EXPECT_NEAR(fresnelDielectric(1.0f, 1.0f, 1.5f), 0.04f, 1e-6f);
  EXPECT_NEAR(fresnelDielectric(1.0f, 1.0f, 1.35f), (0.35f / 2.35f) * (0.35f / 2.35f), 1e-6f);
  EXPECT_NEAR(fresnelDielectric(1.0f, 1.35f, 1.0f), (0.35f / 2.35f) * (0.35f / 2.35f), 1e-6f);
}

TEST(Optics, FresnelAtBrewstersAngleHasNoParallelPart) {
  // At θB = atan(1.5) = 56.31° r_p = 0, so F = r_s²/2; r_s = (cos θi − 1.5 cos θt)/(cos θi + 1.5 cos θt)
  // with θt = 90° − θB: cos θi = 0.55470, cos θt = 0.83205, r_s = −0.38462, F = 0.073964.
  EXPECT_NEAR(fresnelDielectric(std::cos(std::atan(1.5f)), 1.0f, 1.5f), 0.073964f, 1e-5f);
}

TEST(Optics, FresnelAtGrazingIncidenceIsOne) {
  EXPECT_NEAR(fresnelDielectric(0.0f, 1.0f, 1.5f), 1.0f, 1e-6f);
}

TEST(Optics, FresnelVanishesBetweenEqualIndices) {
  EXPECT_NEAR(fresnelDielectric(0.3f, 1.0f, 1.0f), 0.0f, 1e-7f);
}

TEST(Optics, BeerLambertIsExponentialPerChannel) {
  const glm::vec3 t = beerLambert({0.0f, 10.0f, 100.0f}, 0.02f);
  EXPECT_FLOAT_EQ(t.x, 1.0f);
  EXPECT_NEAR(t.y, std::exp(-0.2f), 1e-6f);
  EXPECT_NEAR(t.z, std::exp(-2.0f), 1e-6f);
}

TEST(Optics, AbsorptionMakesTheColourAfterOneOverK) {
  // σ_c = k (−ln c_c): a path of 1/k metres transmits exactly the colour.
  const glm::vec3 color{0.25f, 0.85f, 1.0f};
  const float k = 20.0f;
  const glm::vec3 sigma = absorptionCoefficients(color, k);
  EXPECT_NEAR(sigma.x, -k * std::log(0.25f), 1e-4f);
  EXPECT_FLOAT_EQ(sigma.z, 0.0f);
  const glm::vec3 t = beerLambert(sigma, 1.0f / k);
  EXPECT_NEAR(t.x, 0.25f, 1e-5f);
  EXPECT_NEAR(t.y, 0.85f, 1e-5f);
  EXPECT_NEAR(t.z, 1.0f, 1e-6f);
  EXPECT_EQ(absorptionCoefficients(color, 0.0f), glm::vec3(0.0f));
  EXPECT_TRUE(std::isfinite(absorptionCoefficients({0.0f, 0.0f, 0.0f}, k).x));  // black stays finite
}

TEST(Optics, OffsetMovesToTheSideTheRayLeavesTowards) {
  const glm::vec3 p{0.0f}, n{0.0f, 0.0f, 1.0f};
  EXPECT_GT(offsetRayOrigin(p, n, {0.0f, 0.6f, 0.8f}).z, 0.0f);
  EXPECT_LT(offsetRayOrigin(p, n, {0.0f, 0.6f, -0.8f}).z, 0.0f);
  EXPECT_FLOAT_EQ(offsetRayOrigin(p, n, {0.0f, 0.0f, 1.0f}).z, kRayOffset);
}

}  // namespace
}  // namespace slime

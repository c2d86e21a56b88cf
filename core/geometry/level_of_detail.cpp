#include "core/geometry/level_of_detail.h"

#include "core/geometry/icosphere.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace slime {
namespace {

// δ_L measured on makeIcosphere(L, 1, origin) (tests/core/geometry/level_of_detail_test.cpp checks it).
constexpr std::array<double, kMaxLevel + 1> kSagitta = {
    0.205345528, 0.065827641, 0.0177530536, 0.00452836761, 0.00113788327, 0.000284835354, 7.12316626e-05,
    1.78093428e-05};

constexpr double kPi = 3.14159265358979323846;

}  // namespace

double icosphereSagitta(int level) {
  if (level < 0) return kSagitta.front();
  if (level <= kMaxLevel) return kSagitta[static_cast<std::size_t>(level)];
  return kSagitta.back() * std::pow(0.25, level - kMaxLevel);
}

double pixelsPerMetre(double distance, double fovDegrees, int imageHeight) {
  return imageHeight / (2.0 * distance * std::tan(fovDegrees * kPi / 360.0));
}

double projectedSagittaPixels(int level, double radius, double distance, double fovDegrees, int imageHeight) {
  return icosphereSagitta(level) * radius * pixelsPerMetre(distance, fovDegrees, imageHeight);
}

double largestMotionPixels(const std::vector<glm::dvec3>& drawn, const std::vector<glm::dvec3>& now,
                           const glm::dvec3& eye, double fovDegrees, int imageHeight) {
  constexpr double kUnbounded = std::numeric_limits<double>::infinity();
  if (drawn.size() != now.size() || now.empty()) return kUnbounded;
  glm::dvec3 centre(0.0);
  for (const glm::dvec3& p : now) centre += p;
  centre /= static_cast<double>(now.size());
  double boundSquared = 0.0, motionSquared = 0.0;
  for (std::size_t i = 0; i < now.size(); ++i) {
    boundSquared = std::max(boundSquared, glm::dot(now[i] - centre, now[i] - centre));
    const double moved = glm::dot(now[i] - drawn[i], now[i] - drawn[i]);
    if (!(moved <= motionSquared)) motionSquared = moved;  // NaN wins, and so reads as unbounded
  }
  const double nearest = glm::length(eye - centre) - std::sqrt(boundSquared);
  if (!(nearest > 0.0) || !std::isfinite(motionSquared)) return kUnbounded;
  return std::sqrt(motionSquared) * pixelsPerMetre(nearest, fovDegrees, imageHeight);
}

int chooseLevel(double radius, double distance, double fovDegrees, int imageHeight, double maxErrorPixels) {
  if (!(distance > radius) || imageHeight <= 0 || !(fovDegrees > 0.0 && fovDegrees < 180.0)) return kMaxLevel;
  for (int level = 0; level < kMaxLevel; ++level)
    if (projectedSagittaPixels(level, radius, distance, fovDegrees, imageHeight) <= maxErrorPixels) return level;
  return kMaxLevel;
}

int effectiveLevel(const Settings& settings) {
  const SlimeSettings& slime = settings.slime;
  if (!slime.autoLevel) return slime.level;
  const glm::dvec3 restingCentre{slime.position.x, slime.position.y, slime.radius};
  const double distance = glm::length(settings.camera.position - restingCentre);
  return chooseLevel(slime.radius, distance, settings.camera.fov, settings.camera.height);
}

}  // namespace slime

#include "core/level_of_detail.h"

#include "core/icosphere.h"

#include <glm/geometric.hpp>

#include <array>
#include <cmath>

namespace slime {
namespace {

// δ_L measured on makeIcosphere(L, 1, origin) (tests/core/level_of_detail_test.cpp checks it).
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

double projectedSagittaPixels(int level, double radius, double distance, double fovDegrees, int imageHeight) {
  const double pixelsPerMetre = imageHeight / (2.0 * distance * std::tan(fovDegrees * kPi / 360.0));
  return icosphereSagitta(level) * radius * pixelsPerMetre;
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

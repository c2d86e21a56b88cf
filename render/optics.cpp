#include "render/optics.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace slime {

glm::vec3 reflect(const glm::vec3& v, const glm::vec3& n) { return v - 2.0f * glm::dot(n, v) * n; }

std::optional<glm::vec3> refract(const glm::vec3& v, const glm::vec3& n, float etaFrom, float etaTo) {
  const float eta = etaFrom / etaTo;
  const float cosIncident = -glm::dot(n, v);
  const float sin2Transmitted = eta * eta * std::max(0.0f, 1.0f - cosIncident * cosIncident);
  // Handle total internal reflection: no transmitted angle exists.
  if (sin2Transmitted > 1.0f) return std::nullopt;
  const float cosTransmitted = std::sqrt(1.0f - sin2Transmitted);
  return eta * v + (eta * cosIncident - cosTransmitted) * n;  // unit when v and n are
}

float fresnelDielectric(float cosIncident, float etaFrom, float etaTo) {
  cosIncident = std::clamp(cosIncident, 0.0f, 1.0f);
  const float sinIncident = std::sqrt(std::max(0.0f, 1.0f - cosIncident * cosIncident));
  const float sinTransmitted = etaFrom / etaTo * sinIncident;
  if (sinTransmitted >= 1.0f) return 1.0f;
  const float cosTransmitted = std::sqrt(std::max(0.0f, 1.0f - sinTransmitted * sinTransmitted));
  const float rs = (etaFrom * cosIncident - etaTo * cosTransmitted) / (etaFrom * cosIncident + etaTo * cosTransmitted);
  const float rp = (etaTo * cosIncident - etaFrom * cosTransmitted) / (etaTo * cosIncident + etaFrom * cosTransmitted);
  return 0.5f * (rs * rs + rp * rp);
}

glm::vec3 beerLambert(const glm::vec3& sigma, float length) {
  return {std::exp(-sigma.x * length), std::exp(-sigma.y * length), std::exp(-sigma.z * length)};
}

glm::vec3 absorptionCoefficients(const glm::vec3& color, float absorption) {
  constexpr float kDarkest = 1e-3f;
  return {-absorption * std::log(std::clamp(color.x, kDarkest, 1.0f)),
          -absorption * std::log(std::clamp(color.y, kDarkest, 1.0f)),
          -absorption * std::log(std::clamp(color.z, kDarkest, 1.0f))};
}

glm::vec3 offsetRayOrigin(const glm::vec3& p, const glm::vec3& geometricNormal, const glm::vec3& direction,
                          float offset) {
  return glm::dot(direction, geometricNormal) >= 0.0f ? p + offset * geometricNormal : p - offset * geometricNormal;
}

}  // namespace slime

// Geometric optics as free functions over plain values: reflection, Snell refraction with total
// internal reflection, the dielectric Fresnel reflectance, Beer–Lambert absorption, the slime's
// per-channel absorption coefficient and the secondary-ray origin offset.
#pragma once

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <optional>

namespace slime {

// Inline: they run several times for every ray the tracer shades.

// Mirror reflection of direction v about unit normal n: v_r = v − 2 (n·v) n.
inline glm::vec3 reflect(const glm::vec3& v, const glm::vec3& n) { return v - 2.0f * glm::dot(n, v) * n; }

// Refraction of unit direction v through a surface with unit normal n facing the incoming side
// (n·v < 0), from index etaFrom into index etaTo (Snell: etaFrom sin θi = etaTo sin θt):
//   t = η v + (η cos θi − cos θt) n,  η = etaFrom / etaTo,  cos θt = √(1 − η² (1 − cos² θi)).
// Empty when sin θt > 1: total internal reflection.
inline std::optional<glm::vec3> refract(const glm::vec3& v, const glm::vec3& n, float etaFrom, float etaTo) {
  const float eta = etaFrom / etaTo;
  const float cosIncident = -glm::dot(n, v);
  const float sin2Transmitted = eta * eta * std::max(0.0f, 1.0f - cosIncident * cosIncident);
  if (sin2Transmitted > 1.0f) return std::nullopt;  // total internal reflection
  const float cosTransmitted = std::sqrt(1.0f - sin2Transmitted);
  return eta * v + (eta * cosIncident - cosTransmitted) * n;  // unit when v and n are
}

// Unpolarised dielectric Fresnel reflectance, the mean of the s and p terms:
//   r_s = (η1 cos θi − η2 cos θt)/(η1 cos θi + η2 cos θt), r_p = (η2 cos θi − η1 cos θt)/(η2 cos θi + η1 cos θt),
//   F = (r_s² + r_p²)/2; F = 1 under total internal reflection. cosIncident = |n·v|.
inline float fresnelDielectric(float cosIncident, float etaFrom, float etaTo) {
  cosIncident = std::clamp(cosIncident, 0.0f, 1.0f);
  const float sinIncident = std::sqrt(std::max(0.0f, 1.0f - cosIncident * cosIncident));
  const float sinTransmitted = etaFrom / etaTo * sinIncident;
  if (sinTransmitted >= 1.0f) return 1.0f;
  const float cosTransmitted = std::sqrt(std::max(0.0f, 1.0f - sinTransmitted * sinTransmitted));
  const float rs = (etaFrom * cosIncident - etaTo * cosTransmitted) / (etaFrom * cosIncident + etaTo * cosTransmitted);
  const float rp = (etaTo * cosIncident - etaFrom * cosTransmitted) / (etaTo * cosIncident + etaFrom * cosTransmitted);
  return 0.5f * (rs * rs + rp * rp);
}

// Beer–Lambert transmittance per channel after a path of `length` metres: T = exp(−σ l).
inline glm::vec3 beerLambert(const glm::vec3& sigma, float length) {
  return {std::exp(-sigma.x * length), std::exp(-sigma.y * length), std::exp(-sigma.z * length)};
}

// The slime's per-channel absorption coefficient (1/m) from its colour and absorption k:
//   σ_c = k · (−ln max(color_c, 1/1000)),
// so a path of 1/k metres through the jelly transmits exactly `color` (T_c = color_c^(k l)): the
// slime's hue comes from what it absorbs, k says how quickly; k = 0 or white means clear.
glm::vec3 absorptionCoefficients(const glm::vec3& color, float absorption);

// The secondary-ray offset, in metres: a new ray starts at p + kRayOffset · n_g on the side of the
// geometric normal n_g it leaves towards, with tNear = 0. 1e-5 m is ≈ 1,000 float ulps at the scene's
// 0.1 m coordinates and 1/4,000 of the slime's radius, far below a pixel's footprint
// (render_tests: SecondaryOffset.* measure the self-intersection threshold and check this margin).
constexpr float kRayOffset = 1e-5f;

// The jelly lies on the floor: where its surface is within kContactHeight of the plane z = 0 it is
// in optical contact with it (no air between), so a ray inside the slime that reaches its surface
// there meets the floor, not a jelly–air interface. The drawn surface's contact patch lies exactly
// in the plane (its vertices at z = 0 ± 1e-19 m), where the triangle's t and the plane's t differ
// only by rounding: which one came first was a coin toss, and the loser's total internal reflection
// drew green speckles over the contact patch. Twice the ray offset, so a ray started
// kRayOffset above the floor inside the patch (a shadow ray) is above the patch's triangles.
constexpr float kContactHeight = 2.0f * kRayOffset;

// p moved by `offset` along n_g towards the side `direction` points to.
inline glm::vec3 offsetRayOrigin(const glm::vec3& p, const glm::vec3& geometricNormal, const glm::vec3& direction,
                                 float offset = kRayOffset) {
  return glm::dot(direction, geometricNormal) >= 0.0f ? p + offset * geometricNormal : p - offset * geometricNormal;
}

}  // namespace slime

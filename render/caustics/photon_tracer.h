// Caustics, step one: photons shot from the point light through the slime (Fresnel at each crossing,
// Beer–Lambert inside, total internal reflection followed) to where they land on the floor z = 0.
#pragma once

#include "render/trace/ray.h"
#include "render/trace/shading_parameters.h"
#include "render/slime/slime_geometry.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace slime {

// A photon on the floor: where, and its weight per channel (the fraction of its emitted power that
// arrived: Fresnel, k_t, Beer–Lambert along its path). Its power is weight × I × Ω/N (PhotonCone).
struct PhotonLanding {
  float x = 0.0f, y = 0.0f;
  glm::vec3 weight{0.0f};
};

// Where the photons' power went, in units of one photon's emitted power, summed per channel.
struct PhotonTally {
  double emitted = 0.0;       // photons shot
  double intercepted = 0.0;   // photons that met the slime
  glm::dvec3 reflected{0.0};  // turned back at the first crossing (the slime's reflection, not traced)
  glm::dvec3 landed{0.0};     // reached the floor through the slime
  glm::dvec3 escaped{0.0};    // left the slime upwards, away from the floor
  glm::dvec3 dropped{0.0};    // branches cut off (weight below kMinRayWeight × 1/8, or too many crossings)
  PhotonTally& operator+=(const PhotonTally& o);
};

// The cone of directions from the light that can reach the slime (its bounding sphere): photons
// are shot uniformly in solid angle inside it, Ω = 2π (1 − cos α), sin α = R / D (the whole
// sphere of directions when the light is inside the bounds).
struct PhotonCone {
  glm::vec3 apex{0.0f}, axis{0.0f, 0.0f, -1.0f}, u{1.0f, 0.0f, 0.0f}, v{0.0f, 1.0f, 0.0f};
  float cosHalfAngle = 1.0f;
  double solidAngle = 0.0;
  bool empty() const { return solidAngle <= 0.0; }
  // Direction of photon `index`: the R2 low-discrepancy sequence (Roberts 2018) mapped to the cone
  // uniformly in solid angle (cos θ = 1 − s (1 − cos α), φ = 2π t), so any run of consecutive
  // photons covers it evenly and more photons refine the same pattern.
  glm::vec3 direction(std::uint64_t index) const;
};
PhotonCone photonCone(const SlimeGeometry& geometry, const glm::vec3& light);

struct WavefrontVertex;  // wavefront.h

class PhotonTracer {
 public:
  // `minVertexWeight`: the least weight a wavefront vertex's branch goes on with (traceVertex). By
  // default the Whitted tracer's threshold itself: a vertex follows every branch, no roulette, those
  // below it (a third partial reflection inside, F³ ≈ 10⁻⁴) cut off as the eye's rays cut them.
  PhotonTracer(const SlimeGeometry& geometry, const SlimeIntersector& intersector, const ShadingParameters& parameters,
               float minVertexWeight = kMinRayWeight)
      : geometry_(geometry), intersector_(intersector), parameters_(parameters), minVertexWeight_(minVertexWeight) {}
  // Photons [first, first + count) of the cone's sequence: their floor landings appended to `landings`.
  // With `straight`, each photon that would meet the floor along its straight line from the light is
  // appended there too, at that point, with weight 1 if it missed the slime (the direct light) and 0
  // if it met it: the caustic map's reference for its ratio (caustic_map.h).
  void trace(const PhotonCone& cone, std::uint64_t first, std::uint64_t count, std::vector<PhotonLanding>& landings,
             PhotonTally& tally, std::vector<PhotonLanding>* straight = nullptr) const;
  // One vertex of the light's wavefront (wavefront.h) along `fromLight`: every branch of its path
  // tree followed (no Russian roulette: a partial reflection inside goes on with its weight F while
  // that is at least minVertexWeight), Snell and Fresnel about the shading normal the eye's rays
  // refract about (the hit triangle's vertex normals interpolated, with render.normals=smooth), so
  // that neighbouring vertices land on a continuous wavefront and not facet by facet.
  void traceVertex(const Ray& fromLight, WavefrontVertex& vertex, PhotonTally& tally) const;

 private:
  void tracePhoton(const Ray& fromLight, std::uint64_t index, std::vector<PhotonLanding>& landings, PhotonTally& tally) const;
  float surfaceTransmission(float cosine, bool entering, float& reflectedShare) const;
  // The normal Snell and Fresnel use at a crossing, facing the incoming `direction` (`outward`: the geometric one).
  glm::vec3 shadingFacing(const SlimeHit& hit, const glm::vec3& outward, const glm::vec3& direction, bool entering) const;

  const SlimeGeometry& geometry_;
  const SlimeIntersector& intersector_;
  const ShadingParameters& parameters_;
  float minVertexWeight_ = kMinRayWeight;
};

}  // namespace slime

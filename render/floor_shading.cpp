// The floor and the sky as the Whitted tracer sees them: where a ray meets the plane z = 0, the
// pixel's footprint there, the pattern over it, the light and the horizon haze (litFloor), one ray
// at a time or 8 lanes at a time; and the sky's gradient. The floor has no slime in it: the tracer
// adds the slime's shadow (whitted_tracer.cpp).
#include "render/lanes.h"
#include "render/optics.h"
#include "render/whitted_tracer.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

#if defined(__AVX2__)
#include <immintrin.h>
#endif

namespace slime {
namespace {

// Phong's specular lobe (R·V)^n with R the mirror image of the light direction about the normal.
float phongLobe(const glm::vec3& normal, const glm::vec3& toLight, const glm::vec3& toViewer, float shininess) {
  const glm::vec3 mirrored = reflect(-toLight, normal);
  const float cosine = glm::dot(mirrored, toViewer);
  // cos^n < 2^-12 (invisible) once n·log2(cos) < −12, i.e. n·(1 − cos) ≳ 8.3: skip the pow there.
  if (cosine <= 0.0f || shininess * (1.0f - cosine) > 8.5f) return 0.0f;
  return std::pow(cosine, shininess);
}

#if defined(__AVX2__)
__m256 lane(const float* values) { return _mm256_loadu_ps(values); }
#endif

}  // namespace

glm::vec2 WhittedTracer::floorFootprint(const glm::vec3& direction, float distance) const {
  // The pixel's cone (width w = distance × spread) cuts the floor in an ellipse with half axes
  // w/(2 cos θ) along the ray's horizontal direction (d_x, d_y)/sin θ and w/2 across it; the texture
  // averages over that ellipse's bounding box, whose half extents are
  //   (w/2) √((d_x²/cos²θ + d_y²)/sin²θ) and (w/2) √((d_y²/cos²θ + d_x²)/sin²θ).
  const float halfWidth = 0.5f * distance * parameters_.pixelSpread;
  const float cosTheta = std::max(std::abs(direction.z), 1e-3f);
  const float inverseCos2 = 1.0f / (cosTheta * cosTheta);
  const float dx2 = direction.x * direction.x, dy2 = direction.y * direction.y, sin2 = dx2 + dy2;
  glm::vec2 footprint{halfWidth / cosTheta, halfWidth};  // looking straight down: a circle, any axes
  if (sin2 > 1e-12f) {
    const float scale = halfWidth * halfWidth / sin2;
    footprint = {std::sqrt(scale * (dx2 * inverseCos2 + dy2)), std::sqrt(scale * (dy2 * inverseCos2 + dx2))};
  }
  return footprint;
}

FloorShading WhittedTracer::floorShading(const glm::vec3& point, const glm::vec3& direction, float distance) const {
  return litFloor(point, direction, distance, floor_.albedo({point.x, point.y}, floorFootprint(direction, distance)));
}

void WhittedTracer::floorShading8(const Ray* rays, const float* t, const float* distances, const bool* needed,
                                  FloorShading* shadings) const {
#if defined(__AVX2__) && defined(__FMA__)
  // Ray by ray into lanes (an unneeded lane stays a harmless zero), then floorLanes8.
  FloorRays8 lanesIn;
  for (int i = 0; i < 8; ++i) {
    lanesIn.needed[i] = needed[i];
    if (!needed[i]) continue;
    lanesIn.originX[i] = rays[i].origin.x;
    lanesIn.originY[i] = rays[i].origin.y;
    lanesIn.directionX[i] = rays[i].direction.x;
    lanesIn.directionY[i] = rays[i].direction.y;
    lanesIn.directionZ[i] = rays[i].direction.z;
    lanesIn.t[i] = t[i];
    lanesIn.distance[i] = distances[i];
  }
  FloorLanes8 lanes;
  floorLanes8(lanesIn, lanes);
  const ShadingParameters& p = parameters_;
  for (int i = 0; i < 8; ++i) {
    if (!needed[i]) continue;
    const glm::vec3 albedo{lanes.albedo[0][i], lanes.albedo[1][i], lanes.albedo[2][i]};
    if (p.floorSpecular > 0.0f) {  // the floor's own highlight goes through litFloor one lane at a time
      shadings[i] = litFloor({lanes.x[i], lanes.y[i], 0.0f}, rays[i].direction, distances[i], albedo);
      continue;
    }
    FloorShading& shading = shadings[i];
    shading = FloorShading{};
    shading.filled = true;
    shading.ambient = albedo * p.ambientLight;
    shading.haze = lanes.haze[i];
    if (p.lightPosition.z > 0.0f) shading.lit = p.lightColor * (p.floorDiffuse * lanes.lightZ[i] * albedo);
  }
#else
  float x[8] = {}, y[8] = {}, footprintX[8] = {}, footprintY[8] = {};
  for (int i = 0; i < 8; ++i) {
    if (!needed[i]) continue;
    const glm::vec3 point = rays[i].origin + t[i] * rays[i].direction;
    const glm::vec2 footprint = floorFootprint(rays[i].direction, distances[i]);
    x[i] = point.x;
    y[i] = point.y;
    footprintX[i] = footprint.x;
    footprintY[i] = footprint.y;
  }
  float albedos[3][8];
  floor_.albedo8(x, y, footprintX, footprintY, needed, albedos);
  for (int i = 0; i < 8; ++i)
    if (needed[i])
      shadings[i] = litFloor({x[i], y[i], 0.0f}, rays[i].direction, distances[i], {albedos[0][i], albedos[1][i], albedos[2][i]});
#endif
}

#if defined(__AVX2__) && defined(__FMA__)
void WhittedTracer::floorLanes8(const FloorRays8& rays, FloorLanes8& lanes) const {
  // The same steps as floorFootprint and litFloor, 8 lanes at a time (within rounding of them).
  const ShadingParameters& p = parameters_;
  const __m256 dx = lane(rays.directionX), dy = lane(rays.directionY), dz = lane(rays.directionZ), d = lane(rays.distance);
  const __m256 along = lane(rays.t);
  const __m256 px = _mm256_fmadd_ps(along, dx, lane(rays.originX)), py = _mm256_fmadd_ps(along, dy, lane(rays.originY));
  const __m256 halfWidth = _mm256_mul_ps(_mm256_mul_ps(_mm256_set1_ps(0.5f), d), _mm256_set1_ps(p.pixelSpread));
  const __m256 cosTheta = _mm256_max_ps(_mm256_andnot_ps(_mm256_set1_ps(-0.0f), dz), _mm256_set1_ps(1e-3f));
  const __m256 inverseCos2 = _mm256_div_ps(_mm256_set1_ps(1.0f), _mm256_mul_ps(cosTheta, cosTheta));
  const __m256 dx2 = _mm256_mul_ps(dx, dx), dy2 = _mm256_mul_ps(dy, dy), sin2 = _mm256_add_ps(dx2, dy2);
  const __m256 scale = _mm256_div_ps(_mm256_mul_ps(halfWidth, halfWidth), sin2);
  const __m256 oblique = _mm256_cmp_ps(sin2, _mm256_set1_ps(1e-12f), _CMP_GT_OQ);
  const __m256 fx = _mm256_blendv_ps(_mm256_div_ps(halfWidth, cosTheta),
                                     _mm256_sqrt_ps(_mm256_mul_ps(scale, _mm256_fmadd_ps(dx2, inverseCos2, dy2))), oblique);
  const __m256 fy = _mm256_blendv_ps(halfWidth, _mm256_sqrt_ps(_mm256_mul_ps(scale, _mm256_fmadd_ps(dy2, inverseCos2, dx2))),
                                     oblique);
  float footprintX[8], footprintY[8];
  _mm256_storeu_ps(lanes.x, px);
  _mm256_storeu_ps(lanes.y, py);
  _mm256_storeu_ps(footprintX, fx);
  _mm256_storeu_ps(footprintY, fy);
  floor_.albedo8(lanes.x, lanes.y, footprintX, footprintY, rays.needed, lanes.albedo);

  // litFloor: the haze, and the light's direction (its z) at each point.
  _mm256_storeu_ps(lanes.haze, _mm256_sub_ps(_mm256_set1_ps(1.0f), exp(Lanes(_mm256_div_ps(_mm256_sub_ps(_mm256_setzero_ps(), d), _mm256_set1_ps(p.hazeDistance)))).v));
  const __m256 toLightX = _mm256_sub_ps(_mm256_set1_ps(p.lightPosition.x), px);
  const __m256 toLightY = _mm256_sub_ps(_mm256_set1_ps(p.lightPosition.y), py);
  const __m256 toLightZ = _mm256_set1_ps(p.lightPosition.z);
  const __m256 length2 = _mm256_fmadd_ps(toLightX, toLightX, _mm256_fmadd_ps(toLightY, toLightY, _mm256_mul_ps(toLightZ, toLightZ)));
  _mm256_storeu_ps(lanes.lightZ, _mm256_mul_ps(toLightZ, _mm256_div_ps(_mm256_set1_ps(1.0f), _mm256_sqrt_ps(length2))));
}
#endif

void WhittedTracer::traceFloorOrSky8(const glm::vec3& eye, const float* directionX, const float* directionY,
                                     const float* directionZ, int count, TraceCounters& counters, glm::vec3* colors) const {
  counters.rays.primary += static_cast<std::uint64_t>(count);
#if defined(__AVX2__) && defined(__FMA__)
  const ShadingParameters& p = parameters_;
  if (!(p.floorSpecular > 0.0f)) {
    // floorDistance, floorShading8 and shadeFloorWith's sums (with the light unshadowed) in lanes:
    // the same operations in the same order, so each pixel equals tracePrimary8's bit for bit.
    // floorDistance in lanes; the lanes that do not see the floor (or are past `count`) stay zero.
    FloorRays8 rays;
    const __m256 dz = lane(directionZ);
    const __m256 sees = _mm256_and_ps(_mm256_cmp_ps(dz, _mm256_setzero_ps(), _CMP_LT_OQ),
                                      _mm256_cmp_ps(_mm256_setr_ps(0, 1, 2, 3, 4, 5, 6, 7), _mm256_set1_ps(static_cast<float>(count)), _CMP_LT_OQ));
    const int floorMask = _mm256_movemask_ps(sees);
    for (int i = 0; i < 8; ++i) rays.needed[i] = (floorMask >> i) & 1;
    const __m256 t = _mm256_and_ps(sees, _mm256_div_ps(_mm256_set1_ps(std::max(0.0f, eye.z)), _mm256_sub_ps(_mm256_setzero_ps(), dz)));
    _mm256_storeu_ps(rays.originX, _mm256_and_ps(sees, _mm256_set1_ps(eye.x)));
    _mm256_storeu_ps(rays.originY, _mm256_and_ps(sees, _mm256_set1_ps(eye.y)));
    _mm256_storeu_ps(rays.directionX, _mm256_and_ps(sees, lane(directionX)));
    _mm256_storeu_ps(rays.directionY, _mm256_and_ps(sees, lane(directionY)));
    _mm256_storeu_ps(rays.directionZ, _mm256_and_ps(sees, dz));
    _mm256_storeu_ps(rays.t, t);
    _mm256_storeu_ps(rays.distance, t);
    FloorLanes8 lanes;
    if (floorMask != 0) floorLanes8(rays, lanes);
    const bool lit = p.lightPosition.z > 0.0f;
    const __m256 lightScale = _mm256_mul_ps(_mm256_set1_ps(p.floorDiffuse), lane(lanes.lightZ));
    const __m256 haze = lane(lanes.haze), near = _mm256_sub_ps(_mm256_set1_ps(1.0f), haze);
    float channels[3][8];
    int shadowRays = 0;
    for (int c = 0; c < 3; ++c) {
      const __m256 a = lane(lanes.albedo[c]);
      const __m256 ambient = _mm256_mul_ps(a, _mm256_set1_ps(p.ambientLight[c]));
      const __m256 base = _mm256_add_ps(_mm256_mul_ps(near, ambient), _mm256_mul_ps(haze, _mm256_set1_ps(p.skyHorizon[c])));
      const __m256 light = lit ? _mm256_mul_ps(_mm256_set1_ps(p.lightColor[c]), _mm256_mul_ps(lightScale, a)) : _mm256_setzero_ps();
      _mm256_storeu_ps(channels[c], _mm256_add_ps(base, _mm256_mul_ps(near, light)));
      shadowRays |= floorMask & _mm256_movemask_ps(_mm256_cmp_ps(light, _mm256_setzero_ps(), _CMP_NEQ_UQ));
    }
    for (int i = 0; i < count; ++i)
      colors[i] = rays.needed[i] ? glm::vec3(channels[0][i], channels[1][i], channels[2][i]) : sky({directionX[i], directionY[i], directionZ[i]});
    if (p.shadows) counters.rays.shadow += static_cast<std::uint64_t>(__builtin_popcount(shadowRays));
    return;
  }
#endif
  Ray rays[8];
  SlimeHit misses[8];
  for (int i = 0; i < count; ++i) rays[i] = Ray{eye, {directionX[i], directionY[i], directionZ[i]}, 0.0f, kInfinity};
  counters.rays.primary -= static_cast<std::uint64_t>(count);  // tracePrimary8 counts them
  tracePrimary8(rays, misses, count, counters, nullptr, colors, true);
}

FloorShading WhittedTracer::litFloor(const glm::vec3& point, const glm::vec3& direction, float distance,
                                     const glm::vec3& albedo) const {
  const ShadingParameters& p = parameters_;
  FloorShading shading;
  shading.filled = true;
  shading.ambient = albedo * p.ambientLight;
  shading.haze = 1.0f - std::exp(-distance / p.hazeDistance);
  const glm::vec3 toLight = p.lightPosition - point;
  if (toLight.z <= 0.0f) return shading;
  const glm::vec3 lightDirection = glm::normalize(toLight);
  glm::vec3 reflected = p.floorDiffuse * lightDirection.z * albedo;
  if (p.floorSpecular > 0.0f) {  // a matte floor has no highlight to compute
    const glm::vec3 up{0.0f, 0.0f, 1.0f};
    reflected += p.floorSpecular * phongLobe(up, lightDirection, -direction, p.floorShininess);
  }
  shading.lit = p.lightColor * reflected;
  return shading;
}

glm::vec3 WhittedTracer::sky(const glm::vec3& direction) const {
  // Pale at the horizon, deeper blue towards the zenith.
  const float elevation = std::sqrt(std::clamp(direction.z, 0.0f, 1.0f));
  return glm::mix(parameters_.skyHorizon, parameters_.skyZenith, elevation);
}

}  // namespace slime

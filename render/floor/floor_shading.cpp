// The floor and the sky as the Whitted tracer sees them: where a ray meets the plane z = 0, the
// pixel's footprint there, the pattern over it, the light and the horizon haze (litFloor), one ray
// at a time or in lanes (8 or 16 at a time, render/simd/wide_lanes.h); and the sky's gradient. The floor
// has no slime in it: the tracer adds the slime's shadow (whitted_tracer.cpp).
#include "render/trace/optics.h"
#include "render/trace/whitted_tracer.h"
#include "render/simd/wide_lanes.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

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

void WhittedTracer::floorShadings(const Ray* rays, const float* t, const float* distances, const bool* needed,
                                  FloorShading* shadings) const {
#if defined(SLIME_WIDE_LANES)
  // Ray by ray into lanes (an unneeded lane stays a harmless zero), then floorLanes.
  constexpr int N = kFloorBatch;
  FloorRays<N> lanesIn;
  for (int i = 0; i < N; ++i) {
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
  FloorPoints<N> lanes;
  floorLanes(lanesIn, lanes);
  const ShadingParameters& p = parameters_;
  for (int i = 0; i < N; ++i) {
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
  static_assert(kFloorBatch == 8, "without AVX2 the pattern is looked up 8 at a time");
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
  floor_.albedoLanes<8>(x, y, footprintX, footprintY, needed, albedos);
  for (int i = 0; i < 8; ++i)
    if (needed[i])
      shadings[i] = litFloor({x[i], y[i], 0.0f}, rays[i].direction, distances[i], {albedos[0][i], albedos[1][i], albedos[2][i]});
#endif
}

#if defined(SLIME_WIDE_LANES)
template <int N>
void WhittedTracer::floorLanes(const FloorRays<N>& rays, FloorPoints<N>& points) const {
  // The same steps as floorFootprint and litFloor, N lanes at a time (within rounding of them).
  using F = typename Wide<N>::F;
  using I = typename Wide<N>::I;
  const ShadingParameters& p = parameters_;
  const F dx = loadLanes<F>(rays.directionX), dy = loadLanes<F>(rays.directionY), dz = loadLanes<F>(rays.directionZ);
  const F d = loadLanes<F>(rays.distance), along = loadLanes<F>(rays.t);
  const F px = fmaLanes(along, dx, loadLanes<F>(rays.originX)), py = fmaLanes(along, dy, loadLanes<F>(rays.originY));
  const F halfWidth = (0.5f * d) * p.pixelSpread;
  const F cosTheta = maxLanes(absLanes(dz), splat<F>(1e-3f));
  const F inverseCos2 = 1.0f / (cosTheta * cosTheta);
  const F dx2 = dx * dx, dy2 = dy * dy, sin2 = dx2 + dy2;
  const F scale = (halfWidth * halfWidth) / sin2;
  const I oblique = sin2 > 1e-12f;
  const F fx = oblique ? sqrtLanes(scale * fmaLanes(dx2, inverseCos2, dy2)) : halfWidth / cosTheta;
  const F fy = oblique ? sqrtLanes(scale * fmaLanes(dy2, inverseCos2, dx2)) : halfWidth;
  float footprintX[N], footprintY[N];
  storeLanes(points.x, px);
  storeLanes(points.y, py);
  storeLanes(footprintX, fx);
  storeLanes(footprintY, fy);
  floor_.albedoLanes<N>(points.x, points.y, footprintX, footprintY, rays.needed, points.albedo);

  // litFloor: the haze, and the light's direction (its z) at each point.
  storeLanes(points.haze, 1.0f - expLanes((0.0f - d) / p.hazeDistance));
  const F toLightX = p.lightPosition.x - px, toLightY = p.lightPosition.y - py, toLightZ = splat<F>(p.lightPosition.z);
  const F length2 = fmaLanes(toLightX, toLightX, fmaLanes(toLightY, toLightY, toLightZ * toLightZ));
  storeLanes(points.lightZ, toLightZ * (1.0f / sqrtLanes(length2)));
}

template <int N>
void WhittedTracer::traceFloorOrSkyLanes(const glm::vec3& eye, const float* directionX, const float* directionY,
                                         const float* directionZ, int count, TraceCounters& counters,
                                         glm::vec3* colors) const {
  // floorDistance, floorShadings and shadeFloorWith's sums (with the light unshadowed) in lanes:
  // the same operations in the same order, so each pixel equals tracePrimaries's bit for bit.
  // floorDistance in lanes; the lanes that do not see the floor (or are past `count`) stay zero.
  using F = typename Wide<N>::F;
  using I = typename Wide<N>::I;
  const ShadingParameters& p = parameters_;
  F lane{};
  for (int i = 0; i < N; ++i) lane[i] = static_cast<float>(i);
  FloorRays<N> rays;
  const F dz = loadLanes<F>(directionZ);
  const I sees = (dz < 0.0f) & (lane < static_cast<float>(count));
  const unsigned floorMask = maskBits(sees);
  for (int i = 0; i < N; ++i) rays.needed[i] = (floorMask >> i) & 1u;
  const F none = splat<F>(0.0f);
  const F t = sees ? std::max(0.0f, eye.z) / (0.0f - dz) : none;
  storeLanes(rays.originX, sees ? splat<F>(eye.x) : none);
  storeLanes(rays.originY, sees ? splat<F>(eye.y) : none);
  storeLanes(rays.directionX, sees ? loadLanes<F>(directionX) : none);
  storeLanes(rays.directionY, sees ? loadLanes<F>(directionY) : none);
  storeLanes(rays.directionZ, sees ? dz : none);
  storeLanes(rays.t, t);
  storeLanes(rays.distance, t);
  FloorPoints<N> points;
  if (floorMask != 0) floorLanes(rays, points);
  const bool lit = p.lightPosition.z > 0.0f;
  const F lightScale = p.floorDiffuse * loadLanes<F>(points.lightZ);
  const F haze = loadLanes<F>(points.haze), near = 1.0f - haze;
  // sky() in lanes for the others: glm::mix(horizon, zenith, √clamp(d_z, 0, 1)).
  const F elevation = sqrtLanes(minLanes(maxLanes(dz, none), splat<F>(1.0f)));
  float channels[3][N];
  unsigned shadowRays = 0;
  for (int c = 0; c < 3; ++c) {
    const F a = loadLanes<F>(points.albedo[c]);
    const F ambient = a * p.ambientLight[c];
    const F base = near * ambient + haze * p.skyHorizon[c];
    const F light = lit ? p.lightColor[c] * (lightScale * a) : none;
    const F skyColor = p.skyHorizon[c] * (1.0f - elevation) + p.skyZenith[c] * elevation;
    storeLanes(channels[c], sees ? base + near * light : skyColor);
    shadowRays |= floorMask & maskBits(light != 0.0f);
  }
  for (int i = 0; i < count; ++i) colors[i] = glm::vec3(channels[0][i], channels[1][i], channels[2][i]);
  if (p.shadows) counters.rays.shadow += static_cast<std::uint64_t>(__builtin_popcount(shadowRays));
}
#endif

void WhittedTracer::traceFloorOrSky(const glm::vec3& eye, const float* directionX, const float* directionY,
                                    const float* directionZ, int count, TraceCounters& counters, glm::vec3* colors) const {
  counters.rays.primary += static_cast<std::uint64_t>(count);
#if defined(SLIME_WIDE_LANES)
  if (!(parameters_.floorSpecular > 0.0f)) {
    if (count > 8) traceFloorOrSkyLanes<kFloorOrSkyRays>(eye, directionX, directionY, directionZ, count, counters, colors);
    else traceFloorOrSkyLanes<8>(eye, directionX, directionY, directionZ, count, counters, colors);
    return;
  }
#endif
  // A shiny floor (or no AVX2): tracePrimaries's general path, 8 rays at a time.
  counters.rays.primary -= static_cast<std::uint64_t>(count);  // tracePrimaries counts them
  for (int first = 0; first < count; first += 8) {
    const int size = std::min(8, count - first);
    Ray rays[8];
    SlimeHit misses[8];
    for (int i = 0; i < size; ++i)
      rays[i] = Ray{eye, {directionX[first + i], directionY[first + i], directionZ[first + i]}, 0.0f, kInfinity};
    tracePrimaries(rays, misses, size, counters, nullptr, colors + first, true);
  }
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

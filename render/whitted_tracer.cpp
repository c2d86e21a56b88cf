#include "render/whitted_tracer.h"

#include "render/optics.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace slime {
namespace {

// A shadow ray through a deformed slime may cross its surface several times; beyond this many
// crossings the light is taken as blocked.
constexpr int kMaxShadowCrossings = 8;

float largest(const glm::vec3& v) { return std::max(v.x, std::max(v.y, v.z)); }

// The plane z = 0 seen from above: t = −o_z / d_z (a ray starting below it hits it at once).
float floorDistance(const Ray& ray) {
  if (ray.direction.z >= 0.0f) return kInfinity;
  const float t = std::max(0.0f, ray.origin.z) / -ray.direction.z;
  return t <= ray.tFar ? t : kInfinity;
}

// Phong's specular lobe (R·V)^n with R the mirror image of the light direction about the normal.
float phongLobe(const glm::vec3& normal, const glm::vec3& toLight, const glm::vec3& toViewer, float shininess) {
  const glm::vec3 mirrored = reflect(-toLight, normal);
  const float cosine = glm::dot(mirrored, toViewer);
  // cos^n < 2^-12 (invisible) once n·log2(cos) < −12, i.e. n·(1 − cos) ≳ 8.3: skip the pow there.
  if (cosine <= 0.0f || shininess * (1.0f - cosine) > 8.5f) return 0.0f;
  return std::pow(cosine, shininess);
}

}  // namespace

SlimeHit WhittedTracer::findSlime(const Ray& ray, TraceCounters& counters) const {
  if (!geometry_.mayHit(ray)) return {};
  ++counters.slimeQueries;
  return intersector_.intersect(ray);
}

glm::vec3 WhittedTracer::tracePrimary(const Ray& ray, const SlimeHit& hit, TraceCounters& counters,
                                      FloorShading* floorCache) const {
  ++counters.rays.primary;
  return trace(ray, &hit, Path{}, Kind::Primary, counters, floorCache);
}

glm::vec3 WhittedTracer::tracePrimary(const Ray& ray, TraceCounters& counters) const {
  const SlimeHit hit = findSlime(ray, counters);
  return tracePrimary(ray, hit, counters);
}

glm::vec3 WhittedTracer::trace(const Ray& ray, const SlimeHit* knownHit, const Path& path, Kind kind,
                               TraceCounters& counters, FloorShading* floorCache) const {
  if (kind == Kind::Reflection) ++counters.rays.reflection;
  if (kind == Kind::Refraction) ++counters.rays.refraction;
  const bool cannotMeetSlime = path.leavesSlime && geometry_.isConvex();
  const SlimeHit hit = knownHit ? *knownHit : cannotMeetSlime ? SlimeHit{} : findSlime(ray, counters);
  const float tFloor = floorDistance(ray);
  if (hit.valid() && hit.t <= tFloor) return shadeSlime(ray, hit, path, counters);
  if (tFloor == kInfinity) return sky(ray.direction);
  const glm::vec3 floorColor = shadeFloor(ray, tFloor, path, counters, floorCache);
  // Under the jelly (the contact patch) the floor is seen through Beer–Lambert absorption.
  return path.inside ? floorColor * beerLambert(parameters_.slimeAbsorption, tFloor) : floorColor;
}

glm::vec3 WhittedTracer::shadeSlime(const Ray& ray, const SlimeHit& hit, const Path& path, TraceCounters& counters) const {
  const ShadingParameters& p = parameters_;
  const glm::vec3 point = ray.origin + hit.t * ray.direction;
  const glm::vec3 outward = geometry_.geometricNormal(hit, point);
  const bool entering = glm::dot(ray.direction, outward) < 0.0f;
  // Normals facing the incoming ray: geometric (for offsets) and shading (for optics).
  const glm::vec3 facing = entering ? outward : -outward;
  glm::vec3 normal = geometry_.shadingNormal(hit, point, p.smoothNormals);
  if (!entering) normal = -normal;
  if (glm::dot(normal, ray.direction) >= 0.0f) normal = facing;  // interpolated normal behind a silhouette
  const float cosIncident = -glm::dot(ray.direction, normal);
  const float etaFrom = entering ? 1.0f : p.ior, etaTo = entering ? p.ior : 1.0f;

  // A ray that reaches the surface from inside has crossed the jelly: Beer–Lambert over its length.
  const glm::vec3 absorbed = entering ? glm::vec3(1.0f) : beerLambert(p.slimeAbsorption, hit.t);
  glm::vec3 color(0.0f);
  if (entering) {
    // Local Phong: I = k_a I_a C + T_light I_l (k_d (N·L) C + k_s (R·V)^n).
    color += p.ambient * p.ambientLight * p.slimeColor;
    const glm::vec3 toLight = glm::normalize(p.lightPosition - point);
    const float cosLight = glm::dot(normal, toLight);
    if (cosLight > 0.0f && glm::dot(facing, toLight) > 0.0f) {
      const glm::vec3 visible = p.shadows ? lightTransmittance(offsetRayOrigin(point, facing, toLight), counters, true)
                                          : glm::vec3(1.0f);
      if (largest(visible) > 0.0f)
        color += visible * p.lightColor *
                 (p.diffuse * cosLight * p.slimeColor + p.specular * phongLobe(normal, toLight, -ray.direction, p.shininess));
    }
  }

  // Snell's law; an empty result is total internal reflection.
  std::optional<glm::vec3> refracted = refract(ray.direction, normal, etaFrom, etaTo);
  if (refracted && glm::dot(*refracted, facing) >= 0.0f) refracted = refract(ray.direction, facing, etaFrom, etaTo);
  float reflectWeight = 0.0f, refractWeight = 0.0f;
  if (p.optics == OpticsMode::Fresnel) {
    const float fresnel = refracted ? fresnelDielectric(cosIncident, etaFrom, etaTo) : 1.0f;
    reflectWeight = fresnel;
    refractWeight = (1.0f - fresnel) * (entering ? p.transmission : 1.0f);
  } else {
    reflectWeight = p.specular;
    refractWeight = refracted ? p.transmission : 0.0f;
    if (!refracted) reflectWeight += p.transmission;
  }

  const glm::vec3 weight = path.weight * absorbed;
  Path next;
  next.segment = path.segment + 1;
  next.travelled = path.travelled + hit.t;
  if (path.segment < p.depth) {
    if (reflectWeight > 0.0f && largest(weight * reflectWeight) >= kMinRayWeight) {
      glm::vec3 direction = reflect(ray.direction, normal);
      if (glm::dot(direction, facing) <= 0.0f) direction = reflect(ray.direction, facing);
      next.weight = weight * reflectWeight;
      next.inside = !entering;
      next.leavesSlime = entering;
      const Ray reflectedRay{offsetRayOrigin(point, facing, direction), direction, 0.0f, kInfinity};
      color += reflectWeight * trace(reflectedRay, nullptr, next, Kind::Reflection, counters);
    }
    if (refracted && refractWeight > 0.0f && largest(weight * refractWeight) >= kMinRayWeight) {
      next.weight = weight * refractWeight;
      next.inside = entering;
      next.leavesSlime = !entering;
      const Ray refractedRay{offsetRayOrigin(point, facing, *refracted), *refracted, 0.0f, kInfinity};
      color += refractWeight * trace(refractedRay, nullptr, next, Kind::Refraction, counters);
    }
  } else if (!entering && refracted && refractWeight > 0.0f) {
    // Out of segments on the way out of the jelly: what lies beyond is the analytic floor or sky.
    ++counters.rays.refraction;
    const Ray leaving{offsetRayOrigin(point, facing, *refracted), *refracted, 0.0f, kInfinity};
    color += refractWeight * environment(leaving, next.travelled);
  }
  return color * absorbed;
}

glm::vec3 WhittedTracer::shadeFloor(const Ray& ray, float t, const Path& path, TraceCounters& counters,
                                    FloorShading* floorCache) const {
  const ShadingParameters& p = parameters_;
  glm::vec3 point = ray.origin + t * ray.direction;
  point.z = 0.0f;
  const float distance = path.travelled + t;
  FloorShading fresh;
  if (!floorCache || !floorCache->filled) {
    fresh = floorShading(point, ray.direction, distance);
    if (floorCache) *floorCache = fresh;
  } else {
    ++counters.cachedFloorPixels;
  }
  const FloorShading& shading = floorCache ? *floorCache : fresh;
  glm::vec3 color = floorLocal(shading, point, true, counters);
  if (path.segment < p.depth && p.floorSpecular > 0.0f && largest(path.weight * p.floorSpecular) >= kMinRayWeight) {
    // The varnish mirrors what is above: the reflected ray (d_x, d_y, −d_z).
    const glm::vec3 direction{ray.direction.x, ray.direction.y, -ray.direction.z};
    Path next{path.segment + 1, path.weight * p.floorSpecular, distance, path.inside, false};
    const Ray reflectedRay{point + glm::vec3(0.0f, 0.0f, kRayOffset), direction, 0.0f, kInfinity};
    color += p.floorSpecular * trace(reflectedRay, nullptr, next, Kind::Reflection, counters);
  }
  // Far floor fades into the horizon haze so that the horizon is a soft line.
  return glm::mix(color, p.skyHorizon, shading.haze);
}

FloorShading WhittedTracer::floorShading(const glm::vec3& point, const glm::vec3& direction, float distance) const {
  const ShadingParameters& p = parameters_;
  // The pixel's cone (width w = distance × spread) cuts the floor in an ellipse with half axes
  // w/(2 cos θ) along the ray's horizontal direction (d_x, d_y)/sin θ and w/2 across it; the texture
  // averages over that ellipse's bounding box, whose half extents are
  //   (w/2) √((d_x²/cos²θ + d_y²)/sin²θ) and (w/2) √((d_y²/cos²θ + d_x²)/sin²θ).
  const float halfWidth = 0.5f * distance * p.pixelSpread;
  const float cosTheta = std::max(std::abs(direction.z), 1e-3f);
  const float inverseCos2 = 1.0f / (cosTheta * cosTheta);
  const float dx2 = direction.x * direction.x, dy2 = direction.y * direction.y, sin2 = dx2 + dy2;
  glm::vec2 footprint{halfWidth / cosTheta, halfWidth};  // looking straight down: a circle, any axes
  if (sin2 > 1e-12f) {
    const float scale = halfWidth * halfWidth / sin2;
    footprint = {std::sqrt(scale * (dx2 * inverseCos2 + dy2)), std::sqrt(scale * (dy2 * inverseCos2 + dx2))};
  }
  const glm::vec3 albedo = floor_.albedo({point.x, point.y}, footprint);

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

glm::vec3 WhittedTracer::floorLocal(const FloorShading& shading, const glm::vec3& point, bool shadowed,
                                    TraceCounters& counters) const {
  const ShadingParameters& p = parameters_;
  if (shading.lit == glm::vec3(0.0f)) return shading.ambient;  // the light is below the floor, or black
  const glm::vec3 visible = shadowed && p.shadows
      ? lightTransmittance(point + glm::vec3(0.0f, 0.0f, kRayOffset), counters) : glm::vec3(1.0f);
  if (largest(visible) <= 0.0f) return shading.ambient;
  return shading.ambient + visible * shading.lit;
}

glm::vec3 WhittedTracer::lightTransmittance(const glm::vec3& point, TraceCounters& counters, bool leavesSlime) const {
  const ShadingParameters& p = parameters_;
  ++counters.rays.shadow;
  const glm::vec3 toLight = p.lightPosition - point;
  const float distance = glm::length(toLight);
  Ray ray{point, toLight / distance, 0.0f, distance};
  glm::vec3 transmittance(1.0f);
  const bool convex = geometry_.isConvex();
  if (!(distance > 0.0f) || (leavesSlime && convex) || !geometry_.mayHit(ray)) return transmittance;
  // Walk the crossings along the straight shadow ray (shadow rays are not bent): each crossing passes
  // the surface's transmitted fraction, each stretch inside loses exp(−σ l).
  for (int crossing = 0; crossing < kMaxShadowCrossings; ++crossing) {
    ++counters.slimeQueries;
    const SlimeHit hit = intersector_.intersect(ray);
    if (!hit.valid() || !crossShadowSurface(ray, hit, transmittance)) return transmittance;
  }
  return glm::vec3(0.0f);
}

bool WhittedTracer::crossShadowSurface(Ray& ray, const SlimeHit& hit, glm::vec3& transmittance) const {
  const ShadingParameters& p = parameters_;
  const glm::vec3 hitPoint = ray.origin + hit.t * ray.direction;
  const glm::vec3 outward = geometry_.geometricNormal(hit, hitPoint);
  const bool entering = glm::dot(ray.direction, outward) < 0.0f;
  if (!entering) transmittance *= beerLambert(p.slimeAbsorption, hit.t);
  if (p.optics == OpticsMode::Fresnel) {
    const float cosine = std::abs(glm::dot(ray.direction, outward));
    const float fresnel = entering ? fresnelDielectric(cosine, 1.0f, p.ior) : fresnelDielectric(cosine, p.ior, 1.0f);
    transmittance *= (1.0f - fresnel) * (entering ? p.transmission : 1.0f);
  } else {
    transmittance *= p.transmission;
  }
  if (largest(transmittance) < kMinRayWeight) {
    transmittance = glm::vec3(0.0f);
    return false;
  }
  if (!entering && geometry_.isConvex()) return false;  // out of a convex slime for good
  ray.origin = offsetRayOrigin(hitPoint, outward, ray.direction);
  ray.tFar = std::max(0.0f, ray.tFar - hit.t);
  return true;
}

void WhittedTracer::lightTransmittance8(const glm::vec3* points, const bool* active, glm::vec3* visible,
                                        TraceCounters& counters) const {
  Ray rays[8];
  bool walking[8] = {};
  for (int i = 0; i < 8; ++i) {
    visible[i] = glm::vec3(1.0f);
    if (!active[i]) continue;
    ++counters.rays.shadow;
    const glm::vec3 toLight = parameters_.lightPosition - points[i];
    const float distance = glm::length(toLight);
    rays[i] = Ray{points[i], toLight / distance, 0.0f, distance};
    walking[i] = distance > 0.0f && geometry_.mayHit(rays[i]);
  }
  for (int crossing = 0; crossing < kMaxShadowCrossings; ++crossing) {
    int count = 0;
    for (int i = 0; i < 8; ++i) count += walking[i];
    if (count == 0) return;
    counters.slimeQueries += static_cast<std::uint64_t>(count);
    SlimeHit hits[8];
    intersector_.intersect8(rays, walking, hits);
    for (int i = 0; i < 8; ++i)
      if (walking[i]) walking[i] = hits[i].valid() && crossShadowSurface(rays[i], hits[i], visible[i]);
  }
  for (int i = 0; i < 8; ++i)
    if (walking[i]) visible[i] = glm::vec3(0.0f);  // more crossings than kMaxShadowCrossings: blocked
}

void WhittedTracer::tracePrimary8(const Ray* rays, const SlimeHit* hits, int count, TraceCounters& counters,
                                  FloorShading* floorCache, glm::vec3* colors) const {
  const ShadingParameters& p = parameters_;
  bool floorFirst[8] = {}, shadowed[8] = {};
  glm::vec3 shadowOrigins[8], visible[8];
  for (glm::vec3& origin : shadowOrigins) origin = glm::vec3(0.0f);
  FloorShading fresh[8];
  const FloorShading* shadings[8] = {};
  for (int i = 0; i < count; ++i) {
    const float tFloor = floorDistance(rays[i]);
    floorFirst[i] = p.floorSpecular <= 0.0f && tFloor != kInfinity && !(hits[i].valid() && hits[i].t <= tFloor);
    if (!floorFirst[i]) {  // the slime, the sky, or a varnished floor: one ray at a time
      colors[i] = tracePrimary(rays[i], hits[i], counters, floorCache ? floorCache + i : nullptr);
      continue;
    }
    // As shadeFloor for a primary ray on a matte floor, the shadow ray left for the packet below.
    ++counters.rays.primary;
    glm::vec3 point = rays[i].origin + tFloor * rays[i].direction;
    point.z = 0.0f;
    FloorShading* cached = floorCache ? floorCache + i : nullptr;
    if (cached && cached->filled) {
      ++counters.cachedFloorPixels;
    } else {
      fresh[i] = floorShading(point, rays[i].direction, tFloor);
      if (cached) *cached = fresh[i];
    }
    shadings[i] = cached ? cached : &fresh[i];
    shadowed[i] = p.shadows && shadings[i]->lit != glm::vec3(0.0f);
    shadowOrigins[i] = point + glm::vec3(0.0f, 0.0f, kRayOffset);
  }
  lightTransmittance8(shadowOrigins, shadowed, visible, counters);
  for (int i = 0; i < count; ++i) {
    if (!floorFirst[i]) continue;
    const FloorShading& shading = *shadings[i];
    const glm::vec3 color = largest(visible[i]) > 0.0f ? shading.ambient + visible[i] * shading.lit : shading.ambient;
    colors[i] = glm::mix(color, p.skyHorizon, shading.haze);
  }
}

glm::vec3 WhittedTracer::environment(const Ray& ray, float travelled) const {
  const float t = floorDistance(ray);
  if (t == kInfinity) return sky(ray.direction);
  TraceCounters unused;
  glm::vec3 point = ray.origin + t * ray.direction;
  point.z = 0.0f;
  const FloorShading shading = floorShading(point, ray.direction, travelled + t);
  return glm::mix(floorLocal(shading, point, false, unused), parameters_.skyHorizon, shading.haze);
}

glm::vec3 WhittedTracer::sky(const glm::vec3& direction) const {
  // Pale at the horizon, deeper blue towards the zenith.
  const float elevation = std::sqrt(std::clamp(direction.z, 0.0f, 1.0f));
  return glm::mix(parameters_.skyHorizon, parameters_.skyZenith, elevation);
}

}  // namespace slime

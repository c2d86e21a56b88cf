// The light reaching the points the Whitted tracer shades, through the slime: shadow rays to the point
// light, 8 at a time, walked from crossing to crossing of the slime's surface (each passes the
// surface's transmitted fraction, each stretch inside loses exp(−σ l)), or settled from both their
// ends where the slime can be crossed only once. The queueing is the wavefront's (whitted_tracer.cpp).
#include "render/trace/optics.h"
#include "render/trace/whitted_tracer.h"

#include <glm/geometric.hpp>

#include <algorithm>

namespace slime {
namespace {

// A shadow ray through a deformed slime may cross its surface several times; beyond this many
// crossings the light is taken as blocked.
constexpr int kMaxShadowCrossings = 8;

}  // namespace

void WhittedTracer::traceShadows(const std::vector<PendingShadow>& shadows, TraceCounters& counters,
                                 glm::vec3* colors) const {
  // Two batches of 8: the shadow rays whose light is the straight ray's transmittance, and (with
  // caustics) those from the floor, whose light is the caustic map's wherever the slime is in the way.
  struct Batch {
    Ray rays[8];
    bool active[8] = {};
    int pixels[8] = {};
    glm::vec3 multipliers[8];
    int size = 0;
  };
  Batch straight, floor;
  const auto flush = [&](Batch& batch, bool caustic) {
    glm::vec3 visible[8];
    if (caustic) {
      bool blocked[8] = {};
      lightBlocked8(batch.rays, batch.active, blocked, counters);
      for (int k = 0; k < batch.size; ++k)
        visible[k] = blocked[k] ? caustics_->gain(batch.rays[k].origin, parameters_.lightPosition) : glm::vec3(1.0f);
    } else {
      lightTransmittance8(batch.rays, batch.active, visible, counters);
    }
    for (int k = 0; k < batch.size; ++k)
      if (largest(visible[k]) > 0.0f) colors[batch.pixels[k]] += visible[k] * batch.multipliers[k];
    for (bool& a : batch.active) a = false;
    batch.size = 0;
  };
  for (const PendingShadow& shadow : shadows) {
    const bool caustic = caustics_ && shadow.fromFloor;
    Batch& batch = caustic ? floor : straight;
    batch.rays[batch.size] = shadow.ray;
    batch.active[batch.size] = true;
    batch.pixels[batch.size] = shadow.pixel;
    batch.multipliers[batch.size] = shadow.multiplier;
    if (++batch.size == 8) flush(batch, caustic);
  }
  if (straight.size > 0) flush(straight, false);
  if (floor.size > 0) flush(floor, true);
}

void WhittedTracer::lightBlocked8(const Ray* rays, const bool* active, bool* blocked, TraceCounters& counters) const {
  for (int i = 0; i < 8; ++i) {
    blocked[i] = false;
    counters.slimeQueries += active[i];
  }
  SegmentCrossings crossings[8];
  if (intersector_.lightCrossings8(rays, active, crossings)) {
    for (int i = 0; i < 8; ++i) blocked[i] = active[i] && crossings[i].count > 0;
    return;
  }
  SlimeHit hits[8];
  intersector_.intersect8(rays, active, hits);
  for (int i = 0; i < 8; ++i) blocked[i] = active[i] && hits[i].valid();
}

float WhittedTracer::surfaceTransmission(float cosine, bool entering) const {
  const ShadingParameters& p = parameters_;
  if (p.optics != OpticsMode::Fresnel) return p.transmission;
  const float fresnel = entering ? fresnelDielectric(cosine, 1.0f, p.ior) : fresnelDielectric(cosine, p.ior, 1.0f);
  return (1.0f - fresnel) * (entering ? p.transmission : 1.0f);
}

bool WhittedTracer::crossShadowSurface(Ray& ray, const SlimeHit& hit, glm::vec3& transmittance) const {
  const ShadingParameters& p = parameters_;
  const glm::vec3 hitPoint = ray.origin + hit.t * ray.direction;
  const glm::vec3 outward = geometry_.geometricNormal(hit, hitPoint);
  const bool entering = glm::dot(ray.direction, outward) < 0.0f;
  if (!entering) transmittance *= beerLambert(p.slimeAbsorption, hit.t);
  transmittance *= surfaceTransmission(std::abs(glm::dot(ray.direction, outward)), entering);
  if (!visibleThroughput(transmittance, p.brightest)) {
    transmittance = glm::vec3(0.0f);
    return false;
  }
  if (!entering && geometry_.supports(hit.primitive)) return false;  // out through a supporting triangle: for good
  ray.origin = offsetRayOrigin(hitPoint, outward, ray.direction);
  ray.tFar = std::max(0.0f, ray.tFar - hit.t);
  return true;
}

void WhittedTracer::lightTransmittance8(Ray* rays, const bool* active, glm::vec3* visible, TraceCounters& counters) const {
  bool walking[8];
  for (int i = 0; i < 8; ++i) {
    visible[i] = glm::vec3(1.0f);
    walking[i] = active[i];
  }
  SegmentCrossings crossings[8];
  if (intersector_.lightCrossings8(rays, active, crossings)) {
    for (int i = 0; i < 8; ++i) {
      if (!active[i]) continue;
      ++counters.slimeQueries;
      visible[i] = transmittanceAlong(rays[i], crossings[i]);
    }
    return;
  }
  if (geometry_.fewNonSupporting()) crossFromBothEnds8(rays, walking, visible, counters);
  // Walk the crossings along the straight shadow rays (shadow rays are not bent): each crossing
  // passes the surface's transmitted fraction, each stretch inside loses exp(−σ l).
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

glm::vec3 WhittedTracer::transmittanceAlong(const Ray& ray, const SegmentCrossings& crossings) const {
  // crossShadowSurface's factors, crossing after crossing, with every crossing known at once.
  if (crossings.count > SegmentCrossings::kCapacity) return glm::vec3(0.0f);  // more than kCapacity: blocked
  const ShadingParameters& p = parameters_;
  glm::vec3 transmittance(1.0f);
  float lastT = 0.0f;  // from the ray's origin, or from the last crossing
  int counted = 0;
  bool lastEntering = false;
  for (int k = 0; k < crossings.count; ++k) {
    const SlimeHit& hit = crossings.hits[k];
    const glm::vec3 outward = geometry_.geometricNormal(hit, ray.origin + hit.t * ray.direction);
    const bool entering = glm::dot(ray.direction, outward) < 0.0f;
    // Two hits the same way in a row are one crossing met on two triangles (through their shared edge).
    if (counted > 0 && entering == lastEntering) continue;
    if (++counted > kMaxShadowCrossings) return glm::vec3(0.0f);  // the walk's limit: blocked
    if (!entering) transmittance *= beerLambert(p.slimeAbsorption, hit.t - lastT);
    transmittance *= surfaceTransmission(std::abs(glm::dot(ray.direction, outward)), entering);
    if (!visibleThroughput(transmittance, p.brightest)) return glm::vec3(0.0f);
    lastT = hit.t;
    lastEntering = entering;
  }
  return transmittance;
}

void WhittedTracer::crossFromBothEnds8(Ray* rays, bool* walking, glm::vec3* visible, TraceCounters& counters) const {
  // A straight segment from outside the slime that enters it through a supporting triangle can come
  // back in only through one that does not support it (see findHits). So when it crosses no
  // non-supporting triangle (always, on a convex slime), it meets the slime in one stretch or not at
  // all: the stretch's near end is the first hit from the segment's start, its far end the first
  // hit from the light's end. Both queries start outside the jelly (a walk's second query starts
  // inside); the far end and the check are asked, in a second round, only of the rays that enter.
  const ShadingParameters& p = parameters_;
  const bool convex = geometry_.isConvex();
  int count = 0;
  for (int i = 0; i < 8; ++i) count += walking[i];
  if (count == 0) return;
  counters.slimeQueries += static_cast<std::uint64_t>(count);
  SlimeHit nearHits[8], farHits[8], crossings[8];
  intersector_.intersect8(rays, walking, nearHits);
  // The rays that enter the slime at their near end: the far end and the non-supporting crossings.
  Ray back[8];
  glm::vec3 nearNormals[8];
  bool entering[8] = {}, checked[8] = {};
  int checkCount = 0;
  count = 0;
  for (int i = 0; i < 8; ++i) {
    if (!walking[i]) continue;
    const SlimeHit& near = nearHits[i];
    if (!near.valid()) {  // the light passes
      walking[i] = false;
      continue;
    }
    nearNormals[i] = geometry_.geometricNormal(near, rays[i].origin + near.t * rays[i].direction);
    entering[i] = glm::dot(rays[i].direction, nearNormals[i]) < 0.0f;
    if (!entering[i]) continue;
    ++count;
    back[i] = Ray{rays[i].origin + rays[i].tFar * rays[i].direction, -rays[i].direction, 0.0f, rays[i].tFar};
    checked[i] = !convex && geometry_.mayCrossNonSupporting(rays[i]);
    checkCount += checked[i];
  }
  if (count > 0) {
    counters.slimeQueries += static_cast<std::uint64_t>(count + checkCount);
    intersector_.intersect8(back, entering, farHits);
    if (checkCount > 0) intersector_.intersectNonSupporting8(rays, checked, crossings);
  }
  for (int i = 0; i < 8; ++i) {
    if (!walking[i]) continue;
    const SlimeHit& near = nearHits[i];
    Ray& ray = rays[i];
    const glm::vec3 nearNormal = nearNormals[i];
    const SlimeHit& far = farHits[i];
    // The others walk on, from past their near crossing (the walk's first step).
    const auto walk = [&] { walking[i] = crossShadowSurface(ray, near, visible[i]); };
    if (!entering[i] || crossings[i].valid() || !far.valid() || near.t + far.t >= ray.tFar) {
      walk();
      continue;
    }
    const glm::vec3 farPoint = back[i].origin + far.t * back[i].direction;
    const glm::vec3 farNormal = geometry_.geometricNormal(far, farPoint);
    if (glm::dot(ray.direction, farNormal) <= 0.0f) {  // the light inside the jelly
      walk();
      continue;
    }
    // Entering at the near end, Beer–Lambert over the stretch, leaving at the far end (crossShadowSurface twice).
    glm::vec3& transmittance = visible[i];
    transmittance *= surfaceTransmission(-glm::dot(ray.direction, nearNormal), true);
    walking[i] = false;
    if (!visibleThroughput(transmittance, p.brightest)) {
      transmittance = glm::vec3(0.0f);
      continue;
    }
    transmittance *= beerLambert(p.slimeAbsorption, ray.tFar - near.t - far.t);
    transmittance *= surfaceTransmission(glm::dot(ray.direction, farNormal), false);
    if (!visibleThroughput(transmittance, p.brightest)) transmittance = glm::vec3(0.0f);
  }
}

}  // namespace slime

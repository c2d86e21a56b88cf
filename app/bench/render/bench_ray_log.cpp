#include "app/bench/render/bench_ray_log.h"

#include "core/geometry/camera.h"
#include "render/trace/embree_scene.h"
#include "render/floor/floor_texture.h"
#include "render/trace/shading_parameters.h"
#include "render/slime/slime_geometry.h"
#include "render/trace/whitted_tracer.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace slime {
namespace {

constexpr int kPacket = 8;

// Answers every query of the tracer through Embree and logs it. Shadow packets are those with a
// segment that ends or starts at the light; the other rays are secondary (reflection and refraction
// rays, running to infinity or, inside the slime, asked backwards from beyond its bounds); the
// queries of the non-supporting triangles alone are kept apart (they go to their own BVH).
class RecordingIntersector final : public SlimeIntersector {
 public:
  RecordingIntersector(const SlimeIntersector& inner, RayLog& log, const glm::vec3& light)
      : inner_(inner), log_(log), light_(light) {}

  SlimeHit intersect(const Ray& ray) const override {  // logged as a packet of one
    const bool active[kPacket] = {true};
    const Ray rays[kPacket] = {ray};
    SlimeHit hits[kPacket];
    intersect8(rays, active, hits);
    return hits[0];
  }

  void intersect8(const Ray* rays, const bool* active, SlimeHit* hits) const override {
    bool shadow = false;
    for (int i = 0; i < kPacket; ++i) shadow = shadow || (active[i] && towardsLight(rays[i]));
    record(shadow ? log_.shadow : log_.secondary, rays, active);
    inner_.intersect8(rays, active, hits);
    countHits(active, hits);
  }

  void intersectNonSupporting8(const Ray* rays, const bool* active, SlimeHit* hits) const override {
    record(log_.nonSupporting, rays, active);
    inner_.intersectNonSupporting8(rays, active, hits);
    countHits(active, hits);
  }
  // lightCrossings8 and primaryHits8 are not forwarded: the tracer then asks Embree as it would with
  // no grids (the shadow rays' walk, the primaries' packets), so the replay stays what Embree alone
  // needs for the frame's questions, the same measure as before the renderer answered some itself.

 private:
  static void record(std::vector<RayPacket>& packets, const Ray* rays, const bool* active) {
    RayPacket packet;
    for (int i = 0; i < kPacket; ++i) {
      packet.rays[i] = rays[i];
      packet.active[i] = active[i];
    }
    packets.push_back(packet);
  }
  void countHits(const bool* active, const SlimeHit* hits) const {
    for (int i = 0; i < kPacket; ++i) log_.hits += active[i] && hits[i].valid();
  }

  bool towardsLight(const Ray& ray) const {
    if (std::isinf(ray.tFar)) return false;
    constexpr float kNear = 1e-4f;  // metres
    return glm::distance(ray.origin, light_) < kNear || glm::distance(ray.origin + ray.tFar * ray.direction, light_) < kNear;
  }

  const SlimeIntersector& inner_;
  RayLog& log_;
  glm::vec3 light_;
};

}  // namespace

std::uint64_t RayLog::activeRays(const std::vector<RayPacket>& packets) {
  std::uint64_t count = 0;
  for (const RayPacket& packet : packets)
    for (bool active : packet.active) count += active;
  return count;
}

RayLog recordSlimeQueries(const Settings& settings, const std::vector<glm::dvec3>& positions,
                          const std::vector<Triangle>& triangles, int width, int height) {
  RayLog log;
  SlimeGeometry geometry;
  geometry.update(positions, triangles);
  if (settings.slime.shape == "sphere") geometry.setAnalyticSphere(true, static_cast<float>(settings.slime.radius));
  EmbreeScene embree(settings.render.threads);
  embree.update(geometry, true);
  const RecordingIntersector recorder(embree, log, glm::vec3(settings.light.position));
  const FloorTexture floor(settings.floor);
  const ShadingParameters parameters = makeShadingParameters(settings, height);
  const WhittedTracer tracer(geometry, recorder, floor, parameters);
  const Camera camera = makeCamera(settings.camera, width, height);
  const glm::vec3 eye(camera.position);
  TraceCounters counters;
  // The renderer's primary loop at one sample per pixel: rows of 8-ray packets, only the rays that
  // can reach the slime's bounding sphere are active, then the Whitted trees of the 8 pixels.
  for (int y = 0; y < height; ++y) {
    for (int x0 = 0; x0 < width; x0 += kPacket) {
      RayPacket packet;
      SlimeHit hits[kPacket];
      int activeCount = 0;
      const int count = std::min(kPacket, width - x0);
      for (int i = 0; i < count; ++i) {
        const double u = (x0 + i + 0.5) / width;
        const double v = (y + 0.5) / height;
        packet.rays[i] = Ray{eye, glm::vec3(camera.rayDirection(u, v)), 0.0f, kInfinity};
        packet.active[i] = geometry.mayHit(packet.rays[i]);
        activeCount += packet.active[i];
      }
      if (activeCount > 0) {
        log.primary.push_back(packet);
        embree.intersect8(packet.rays.data(), packet.active.data(), hits);
        for (int i = 0; i < kPacket; ++i) log.hits += packet.active[i] && hits[i].valid();
      }
      glm::vec3 colors[kPacket];
      tracer.tracePrimaries(packet.rays.data(), hits, count, counters, nullptr, colors);
    }
  }
  return log;
}

}  // namespace slime

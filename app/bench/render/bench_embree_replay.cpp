#include "app/bench/render/bench_embree_replay.h"

#include "app/bench/report/bench_timing.h"
#include "render/trace/embree_util.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <stdexcept>

namespace slime {
namespace {

constexpr std::size_t kPacketGrain = 16;  // packets per task


std::uint64_t tracePackets(RTCScene scene, const std::vector<RayPacket>& packets, std::size_t begin, std::size_t end) {
  FlushDenormals flush;
  std::uint64_t hits = 0;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  for (std::size_t p = begin; p < end; ++p) {
    const RayPacket& packet = packets[p];
    alignas(32) int valid[8];
    alignas(32) RTCRayHit8 rays;
    for (int i = 0; i < 8; ++i) {
      valid[i] = packet.active[i] ? -1 : 0;
      const Ray& ray = packet.rays[i];
      rays.ray.org_x[i] = ray.origin.x;
      rays.ray.org_y[i] = ray.origin.y;
      rays.ray.org_z[i] = ray.origin.z;
      rays.ray.dir_x[i] = ray.direction.x;
      rays.ray.dir_y[i] = ray.direction.y;
      rays.ray.dir_z[i] = ray.direction.z;
      rays.ray.tnear[i] = ray.tNear;
      rays.ray.tfar[i] = ray.tFar;
      rays.ray.time[i] = 0.0f;
      rays.ray.mask[i] = 0xFFFFFFFFu;
      rays.ray.id[i] = static_cast<unsigned>(i);
      rays.ray.flags[i] = 0;
      rays.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect8(valid, scene, &context, &rays);
    for (int i = 0; i < 8; ++i) hits += packet.active[i] && rays.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
  }
  return hits;
}

// Runs `trace(begin, end)` over [0, count) in parallel tasks of `grain`; returns the milliseconds.
template <typename Trace>
double timeParallel(tbb::task_arena& arena, std::size_t count, std::size_t grain, std::atomic<std::uint64_t>& hits,
                    const Trace& trace) {
  const Stopwatch watch;
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, grain), [&](const tbb::blocked_range<std::size_t>& range) {
      hits += trace(range.begin(), range.end());
    });
  });
  return watch.milliseconds();
}

}  // namespace

std::string bvhUpdateName(BvhUpdate update) {
  switch (update) {
    case BvhUpdate::Refit: return "refit";
    case BvhUpdate::RebuildLow: return "low";
    case BvhUpdate::RebuildMedium: return "medium";
    case BvhUpdate::RebuildHigh: return "high";
  }
  return "?";
}

EmbreeReplay::EmbreeReplay(int threads, BvhUpdate update) : method_(update) {
  const std::string config = threads > 0 ? "threads=" + std::to_string(threads) + ",set_affinity=0" : "set_affinity=0";
  device_ = rtcNewDevice(config.c_str());
  if (!device_) throw std::runtime_error("Embree: cannot create a device for the benchmark");
  rtcSetDeviceErrorFunction(device_, recordEmbreeError, &error_);
  nonSupporting_ = std::make_unique<EmbreeScene>(threads);
}

void EmbreeReplay::updateNonSupporting(bool topologyChanged) {
  const std::vector<glm::dvec3> positions(vertices_.begin(), vertices_.end() - 1);
  geometry_.update(positions, triangles_);
  nonSupporting_->update(geometry_, topologyChanged);
}

EmbreeReplay::~EmbreeReplay() {
  if (mesh_) rtcReleaseGeometry(mesh_);
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

void EmbreeReplay::throwOnError(const char* during) {
  if (error_.empty()) return;
  const std::string message = error_ + " (while " + during + ")";
  error_.clear();
  throw std::runtime_error(message);
}

void EmbreeReplay::copyPositions(const std::vector<glm::dvec3>& positions) {
  vertices_.resize(positions.size() + 1);
  for (std::size_t i = 0; i < positions.size(); ++i) vertices_[i] = glm::vec3(positions[i]);
  vertices_.back() = glm::vec3(0.0f);
}

double EmbreeReplay::build(const std::vector<glm::dvec3>& positions, const std::vector<Triangle>& triangles) {
  if (mesh_) rtcReleaseGeometry(mesh_);
  if (scene_) rtcReleaseScene(scene_);
  copyPositions(positions);
  triangles_ = triangles;
  // Refit and LOW use the dynamic scene's fast (Morton) builder, as the renderer does; MEDIUM and
  // HIGH the SAH builders (HIGH with spatial splits).
  RTCBuildQuality sceneQuality = RTC_BUILD_QUALITY_LOW, meshQuality = RTC_BUILD_QUALITY_REFIT;
  RTCSceneFlags flags = RTC_SCENE_FLAG_DYNAMIC;
  if (method_ == BvhUpdate::RebuildLow) meshQuality = RTC_BUILD_QUALITY_LOW;
  if (method_ == BvhUpdate::RebuildMedium || method_ == BvhUpdate::RebuildHigh) {
    sceneQuality = meshQuality = method_ == BvhUpdate::RebuildMedium ? RTC_BUILD_QUALITY_MEDIUM : RTC_BUILD_QUALITY_HIGH;
    flags = RTC_SCENE_FLAG_NONE;
  }

  const Stopwatch watch;
  scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(scene_, flags);
  rtcSetSceneBuildQuality(scene_, sceneQuality);
  mesh_ = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryBuildQuality(mesh_, meshQuality);
  rtcSetSharedGeometryBuffer(mesh_, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, vertices_.data(), 0,
                             sizeof(glm::vec3), vertices_.size() - 1);
  rtcSetSharedGeometryBuffer(mesh_, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, triangles_.data(), 0,
                             sizeof(Triangle), triangles_.size());
  rtcCommitGeometry(mesh_);
  rtcAttachGeometry(scene_, mesh_);
  rtcCommitScene(scene_);
  const double ms = watch.milliseconds();
  throwOnError("building the benchmark scene");
  updateNonSupporting(true);
  return ms;
}

double EmbreeReplay::update(const std::vector<glm::dvec3>& positions) {
  if (positions.size() + 1 != vertices_.size()) throw std::invalid_argument("EmbreeReplay::update: vertex count changed");
  copyPositions(positions);
  // Refit quality: the commit refits the existing BVH; any other quality rebuilds it from scratch.
  const Stopwatch watch;
  rtcUpdateGeometryBuffer(mesh_, RTC_BUFFER_TYPE_VERTEX, 0);
  rtcCommitGeometry(mesh_);
  rtcCommitScene(scene_);
  const double ms = watch.milliseconds();
  throwOnError("updating the benchmark scene");
  updateNonSupporting(false);
  return ms;
}

ReplayTimes EmbreeReplay::replay(const RayLog& log, int threads) const {
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  std::atomic<std::uint64_t> hits{0};
  ReplayTimes times;
  RTCScene scene = scene_;
  const auto replayPackets = [&](const std::vector<RayPacket>& packets) {
    return timeParallel(arena, packets.size(), kPacketGrain, hits,
                        [&](std::size_t b, std::size_t e) { return tracePackets(scene, packets, b, e); });
  };
  times.primaryMs = replayPackets(log.primary);
  times.secondaryMs = replayPackets(log.secondary);
  times.shadowMs = replayPackets(log.shadow);
  const EmbreeScene& nonSupporting = *nonSupporting_;
  times.nonSupportingMs =
      timeParallel(arena, log.nonSupporting.size(), kPacketGrain, hits, [&](std::size_t begin, std::size_t end) {
        FlushDenormals flush;
        std::uint64_t found = 0;
        for (std::size_t p = begin; p < end; ++p) {
          const RayPacket& packet = log.nonSupporting[p];
          SlimeHit crossings[8];
          nonSupporting.intersectNonSupporting8(packet.rays.data(), packet.active.data(), crossings);
          for (int i = 0; i < 8; ++i) found += packet.active[i] && crossings[i].valid();
        }
        return found;
      });
  times.hits = hits;
  return times;
}

}  // namespace slime

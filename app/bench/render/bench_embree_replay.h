// A bare Embree 3 scene of the slime mesh, built the way a benchmark asks (refit, or a rebuild at
// LOW / MEDIUM / HIGH quality), through which a recorded RayLog is replayed in parallel: the time
// Embree alone needs for a frame's slime queries (those of the non-supporting triangles through the
// renderer's scene of them).
#pragma once

#include "app/bench/render/bench_ray_log.h"
#include "core/geometry/icosphere.h"
#include "render/trace/embree_scene.h"
#include "render/slime/slime_geometry.h"

#include <embree3/rtcore.h>
#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace slime {

enum class BvhUpdate { Refit, RebuildLow, RebuildMedium, RebuildHigh };

std::string bvhUpdateName(BvhUpdate update);  // "refit", "low", "medium", "high"

struct ReplayTimes {
  double primaryMs = 0.0;    // every query as the tracer's 8-wide packets (rtcIntersect8):
  double secondaryMs = 0.0;  // reflection and refraction
  double shadowMs = 0.0;     // shadow crossings
  double nonSupportingMs = 0.0;  // crossings with the non-supporting triangles (their own BVH)
  std::uint64_t hits = 0;    // queries that found the slime
  double totalMs() const { return primaryMs + secondaryMs + shadowMs + nonSupportingMs; }
};

class EmbreeReplay {
 public:
  // threads = 0: all cores. The device is configured as the renderer's (no start_threads, SPEC §10).
  EmbreeReplay(int threads, BvhUpdate update);
  ~EmbreeReplay();
  EmbreeReplay(const EmbreeReplay&) = delete;
  EmbreeReplay& operator=(const EmbreeReplay&) = delete;

  // Builds the BVH from scratch for this mesh (any method); returns the build time in ms.
  double build(const std::vector<glm::dvec3>& positions, const std::vector<Triangle>& triangles);
  // New vertex positions, same triangles: refits or rebuilds as the method says; returns ms.
  double update(const std::vector<glm::dvec3>& positions);

  // Replays every query of the log with `threads` worker threads (0 = all).
  ReplayTimes replay(const RayLog& log, int threads) const;

 private:
  void copyPositions(const std::vector<glm::dvec3>& positions);
  void throwOnError(const char* during);

  // The frame's non-supporting triangles, in a scene of the renderer's own (rebuilt with each shape,
  // outside the timed build or update: it is the same whatever the method).
  void updateNonSupporting(bool topologyChanged);

  BvhUpdate method_;
  SlimeGeometry geometry_;
  std::unique_ptr<EmbreeScene> nonSupporting_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  RTCGeometry mesh_ = nullptr;
  std::vector<glm::vec3> vertices_;  // one padding vertex: Embree reads 16 bytes at a time
  std::vector<Triangle> triangles_;
  std::string error_;
};

}  // namespace slime

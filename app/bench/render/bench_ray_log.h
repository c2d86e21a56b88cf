// The slime queries of one frame, recorded so that they can be replayed through Embree alone: the
// "limit" pass (the same rays in the same packets, no shading, no ray generation, no analytic floor or sky) and the
// trace time after a refit or a rebuild of the BVH. Recorded by running the renderer's own
// WhittedTracer once over every pixel (one sample per pixel) with an intersector that logs each query.
#pragma once

#include "core/geometry/icosphere.h"
#include "core/settings/settings.h"
#include "render/trace/ray.h"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace slime {

struct RayPacket {
  std::array<Ray, 8> rays;
  std::array<bool, 8> active{};
};

// Every query as the tracer made it: packets of up to 8 rays (the tracer asks nothing one ray at a time).
struct RayLog {
  std::vector<RayPacket> primary;    // coherent primaries, 8 pixels of a row at a time
  std::vector<RayPacket> secondary;  // reflection and refraction queries, a generation of 8 pixels' rays
  std::vector<RayPacket> shadow;     // shadow-ray crossings, segments with one end at the light
  std::vector<RayPacket> nonSupporting;  // crossings with the non-supporting triangles alone (their own BVH)
  std::uint64_t hits = 0;            // queries that found the slime while recording

  static std::uint64_t activeRays(const std::vector<RayPacket>& packets);
  std::uint64_t queries() const {
    return activeRays(primary) + activeRays(secondary) + activeRays(shadow) + activeRays(nonSupporting);
  }
};

// Traces the frame that `settings.camera` sees at width × height with the slime mesh given, and
// returns every query the tracer made of the slime.
RayLog recordSlimeQueries(const Settings& settings, const std::vector<glm::dvec3>& positions,
                          const std::vector<Triangle>& triangles, int width, int height);

}  // namespace slime

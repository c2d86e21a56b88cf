// The caustic map kept from frame to frame (caustics.h).
#include "render/caustics/caustics.h"

#include "render/trace/tsan_handoff.h"

#include <tbb/parallel_for.h>

#include <chrono>

namespace slime {
namespace {

constexpr std::uint64_t kChunk = 1024;  // photons per task; landings concatenated in chunk order (deterministic)

}  // namespace

const CausticMap* Caustics::update(const Settings& settings, const ShadingParameters& parameters,
                                   const SlimeGeometry& geometry, const SlimeIntersector& intersector,
                                   tbb::task_arena* arena, bool progressive) {
  const auto start = std::chrono::steady_clock::now();
  lastMs_ = 0.0;
  const bool slime = geometry.boundRadius > 0.0f || geometry.analyticSphere;
  if (!settings.render.caustics || !parameters.shadows || !(parameters.lightPosition.z > 0.0f) || !slime) {
    key_.clear();
    map_.clear();
    traced_ = 0;
    return nullptr;
  }
  // Everything the photons' paths depend on.
  std::vector<float> key;
  key.reserve(3 * geometry.positions.size() + 24);
  for (const glm::vec3& v : geometry.positions) key.insert(key.end(), {v.x, v.y, v.z});
  const glm::vec3& a = parameters.slimeAbsorption;
  key.insert(key.end(), {parameters.lightPosition.x, parameters.lightPosition.y, parameters.lightPosition.z, a.x, a.y, a.z,
                         parameters.ior, parameters.transmission, static_cast<float>(parameters.optics),
                         static_cast<float>(geometry.analyticSphere), geometry.sphereRadius, geometry.boundRadius,
                         static_cast<float>(settings.render.photons), static_cast<float>(settings.render.backend == "brute"),
                         static_cast<float>(geometry.triangles.size())});
  budget_ = static_cast<std::uint64_t>(std::max(1, settings.render.photons));
  if (key != key_) {
    key_ = std::move(key);
    landings_.clear();
    straight_.clear();
    tally_ = PhotonTally{};
    traced_ = 0;
    frames_ = 0;
    cone_ = photonCone(geometry, parameters.lightPosition);
  } else if (converged()) {
    return map_.empty() ? nullptr : &map_;
  }
  // The photons the map lacks (all of the finished map's, or this progressive frame's), in chunks.
  const PhotonTracer tracer(geometry, intersector, parameters);
  const std::uint64_t finished = budget_ * kStillBudgets;
  std::uint64_t target = finished;
  if (progressive) {
    ++frames_;
    target = frames_ == 1 ? std::max<std::uint64_t>(1, budget_ / kMovingDivisor)
                          : std::min(finished, budget_ * static_cast<std::uint64_t>(frames_));
  }
  const std::uint64_t first = traced_, photons = target - traced_;
  const std::uint64_t chunks = (photons + kChunk - 1) / kChunk;
  std::vector<std::vector<PhotonLanding>> found(chunks), straight(chunks);
  std::vector<PhotonTally> tallies(chunks);
  const auto traceChunk = [&](std::uint64_t c) {
    const std::uint64_t begin = c * kChunk, count = std::min(kChunk, photons - begin);
    tracer.trace(cone_, first + begin, count, found[c], tallies[c], &straight[c]);
  };
  if (arena) {
    handOff(this);  // the inputs, to the workers (tsan_handoff.h)
    arena->execute([&] {
      tbb::parallel_for(std::uint64_t{0}, chunks, [&](std::uint64_t c) {
        takeOver(this);
        traceChunk(c);
        handOff(this);  // the chunk's landings, back
      });
    });
    takeOver(this);
  } else {
    for (std::uint64_t c = 0; c < chunks; ++c) traceChunk(c);
  }
  for (std::uint64_t c = 0; c < chunks; ++c) {
    landings_.insert(landings_.end(), found[c].begin(), found[c].end());
    straight_.insert(straight_.end(), straight[c].begin(), straight[c].end());
    tally_ += tallies[c];
  }
  traced_ += photons;
  map_.build(landings_, static_cast<double>(traced_), cone_.solidAngle, shadowRegion(cone_, geometry.boundCenter, geometry.boundRadius),
             &straight_);
  lastMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return map_.empty() ? nullptr : &map_;
}

}  // namespace slime

// The caustic map kept from frame to frame (caustics.h).
#include "render/caustics/caustics.h"

#include "render/trace/tsan_handoff.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>

namespace slime {
namespace {

constexpr std::uint64_t kChunk = 1024;  // photons per task; landings concatenated in chunk order (deterministic)

}  // namespace

std::uint64_t Caustics::withinBudget(std::uint64_t wanted) const {
  if (!(frameBudgetMs_ > 0.0)) return wanted;
  if (!(msPerPhoton_ > 0.0)) return std::min(wanted, kFirstPhotons);  // no rate yet: a first trace to time
  const double affordable = std::max(static_cast<double>(kFewestPhotons), frameBudgetMs_ / msPerPhoton_);
  return affordable < static_cast<double>(wanted) ? static_cast<std::uint64_t>(affordable) : wanted;
}

void Caustics::trace(const PhotonTracer& tracer, std::uint64_t first, std::uint64_t photons, tbb::task_arena* arena,
                     Photons& out) {
  const auto start = std::chrono::steady_clock::now();
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
    out.landings.insert(out.landings.end(), found[c].begin(), found[c].end());
    out.straight.insert(out.straight.end(), straight[c].begin(), straight[c].end());
    out.tally += tallies[c];
  }
  lastTraced_ += photons;
  // The rate for the frame budget, from traces long enough to time (smoothed: a loaded machine's
  // frames vary).
  if (photons >= kFewestPhotons) {
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const double rate = ms / static_cast<double>(photons);
    msPerPhoton_ = msPerPhoton_ > 0.0 ? 0.5 * (msPerPhoton_ + rate) : rate;
  }
}

void Caustics::append(const Photons& photons) {
  landings_.insert(landings_.end(), photons.landings.begin(), photons.landings.end());
  straight_.insert(straight_.end(), photons.straight.begin(), photons.straight.end());
  tally_ += photons.tally;
}

const CausticMap* Caustics::update(const Settings& settings, const ShadingParameters& parameters,
                                   const SlimeGeometry& geometry, const SlimeIntersector& intersector,
                                   tbb::task_arena* arena, bool progressive) {
  const auto start = std::chrono::steady_clock::now();
  lastMs_ = 0.0;
  lastTraced_ = 0;
  const bool slime = geometry.boundRadius > 0.0f || geometry.analyticSphere;
  if (!settings.render.caustics || !parameters.shadows || !(parameters.lightPosition.z > 0.0f) || !slime) {
    key_.clear();
    map_.clear();
    traced_ = 0;
    halvesValid_ = stale_ = false;
    return nullptr;
  }
  // Everything the photons' paths depend on: the slime's shape first (its vertices and bounds), then the rest.
  const std::size_t shapeFloats = 3 * geometry.positions.size() + 1;
  std::vector<float> key;
  key.reserve(shapeFloats + 24);
  for (const glm::vec3& v : geometry.positions) key.insert(key.end(), {v.x, v.y, v.z});
  key.push_back(geometry.boundRadius);
  const glm::vec3& a = parameters.slimeAbsorption;
  key.insert(key.end(), {parameters.lightPosition.x, parameters.lightPosition.y, parameters.lightPosition.z, a.x, a.y, a.z,
                         parameters.ior, parameters.transmission, static_cast<float>(parameters.optics),
                         static_cast<float>(geometry.analyticSphere), geometry.sphereRadius,
                         static_cast<float>(settings.render.photons), static_cast<float>(settings.render.backend == "brute"),
                         static_cast<float>(geometry.triangles.size())});
  budget_ = static_cast<std::uint64_t>(std::max(1, settings.render.photons));
  const PhotonTracer tracer(geometry, intersector, parameters);
  if (key != key_) {
    // Only the slime's shape changed since the last moving frame (its light, optics and budget
    // as they were): the photons' other half may be kept from it.
    const bool onlyTheSlimeMoved = key.size() == key_.size() &&
                                   std::equal(key.begin() + static_cast<std::ptrdiff_t>(shapeFloats), key.end(),
                                              key_.begin() + static_cast<std::ptrdiff_t>(shapeFloats));
    key_ = std::move(key);
    landings_.clear();
    straight_.clear();
    tally_ = PhotonTally{};
    traced_ = 0;
    frames_ = 0;
    cone_ = photonCone(geometry, parameters.lightPosition);
    if (progressive) {
      // A moving frame: M photons, half of them kept from the last moving frame where only the slime moved.
      frames_ = 1;
      const std::uint64_t moving = withinBudget(std::max<std::uint64_t>(1, budget_ / kMovingDivisor)), half = moving / 2;
      const std::uint64_t firsts[2] = {0, half}, counts[2] = {half, moving - half};
      const bool keep = halvesValid_ && onlyTheSlimeMoved && half > 0 && moving == moving_;
      moving_ = moving;
      for (int h = 0; h < 2; ++h) {
        if (keep && h != nextHalf_) continue;
        halves_[h].clear();
        trace(tracer, firsts[h], counts[h], arena, halves_[h]);
      }
      nextHalf_ = keep ? 1 - nextHalf_ : 0;
      stale_ = keep;
      halvesValid_ = true;
      for (const Photons& h : halves_) append(h);  // in the sequence's order: [0, M/2) then [M/2, M)
      traced_ = moving;
      map_.build(landings_, static_cast<double>(traced_), cone_.solidAngle,
                 shadowRegion(cone_, geometry.boundCenter, geometry.boundRadius), &straight_);
      lastMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      return map_.empty() ? nullptr : &map_;
    }
  } else if (converged() && !stale_) {
    return map_.empty() ? nullptr : &map_;
  }
  halvesValid_ = false;  // a still frame: the next moving frame traces all its photons
  if (stale_) {
    // Half of the map was traced on an earlier shape: the still map starts again from fresh photons,
    // the same sequence, so that it still ends at the finished map.
    landings_.clear();
    straight_.clear();
    tally_ = PhotonTally{};
    traced_ = 0;
    stale_ = false;
  }
  // The photons the map lacks (all of the finished map's, or this progressive frame's), in chunks.
  const std::uint64_t finished = budget_ * kStillBudgets;
  std::uint64_t target = finished;
  if (progressive) {
    ++frames_;
    target = std::min(finished, budget_ * static_cast<std::uint64_t>(frames_));
    if (target > traced_) target = traced_ + withinBudget(target - traced_);  // the rest in later frames
  }
  added_.clear();
  trace(tracer, traced_, target - traced_, arena, added_);
  append(added_);
  traced_ = target;
  map_.build(landings_, static_cast<double>(traced_), cone_.solidAngle, shadowRegion(cone_, geometry.boundCenter, geometry.boundRadius),
             &straight_);
  lastMs_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return map_.empty() ? nullptr : &map_;
}

}  // namespace slime

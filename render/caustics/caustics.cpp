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

int Caustics::movingSide(std::uint64_t vertices) {
  return std::max(2, static_cast<int>(std::sqrt(static_cast<double>(vertices))) - 1);
}

int Caustics::stillSide(std::uint64_t budget) {
  return 4 * std::max(1, static_cast<int>(std::lround(std::sqrt(static_cast<double>(budget)))));
}

std::uint64_t Caustics::movingVertices(std::uint64_t budget) {
  const auto n = static_cast<std::uint64_t>(movingSide(std::max<std::uint64_t>(1, budget / kMovingDivisor)) + 1);
  return n * n;
}

std::uint64_t Caustics::finishedVertices(std::uint64_t budget) {
  const auto n = static_cast<std::uint64_t>(stillSide(budget) + 1);
  return n * n;
}

std::uint64_t Caustics::stillTarget(std::uint64_t budget, int frame) {
  const std::uint64_t finished = finishedVertices(budget);
  const auto k = static_cast<std::uint64_t>(std::clamp(frame, 0, kStillBudgets));
  return (finished * k + kStillBudgets - 1) / kStillBudgets;
}

void Caustics::trace(const PhotonTracer& tracer, const WavefrontGrid& grid, std::uint64_t first, std::uint64_t count,
                     tbb::task_arena* arena, Vertices& out) {
  const auto start = std::chrono::steady_clock::now();
  const std::uint64_t chunks = (count + kChunk - 1) / kChunk;
  std::vector<std::vector<WavefrontVertex>> found(chunks);
  std::vector<PhotonTally> tallies(chunks);
  const auto traceChunk = [&](std::uint64_t c) {
    const std::uint64_t begin = c * kChunk, n = std::min(kChunk, count - begin);
    found[c].reserve(n);
    traceWavefront(tracer, cone_, grid, first + begin, n, found[c], tallies[c]);
  };
  if (arena) {
    handOff(this);  // the inputs, to the workers (tsan_handoff.h)
    arena->execute([&] {
      tbb::parallel_for(std::uint64_t{0}, chunks, [&](std::uint64_t c) {
        takeOver(this);
        traceChunk(c);
        handOff(this);  // the chunk's vertices, back
      });
    });
    takeOver(this);
  } else {
    for (std::uint64_t c = 0; c < chunks; ++c) traceChunk(c);
  }
  for (std::uint64_t c = 0; c < chunks; ++c) {
    out.vertices.insert(out.vertices.end(), found[c].begin(), found[c].end());
    out.tally += tallies[c];
  }
  lastTraced_ += count;
  // The rate for the frame budget, from traces long enough to time (smoothed: a loaded machine's
  // frames vary).
  if (count >= kFewestPhotons) {
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const double rate = ms / static_cast<double>(count);
    msPerPhoton_ = msPerPhoton_ > 0.0 ? 0.5 * (msPerPhoton_ + rate) : rate;
  }
}

void Caustics::append(const Vertices& traced) {
  vertices_.insert(vertices_.end(), traced.vertices.begin(), traced.vertices.end());
  tally_ += traced.tally;
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
    next_.clear();
    traced_ = 0;
    halvesValid_ = stale_ = false;
    return nullptr;
  }
  // Everything the light's paths depend on: the slime's shape first (its vertices and bounds), then the rest.
  const std::size_t shapeFloats = 3 * geometry.positions.size() + 1;
  std::vector<float> key;
  key.reserve(shapeFloats + 24);
  for (const glm::vec3& v : geometry.positions) key.insert(key.end(), {v.x, v.y, v.z});
  key.push_back(geometry.boundRadius);
  const glm::vec3& a = parameters.slimeAbsorption;
  key.insert(key.end(), {parameters.lightPosition.x, parameters.lightPosition.y, parameters.lightPosition.z, a.x, a.y, a.z,
                         parameters.ior, parameters.transmission, static_cast<float>(parameters.optics),
                         static_cast<float>(parameters.smoothNormals), static_cast<float>(geometry.analyticSphere),
                         geometry.sphereRadius, static_cast<float>(settings.render.photons),
                         static_cast<float>(settings.render.backend == "brute"), static_cast<float>(geometry.triangles.size())});
  const std::uint64_t budget = static_cast<std::uint64_t>(std::max(1, settings.render.photons));
  if (budget != budget_ || stillGrid_.vertices() == 0) {
    budget_ = budget;
    stillGrid_ = WavefrontGrid(stillSide(budget), 3);
    halvesValid_ = false;
  }
  const PhotonTracer tracer(geometry, intersector, parameters);
  const auto elapsed = [&] { return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count(); };
  // The map of `grid`'s `level` spread in next_ (its squares within the first `traced` vertices),
  // shown in map_'s place once whole; none where the vertices are missing (the cone empty).
  const auto build = [&](const WavefrontGrid& grid, int level, std::uint64_t traced, double cellPerTriangle) {
    if (!next_.spreading() || buildingLevel_ != level) {
      next_.beginWavefront(grid, level, vertices_, cone_, shadowRegion(cone_, geometry.boundCenter, geometry.boundRadius),
                           cellPerTriangle);
      buildingLevel_ = level;
    }
    if (next_.spreadWavefront(arena, traced)) {
      std::swap(map_, next_);
      builtLevel_ = level;
    } else if (!next_.spreading()) {
      map_.clear();
      builtLevel_ = -1;
    }
    lastMs_ = elapsed();
    return map_.empty() ? nullptr : &map_;
  };
  if (key != key_) {
    // Only the slime's shape changed since the last moving frame (its light, optics and budget
    // as they were): the other half of the vertices may be kept from it.
    const bool onlyTheSlimeMoved = key.size() == key_.size() &&
                                   std::equal(key.begin() + static_cast<std::ptrdiff_t>(shapeFloats), key.end(),
                                              key_.begin() + static_cast<std::ptrdiff_t>(shapeFloats));
    key_ = std::move(key);
    next_.clear();  // a map under way is of the old vertices
    vertices_.clear();
    tally_ = PhotonTally{};
    traced_ = 0;
    frames_ = 0;
    builtLevel_ = -1;
    onStillGrid_ = true;
    cone_ = photonCone(geometry, parameters.lightPosition);
    if (progressive) {
      // A moving frame: the moving grid, half of its vertices kept from the last moving frame where only the slime moved.
      frames_ = 1;
      onStillGrid_ = false;
      // Its grid: about M = render.photons / kMovingDivisor vertices, or fewer where the frame budget says so.
      const int side = movingSide(withinBudget(std::max<std::uint64_t>(1, budget_ / kMovingDivisor)));
      const bool sameGrid = side == movingGrid_.side();
      if (!sameGrid) movingGrid_ = WavefrontGrid(side, 1);
      const std::uint64_t moving = movingGrid_.vertices(), half = moving / 2;
      const std::uint64_t firsts[2] = {0, half}, counts[2] = {half, moving - half};
      const bool keep = halvesValid_ && onlyTheSlimeMoved && half > 0 && sameGrid;
      for (int h = 0; h < 2; ++h) {
        if (keep && h != nextHalf_) continue;
        halves_[h].clear();
        trace(tracer, movingGrid_, firsts[h], counts[h], arena, halves_[h]);
      }
      nextHalf_ = keep ? 1 - nextHalf_ : 0;
      stale_ = keep;
      halvesValid_ = true;
      for (const Vertices& h : halves_) append(h);  // in the grid's order: [0, M/2) then [M/2, M)
      traced_ = moving;
      next_.clear();
      return build(movingGrid_, 0, CausticMap::kAllTraced, CausticMap::kCoarseCells);
    }
  } else if (converged() && onStillGrid_) {
    return map_.empty() ? nullptr : &map_;
  }
  halvesValid_ = false;  // a still frame: the next moving frame traces all its vertices
  if (!onStillGrid_) {
    // The map holds the moving grid's vertices: the still map starts again on its own grid, in its
    // order, so that it still ends at the finished map.
    next_.clear();
    vertices_.clear();
    tally_ = PhotonTally{};
    traced_ = 0;
    builtLevel_ = -1;
    onStillGrid_ = true;
  }
  stale_ = false;
  // The vertices the map lacks (all of the finished map's, or this progressive frame's), in chunks.
  const std::uint64_t finished = stillGrid_.vertices();
  std::uint64_t target = finished;
  if (progressive) {
    ++frames_;
    target = std::max(traced_, stillTarget(budget_, frames_));
    if (target > traced_) target = traced_ + withinBudget(target - traced_);  // the rest in later frames
  }
  added_.clear();
  trace(tracer, stillGrid_, traced_, target - traced_, arena, added_);
  append(added_);
  traced_ = target;
  // The map: the finest grid whose vertices are all traced (until the first is, the moving grid's map
  // stays). A progressive frame spreads the squares of the level it traces as their corners arrive,
  // so that the frame that completes the level spreads only its last ones and makes the map.
  const int complete = stillGrid_.completeLevel(traced_);
  int level = complete;
  if (progressive && complete + 1 < stillGrid_.levels() && traced_ > (complete < 0 ? 0 : stillGrid_.levelEnd(complete)))
    level = complete + 1;
  if (level < 0 || level <= builtLevel_) {
    lastMs_ = elapsed();
    return map_.empty() ? nullptr : &map_;
  }
  return build(stillGrid_, level, progressive ? traced_ : CausticMap::kAllTraced, CausticMap::kFineCells);
}

}  // namespace slime

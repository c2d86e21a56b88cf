// The caustic map kept from frame to frame (caustics.h).
#include "render/caustics/caustics.h"

#include "render/trace/tsan_handoff.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>

namespace slime {
namespace {

constexpr std::uint64_t kChunk = 1024;  // photons per task; landings concatenated in chunk order (deterministic)
// The moving grid's finer vertices not traced (refine): a count no traced vertex has, and queued.
constexpr std::uint8_t kUntraced = 255, kQueued = 254;

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
}

void Caustics::timeUpdate(double milliseconds) {
  lastMs_ = milliseconds;
  // The rate for the frame budget: the whole update's time (the vertices traced and their squares
  // spread) over the vertices it traced, from updates long enough to time (smoothed: a loaded
  // machine's frames vary). A quarter of kFewestPhotons: the least moving frame (its coarse level
  // of kFewestPhotons / 2, refined) must time itself too, or one slow frame would hold the grid down.
  if (lastTraced_ < kFewestPhotons / 4) return;
  const double rate = milliseconds / static_cast<double>(lastTraced_);
  msPerPhoton_ = msPerPhoton_ > 0.0 ? 0.5 * (msPerPhoton_ + rate) : rate;
}

void Caustics::refine(const PhotonTracer& tracer, int side, tbb::task_arena* arena) {
  // vertices_ holds the coarse level's (side + 1)² vertices, in the grid's order (its first ones).
  WavefrontVertex untraced;
  untraced.count = kUntraced;
  vertices_.resize(movingGrid_.vertices(), untraced);
  refined_.assign(static_cast<std::size_t>(side) * side, 0);
  fineRanks_.clear();
  for (int row = 0; row < side; ++row)
    for (int column = 0; column < side; ++column) {
      if (!needsFinerVertices(movingGrid_, vertices_, 2 * column, 2 * row, 2)) continue;
      refined_[static_cast<std::size_t>(row) * side + column] = 1;
      // The square's five finer vertices: its edges' midpoints and its centre (each once).
      const int x = 2 * column, y = 2 * row;
      const int points[5][2] = {{x + 1, y}, {x, y + 1}, {x + 1, y + 1}, {x + 2, y + 1}, {x + 1, y + 2}};
      for (const auto& p : points) {
        const std::uint32_t rank = movingGrid_.rank(p[0], p[1]);
        if (vertices_[rank].count != kUntraced) continue;
        vertices_[rank].count = kQueued;
        fineRanks_.push_back(rank);
      }
    }
  const std::uint64_t count = fineRanks_.size(), chunks = (count + kChunk - 1) / kChunk;
  std::vector<PhotonTally> tallies(chunks);
  const auto traceChunk = [&](std::uint64_t c) {
    const std::uint64_t begin = c * kChunk;
    traceWavefrontAt(tracer, cone_, movingGrid_, fineRanks_.data() + begin, std::min(kChunk, count - begin), vertices_.data(),
                     tallies[c]);
  };
  if (arena) {
    handOff(this);
    arena->execute([&] {
      tbb::parallel_for(std::uint64_t{0}, chunks, [&](std::uint64_t c) {
        takeOver(this);
        traceChunk(c);
        handOff(this);
      });
    });
    takeOver(this);
  } else {
    for (std::uint64_t c = 0; c < chunks; ++c) traceChunk(c);
  }
  for (const PhotonTally& t : tallies) tally_ += t;
  lastTraced_ += count;
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
    return nullptr;
  }
  // Everything the light's paths depend on: the slime's shape (its vertices and bounds), the light, the optics, the budget.
  std::vector<float> key;
  key.reserve(3 * geometry.positions.size() + 25);
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
  }
  const PhotonTracer tracer(geometry, intersector, parameters);
  const auto elapsed = [&] { return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count(); };
  // The map of `grid`'s `level` spread in next_ (its squares within the first `traced` vertices),
  // shown in map_'s place once whole; none where the vertices are missing (the cone empty).
  const auto build = [&](const WavefrontGrid& grid, int level, std::uint64_t traced, double cellPerTriangle,
                         const std::vector<std::uint8_t>* refined = nullptr) {
    if (!next_.spreading() || buildingLevel_ != level) {
      next_.beginWavefront(grid, level, vertices_, cone_, shadowRegion(cone_, geometry.boundCenter, geometry.boundRadius),
                           cellPerTriangle, refined);
      buildingLevel_ = level;
    }
    if (next_.spreadWavefront(arena, traced)) {
      std::swap(map_, next_);
      builtLevel_ = level;
    } else if (!next_.spreading()) {
      map_.clear();
      builtLevel_ = -1;
    }
    timeUpdate(elapsed());
    return map_.empty() ? nullptr : &map_;
  };
  if (key != key_) {
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
      // A moving frame: the moving grid's coarse level, of about render.photons / kMovingDivisor vertices
      // (or fewer where the frame budget says so), and its finer vertices where its squares need them.
      frames_ = 1;
      onStillGrid_ = false;
      // (A refined grid traces about twice its coarse level's vertices on the default slime.)
      const std::uint64_t coarseWanted = std::max<std::uint64_t>(1, budget_ / kMovingDivisor);
      const int side = movingSide(withinBudget(2 * coarseWanted) / 2);
      if (2 * side != movingGrid_.side()) movingGrid_ = WavefrontGrid(2 * side, 2);
      const std::uint64_t coarse = movingGrid_.levelEnd(0);
      const PhotonTracer moving(geometry, intersector, parameters, kMovingVertexWeight);
      added_.clear();
      trace(moving, movingGrid_, 0, coarse, arena, added_);
      append(added_);
      refine(moving, side, arena);
      traced_ = coarse + fineRanks_.size();
      return build(movingGrid_, 0, CausticMap::kAllTraced, CausticMap::kFineCells, &refined_);
    }
  } else if (converged() && onStillGrid_) {
    return map_.empty() ? nullptr : &map_;
  }
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
  // A level under way whose vertices are all traced now is finished first, in this frame, and the
  // next begins in the next (a frame budget can trace past a level's end before its squares are
  // spread; the map would else skip that level).
  if (progressive && next_.spreading() && buildingLevel_ > builtLevel_ && buildingLevel_ < level) level = buildingLevel_;
  if (level < 0 || level <= builtLevel_) {
    timeUpdate(elapsed());
    return map_.empty() ? nullptr : &map_;
  }
  return build(stillGrid_, level, progressive ? traced_ : CausticMap::kAllTraced, CausticMap::kFineCells);
}

}  // namespace slime

#include "core/integrators/damped_symplectic_euler.h"

#include "core/contact/floor_contact.h"
#include "core/geometry/volume.h"

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>

namespace slime {
namespace {

// The helpers pass 32-byte vectors by reference only: by value their ABI would differ between the
// AVX2 and the baseline build (GCC warns, Clang refuses). A scalar times a vector multiplies each lane.
[[gnu::always_inline]] inline void pad(const glm::dvec3& v, Vector4& padded) {
  padded = Vector4{v.x, v.y, v.z, 0.0};
}
[[gnu::always_inline]] inline glm::dvec3 unpad(const Vector4& v) { return {v[0], v[1], v[2]}; }
// glm::dot's order, ((x + y) + z), so the result does not depend on the vector width.
[[gnu::always_inline]] inline double dot(const Vector4& a, const Vector4& b) {
  const Vector4 product = a * b;
  return (product[0] + product[1]) + product[2];
}
// a × b = a.yzx b.zxy - a.zxy b.yzx (the fourth lane stays 0).
[[gnu::always_inline]] inline void cross(const Vector4& a, const Vector4& b, Vector4& product) {
  const Vector4 aYzx = __builtin_shufflevector(a, a, 1, 2, 0, 3);
  const Vector4 aZxy = __builtin_shufflevector(a, a, 2, 0, 1, 3);
  const Vector4 bYzx = __builtin_shufflevector(b, b, 1, 2, 0, 3);
  const Vector4 bZxy = __builtin_shufflevector(b, b, 2, 0, 1, 3);
  product = aYzx * bZxy - aZxy * bYzx;
}

// What the passes of one substep read and write, as plain pointers so that the range kernels
// below can be built for AVX2 and called from threads.
struct SubstepData {
  std::size_t pointCount = 0;
  std::size_t blockCount = 1;  // spring blocks, each with its own force and gradient accumulators
  double h = 0.0;
  glm::dvec3* statePositions = nullptr;
  glm::dvec3* stateVelocities = nullptr;
  const double* inverseMasses = nullptr;
  PaddedVector* positions = nullptr;
  PaddedVector* velocities = nullptr;
  PaddedVector* springForces = nullptr;       // blockCount arrays of pointCount
  PaddedVector* sixVolumeGradient = nullptr;  // blockCount arrays of pointCount
  PaddedVector* springVectors = nullptr;
  glm::dvec2* damperFactors = nullptr;
  const glm::u32vec2* ends = nullptr;
  const glm::u32vec2* opposites = nullptr;  // null: no volume term
  const double* stiffnesses = nullptr;
  const double* restLengths = nullptr;
  const glm::dvec2* dampingShares = nullptr;
  Vector4 origin{};  // p_0, near the mesh, so the cross products stay well conditioned
  Vector4 gravity{};
  double friction = 0.0;
};

// The clones are chosen by an ifunc resolver that the dynamic loader runs before any sanitizer's
// runtime is up; an instrumented resolver crashes there, so sanitized builds keep the baseline only.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__SANITIZE_ADDRESS__) && \
    !defined(__SANITIZE_THREAD__)
#define SLIME_AVX2_CLONE __attribute__((target_clones("avx2", "default")))
#else
#define SLIME_AVX2_CLONE
#endif

// Pass 0: the state, padded.
SLIME_AVX2_CLONE void padPoints(const SubstepData& d, std::size_t begin, std::size_t end) {
  for (std::size_t i = begin; i < end; ++i) {
    pad(d.statePositions[i], d.positions[i].lanes);
    pad(d.stateVelocities[i], d.velocities[i].lanes);
  }
}

// Pass 1 over springs [begin, end): Hooke's force F_j = -k (|x| - l) x/|x| (no damper: it is
// solved in pass 4), the edge's share ±(p_i - o) × x_ij of 6∇V at its opposite vertices
// ((p_i - o) × (p_j - o) with the same origin o for every edge), and what the damper needs of the
// same x_ij, with the inverse masses folded in.
SLIME_AVX2_CLONE void addSpringForces(const SubstepData& d, std::size_t begin, std::size_t end,
                                      PaddedVector* forces, PaddedVector* sixGradient) {
  // Locals, so the compiler need not reload them after each store through a pointer.
  const glm::u32vec2* ends = d.ends;
  const glm::u32vec2* opposites = d.opposites;
  const PaddedVector* positions = d.positions;
  const double* stiffnesses = d.stiffnesses;
  const double* restLengths = d.restLengths;
  const glm::dvec2* dampingShares = d.dampingShares;
  PaddedVector* springVectors = d.springVectors;
  glm::dvec2* damperFactors = d.damperFactors;
  const Vector4 origin = d.origin;
  for (std::size_t s = begin; s < end; ++s) {
    const std::uint32_t i = ends[s].x, j = ends[s].y;
    const Vector4 positionI = positions[i].lanes;
    const Vector4 x = positions[j].lanes - positionI;
    const double length = std::sqrt(dot(x, x));
    const double inverseLength = 1.0 / length;  // the one division per spring
    const double hooke = stiffnesses[s] * (length - restLengths[s]) * inverseLength;
    const Vector4 forceOnJ = -hooke * x;
    forces[j].lanes += forceOnJ;
    forces[i].lanes -= forceOnJ;
    if (opposites) {
      Vector4 share;
      cross(positionI - origin, x, share);
      sixGradient[opposites[s].x].lanes += share;
      sixGradient[opposites[s].y].lanes -= share;
    }
    springVectors[s].lanes = x;
    damperFactors[s] = dampingShares[s] * (inverseLength * inverseLength);
  }
}

// Pass 2 over points [begin, end): their part of 18 V = Σ (p_i - o) · 6∇_i V.
SLIME_AVX2_CLONE double eighteenTimesVolume(const SubstepData& d, std::size_t begin, std::size_t end) {
  double sum = 0.0;
  for (std::size_t i = begin; i < end; ++i) {
    Vector4 sixGradient = d.sixVolumeGradient[i].lanes;
    for (std::size_t b = 1; b < d.blockCount; ++b)
      sixGradient += d.sixVolumeGradient[b * d.pointCount + i].lanes;
    sum += dot(d.positions[i].lanes - d.origin, sixGradient);
  }
  return sum;
}

// Pass 3 over points [begin, end): the first half kick, v += a h/2 with a = w F + g (kinematic
// points keep their velocity). It clears the accumulators it read, except that block 0's force
// keeps the half kick a h/2 for the drift pass to give again.
SLIME_AVX2_CLONE void kick(const SubstepData& d, std::size_t begin, std::size_t end, double pressureOverSix) {
  const double halfStep = 0.5 * d.h;
  for (std::size_t i = begin; i < end; ++i) {
    Vector4 springForce{}, sixGradient{};
    for (std::size_t b = 0; b < d.blockCount; ++b) {
      springForce += d.springForces[b * d.pointCount + i].lanes;
      sixGradient += d.sixVolumeGradient[b * d.pointCount + i].lanes;
      d.springForces[b * d.pointCount + i].lanes = Vector4{};
      d.sixVolumeGradient[b * d.pointCount + i].lanes = Vector4{};
    }
    const double w = d.inverseMasses[i];
    if (w == 0.0) continue;
    const Vector4 halfKick = ((springForce + pressureOverSix * sixGradient) * w + d.gravity) * halfStep;
    d.velocities[i].lanes += halfKick;
    d.springForces[i].lanes = halfKick;
  }
}

// Pass 4, one spring: its relative speed along x̂ decays exactly over the half substep, the impulse
// split by inverse mass (springs.cpp's dampOneSpring with the division and the inverse masses
// folded into the two factors in pass 1).
[[gnu::always_inline]] inline void dampOneSpring(const glm::u32vec2& ends, const Vector4& x,
                                                 const glm::dvec2& factors, PaddedVector* velocities) {
  const std::uint32_t i = ends.x, j = ends.y;
  const double relative = dot(velocities[j].lanes - velocities[i].lanes, x);
  velocities[j].lanes += (relative * factors.y) * x;
  velocities[i].lanes -= (relative * factors.x) * x;
}
SLIME_AVX2_CLONE void dampForward(const SubstepData& d, std::size_t begin, std::size_t end) {
  const glm::u32vec2* ends = d.ends;
  const PaddedVector* springVectors = d.springVectors;
  const glm::dvec2* damperFactors = d.damperFactors;
  PaddedVector* velocities = d.velocities;
  for (std::size_t s = begin; s < end; ++s)
    dampOneSpring(ends[s], springVectors[s].lanes, damperFactors[s], velocities);
}
SLIME_AVX2_CLONE void dampBackward(const SubstepData& d, std::size_t begin, std::size_t end) {
  const glm::u32vec2* ends = d.ends;
  const PaddedVector* springVectors = d.springVectors;
  const glm::dvec2* damperFactors = d.damperFactors;
  PaddedVector* velocities = d.velocities;
  for (std::size_t s = end; s-- > begin;)
    dampOneSpring(ends[s], springVectors[s].lanes, damperFactors[s], velocities);
}

// Pass 5 over points [begin, end): the second half kick (clearing what pass 3 kept of it), the
// drift, then the floor puts back on it whatever went through it.
SLIME_AVX2_CLONE void drift(const SubstepData& d, std::size_t begin, std::size_t end) {
  for (std::size_t i = begin; i < end; ++i) {
    glm::dvec3& position = d.statePositions[i];
    glm::dvec3& velocity = d.stateVelocities[i];
    velocity = unpad(d.velocities[i].lanes + d.springForces[i].lanes);
    d.springForces[i].lanes = Vector4{};
    position += velocity * d.h;
    if (d.inverseMasses[i] != 0.0) resolveFloorContactAt(position, velocity, d.friction);
  }
}

// Runs `kernel(begin, end)` over [0, count) in fixed chunks, on threads or not.
// TBB orders the passes already, but inside Debian's uninstrumented libtbb, where ThreadSanitizer
// cannot see it: it would report (and spend minutes suppressing) every hand-over between passes.
// So each pass also hands over through an atomic of ours, one release/acquire per chunk: what came
// before the pass happens before every chunk, and every chunk before what comes after.
template <typename Kernel>
void forChunks(bool parallel, std::size_t count, std::size_t chunk, const Kernel& kernel) {
  if (!parallel) {
    kernel(std::size_t{0}, count);
    return;
  }
  std::atomic<std::size_t> handOver{0};
  handOver.store(0, std::memory_order_release);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, count, chunk),
      [&](const tbb::blocked_range<std::size_t>& range) {
        handOver.load(std::memory_order_acquire);
        kernel(range.begin(), range.end());
        handOver.fetch_add(1, std::memory_order_release);
      },
      tbb::simple_partitioner{});
  handOver.load(std::memory_order_acquire);
}

}  // namespace

void dampedSymplecticEulerSubstep(ParticleState& state, double h, const DampedSymplecticEulerModel& model,
                                  DampedSymplecticEulerScratch& scratch) {
  const std::size_t count = state.size();
  if (count == 0) return;
  const SpringSet& springs = *model.springs;
  const std::size_t springCount = springs.size();
  // Threads only for big meshes, chosen by size alone, so that the result never depends on how
  // many threads there are (every sum below is over fixed chunks in a fixed order).
  const bool parallel = count >= kParallelPointCount && model.independentRuns != nullptr;
  const std::size_t blockCount = parallel ? kParallelSpringBlocks : 1;
  // The accumulators stay zero between substeps (pass 3 clears what it reads), so only a new size
  // needs filling here.
  if (scratch.springForces.size() != count * blockCount) {
    scratch.springForces.assign(count * blockCount, PaddedVector{});
    scratch.sixVolumeGradient.assign(count * blockCount, PaddedVector{});
  }
  scratch.positions.resize(count);
  scratch.velocities.resize(count);
  scratch.springVectors.resize(springCount);
  scratch.damperFactors.resize(springCount);

  SubstepData d;
  d.pointCount = count;
  d.blockCount = blockCount;
  d.h = h;
  d.statePositions = state.positions.data();
  d.stateVelocities = state.velocities.data();
  d.inverseMasses = state.inverseMasses.data();
  d.positions = scratch.positions.data();
  d.velocities = scratch.velocities.data();
  d.springForces = scratch.springForces.data();
  d.sixVolumeGradient = scratch.sixVolumeGradient.data();
  d.springVectors = scratch.springVectors.data();
  d.damperFactors = scratch.damperFactors.data();
  d.ends = springs.ends.data();
  d.opposites = model.springOpposites ? model.springOpposites->data() : nullptr;
  d.stiffnesses = springs.stiffnesses.data();
  d.restLengths = springs.restLengths.data();
  d.dampingShares = model.dampingShares->data();
  pad(state.positions[0], d.origin);
  pad(model.gravity, d.gravity);
  d.friction = model.friction;

  // 0. The state, padded.
  forChunks(parallel, count, kPointChunk, [&](std::size_t b, std::size_t e) { padPoints(d, b, e); });
  // 1. The springs, and the fill's ∇V, at the positions of the kick: block b of the springs into
  //    accumulator b (the springs of a block may share vertices with another block's).
  const std::size_t blockSize = (springCount + blockCount - 1) / blockCount;
  forChunks(parallel, blockCount, 1, [&](std::size_t first, std::size_t last) {
    for (std::size_t b = first; b < last; ++b)
      addSpringForces(d, std::min(springCount, b * blockSize), std::min(springCount, (b + 1) * blockSize),
                      d.springForces + b * count, d.sixVolumeGradient + b * count);
  });
  // 2. The fill pressure p = p0 + K (1 - V/V0), V summed over fixed chunks of points.
  double pressureOverSix = 0.0;
  if (d.opposites) {
    const std::size_t chunks = (count + kPointChunk - 1) / kPointChunk;
    scratch.volumeParts.assign(chunks, 0.0);
    forChunks(parallel, chunks, 1, [&](std::size_t first, std::size_t last) {
      for (std::size_t c = first; c < last; ++c)
        scratch.volumeParts[c] =
            eighteenTimesVolume(d, c * kPointChunk, std::min(count, (c + 1) * kPointChunk));
    });
    double sum = 0.0;
    for (double part : scratch.volumeParts) sum += part;
    pressureOverSix = fillPressure(sum / 18.0, model.restVolume, model.restPressure, model.bulkModulus) / 6.0;
  }
  // 3. The first half kick.
  forChunks(parallel, count, kPointChunk,
            [&](std::size_t b, std::size_t e) { kick(d, b, e, pressureOverSix); });
  // 4. The damper, implicitly: symmetric Gauss–Seidel, forward then backward, h/2 each (a one-way
  //    sweep is not a symmetric contraction and destabilised symplectic Euler). On threads, run by
  //    run of springs that share no vertex, so that every spring sees what the serial sweep shows it.
  if (!parallel) {
    dampForward(d, 0, springCount);
    dampBackward(d, 0, springCount);
  } else {
    const std::vector<std::size_t>& runs = *model.independentRuns;  // starts, then springCount
    auto sweepRun = [&](std::size_t run, bool forward) {
      const std::size_t first = runs[run], length = runs[run + 1] - first;
      forChunks(length >= 2 * kSpringChunk, length, kSpringChunk, [&](std::size_t b, std::size_t e) {
        forward ? dampForward(d, first + b, first + e) : dampBackward(d, first + b, first + e);
      });
    };
    for (std::size_t run = 0; run + 1 < runs.size(); ++run) sweepRun(run, true);
    for (std::size_t run = runs.size() - 1; run-- > 0;) sweepRun(run, false);
  }
  // 5. The second half kick, the drift and the floor, back into the state.
  forChunks(parallel, count, kPointChunk, [&](std::size_t b, std::size_t e) { drift(d, b, e); });
}

}  // namespace slime

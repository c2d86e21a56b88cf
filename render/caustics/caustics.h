// Caustics: light the slime focuses onto the floor, as photons gathered into a floor map, kept across frames.
//
// Photons are traced through the slime (photon_tracer.h) and gathered into the floor's caustic map
// (caustic_map.h): a bounded budget while anything moves, more photons accumulated while all stays still.
#pragma once

#include "core/settings/settings.h"
#include "render/caustics/caustic_map.h"
#include "render/caustics/photon_tracer.h"

#include <tbb/task_arena.h>

#include <cstdint>
#include <vector>

namespace slime {

class Caustics {
 public:
  // While the slime, the light and the optics stay as in the last frame, each frame adds this many
  // budgets of photons to the last, up to kStillBudgets in all.
  static constexpr int kStillBudgets = 16;
  // A frame that starts the map again (the slime, the light or the optics moved) traces a budget over
  // this: the map a handled slime shows every frame, its cost the caustics' share of a handled frame
  // (issue 30 item 4: 5,000 photons by default, 8–9 % of a loaded 1280×720 frame against 18 % for
  // 10,000). The kernel adapts to the smaller count (caustic_map.h); the next still frame catches up.
  static constexpr int kMovingDivisor = 2;
  // Kept halves: while only the slime moves, frame after frame (held, dragged, falling), a moving frame traces half
  // of its M = render.photons / kMovingDivisor photons afresh, in turn photons [0, M/2) and [M/2, M) of
  // the sequence, and keeps the other half from the moving frame before (issue 28: the photons were
  // 5 of a held frame's ~30 ms on AMD family 25). The map still holds M photons, so it is no noisier;
  // half of them are one frame behind the slime (≈ 30 ms of a hand's motion). A light, optics or
  // budget change, or the first moving frame after a still one, traces all M; the first still frame
  // after a kept half starts the map again from fresh photons, so the progressive map still ends at
  // the finished one.

  // The map for this frame, or null when caustics are off (render.caustics, render.shadows, the light
  // below the floor, no slime). `arena`: the photons in its threads; null: on this thread (the brute
  // force, the oracle). Brings the map up to date:
  // - not `progressive` (a snapshot, a test, any plain render): the finished map at once, photons
  //   0 … kStillBudgets · render.photons − 1, whatever came before (kept while nothing changes), so
  //   the image is a function of the scene alone, not of the frames this object saw;
  // - `progressive` (the interactive viewer): a new shape, light or setting starts again from
  //   render.photons / kMovingDivisor photons; the k-th frame in a row with nothing changed brings
  //   the map to k · render.photons photons, until kStillBudgets of them: the same photons in the same
  //   order, so the 16th still frame is the finished map; a frame where only the slime moved since
  //   the last moving frame traces half of them (kept halves, above).
  const CausticMap* update(const Settings& settings, const ShadingParameters& parameters, const SlimeGeometry& geometry,
                           const SlimeIntersector& intersector, tbb::task_arena* arena, bool progressive = false);

  // Progressive updates only (the viewer): no update traces photons for longer than about this, at the
  // rate the last updates traced them (at least kFewestPhotons a frame); 0, the default: no limit.
  // render.photons is a slider up to 10⁷ a frame (seconds of tracing): the map then gathers them over
  // more frames instead, a moving frame's map is built from fewer, and the still map still ends at the
  // finished one (the same photons in the same order).
  void setFrameBudget(double milliseconds) { frameBudgetMs_ = milliseconds; }
  static constexpr std::uint64_t kFewestPhotons = 1000;
  static constexpr std::uint64_t kFirstPhotons = 5000;  // before the rate is known: the default's moving frame

  std::uint64_t photons() const { return traced_; }  // photons behind the current map
  std::uint64_t lastTraced() const { return lastTraced_; }  // photons the last update traced
  const PhotonTally& tally() const { return tally_; }
  bool converged() const { return traced_ >= budget_ * kStillBudgets; }
  double lastMs() const { return lastMs_; }  // the last update's time, wall clock

 private:
  // The photons [first, first + count) traced on `geometry`: their landings and tally appended.
  struct Photons {
    std::vector<PhotonLanding> landings, straight;
    PhotonTally tally;
    void clear() { landings.clear(), straight.clear(), tally = PhotonTally{}; }  // keeps the vectors' capacity
  };
  void trace(const PhotonTracer& tracer, std::uint64_t first, std::uint64_t count, tbb::task_arena* arena, Photons& out);

  std::vector<float> key_;  // the slime's vertices, the light, the optics and the budget of the map
  // The map's photons gain `photons`' landings and tally.
  void append(const Photons& photons);

  // The last moving frame's two halves of its M photons (kept halves): valid while no still frame
  // came after it; the next moving frame traces halves_[nextHalf_] afresh and keeps the other.
  Photons halves_[2];
  Photons added_;  // a still frame's new photons, reused from frame to frame
  bool halvesValid_ = false;
  int nextHalf_ = 0;
  bool stale_ = false;  // the map holds a half traced on an earlier shape of the slime
  std::uint64_t lastTraced_ = 0;
  std::vector<PhotonLanding> landings_, straight_;  // through the slime; every photon's straight line (caustic_map.h)
  PhotonTally tally_;
  CausticMap map_;
  PhotonCone cone_;
  std::uint64_t traced_ = 0, budget_ = 0;
  int frames_ = 0;  // progressive updates since the map started again
  std::uint64_t moving_ = 0;  // the last moving frame's M (kept halves need the same M)
  // setFrameBudget: the budget, and the time per photon measured on the last traces (0: none yet).
  double frameBudgetMs_ = 0.0;
  double msPerPhoton_ = 0.0;
  // `wanted` photons, or fewer where the frame budget says so.
  std::uint64_t withinBudget(std::uint64_t wanted) const;
  double lastMs_ = 0.0;
};

}  // namespace slime

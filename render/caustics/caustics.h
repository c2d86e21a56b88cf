// Caustics: light the slime focuses onto the floor, as the light's wavefront splatted onto a floor map, kept across frames.
//
// The vertices of a grid over the light's cone are traced through the slime (wavefront.h,
// photon_tracer.h) and its triangles spread over the floor's caustic map (caustic_map.h): a bounded
// grid while anything moves, refined where its vertices' paths part, and a finer one traced over the
// frames while all stays still.
#pragma once

#include "core/settings/settings.h"
#include "render/caustics/caustic_map.h"
#include "render/caustics/photon_tracer.h"
#include "render/caustics/wavefront.h"

#include <tbb/task_arena.h>

#include <cstdint>
#include <vector>

namespace slime {

class Caustics {
 public:
  // While the slime, the light and the optics stay as in the last frame, each frame traces another
  // 1/kStillBudgets of the still grid's vertices (about one budget, render.photons), kStillBudgets frames in all.
  static constexpr int kStillBudgets = 16;
  // A frame that starts the map again (the slime, the light or the optics moved) traces the moving
  // grid's coarse level, of about a budget over this (961 vertices by default), and in each of its
  // squares whose corners take different paths (the outline, the edge of total internal reflection:
  // needsFinerVertices) the finer level's five vertices, spreading that square as four: about 1,600
  // vertices in all on the default slime held. The refinement keeps the moving frame's image 38–39 dB
  // from the finished map's, as `slime view --check-every` measures it (the coarse level alone: 36.6–36.9;
  // caustics_test.cpp), at about the photon map's cost of a held frame (docs/rendering.md).
  static constexpr int kMovingDivisor = 10;
  // A moving frame's vertices follow a partial reflection inside only while it keeps this much of
  // the light: the finished map's 2–4 % echoes inside the jelly cost a query each and split the
  // vertices' paths (more squares refined) for a faint glow the moving frame leaves out.
  static constexpr float kMovingVertexWeight = 0.1f;
  // The map for this frame, or null when caustics are off (render.caustics, render.shadows, the light
  // below the floor, no slime). `arena`: the vertices in its threads; null: on this thread (the brute
  // force, the oracle). Brings the map up to date:
  // - not `progressive` (a snapshot, a test, any plain render): the finished map at once, all the
  //   still grid's vertices, whatever came before (kept while nothing changes), so the image is a
  //   function of the scene alone, not of the frames this object saw;
  // - `progressive` (the interactive viewer): a new shape, light or setting starts again from the
  //   moving grid; the k-th frame in a row with nothing changed brings the still grid to k/16 of its
  //   vertices, coarse to fine, the map drawn from its finest whole level (its 2nd, 5th and 16th
  //   frames), so the 16th still frame is the finished map.
  const CausticMap* update(const Settings& settings, const ShadingParameters& parameters, const SlimeGeometry& geometry,
                           const SlimeIntersector& intersector, tbb::task_arena* arena, bool progressive = false);

  // Progressive updates only (the viewer): no update traces vertices for longer than about this, at
  // the rate the last updates traced them (at least kFewestPhotons a frame); 0, the default: no limit.
  // render.photons is a slider up to 10⁷ a frame (seconds of tracing): the still grid is then traced
  // over more frames instead, a moving frame's grid is coarser, and the still map still ends at the
  // finished one (the same vertices in the same order).
  void setFrameBudget(double milliseconds) { frameBudgetMs_ = milliseconds; }
  static constexpr std::uint64_t kFewestPhotons = 1000;
  static constexpr std::uint64_t kFirstPhotons = 5000;  // before the rate is known: the default's moving frame

  // The wavefront grids (wavefront.h) of a budget B = render.photons: a moving frame's coarse level of about
  // B / kMovingDivisor vertices (movingVertices; its finer level of side 2 movingSide), and the still map's of about kStillBudgets · B in three levels (sides
  // 4m, 2m, m with m = √B: about B, 4 B and 16 B vertices), traced coarse to fine.
  static int movingSide(std::uint64_t vertices);  // the side of a moving grid of at most that many vertices (≥ 9)
  static int stillSide(std::uint64_t budget);
  static std::uint64_t movingVertices(std::uint64_t budget);
  static std::uint64_t finishedVertices(std::uint64_t budget);
  // The still map's vertices traced by its k-th progressive frame: k / kStillBudgets of them.
  static std::uint64_t stillTarget(std::uint64_t budget, int frame);

  std::uint64_t photons() const { return traced_; }  // vertices behind the current map's grid
  std::uint64_t lastTraced() const { return lastTraced_; }  // vertices the last update traced
  const PhotonTally& tally() const { return tally_; }
  bool converged() const { return onStillGrid_ && traced_ >= stillGrid_.vertices() && !next_.spreading(); }
  double lastMs() const { return lastMs_; }  // the last update's time, wall clock
  int shownLevel() const { return onStillGrid_ ? builtLevel_ : -1; }  // the still grid's level shown (−1: the moving map or none)

 private:
  // The vertices [first, first + count) of `grid`'s order traced on `geometry`: appended, with their tally.
  struct Vertices {
    std::vector<WavefrontVertex> vertices;
    PhotonTally tally;
    void clear() { vertices.clear(), tally = PhotonTally{}; }  // keeps the vector's capacity
  };
  void trace(const PhotonTracer& tracer, const WavefrontGrid& grid, std::uint64_t first, std::uint64_t count,
             tbb::task_arena* arena, Vertices& out);

  std::vector<float> key_;  // the slime's vertices, the light, the optics and the budget of the map
  // The moving grid's refinement: the coarse squares needsFinerVertices picks (refined_, side² flags)
  // get their finer vertices (fineRanks_) traced into vertices_, which becomes indexed by rank.
  void refine(const PhotonTracer& tracer, int side, tbb::task_arena* arena);
  std::vector<std::uint8_t> refined_;
  std::vector<std::uint32_t> fineRanks_;
  // The map's vertices gain `traced`'s.
  void append(const Vertices& traced);

  Vertices added_;  // a frame's new vertices, reused from frame to frame
  std::uint64_t lastTraced_ = 0;
  WavefrontGrid movingGrid_, stillGrid_;
  bool onStillGrid_ = true;  // vertices_ are the still grid's (else the moving grid's)
  int builtLevel_ = -1;      // the still grid's level the map was built from (−1: none yet)
  std::vector<WavefrontVertex> vertices_;  // the map's, in its grid's order
  PhotonTally tally_;
  CausticMap map_;
  // The map being built (CausticMap::beginWavefront), shown in map_'s place once whole: a moving
  // frame's at once; a progressive still frame's level as its vertices arrive, its squares spread in
  // the frames that trace their corners.
  CausticMap next_;
  int buildingLevel_ = -1;  // next_'s level of the still grid
  PhotonCone cone_;
  std::uint64_t traced_ = 0, budget_ = 0;
  int frames_ = 0;  // progressive updates since the map started again
  // setFrameBudget: the budget, and the time per photon measured on the last traces (0: none yet).
  double frameBudgetMs_ = 0.0;
  double msPerPhoton_ = 0.0;
  // `wanted` photons, or fewer where the frame budget says so.
  std::uint64_t withinBudget(std::uint64_t wanted) const;
  double lastMs_ = 0.0;
  void timeUpdate(double milliseconds);  // lastMs_, and the rate for the frame budget
};

}  // namespace slime

// The slime's physics as one object, advanced with a fixed time step by the integrator that
// sim.integrator names. The slime is a list of pieces (piece.h), each a body behind one interface:
// slime.model=bulk (the default) is a viscoelastic tetrahedral body carrying the drawn icosphere
// (bulk_piece.h); slime.model=membrane is the seed's skin, the mass points of the drawn icosphere joined
// by springs around a pressurised fill (membrane_piece.h). Each piece has its own hands, floor contact
// and guard state; today a slime is one piece. A headless run, a test and a viewer reset each make a
// new Simulation.
//
// CONTRACT used by render/ and app/ (keep these signatures; add whatever else physics needs):
//   Simulation(const Settings&), reload, applySettings, step, time, stepCount, surfaces, positions,
//   triangles, metrics, divergences, grab, dragTo, release, grabbing, grabTarget, grabbedIndices.
// The drawn slime is surfaces(): a list of closed surfaces, one per piece (pieceCount, piece; today
// always one), which the renderer draws and the exporters write. positions() and triangles() are the
// first piece's, as are state() and the hands' nodes; metrics() and pieceSolids() cover every piece.
// Two hands (kHands): each grab/drag/release names its hand, 0 (the default) or 1; each hand holds its
// own nodes with its own target, radius and force limit, and the two act on the body together.
#pragma once

#include "core/geometry/enclosed_solid.h"
#include "core/geometry/icosphere.h"
#include "core/geometry/surface_view.h"
#include "core/integrators/integrators.h"
#include "core/integrators/stability.h"
#include "core/settings/settings.h"
#include "core/simulation/bulk_piece.h"
#include "core/simulation/membrane_piece.h"
#include "core/simulation/piece.h"

#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace slime {

// A step that produced NaN/inf or an absurd speed; the state was rolled back to the last good one.
struct DivergenceEvent {
  std::int64_t step = 0;
  double time = 0.0;
  std::string integrator;
  std::string what;  // e.g. "NaN position at vertex 17", "speed 3.2e4 m/s at vertex 5"
};

class Simulation {
 public:
  explicit Simulation(const Settings& settings);  // builds the slime at slime.position, at rest
  // Runs the physics on a body built elsewhere (tests: one spring against its analytic solution, run
  // by exactly the code that runs the slime). The settings give the integrator, dt, substeps, damping,
  // gravity and friction; reload() and a structural applySettings() build the icosphere instead.
  Simulation(const Settings& settings, SlimeBody body);
  // As above with one piece per body (tests: a slime of several pieces, which nothing else makes yet).
  // Throws std::invalid_argument when `bodies` is empty.
  Simulation(const Settings& settings, std::vector<SlimeBody> bodies);
  // A bulk slime of several pieces, one per body (tests: pieces stacked or pressed together).
  // Throws std::invalid_argument when `bodies` is empty.
  Simulation(const Settings& settings, std::vector<BulkBody> bodies);
  // A copy steps on from the same state on its own (its pieces cloned).
  Simulation(const Simulation& other);
  Simulation& operator=(const Simulation& other);
  Simulation(Simulation&&) noexcept = default;
  Simulation& operator=(Simulation&&) noexcept = default;

  void reload(const Settings& settings);          // rebuild from the settings (level, radius, ...)
  void applySettings(const Settings& settings);   // live changes: mass, stiffness, damping, dt, integrator, ...
  void step();                                    // advance one fixed step sim.dt

  double time() const;                            // simulated seconds since (re)load
  std::int64_t stepCount() const;
  // The drawn slime: one closed surface per piece, valid until the next step, reload or applySettings.
  const std::vector<SurfaceView>& surfaces() const;
  const std::vector<glm::dvec3>& positions() const;  // the first piece's drawn vertices
  const std::vector<Triangle>& triangles() const;    // the first piece's drawn triangles
  // Over every piece: the shape of all the drawn surfaces, the summed kinetic energy, the fastest point,
  // the summed volume over the summed rest volume.
  SlimeMetrics metrics() const;
  // Each piece's drawn surface's enclosed volume and centroid, in the order of surfaces().
  std::vector<EnclosedSolid> pieceSolids() const;
  const std::vector<DivergenceEvent>& divergences() const;

  // Grab the mass points within `radius` of the surface point nearest to `point` with hand `hand`
  // (0 or 1; a hand already holding lets go first); false if none. Membrane: points the other hand
  // holds are left to it. A bulk slime's grip is a pinch or a fist (grab.h).
  bool grab(const glm::dvec3& point, double radius, int hand = 0, Grip grip = Grip::Pinch);
  void dragTo(const glm::dvec3& target, int hand = 0);  // move the hand's target (its points follow)
  void release(int hand = 0);
  void releaseAll();
  bool grabbing(int hand = 0) const;
  bool anyGrabbing() const;
  glm::dvec3 grabTarget(int hand = 0) const;
  glm::dvec3 grabbedPoint(int hand = 0) const;     // where the hand's part of the surface is now
  glm::dvec3 handForce(int hand = 0) const;        // bulk: the hand's spring force on the body, N
  // The simulated points the hand holds (indices into state().positions).
  const std::vector<std::uint32_t>& grabbedIndices(int hand = 0) const;
  const Hand& hand(int hand) const { return handPiece(hand).hand(static_cast<int>(checkedHand(hand))); }

  // More for tests, reports and tools.
  bool bulk() const { return piece().bulk(); }
  const ParticleState& state() const { return piece().state(); }  // simulated points
  const SlimeBody& body() const;          // membrane only (empty for a bulk slime)
  const BulkBody& bulkBody() const;       // bulk only (empty for a membrane)
  std::size_t pieceCount() const { return pieces_.size(); }
  const Piece& piece(std::size_t index = 0) const { return *pieces_.at(index); }
  // Starts the simulated points moving (an initial condition for oracles); sizes must match state().
  void setVelocities(const std::vector<glm::dvec3>& velocities);
  std::size_t elementCount() const;                         // tetrahedra (bulk) or springs (membrane)
  double elasticEnergy() const;                             // bulk: elastic and volume energy, J
  std::size_t invertedElements() const;                     // bulk: tetrahedra with det Ds ≤ 0 (invertedBulkElements)
  const Settings& settings() const { return settings_; }
  double restVolume() const;  // summed over the pieces, as volume()
  double volume() const;
  int substepsPerStep() const;  // sim.substeps times the guard's refinement after rollbacks
  int lastSolverIterations() const { return piece().lastSolverIterations(); }  // CG iterations (implicit_euler)
  Integrator integrator() const { return integrator_; }  // the one stepping (sim.integrator, auto resolved)
  // Substeps are at least what the integrator needs to stay stable at this level and material
  // (stability.h); off: exactly sim.substeps, so tests and benchmarks can watch a method blow up.
  void setAutomaticSubsteps(bool automatic);
  double highestFrequency() const { return piece().highestFrequency(); }  // ω_max, rad/s
  const FloorAdhesion& adhesion() const;  // bulk: which nodes stick to the floor (empty for a membrane)
  const SelfContact& selfContact() const { return selfContact_; }  // bulk: the pieces' contacts with themselves and each other
  double largestStableStep() const;       // for the current integrator, s: the smallest of the pieces'
  // Tearing and merging (slime.tearing, slime.mergeTime; tearing.h, merging.h).
  std::size_t handPieceIndex(int hand) const { return handPiece_.at(checkedHand(hand)); }  // the piece it acts on
  int tears() const { return tears_; }     // since (re)load
  int merges() const { return merges_; }
  double lastTopologyMilliseconds() const { return lastTopologyMilliseconds_; }  // the last tear's or merge's cost
  // The same in the thread's CPU time: what the work costs, whatever else the machine runs.
  double lastTopologyCpuMilliseconds() const { return lastTopologyCpuMilliseconds_; }

 private:
  void start();  // time zero, models built for the pieces, their good state saved
  void rebuildModels();
  static std::size_t checkedHand(int hand);
  // The piece hand `hand` acts on: the one it grabbed (after a tear, the part that kept its nodes).
  Piece& handPiece(int hand) { return *pieces_[handPiece_[checkedHand(hand)]]; }
  const Piece& handPiece(int hand) const { return *pieces_[handPiece_[checkedHand(hand)]]; }
  // At most one tear per call; true if a piece tore. A tear takes two calls kTearStageSteps apart (its
  // drawn surfaces at the first, the pieces at the second: pendingTear_), so that no one step does it all.
  bool tearPieces();
  bool mergePieces();  // at most one merge per call; true if two pieces fused
  void saveGoodState();
  void rollBack(const std::string& what);
  // The divergence guard's speed limit for this step: kAbsurdSpeed, or more while the hands move fast
  // (simulation.cpp's kHandSpeedFactor); follows the hands' targets since the last step.
  double speedLimit();
  void resolveSelfContact(double h);  // after each substep h: the bulk pieces' drawn surfaces apart

  Settings settings_;
  std::vector<std::unique_ptr<Piece>> pieces_;  // never empty
  SelfContact selfContact_;                     // slime.selfContact, over the bulk pieces
  std::vector<ContactBody> contactBodies_;      // its views of them, rebuilt each step (storage kept)
  mutable std::vector<SurfaceView> drawnSurfaces_;  // what surfaces() gives (its storage kept)
  Integrator integrator_ = Integrator::SymplecticEuler;
  bool automaticSubsteps_ = true;
  double time_ = 0.0;
  std::int64_t stepCount_ = 0;
  int refinement_ = 1;  // extra substeps the divergence guard asked for
  int cleanSteps_ = 0;  // steps since the last rollback or coarsening
  std::vector<DivergenceEvent> divergences_;
  double goodTime_ = 0.0;  // when the pieces' good states were saved
  std::int64_t goodStep_ = 0;
  std::array<std::size_t, kHands> handPiece_{};   // per hand, the index of the piece it acts on
  double slimeRestVolume_ = 0.0;  // the whole slime's, m³ (the smallest piece is a share of it)
  double drawnSpacing_ = 0.0;     // the grid of a drawn surface made afresh, m
  int tears_ = 0, merges_ = 0;
  std::vector<double> touchingFor_;  // per pair (i < j, row after row) of pieces, s touching without a break
  struct PendingTear {
    std::size_t piece = 0;               // the piece that tears
    BulkPiece::SplitSurfaces surfaces;   // its parts' drawn surfaces, made at the tear's first step
    std::int64_t dueStep = 0;            // when the pieces are made
    double milliseconds = 0.0;           // the first step's cost
    double cpuMilliseconds = 0.0;        // ... in CPU time
  };
  std::optional<PendingTear> pendingTear_;  // a tear half done (merges wait; a rollback drops it)
  double lastTopologyMilliseconds_ = 0.0;
  double lastTopologyCpuMilliseconds_ = 0.0;
  bool handHeld_[kHands] = {false, false};  // the hand held at the last step
  glm::dvec3 handTarget_[kHands] = {};      // ... with this target
  double handSpeed_ = 0.0;                  // the hands' recent fastest target speed, m/s (speedLimit)
};

}  // namespace slime

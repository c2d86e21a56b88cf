// The slime's physics as one object, advanced with a fixed time step by the integrator that
// sim.integrator names: slime.model=bulk (the default) is a viscoelastic tetrahedral body carrying the
// drawn icosphere (bulk_body.h); slime.model=membrane is the seed's skin, the mass points of the drawn
// icosphere joined by springs around a pressurised fill (slime_body.h). Both have floor contact and
// grab/press. A headless run, a test and a viewer reset each make a new Simulation.
//
// CONTRACT used by render/ and app/ (keep these signatures; add whatever else physics needs):
//   Simulation(const Settings&), reload, applySettings, step, time, stepCount, surfaces, positions,
//   triangles, metrics, divergences, grab, dragTo, release, grabbing, grabTarget, grabbedIndices.
// The drawn slime is surfaces(): a list of closed surfaces, one per piece (today always one), which
// the renderer draws and the exporters write. positions() and triangles() are the first piece's.
// Two hands (kHands): each grab/drag/release names its hand, 0 (the default) or 1; each hand holds its
// own nodes with its own target, radius and force limit, and the two act on the body together.
#pragma once

#include "core/bulk/bulk_body.h"
#include "core/bulk/projective_dynamics.h"
#include "core/integrators/damped_symplectic_euler.h"
#include "core/membrane/force_model.h"
#include "core/contact/floor_adhesion.h"
#include "core/hands/grab.h"
#include "core/geometry/icosphere.h"
#include "core/geometry/surface_view.h"
#include "core/integrators/implicit_euler.h"
#include "core/integrators/integrators.h"
#include "core/settings/settings.h"
#include "core/membrane/slime_body.h"
#include "core/integrators/stability.h"
#include "core/integrators/xpbd.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace slime {

// Shape and energy figures of the current state (what `slime sim` reports).
struct SlimeMetrics {
  double volumeRatio = 1.0;    // enclosed volume / rest volume
  double height = 0.0;         // max z - min z, m
  double width = 0.0;          // largest horizontal extent (max of x and y extents), m
  double aspect = 1.0;         // height / width
  double minZ = 0.0;           // lowest vertex z, m
  double kineticEnergy = 0.0;  // J
  double maxSpeed = 0.0;       // fastest vertex, m/s
};

// A step that produced NaN/inf or an absurd speed; the state was rolled back to the last good one.
struct DivergenceEvent {
  std::int64_t step = 0;
  double time = 0.0;
  std::string integrator;
  std::string what;  // e.g. "NaN position at vertex 17", "speed 3.2e4 m/s at vertex 5"
};

constexpr int kHands = 2;  // hands that can hold the slime at once (0 and 1)

// One hand: the nodes it holds and where it pulls them. Bulk: a mouse spring (grab.h); membrane: the
// held points are kinematic and follow `anchor`, rate-limited towards `target`.
struct Hand {
  bool holding = false;
  std::vector<std::uint32_t> nodes;  // ascending
  std::vector<glm::dvec3> offsets;   // membrane: node − grab point at the grab
  glm::dvec3 target{0.0};            // where dragTo put it
  glm::dvec3 anchor{0.0};            // membrane: where the held points are now
  glm::dvec3 pendingTarget{0.0};     // bulk: the spring's target reaches it over a step
  glm::dvec3 force{0.0};             // bulk: the spring's force on the body, N
  double radius = 0.0;               // m, as grabbed
  MouseSpring spring;                // bulk
};

class Simulation {
 public:
  explicit Simulation(const Settings& settings);  // builds the slime at slime.position, at rest
  // Runs the physics on a body built elsewhere (tests: one spring against its analytic solution, run
  // by exactly the code that runs the slime). The settings give the integrator, dt, substeps, damping,
  // gravity and friction; reload() and a structural applySettings() build the icosphere instead.
  Simulation(const Settings& settings, SlimeBody body);

  void reload(const Settings& settings);          // rebuild from the settings (level, radius, ...)
  void applySettings(const Settings& settings);   // live changes: mass, stiffness, damping, dt, integrator, ...
  void step();                                    // advance one fixed step sim.dt

  double time() const;                            // simulated seconds since (re)load
  std::int64_t stepCount() const;
  // The drawn slime: one closed surface per piece, valid until the next step, reload or applySettings.
  const std::vector<SurfaceView>& surfaces() const;
  const std::vector<glm::dvec3>& positions() const;  // the first piece's drawn vertices
  const std::vector<Triangle>& triangles() const;    // the first piece's drawn triangles
  SlimeMetrics metrics() const;
  const std::vector<DivergenceEvent>& divergences() const;

  // Grab the mass points within `radius` of the surface point nearest to `point` with hand `hand`
  // (0 or 1; a hand already holding lets go first); false if none. Membrane: points the other hand
  // holds are left to it.
  bool grab(const glm::dvec3& point, double radius, int hand = 0);
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
  const Hand& hand(int hand) const { return hands_[checkedHand(hand)]; }

  // More for tests, reports and tools.
  bool bulk() const { return bulk_; }
  const ParticleState& state() const { return bulk_ ? bulkBody_.state : body_.state; }  // simulated points
  const SlimeBody& body() const { return body_; }           // membrane only
  const BulkBody& bulkBody() const { return bulkBody_; }    // bulk only
  // Starts the simulated points moving (an initial condition for oracles); sizes must match state().
  void setVelocities(const std::vector<glm::dvec3>& velocities);
  std::size_t elementCount() const;                         // tetrahedra (bulk) or springs (membrane)
  double elasticEnergy() const;                             // bulk: elastic and volume energy, J
  std::size_t invertedElements() const;                     // bulk: tetrahedra with det Ds ≤ 0 (invertedBulkElements)
  const Settings& settings() const { return settings_; }
  double restVolume() const { return bulk_ ? bulkBody_.restVolume : body_.restVolume; }
  double volume() const;
  int substepsPerStep() const;  // sim.substeps times the guard's refinement after rollbacks
  int lastSolverIterations() const { return lastSolverIterations_; }  // CG iterations (implicit_euler)
  Integrator integrator() const { return integrator_; }  // the one stepping (sim.integrator, auto resolved)
  // Substeps are at least what the integrator needs to stay stable at this level and material
  // (stability.h); off: exactly sim.substeps, so tests and benchmarks can watch a method blow up.
  void setAutomaticSubsteps(bool automatic);
  double highestFrequency() const { return highestFrequency_; }  // ω_max, rad/s
  const FloorAdhesion& adhesion() const { return adhesion_; }   // bulk: which nodes stick to the floor
  double largestStableStep() const;                              // for the current integrator, s

 private:
  void start();  // time zero, nothing grabbed, models built for body_
  void rebuildModels();
  void substep(double h);
  void bulkSubstep(double h);
  void bulkAccelerations(const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& v,
                         std::vector<glm::dvec3>& a);
  ParticleState& activeState() { return bulk_ ? bulkBody_.state : body_.state; }
  static std::size_t checkedHand(int hand);
  void driveGrabbedPoints(double h);
  void placeGrabbedPoints();
  void saveGoodState();
  void rollBack(const std::string& what);
  int bulkTravelSubsteps() const;  // substeps so that no node crosses kTravelPerSubstep of an edge

  Settings settings_;
  bool bulk_ = false;
  SlimeBody body_;
  BulkBody bulkBody_;
  BulkScratch bulkScratch_;
  Hand hands_[kHands];
  FloorAdhesion adhesion_;  // bulk: the sticky floor (slime.adhesion)
  mutable std::vector<glm::dvec3> drawnPositions_;  // bulk: placed from the body when first asked for
  mutable bool drawnStale_ = true;
  mutable std::vector<SurfaceView> drawnSurfaces_;  // what surfaces() gives (its storage kept)
  Integrator integrator_ = Integrator::SymplecticEuler;
  ForceModel forceModel_;    // every force, the damper explicit
  bool automaticSubsteps_ = true;
  double highestFrequency_ = 0.0;
  double restFrequency_ = 0.0;     // bulk: ω_max at the rest shape; highestFrequency_ never drops below it
  bool deformedFrequency_ = false; // bulk: highestFrequency_ is above the rest one (a stretched body)
  double highestDampingRate_ = 0.0;
  double bulkDampingRate_ = 0.0;  // bulk: the dampers' Gershgorin rate, for symplectic_euler's cap
  std::vector<glm::dvec2> dampingShares_;  // per spring, for the substep length dampingDecayStep_
  double dampingDecayStep_ = -1.0;      // -1: recompute (after a grab, release or material change)
  DampedSymplecticEulerModel symplecticModel_;  // what symplectic_euler's fused substep reads
  DampedSymplecticEulerScratch symplecticScratch_;
  std::vector<std::size_t> independentSpringRuns_;  // for the fused substep's threads
  XpbdModel xpbdModel_;
  ProjectiveSolver projective_;     // bulk, sim.integrator=projective
  bool projectiveActive_ = false;   // its Maxwell stretches are the live ones (the body's metrics a copy)
  AccelerationField accelerationField_;
  ForceScratch forceScratch_;
  IntegratorScratch integratorScratch_;
  ImplicitEulerScratch implicitScratch_;
  XpbdScratch xpbdScratch_;
  double time_ = 0.0;
  std::int64_t stepCount_ = 0;
  int refinement_ = 1;  // extra substeps the divergence guard asked for
  int travelSubsteps_ = 1;  // bulk, explicit: what the fastest node's speed asks for this step
  double shortestEdge_ = 0.0;  // bulk: the tetrahedra's shortest rest edge, m
  int cleanSteps_ = 0;  // steps since the last rollback or coarsening
  int lastSolverIterations_ = 0;
  std::vector<DivergenceEvent> divergences_;

  // The last good state the guard rolls back to.
  ParticleState goodState_;
  std::vector<MaxwellBlock> goodMaxwell_;  // the bulk's B_v and G_v then
  double goodTime_ = 0.0;
  std::int64_t goodStep_ = 0;
};

}  // namespace slime

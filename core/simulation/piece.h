// One piece of slime as Simulation steps it: a body (bulk_piece.h, the default viscoelastic one, or
// membrane_piece.h, the seed's spring skin) with its own hands, floor contact and adhesion, drawn
// surface, metrics and the state the divergence guard rolls it back to. Simulation holds a list of
// pieces and runs the same step on each: beginStep, the substeps, endStep.
#pragma once

#include "core/geometry/particle_state.h"
#include "core/geometry/surface_view.h"
#include "core/hands/grab.h"
#include "core/integrators/integrators.h"
#include "core/settings/settings.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace slime {

// Shape and energy figures of the current state (what `slime sim` reports). The shape is the drawn
// surfaces' (every piece's, as the renderer draws and the exporters write them); the volume ratio is the
// simulated bodies'.
struct SlimeMetrics {
  double volumeRatio = 1.0;    // enclosed volume / rest volume, summed over the pieces
  double height = 0.0;         // max z - min z of the drawn vertices, m
  double width = 0.0;          // largest horizontal extent of the drawn vertices (max of x and y extents), m
  double aspect = 1.0;         // height / width
  double minZ = 0.0;           // lowest drawn vertex z, m
  double kineticEnergy = 0.0;  // J
  double maxSpeed = 0.0;       // fastest vertex, m/s
};

// Sets the shape figures of `metrics` (height, width, aspect, min z) from the vertices of `surfaces`.
void measureShape(std::span<const SurfaceView> surfaces, SlimeMetrics& metrics);

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

// Steps between applications of the floor's rolling resistance (both bodies).
constexpr int kRollingInterval = 4;

// What a step needs to know of the simulation around the piece.
struct StepContext {
  std::int64_t stepCount = 0;     // steps before this one (beginStep), or with it (endStep)
  bool automaticSubsteps = true;  // Simulation::setAutomaticSubsteps
};

class Piece {
 public:
  virtual ~Piece() = default;
  // A copy whose models point at its own body (Simulation's copy: a settled slime pulled many ways).
  virtual std::unique_ptr<Piece> clone() const = 0;

  virtual bool bulk() const = 0;
  // The settings the piece steps by and the integrator that steps it (sim.integrator, auto resolved):
  // after a new body, a material change or a live change of the settings.
  virtual void rebuildModels(const Settings& settings, Integrator integrator) = 0;
  virtual void applyMaterial(const SlimeSettings& slime) = 0;  // mass, moduli, damping, ... changed

  // The step: beginStep (the step's own limits and the hands' targets), substeps of length h, endStep.
  virtual void beginStep(const StepContext& context) = 0;
  virtual void substep(double h) = 0;
  virtual void endStep(const StepContext& context) = 0;
  virtual double largestStableStep() const;  // for the piece's integrator, s
  int travelSubsteps() const { return travelSubsteps_; }  // what the fastest node asks of this step
  double highestFrequency() const { return highestFrequency_; }  // ω_max, rad/s
  int lastSolverIterations() const { return lastSolverIterations_; }

  // The guard's good state: saved, and rolled back to.
  virtual void saveGoodState() = 0;
  virtual void rollBack() = 0;

  virtual const ParticleState& state() const = 0;  // the simulated points
  virtual ParticleState& state() = 0;
  virtual const std::vector<glm::dvec3>& drawnPositions() const = 0;
  virtual const std::vector<Triangle>& drawnTriangles() const = 0;
  SurfaceView surface() const { return {drawnPositions(), drawnTriangles()}; }
  virtual double volume() const = 0;
  virtual double restVolume() const = 0;
  virtual SlimeMetrics metrics() const = 0;
  virtual std::size_t elementCount() const = 0;
  virtual double elasticEnergy() const { return 0.0; }
  virtual std::size_t invertedElements() const { return 0; }

  // Hands: grab (false if no point is taken), drag and release, as Simulation's.
  virtual bool grab(const glm::dvec3& point, double radius, int hand, Grip grip) = 0;
  void dragTo(const glm::dvec3& target, int hand);
  virtual void release(int hand);
  void applyHandForce(double maxForce);  // a hand that holds feels a new sim.handForce now
  bool anyGrabbing() const;
  glm::dvec3 grabbedPoint(int hand) const;
  const Hand& hand(int hand) const { return hands_[hand]; }

 protected:
  // Shape from the drawn surface, energy and speed from all the simulated points.
  SlimeMetrics metricsOf(const std::vector<double>& freeInverseMasses) const;
  virtual const glm::dvec3& grabOffset(const Hand& hand, std::size_t k) const = 0;

  Settings settings_;
  Integrator integrator_ = Integrator::SymplecticEuler;
  Hand hands_[kHands];
  double highestFrequency_ = 0.0;
  double highestDampingRate_ = 0.0;
  int travelSubsteps_ = 1;
  int lastSolverIterations_ = 0;
  ParticleState goodState_;
};

}  // namespace slime

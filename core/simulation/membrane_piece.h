// The seed's spring skin as a piece (slime.model=membrane): the mass points of the drawn icosphere
// joined by springs around a pressurised fill (core/membrane/slime_body.h), stepped by any integrator
// but projective; a hand's points are kinematic and follow it.
#pragma once

#include <utility>

#include "core/integrators/damped_symplectic_euler.h"
#include "core/integrators/implicit_euler.h"
#include "core/integrators/xpbd.h"
#include "core/membrane/force_model.h"
#include "core/membrane/slime_body.h"
#include "core/simulation/piece.h"

namespace slime {

class MembranePiece final : public Piece {
 public:
  explicit MembranePiece(SlimeBody body) : body_(std::move(body)) {}

  std::unique_ptr<Piece> clone() const override;
  bool bulk() const override { return false; }
  void rebuildModels(const Settings& settings, Integrator integrator) override;
  void applyMaterial(const SlimeSettings& slime) override;
  void beginStep(const StepContext&) override {}
  void substep(double h) override;
  void endStep(const StepContext& context) override;
  void saveGoodState() override { goodState_ = body_.state; }
  void rollBack() override { body_.state = goodState_; }

  const ParticleState& state() const override { return body_.state; }
  ParticleState& state() override { return body_.state; }
  const std::vector<glm::dvec3>& drawnPositions() const override { return body_.state.positions; }
  const std::vector<Triangle>& drawnTriangles() const override { return body_.triangles; }
  double volume() const override;
  double restVolume() const override { return body_.restVolume; }
  SlimeMetrics metrics() const override { return metricsOf(body_.freeInverseMasses); }
  std::size_t elementCount() const override { return body_.springs.size(); }

  bool grab(const glm::dvec3& point, double radius, int hand, Grip grip) override;  // holds kinematically, either grip
  void release(int hand) override;

  const SlimeBody& body() const { return body_; }

 private:
  const glm::dvec3& grabOffset(const Hand& hand, std::size_t k) const override { return hand.offsets[k]; }
  void bindModels();  // the models' pointers and the acceleration field, to this object's body
  void driveGrabbedPoints(double h);
  void placeGrabbedPoints();

  SlimeBody body_;
  ForceModel forceModel_;    // every force, the damper explicit
  std::vector<glm::dvec2> dampingShares_;  // per spring, for the substep length dampingDecayStep_
  double dampingDecayStep_ = -1.0;      // -1: recompute (after a grab, release or material change)
  DampedSymplecticEulerModel symplecticModel_;  // what symplectic_euler's fused substep reads
  DampedSymplecticEulerScratch symplecticScratch_;
  std::vector<std::size_t> independentSpringRuns_;  // for the fused substep's threads
  XpbdModel xpbdModel_;
  AccelerationField accelerationField_;
  ForceScratch forceScratch_;
  IntegratorScratch integratorScratch_;
  ImplicitEulerScratch implicitScratch_;
  XpbdScratch xpbdScratch_;
};

}  // namespace slime

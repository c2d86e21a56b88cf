#include "core/simulation/membrane_piece.h"

#include "core/contact/floor_contact.h"
#include "core/geometry/volume.h"
#include "core/hands/grab.h"
#include "core/integrators/stability.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace slime {

std::unique_ptr<Piece> MembranePiece::clone() const {
  auto copy = std::make_unique<MembranePiece>(*this);
  copy->bindModels();
  return copy;
}

void MembranePiece::bindModels() {
  const bool hasVolume = forceModel_.triangles != nullptr;
  forceModel_.springs = &body_.springs;
  forceModel_.triangles = hasVolume ? &body_.triangles : nullptr;
  xpbdModel_.springs = &body_.springs;
  xpbdModel_.triangles = hasVolume ? &body_.triangles : nullptr;
  symplecticModel_.springs = &body_.springs;
  symplecticModel_.dampingShares = &dampingShares_;
  symplecticModel_.springOpposites = hasVolume ? &body_.springOpposites : nullptr;
  symplecticModel_.independentRuns = &independentSpringRuns_;
  accelerationField_ = [this](const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& v,
                               std::vector<glm::dvec3>& a) {
    computeAccelerations(forceModel_, body_.state.inverseMasses, x, v, forceScratch_, a);
  };
}

void MembranePiece::rebuildModels(const Settings& settings, Integrator integrator) {
  settings_ = settings;
  integrator_ = integrator;
  const glm::dvec3 gravity{0.0, 0.0, -settings_.sim.gravity};
  if (integrator_ == Integrator::Projective || integrator_ == Integrator::ProjectiveMidpoint)
    throw std::invalid_argument("sim.integrator=" + integratorName(integrator_) + " is the bulk body's only (slime.model=bulk)");
  const bool hasVolume = settings_.slime.pressure > 0.0;
  forceModel_ = ForceModel{};
  forceModel_.springs = &body_.springs;
  forceModel_.damping = settings_.slime.damping;
  forceModel_.triangles = hasVolume ? &body_.triangles : nullptr;
  forceModel_.restVolume = body_.restVolume;
  forceModel_.restPressure = body_.restPressure;
  forceModel_.bulkModulus = body_.bulkModulus;
  forceModel_.gravity = gravity;
  xpbdModel_ = XpbdModel{};
  xpbdModel_.springs = &body_.springs;
  xpbdModel_.damping = settings_.slime.damping;
  xpbdModel_.triangles = hasVolume ? &body_.triangles : nullptr;
  xpbdModel_.restVolume = body_.restVolume;
  xpbdModel_.gravity = gravity;
  xpbdModel_.friction = settings_.slime.friction;
  symplecticModel_ = DampedSymplecticEulerModel{};
  symplecticModel_.springs = &body_.springs;
  symplecticModel_.dampingShares = &dampingShares_;
  symplecticModel_.springOpposites = hasVolume ? &body_.springOpposites : nullptr;
  symplecticModel_.restVolume = body_.restVolume;
  symplecticModel_.restPressure = body_.restPressure;
  symplecticModel_.bulkModulus = body_.bulkModulus;
  symplecticModel_.gravity = gravity;
  symplecticModel_.friction = settings_.slime.friction;
  independentSpringRuns_ = independentSpringRuns(body_.springs.ends, body_.state.size());
  symplecticModel_.independentRuns = &independentSpringRuns_;
  // What explicit_euler and rk4 integrate (symplectic_euler has its own fused substep).
  accelerationField_ = [this](const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& v,
                               std::vector<glm::dvec3>& a) {
    computeAccelerations(forceModel_, body_.state.inverseMasses, x, v, forceScratch_, a);
  };
  dampingDecayStep_ = -1.0;
  // ω_max² of the springs plus that of the fill's breathing mode, (K/V0) Σ w_i |∇_i V|².
  const double springFrequency = slime::highestFrequency(body_.springs, body_.restPositions, body_.freeInverseMasses);
  double breathing = 0.0;
  if (hasVolume) {
    std::vector<glm::dvec3> gradient;
    volumeGradient(body_.restPositions, body_.triangles, gradient);
    for (std::size_t i = 0; i < gradient.size(); ++i)
      breathing += body_.freeInverseMasses[i] * glm::dot(gradient[i], gradient[i]);
    breathing *= body_.bulkModulus / body_.restVolume;
  }
  highestFrequency_ = std::sqrt(springFrequency * springFrequency + breathing);
  highestDampingRate_ =
      highestDampingRate(body_.springs, body_.restPositions, body_.freeInverseMasses, settings_.slime.damping);
}

void MembranePiece::applyMaterial(const SlimeSettings& slime) { applySlimeMaterial(body_, slime); }

void MembranePiece::substep(double h) {
  if (anyGrabbing()) driveGrabbedPoints(h);
  ParticleState& state = body_.state;
  if (integrator_ == Integrator::SymplecticEuler) {
    // The default, fused (damped_symplectic_euler.h): kick, implicit damper, drift and floor contact
    // in one call. The floor leaves kinematic points alone, so placing the grabbed ones after it
    // gives what the other integrators' order gives.
    if (dampingDecayStep_ != h) {
      springDampingShares(body_.springs, state.inverseMasses, settings_.slime.damping, h, dampingShares_);
      dampingDecayStep_ = h;
    }
    dampedSymplecticEulerSubstep(state, h, symplecticModel_, symplecticScratch_);
    placeGrabbedPoints();
    return;
  }
  switch (integrator_) {
    case Integrator::ExplicitEuler: explicitEulerStep(state, h, accelerationField_, integratorScratch_); break;
    case Integrator::SymplecticEuler: break;  // above
    case Integrator::Rk4: rk4Step(state, h, accelerationField_, integratorScratch_); break;
    case Integrator::ImplicitEuler:
      lastSolverIterations_ = implicitEulerStep(state, h, forceModel_, ImplicitEulerOptions{}, implicitScratch_);
      break;
    case Integrator::Xpbd: xpbdSubstep(state, h, xpbdModel_, xpbdScratch_); break;
    case Integrator::Projective:
    case Integrator::ProjectiveMidpoint: break;  // the bulk body's only (rebuildModels refuses it here)
  }
  placeGrabbedPoints();
  resolveFloorContact(state, settings_.slime.friction);
}

void MembranePiece::endStep(const StepContext& context) {
  // Rolling resistance damps a slow motion (the rocking it is for has a period near 1.4 s), so it
  // acts every few steps, decaying over all of them at once; every step it cost 13 % of a step.
  if (context.stepCount % kRollingInterval == 0)
    dampTurningOnFloor(body_.state, settings_.slime.rolling, kRollingInterval * settings_.sim.dt);
}

double MembranePiece::volume() const { return enclosedVolume(body_.state.positions, body_.triangles); }

bool MembranePiece::grab(const glm::dvec3& point, double radius, int index, Grip /*grip*/) {
  Hand& hand = hands_[index];
  const glm::dvec3 surface = nearestSurfacePoint(body_.state.positions, body_.triangles, point);
  std::vector<std::uint32_t> indices = pointsWithinRadius(body_.state.positions, surface, radius);
  // Points the other hand holds stay with it (a point has one kinematic driver).
  const Hand& other = hands_[1 - index];
  indices.erase(std::remove_if(indices.begin(), indices.end(),
                               [&](std::uint32_t i) {
                                 return std::binary_search(other.nodes.begin(), other.nodes.end(), i);
                               }),
                indices.end());
  if (indices.empty()) return false;
  hand.holding = true;
  hand.nodes = std::move(indices);
  hand.target = surface;
  hand.anchor = surface;
  hand.radius = radius;
  hand.offsets.clear();
  dampingDecayStep_ = -1.0;
  for (std::uint32_t i : hand.nodes) {
    hand.offsets.push_back(body_.state.positions[i] - surface);
    body_.state.inverseMasses[i] = 0.0;
  }
  return true;
}

void MembranePiece::release(int which) {
  const Hand& hand = hands_[which];
  for (std::uint32_t i : hand.nodes) body_.state.inverseMasses[i] = body_.freeInverseMasses[i];
  if (!hand.nodes.empty()) dampingDecayStep_ = -1.0;
  Piece::release(which);
}

// Grabbed points land exactly where they are driven (the integrators moved them by v h).
void MembranePiece::placeGrabbedPoints() {
  ParticleState& state = body_.state;
  for (const Hand& hand : hands_) {
    for (std::size_t k = 0; k < hand.nodes.size(); ++k) {
      glm::dvec3 target = hand.anchor + hand.offsets[k];
      target.z = std::max(target.z, 0.0);
      state.positions[hand.nodes[k]] = target;
    }
  }
}

void MembranePiece::driveGrabbedPoints(double h) {
  ParticleState& state = body_.state;
  for (Hand& hand : hands_) {
    if (!hand.holding) continue;
    const glm::dvec3 next = stepTowards(hand.anchor, hand.target, kGrabSpeed * h);
    for (std::size_t k = 0; k < hand.nodes.size(); ++k) {
      glm::dvec3 target = next + hand.offsets[k];
      target.z = std::max(target.z, 0.0);
      state.velocities[hand.nodes[k]] = (target - state.positions[hand.nodes[k]]) / h;
    }
    hand.anchor = next;
  }
}

}  // namespace slime

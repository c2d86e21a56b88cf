#include "core/simulation.h"

#include "core/divergence.h"
#include "core/floor_contact.h"
#include "core/grab.h"
#include "core/level_of_detail.h"
#include "core/volume.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace slime {
namespace {

constexpr int kGoodStateInterval = 8;   // steps between saved good states
constexpr int kMaxRefinement = 64;      // the guard doubles substeps after a rollback, up to this
constexpr int kRollingInterval = 4;     // steps between applications of the rolling resistance

}  // namespace

Simulation::Simulation(const Settings& settings) { reload(settings); }

Simulation::Simulation(const Settings& settings, SlimeBody body) {
  settings_ = settings;
  settings_.slime.level = effectiveLevel(settings);
  body_ = std::move(body);
  start();
}

void Simulation::reload(const Settings& settings) {
  settings_ = settings;
  settings_.slime.level = effectiveLevel(settings);  // slime.level=auto resolved once, here
  body_ = buildSlimeBody(settings_.slime);
  start();
}

void Simulation::start() {
  time_ = 0.0;
  stepCount_ = 0;
  refinement_ = 1;
  divergences_.clear();
  grabbing_ = false;
  grabbed_.clear();
  grabOffsets_.clear();
  rebuildModels();
  saveGoodState();
}

void Simulation::applySettings(const Settings& settings) {
  const bool rebuild = effectiveLevel(settings) != settings_.slime.level ||
                       settings.slime.radius != settings_.slime.radius ||
                       settings.slime.shape != settings_.slime.shape;
  if (rebuild) {
    reload(settings);
    return;
  }
  const bool material = settings.slime.mass != settings_.slime.mass ||
                        settings.slime.stiffness != settings_.slime.stiffness ||
                        settings.slime.pressure != settings_.slime.pressure;
  const int level = settings_.slime.level;
  settings_ = settings;
  settings_.slime.level = level;
  if (material) applySlimeMaterial(body_, settings.slime);
  refinement_ = 1;
  rebuildModels();
}

void Simulation::rebuildModels() {
  integrator_ = parseIntegrator(settings_.sim.integrator);
  const glm::dvec3 gravity{0.0, 0.0, -settings_.sim.gravity};
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

void Simulation::setAutomaticSubsteps(bool automatic) { automaticSubsteps_ = automatic; }

double Simulation::largestStableStep() const {
  return slime::largestStableStep(integrator_, highestFrequency_, highestDampingRate_);
}

int Simulation::substepsPerStep() const {
  int substeps = std::max(1, settings_.sim.substeps);
  if (automaticSubsteps_) {
    const double needed = std::ceil(settings_.sim.dt / (kStabilitySafety * largestStableStep()));
    if (needed > substeps) substeps = static_cast<int>(std::min(needed, 1.0e4));
  }
  return substeps * refinement_;
}

void Simulation::step() {
  const int substeps = substepsPerStep();
  const double h = settings_.sim.dt / substeps;
  for (int s = 0; s < substeps; ++s) substep(h);
  time_ += settings_.sim.dt;
  ++stepCount_;
  // Rolling resistance damps a slow motion (the rocking it is for has a period near 1.4 s), so it
  // acts every few steps, decaying over all of them at once; every step it cost 13 % of a step.
  if (stepCount_ % kRollingInterval == 0)
    dampTurningOnFloor(body_.state, settings_.slime.rolling, kRollingInterval * settings_.sim.dt);
  const std::string what = findDivergence(body_.state);
  if (!what.empty()) {
    rollBack(what);
    return;
  }
  if (stepCount_ % kGoodStateInterval == 0) saveGoodState();
}

void Simulation::substep(double h) {
  if (grabbing_) driveGrabbedPoints(h);
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
  }
  placeGrabbedPoints();
  resolveFloorContact(state, settings_.slime.friction);
}

// Grabbed points land exactly where they are driven (the integrators moved them by v h).
void Simulation::placeGrabbedPoints() {
  ParticleState& state = body_.state;
  for (std::size_t k = 0; k < grabbed_.size(); ++k) {
    glm::dvec3 target = grabAnchor_ + grabOffsets_[k];
    target.z = std::max(target.z, 0.0);
    state.positions[grabbed_[k]] = target;
  }
}

void Simulation::driveGrabbedPoints(double h) {
  const glm::dvec3 next = stepTowards(grabAnchor_, grabTarget_, kGrabSpeed * h);
  ParticleState& state = body_.state;
  for (std::size_t k = 0; k < grabbed_.size(); ++k) {
    glm::dvec3 target = next + grabOffsets_[k];
    target.z = std::max(target.z, 0.0);
    state.velocities[grabbed_[k]] = (target - state.positions[grabbed_[k]]) / h;
  }
  grabAnchor_ = next;
}

void Simulation::saveGoodState() {
  goodState_ = body_.state;
  goodTime_ = time_;
  goodStep_ = stepCount_;
}

void Simulation::rollBack(const std::string& what) {
  DivergenceEvent event;
  event.step = stepCount_;
  event.time = time_;
  event.integrator = integratorName(integrator_);
  refinement_ = std::min(refinement_ * 2, kMaxRefinement);
  event.what = what + "; rolled back to step " + std::to_string(goodStep_) + ", now " +
               std::to_string(substepsPerStep()) + " substeps per step";
  divergences_.push_back(event);
  body_.state = goodState_;
  time_ = goodTime_;
  stepCount_ = goodStep_;
}

double Simulation::time() const { return time_; }
std::int64_t Simulation::stepCount() const { return stepCount_; }
const std::vector<glm::dvec3>& Simulation::positions() const { return body_.state.positions; }
const std::vector<Triangle>& Simulation::triangles() const { return body_.triangles; }
const std::vector<DivergenceEvent>& Simulation::divergences() const { return divergences_; }
double Simulation::volume() const { return enclosedVolume(body_.state.positions, body_.triangles); }

SlimeMetrics Simulation::metrics() const {
  SlimeMetrics metrics;
  const ParticleState& state = body_.state;
  glm::dvec3 low(std::numeric_limits<double>::infinity()), high(-std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < state.size(); ++i) {
    low = glm::min(low, state.positions[i]);
    high = glm::max(high, state.positions[i]);
    const double speedSquared = glm::dot(state.velocities[i], state.velocities[i]);
    metrics.kineticEnergy += 0.5 * speedSquared / body_.freeInverseMasses[i];
    metrics.maxSpeed = std::max(metrics.maxSpeed, std::sqrt(speedSquared));
  }
  metrics.volumeRatio = volume() / body_.restVolume;
  metrics.height = high.z - low.z;
  metrics.width = std::max(high.x - low.x, high.y - low.y);
  metrics.aspect = metrics.width > 0.0 ? metrics.height / metrics.width : 1.0;
  metrics.minZ = low.z;
  return metrics;
}

bool Simulation::grab(const glm::dvec3& point, double radius) {
  release();
  const glm::dvec3 surface = nearestSurfacePoint(body_.state.positions, body_.triangles, point);
  std::vector<std::uint32_t> indices = pointsWithinRadius(body_.state.positions, surface, radius);
  if (indices.empty()) return false;
  grabbing_ = true;
  grabbed_ = std::move(indices);
  grabTarget_ = surface;
  grabAnchor_ = surface;
  grabOffsets_.clear();
  dampingDecayStep_ = -1.0;
  for (std::uint32_t i : grabbed_) {
    grabOffsets_.push_back(body_.state.positions[i] - surface);
    body_.state.inverseMasses[i] = 0.0;
  }
  return true;
}

void Simulation::dragTo(const glm::dvec3& target) {
  if (grabbing_) grabTarget_ = target;
}

void Simulation::release() {
  for (std::uint32_t i : grabbed_) body_.state.inverseMasses[i] = body_.freeInverseMasses[i];
  if (!grabbed_.empty()) dampingDecayStep_ = -1.0;
  grabbing_ = false;
  grabbed_.clear();
  grabOffsets_.clear();
}

bool Simulation::grabbing() const { return grabbing_; }
glm::dvec3 Simulation::grabTarget() const { return grabTarget_; }
const std::vector<std::uint32_t>& Simulation::grabbedIndices() const { return grabbed_; }

}  // namespace slime

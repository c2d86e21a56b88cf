#include "core/simulation/simulation.h"

#include "core/integrators/divergence.h"
#include "core/contact/floor_contact.h"
#include "core/hands/grab.h"
#include "core/simulation/integrator_choice.h"
#include "core/geometry/level_of_detail.h"
#include "core/geometry/volume.h"
#include "core/bulk/element_pass.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace slime {
namespace {

constexpr int kGoodStateInterval = 8;   // steps between saved good states
constexpr int kMaxRefinement = 64;      // the guard doubles substeps after a rollback, up to this
constexpr double kExactDamperStepFactor = 12.0;  // see largestStableStep
constexpr int kCleanStepsToCoarsen = 500;  // after this many steps with no rollback it halves them again
constexpr int kRollingInterval = 4;     // steps between applications of the rolling resistance
// Steps between the Maxwell branches' flow updates (exact over the interval for the strain at its end;
// 4 ms against relaxation times of 10 ms and more). Every step it cost a quarter of the step. The explicit
// step's interval also follows τ (maxwellFlowInterval, viscoelastic.h), never below this.
constexpr int kRelaxInterval = 4;
// An explicit bulk substep moves no node farther than this share of the body's shortest rest edge
// (a collision's CFL rule: the stability bound of largestStableStep is for small vibrations, and a
// landing at 4.4 m/s pushed the lowest layer 4.4 mm — 40 % of an element — into the floor in one
// 1 ms substep, which inverted elements and made the guard roll back twice).
constexpr double kTravelPerSubstep = 0.25;

// Sets every drawn vertex below the floor (z < 0) on it. The physics holds the element map's vertices
// on the floor (resolveDrawnFloorContact); the smooth map that places the drawn surface differs by
// millimetres (most at the contact's rim and under a press) and may dip under it: drawn on the floor.
void liftOntoFloor(std::vector<glm::dvec3>& drawn) {
  for (glm::dvec3& p : drawn) p.z = std::max(p.z, 0.0);
}
// Steps between estimates of the bulk body's highest frequency while a hand holds it or it is still
// stretched (Simulation::step): 41 force evaluations, a fifth of a step's forces a step every 200 steps;
// every 50 took 19 % of a held slime's physics (perf, drag_top_in_circles_6s).
constexpr int kFrequencyInterval = 200;

}  // namespace

Simulation::Simulation(const Settings& settings) { reload(settings); }

Simulation::Simulation(const Settings& settings, SlimeBody body) {
  settings_ = settings;
  settings_.slime.level = effectiveLevel(settings);
  settings_.slime.model = "membrane";  // a body of springs made elsewhere
  bulk_ = false;
  body_ = std::move(body);
  start();
}

void Simulation::reload(const Settings& settings) {
  settings_ = settings;
  settings_.slime.level = effectiveLevel(settings);  // slime.level=auto resolved once, here
  bulk_ = settings_.slime.model == "bulk";
  if (bulk_) {
    body_ = SlimeBody{};
    bulkBody_ = buildBulkBody(settings_.slime);
  } else {
    bulkBody_ = BulkBody{};
    body_ = buildSlimeBody(settings_.slime);
  }
  start();
}

void Simulation::start() {
  for (Hand& hand : hands_) hand = Hand{};
  adhesion_.reset(bulkBody_.mesh.surface, bulk_ ? bulkBody_.mesh.surfaceNodes : 0);
  drawnStale_ = true;
  cleanSteps_ = 0;
  time_ = 0.0;
  stepCount_ = 0;
  refinement_ = 1;
  divergences_.clear();
  projectiveActive_ = false;  // a new body: its metrics are the live Maxwell state
  rebuildModels();
  saveGoodState();
}

void Simulation::applySettings(const Settings& settings) {
  const bool rebuild = effectiveLevel(settings) != settings_.slime.level ||
                       settings.slime.radius != settings_.slime.radius ||
                       settings.slime.shape != settings_.slime.shape ||
                       settings.slime.model != settings_.slime.model ||
                       settings.slime.resolution != settings_.slime.resolution;
  if (rebuild) {
    reload(settings);
    return;
  }
  const bool material = settings.slime.mass != settings_.slime.mass ||
                        settings.slime.stiffness != settings_.slime.stiffness ||
                        settings.slime.pressure != settings_.slime.pressure ||
                        settings.slime.modulus != settings_.slime.modulus ||
                        settings.slime.longTerm != settings_.slime.longTerm ||
                        settings.slime.relaxation != settings_.slime.relaxation ||
                        settings.slime.poisson != settings_.slime.poisson ||
                        settings.slime.viscosity != settings_.slime.viscosity;
  const int level = settings_.slime.level;
  settings_ = settings;
  settings_.slime.level = level;
  if (material && bulk_) applyBulkMaterial(bulkBody_, settings.slime);
  if (material && !bulk_) applySlimeMaterial(body_, settings.slime);
  for (Hand& hand : hands_) hand.spring.maxForce = settings_.sim.handForce;  // a hand that holds feels it now
  refinement_ = 1;
  rebuildModels();
}

void Simulation::rebuildModels() {
  integrator_ = chooseIntegrator(settings_);
  const glm::dvec3 gravity{0.0, 0.0, -settings_.sim.gravity};
  if (bulk_) {
    // The Maxwell state moves between the projective solver's stretches U_v and the body's metrics G_v.
    if (projectiveActive_) projective_.storeMaxwell(bulkBody_);
    projectiveActive_ = integrator_ == Integrator::Projective;
    if (projectiveActive_) {
      projective_.loadMaxwell(bulkBody_);
      projective_.invalidate();
    }
    accelerationField_ = [this](const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& v,
                                std::vector<glm::dvec3>& a) { bulkAccelerations(x, v, a); };
    highestFrequency_ = restFrequency_ = bulkHighestFrequency(bulkBody_, bulkScratch_);
    deformedFrequency_ = false;
    // symplectic_euler integrates the dampers exactly; the explicit methods feel their rate.
    bulkDampingRate_ = bulkHighestDampingRate(bulkBody_);
    highestDampingRate_ = integrator_ == Integrator::SymplecticEuler ? 0.0 : bulkDampingRate_;
    bulkScratch_.decayStep = -1.0;
    shortestEdge_ = std::numeric_limits<double>::infinity();
    for (const glm::u32vec2& e : bulkBody_.edges)
      shortestEdge_ = std::min(shortestEdge_, glm::length(bulkBody_.mesh.positions[e.y] - bulkBody_.mesh.positions[e.x]));
    return;
  }
  if (integrator_ == Integrator::Projective)
    throw std::invalid_argument("sim.integrator=projective is the bulk body's only (slime.model=bulk)");
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
  const double step = slime::largestStableStep(integrator_, highestFrequency_, highestDampingRate_);
  // The bulk's exact dampers are a contraction pair by pair, but one pair after another between the
  // kicks not unconditionally stable: on the lightest slime (slime.mass=0.01, Gershgorin rate 7.3e4/s),
  // colour after colour (edge_colours.h), 0.2 ms held and 0.225 ms rolled back, so the step is capped
  // at kExactDamperStepFactor / rate = 12 / rate (0.164 ms there; no cap at the defaults: 4.4 ms).
  if (bulk_ && integrator_ == Integrator::SymplecticEuler && bulkDampingRate_ > 0.0)
    return std::min(step, kExactDamperStepFactor / bulkDampingRate_);
  return step;
}

int Simulation::substepsPerStep() const {
  int substeps = std::max(1, settings_.sim.substeps);
  if (automaticSubsteps_) {
    const double needed = std::ceil(settings_.sim.dt / (kStabilitySafety * largestStableStep()));
    if (needed > substeps) substeps = static_cast<int>(std::min(needed, 1.0e4));
    if (travelSubsteps_ > substeps) substeps = travelSubsteps_;
  }
  return substeps * refinement_;
}

int Simulation::bulkTravelSubsteps() const {
  if (!bulk_ || integrator_ == Integrator::Projective) return 1;
  double fastest = 0.0;
  for (const glm::dvec3& v : bulkBody_.state.velocities) fastest = std::max(fastest, glm::dot(v, v));
  const double travel = std::sqrt(fastest) * settings_.sim.dt;
  return static_cast<int>(std::min(std::ceil(travel / (kTravelPerSubstep * shortestEdge_)), 1.0e4));
}

void Simulation::step() {
  travelSubsteps_ = bulkTravelSubsteps();
  // The explicit step limit 2/ω_max follows the shape. A stretched body's thinner elements raise ω (×1.5
  // in a 5× strand, issue 29): the estimate runs every 200 steps while held or deformed. An inverted
  // element's volumetric stress raises it within steps (flung and slammed at resolution 3: J to −2.5, ω
  // 2,400 → 13,000 /s in 20 steps, a rollback): it runs every step that one meets a body fast enough for
  // the travel rule (a landing's J stays above 0.1).
  const bool explicitBulk = bulk_ && automaticSubsteps_ && !projectiveActive_;
  const bool invertedAndFast =
      explicitBulk && travelSubsteps_ > 1 && invertedBulkElements(bulkBody_, bulkBody_.state.positions) > 0;
  if (invertedAndFast || (explicitBulk && (anyGrabbing() || deformedFrequency_) && stepCount_ % kFrequencyInterval == 0)) {
    const double now = bulkHighestFrequencyAt(bulkBody_, bulkBody_.state.positions, bulkScratch_);
    highestFrequency_ = std::max(restFrequency_, now);
    deformedFrequency_ = now > restFrequency_;
  }
  const int substeps = substepsPerStep();
  const double h = settings_.sim.dt / substeps;
  if (bulk_) {  // each mouse target moves to where dragTo put it over this step
    for (Hand& hand : hands_) {
      if (!hand.holding) continue;
      hand.spring.targetVelocity = (hand.pendingTarget - hand.spring.target) / settings_.sim.dt;
      hand.spring.target = hand.pendingTarget;
    }
  }
  for (int s = 0; s < substeps; ++s) substep(h);
  time_ += settings_.sim.dt;
  ++stepCount_;
  if (bulk_) {
    // projective flows its Maxwell branches every substep; the body's metrics follow as a copy.
    const int flowInterval = projectiveActive_
                                 ? kRelaxInterval
                                 : maxwellFlowInterval(settings_.slime.relaxation, settings_.sim.dt, kRelaxInterval);
    if (stepCount_ % flowInterval == 0) {
      if (projectiveActive_) projective_.storeMaxwell(bulkBody_);
      else relaxBulk(bulkBody_, flowInterval * settings_.sim.dt);
    }
    const bool touching = resolveDrawnFloorContact(bulkBody_, settings_.slime.friction) > 0;
    // The floor's rolling resistance acts on the bulk slime too: Coulomb friction lets a ball roll,
    // and the bulk's own viscosity barely slows a bun rolling on its patch (a yanked slime rolled 3 m).
    if (stepCount_ % kRollingInterval == 0)
      dampTurningOnFloor(bulkBody_.state, settings_.slime.rolling, kRollingInterval * settings_.sim.dt, touching);
    drawnStale_ = true;
  } else if (stepCount_ % kRollingInterval == 0) {
    // Rolling resistance damps a slow motion (the rocking it is for has a period near 1.4 s), so it
    // acts every few steps, decaying over all of them at once; every step it cost 13 % of a step.
    dampTurningOnFloor(body_.state, settings_.slime.rolling, kRollingInterval * settings_.sim.dt);
  }
  const std::string what = findDivergence(activeState());
  if (!what.empty()) {
    rollBack(what);
    return;
  }
  if (refinement_ > 1 && ++cleanSteps_ >= kCleanStepsToCoarsen) {
    refinement_ /= 2;
    cleanSteps_ = 0;
  }
  if (stepCount_ % kGoodStateInterval == 0) saveGoodState();
}

void Simulation::substep(double h) {
  if (bulk_) {
    bulkSubstep(h);
    return;
  }
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
    case Integrator::Projective: break;  // the bulk body's only (rebuildModels refuses it here)
  }
  placeGrabbedPoints();
  resolveFloorContact(state, settings_.slime.friction);
}

// a = (internal forces + mouse spring) / m + g for the bulk body; pinned nodes (w = 0) do not move.
void Simulation::bulkAccelerations(const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& v,
                                   std::vector<glm::dvec3>& a) {
  bulkInternalForces(bulkBody_, x, v, a);
  for (Hand& hand : hands_)
    if (hand.holding) hand.force = addMouseSpringForces(hand.spring, x, v, a);
  const glm::dvec3 gravity{0.0, 0.0, -settings_.sim.gravity};
  const std::vector<double>& w = bulkBody_.state.inverseMasses;
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = w[i] > 0.0 ? a[i] * w[i] + gravity : glm::dvec3(0.0);
}

// The bulk body's substep. symplectic_euler: v += h a(x), the dampers exactly, x += h v; explicit_euler and rk4
// integrate the same accelerations, dampers included, through integrators.h. Then the floor on every node and the
// volume projection, which leaves the nodes on the floor where they are (projective's: on the drawn surface's
// floor; the drawn surface's own contact follows once per step).
void Simulation::bulkSubstep(double h) {
  ParticleState& state = bulkBody_.state;
  // The sticky floor reads a stuck node's pull from the kick-drift step's Δx = h²F/m; projective's implicit step
  // is not that, and holding its nodes back made it roll back (21 times in a two-hand pull at 6000 Pa): no adhesion.
  const double adhesion = integrator_ == Integrator::Projective ? 0.0 : settings_.slime.adhesion;
  const double friction = settings_.slime.friction;
  bool floorDone = false;  // the floor contact on every node, fused with the drift below
  if (adhesion > 0.0) adhesion_.beginSubstep(state);
  switch (integrator_) {
    case Integrator::ExplicitEuler: explicitEulerStep(state, h, accelerationField_, integratorScratch_); break;
    case Integrator::Rk4: rk4Step(state, h, accelerationField_, integratorScratch_); break;
    case Integrator::Projective: {
      ProjectiveStep options;
      options.h = h;
      options.iterations = settings_.sim.iterations;
      options.gravity = glm::dvec3(0.0, 0.0, -settings_.sim.gravity);
      options.friction = settings_.slime.friction;
      // The first holding hand goes through the solver (as with one hand); a second one is applied
      // the same way just before it.
      Hand* first = nullptr;
      for (Hand& hand : hands_) {
        if (!hand.holding) continue;
        if (first == nullptr) {
          first = &hand;
          continue;
        }
        hand.force = applyMouseSpringImplicitly(hand.spring, state.positions, state.inverseMasses, h, state.velocities);
      }
      options.mouse = first != nullptr ? &first->spring : nullptr;
      const glm::dvec3 force = projective_.step(bulkBody_, bulkScratch_, options);
      if (first != nullptr) first->force = force;
      break;
    }
    default: {
      // Kick with every force but the dampers, the dampers exactly (dampEdges), then drift.
      std::vector<glm::dvec3>& a = bulkScratch_.forces;
      bulkInternalForces(bulkBody_, state.positions, state.velocities, a, false);
      for (Hand& hand : hands_)
        if (hand.holding) hand.force = addMouseSpringForces(hand.spring, state.positions, state.velocities, a);
      const glm::dvec3 gravity{0.0, 0.0, -settings_.sim.gravity};
      for (std::size_t i = 0; i < state.size(); ++i) {
        const double w = state.inverseMasses[i];
        if (w != 0.0) state.velocities[i] += h * (a[i] * w + gravity);
      }
      dampEdges(bulkBody_, h, bulkScratch_, state);
      // Drift and the floor in one pass (the floor moves only the node it holds).
      for (std::size_t i = 0; i < state.size(); ++i) {
        if (state.inverseMasses[i] == 0.0) continue;
        state.positions[i] += h * state.velocities[i];
        if (state.inverseMasses[i] > 0.0) resolveFloorContactAt(state.positions[i], state.velocities[i], friction);
      }
      floorDone = true;
      break;
    }
  }
  if (!floorDone)
    for (std::size_t i = 0; i < state.size(); ++i)
      if (state.inverseMasses[i] > 0.0) resolveFloorContactAt(state.positions[i], state.velocities[i], friction);
  projectBulkVolume(bulkBody_, h, bulkScratch_, state, projectiveActive_ ? &projective_.floorHeights() : nullptr);
  if (adhesion > 0.0) adhesion_.endSubstep(state, bulkBody_.mesh.surface, bulkBody_.freeInverseMasses, adhesion, h);
}

void Simulation::saveGoodState() {
  if (projectiveActive_) projective_.storeMaxwell(bulkBody_);
  goodState_ = activeState();
  goodMaxwell_ = bulkBody_.maxwell;
  goodTime_ = time_;
  goodStep_ = stepCount_;
}

void Simulation::rollBack(const std::string& what) {
  DivergenceEvent event;
  event.step = stepCount_;
  event.time = time_;
  event.integrator = integratorName(integrator_);
  refinement_ = std::min(refinement_ * 2, kMaxRefinement);
  cleanSteps_ = 0;
  event.what = what + "; rolled back to step " + std::to_string(goodStep_) + ", now " +
               std::to_string(substepsPerStep()) + " substeps per step";
  divergences_.push_back(event);
  activeState() = goodState_;
  bulkBody_.maxwell = goodMaxwell_;
  if (bulk_) refreshMaxwellForceMaps(bulkBody_);  // M follows B_v (element_pass.h)
  if (projectiveActive_) projective_.loadMaxwell(bulkBody_);
  drawnStale_ = true;
  time_ = goodTime_;
  stepCount_ = goodStep_;
}

double Simulation::time() const { return time_; }
std::int64_t Simulation::stepCount() const { return stepCount_; }
const std::vector<glm::dvec3>& Simulation::positions() const {
  if (!bulk_) return body_.state.positions;
  if (drawnStale_) {
    placeEmbedded(bulkBody_.embedding, bulkBody_.state.positions, drawnPositions_);
    liftOntoFloor(drawnPositions_);  // the smooth map may dip under the floor the element map rests on
    drawnStale_ = false;
  }
  return drawnPositions_;
}
const std::vector<Triangle>& Simulation::triangles() const {
  return bulk_ ? bulkBody_.drawn.triangles : body_.triangles;
}
const std::vector<SurfaceView>& Simulation::surfaces() const {
  drawnSurfaces_.assign(1, SurfaceView{positions(), triangles()});
  return drawnSurfaces_;
}
const std::vector<DivergenceEvent>& Simulation::divergences() const { return divergences_; }
double Simulation::volume() const {
  return bulk_ ? enclosedVolume(bulkBody_.state.positions, bulkBody_.mesh.surface)
               : enclosedVolume(body_.state.positions, body_.triangles);
}
void Simulation::setVelocities(const std::vector<glm::dvec3>& velocities) {
  if (velocities.size() != state().size())
    throw std::invalid_argument("setVelocities: " + std::to_string(velocities.size()) + " velocities for " +
                                std::to_string(state().size()) + " points");
  activeState().velocities = velocities;
  saveGoodState();
}

std::size_t Simulation::elementCount() const {
  return bulk_ ? bulkBody_.mesh.tetrahedra.size() : body_.springs.size();
}
std::size_t Simulation::invertedElements() const {
  return bulk_ ? invertedBulkElements(bulkBody_, bulkBody_.state.positions) : 0;
}
double Simulation::elasticEnergy() const {
  return bulk_ ? bulkElasticEnergy(bulkBody_, bulkBody_.state.positions) : 0.0;
}

// Shape from the surface points (the membrane's vertices, the body's outer nodes); energy and speed
// from every simulated point.
SlimeMetrics Simulation::metrics() const {
  SlimeMetrics metrics;
  const ParticleState& state = this->state();
  const std::vector<double>& freeInverseMasses = bulk_ ? bulkBody_.freeInverseMasses : body_.freeInverseMasses;
  const std::size_t surfacePoints = bulk_ ? bulkBody_.mesh.surfaceNodes : state.size();
  glm::dvec3 low(std::numeric_limits<double>::infinity()), high(-std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < state.size(); ++i) {
    if (i < surfacePoints) {
      low = glm::min(low, state.positions[i]);
      high = glm::max(high, state.positions[i]);
    }
    const double speedSquared = glm::dot(state.velocities[i], state.velocities[i]);
    metrics.kineticEnergy += 0.5 * speedSquared / freeInverseMasses[i];
    metrics.maxSpeed = std::max(metrics.maxSpeed, std::sqrt(speedSquared));
  }
  metrics.volumeRatio = volume() / restVolume();
  metrics.height = high.z - low.z;
  metrics.width = std::max(high.x - low.x, high.y - low.y);
  metrics.aspect = metrics.width > 0.0 ? metrics.height / metrics.width : 1.0;
  metrics.minZ = low.z;
  return metrics;
}

std::size_t Simulation::checkedHand(int hand) {
  if (hand < 0 || hand >= kHands)
    throw std::invalid_argument("hand " + std::to_string(hand) + " does not exist; hands are 0 and 1");
  return static_cast<std::size_t>(hand);
}

bool Simulation::grab(const glm::dvec3& point, double radius, int which) {
  const std::size_t index = checkedHand(which);
  release(which);
  Hand& hand = hands_[index];
  if (bulk_) {
    // The drawn surface point nearest to `point`, and the body's nodes within `radius` of it (or,
    // when none is that close, the nodes that carry the nearest drawn vertex). The surface as the
    // element map places it, as the floor contact sees it (the physics never evaluates the smooth map,
    // which differs by millimetres: a press grabbed through the smooth map left the body flat in
    // BulkTorture's press_top_to_the_floor, aspect 0.48 against 0.66, where main's grab recovers).
    std::vector<glm::dvec3> drawn;
    placeByElements(bulkBody_.embedding, bulkBody_.state.positions, drawn);
    const glm::dvec3 surface = nearestSurfacePoint(drawn, bulkBody_.drawn.triangles, point);
    const ParticleState& state = bulkBody_.state;
    std::vector<std::uint32_t> nodes = pointsWithinRadius(state.positions, surface, radius);
    if (nodes.empty()) {
      std::uint32_t nearest = 0;
      for (std::uint32_t i = 1; i < drawn.size(); ++i)
        if (glm::length(drawn[i] - surface) < glm::length(drawn[nearest] - surface)) nearest = i;
      const Tetrahedron& t = bulkBody_.embedding.nodes[nearest];
      nodes = {t.x, t.y, t.z, t.w};
      std::sort(nodes.begin(), nodes.end());
      nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    }
    MouseSpring& spring = hand.spring;
    spring = MouseSpring{};
    double mass = 0.0;
    // The body's bottom: under a grabbed node lie z_i − bottom of material, which a press onto the floor
    // squeezes no thinner than kPressStopFraction of that (grab.h), wherever the body is when grabbed.
    double bottom = std::numeric_limits<double>::infinity();
    for (const glm::dvec3& x : state.positions) bottom = std::min(bottom, x.z);
    for (std::uint32_t i : nodes) {
      spring.offsets.push_back(state.positions[i] - surface);
      spring.shares.push_back(1.0 / static_cast<double>(nodes.size()));
      spring.lowest.push_back(kPressStopFraction * std::max(state.positions[i].z - bottom, 0.0));
      mass += 1.0 / bulkBody_.freeInverseMasses[i];
    }
    spring.nodes = nodes;
    spring.target = surface;
    spring.damping = kMouseDampingRatio * 2.0 * std::sqrt(spring.stiffness * mass);
    spring.maxForce = settings_.sim.handForce;
    hand.pendingTarget = surface;
    hand.holding = true;
    hand.nodes = std::move(nodes);
    hand.target = surface;
    hand.radius = radius;
    return true;
  }
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

void Simulation::dragTo(const glm::dvec3& target, int which) {
  Hand& hand = hands_[checkedHand(which)];
  if (!hand.holding) return;
  hand.target = target;
  hand.pendingTarget = target;
}

glm::dvec3 Simulation::grabbedPoint(int which) const {
  const Hand& hand = hands_[checkedHand(which)];
  if (!hand.holding) return hand.target;
  glm::dvec3 sum(0.0);
  const std::vector<glm::dvec3>& x = state().positions;
  for (std::size_t k = 0; k < hand.nodes.size(); ++k)
    sum += x[hand.nodes[k]] - (bulk_ ? hand.spring.offsets[k] : hand.offsets[k]);
  return sum / static_cast<double>(hand.nodes.size());
}

void Simulation::release(int which) {
  Hand& hand = hands_[checkedHand(which)];
  if (!bulk_) {
    for (std::uint32_t i : hand.nodes) body_.state.inverseMasses[i] = body_.freeInverseMasses[i];
    if (!hand.nodes.empty()) dampingDecayStep_ = -1.0;
  }
  const glm::dvec3 target = hand.target;
  hand = Hand{};
  hand.target = target;  // grabTarget() still says where it let go
}

void Simulation::releaseAll() {
  for (int i = 0; i < kHands; ++i) release(i);
}

bool Simulation::grabbing(int which) const { return hands_[checkedHand(which)].holding; }
bool Simulation::anyGrabbing() const {
  return std::any_of(std::begin(hands_), std::end(hands_), [](const Hand& hand) { return hand.holding; });
}
glm::dvec3 Simulation::grabTarget(int which) const { return hands_[checkedHand(which)].target; }
glm::dvec3 Simulation::handForce(int which) const { return hands_[checkedHand(which)].force; }
const std::vector<std::uint32_t>& Simulation::grabbedIndices(int which) const {
  return hands_[checkedHand(which)].nodes;
}

// The membrane's grabbed points.
// Grabbed points land exactly where they are driven (the integrators moved them by v h).
void Simulation::placeGrabbedPoints() {
  ParticleState& state = body_.state;
  for (const Hand& hand : hands_) {
    for (std::size_t k = 0; k < hand.nodes.size(); ++k) {
      glm::dvec3 target = hand.anchor + hand.offsets[k];
      target.z = std::max(target.z, 0.0);
      state.positions[hand.nodes[k]] = target;
    }
  }
}

void Simulation::driveGrabbedPoints(double h) {
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

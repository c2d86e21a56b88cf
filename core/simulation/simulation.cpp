#include "core/simulation/simulation.h"

#include "core/integrators/divergence.h"
#include "core/simulation/integrator_choice.h"
#include "core/geometry/level_of_detail.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace slime {
namespace {

constexpr int kGoodStateInterval = 8;   // steps between saved good states
constexpr int kMaxRefinement = 64;      // the guard doubles substeps after a rollback, up to this
constexpr int kCleanStepsToCoarsen = 500;  // after this many steps with no rollback it halves them again

}  // namespace

Simulation::Simulation(const Settings& settings) { reload(settings); }

Simulation::Simulation(const Settings& settings, SlimeBody body) {
  std::vector<SlimeBody> bodies;
  bodies.push_back(std::move(body));
  *this = Simulation(settings, std::move(bodies));
}

Simulation::Simulation(const Settings& settings, std::vector<SlimeBody> bodies) {
  if (bodies.empty()) throw std::invalid_argument("Simulation: no bodies; a slime needs at least one piece");
  settings_ = settings;
  settings_.slime.level = effectiveLevel(settings);
  settings_.slime.model = "membrane";  // bodies of springs made elsewhere
  pieces_.clear();
  for (SlimeBody& body : bodies) pieces_.push_back(std::make_unique<MembranePiece>(std::move(body)));
  start();
}

Simulation::Simulation(const Settings& settings, std::vector<BulkBody> bodies) {
  if (bodies.empty()) throw std::invalid_argument("Simulation: no bodies; a slime needs at least one piece");
  settings_ = settings;
  settings_.slime.level = effectiveLevel(settings);
  settings_.slime.model = "bulk";
  pieces_.clear();
  for (BulkBody& body : bodies) pieces_.push_back(std::make_unique<BulkPiece>(std::move(body)));
  start();
}

Simulation::Simulation(const Simulation& other)
    : settings_(other.settings_),
      integrator_(other.integrator_),
      automaticSubsteps_(other.automaticSubsteps_),
      time_(other.time_),
      stepCount_(other.stepCount_),
      refinement_(other.refinement_),
      cleanSteps_(other.cleanSteps_),
      divergences_(other.divergences_),
      goodTime_(other.goodTime_),
      goodStep_(other.goodStep_) {
  selfContact_ = other.selfContact_;
  for (const std::unique_ptr<Piece>& piece : other.pieces_) pieces_.push_back(piece->clone());
}

Simulation& Simulation::operator=(const Simulation& other) {
  if (this != &other) *this = Simulation(other);
  return *this;
}

void Simulation::reload(const Settings& settings) {
  settings_ = settings;
  settings_.slime.level = effectiveLevel(settings);  // slime.level=auto resolved once, here
  pieces_.clear();
  if (settings_.slime.model == "bulk") pieces_.push_back(std::make_unique<BulkPiece>(buildBulkBody(settings_.slime)));
  else pieces_.push_back(std::make_unique<MembranePiece>(buildSlimeBody(settings_.slime)));
  start();
}

void Simulation::start() {
  cleanSteps_ = 0;
  time_ = 0.0;
  stepCount_ = 0;
  refinement_ = 1;
  divergences_.clear();
  selfContact_.forget();
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
  for (const std::unique_ptr<Piece>& piece : pieces_) {
    if (material) piece->applyMaterial(settings.slime);
    piece->applyHandForce(settings_.sim.handForce);  // a hand that holds feels it now
  }
  refinement_ = 1;
  rebuildModels();
}

void Simulation::rebuildModels() {
  integrator_ = chooseIntegrator(settings_);
  for (const std::unique_ptr<Piece>& piece : pieces_) piece->rebuildModels(settings_, integrator_);
}

void Simulation::setAutomaticSubsteps(bool automatic) { automaticSubsteps_ = automatic; }

double Simulation::largestStableStep() const {
  double step = std::numeric_limits<double>::infinity();
  for (const std::unique_ptr<Piece>& piece : pieces_) step = std::min(step, piece->largestStableStep());
  return step;
}

int Simulation::substepsPerStep() const {
  int substeps = std::max(1, settings_.sim.substeps);
  if (automaticSubsteps_) {
    for (const std::unique_ptr<Piece>& piece : pieces_) {
      const double needed = std::ceil(settings_.sim.dt / (kStabilitySafety * piece->largestStableStep()));
      if (needed > substeps) substeps = static_cast<int>(std::min(needed, 1.0e4));
      if (piece->travelSubsteps() > substeps) substeps = piece->travelSubsteps();
    }
  }
  return substeps * refinement_;
}

void Simulation::step() {
  for (const std::unique_ptr<Piece>& piece : pieces_) piece->beginStep({stepCount_, automaticSubsteps_});
  const int substeps = substepsPerStep();
  const double h = settings_.sim.dt / substeps;
  for (int s = 0; s < substeps; ++s) {
    for (const std::unique_ptr<Piece>& piece : pieces_) piece->substep(h);
    resolveSelfContact(h);
  }
  time_ += settings_.sim.dt;
  ++stepCount_;
  for (const std::unique_ptr<Piece>& piece : pieces_) piece->endStep({stepCount_, automaticSubsteps_});
  for (const std::unique_ptr<Piece>& piece : pieces_) {
    const std::string what = findDivergence(piece->state());
    if (!what.empty()) {
      rollBack(what);
      return;
    }
  }
  if (refinement_ > 1 && ++cleanSteps_ >= kCleanStepsToCoarsen) {
    refinement_ /= 2;
    cleanSteps_ = 0;
  }
  if (stepCount_ % kGoodStateInterval == 0) saveGoodState();
}

void Simulation::resolveSelfContact(double h) {
  if (!settings_.slime.selfContact) return;
  contactBodies_.clear();
  for (const std::unique_ptr<Piece>& piece : pieces_)
    if (auto* bulk = dynamic_cast<BulkPiece*>(piece.get())) contactBodies_.push_back(bulk->contactBody());
  if (contactBodies_.empty()) return;  // the membrane has no self-contact
  SelfContactOptions options;
  options.friction = settings_.slime.friction;
  options.cling = settings_.slime.cling;
  options.dt = h;
  selfContact_.resolve(contactBodies_, options);
}

void Simulation::saveGoodState() {
  for (const std::unique_ptr<Piece>& piece : pieces_) piece->saveGoodState();
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
  for (const std::unique_ptr<Piece>& piece : pieces_) piece->rollBack();
  selfContact_.forget();  // its last positions and contacts are not the good state's
  time_ = goodTime_;
  stepCount_ = goodStep_;
}

double Simulation::time() const { return time_; }
std::int64_t Simulation::stepCount() const { return stepCount_; }
const std::vector<glm::dvec3>& Simulation::positions() const { return piece().drawnPositions(); }
const std::vector<Triangle>& Simulation::triangles() const { return piece().drawnTriangles(); }
const std::vector<SurfaceView>& Simulation::surfaces() const {
  drawnSurfaces_.clear();
  for (const std::unique_ptr<Piece>& piece : pieces_) drawnSurfaces_.push_back(piece->surface());
  return drawnSurfaces_;
}
const std::vector<DivergenceEvent>& Simulation::divergences() const { return divergences_; }
double Simulation::volume() const { return piece().volume(); }
void Simulation::setVelocities(const std::vector<glm::dvec3>& velocities) {
  if (velocities.size() != state().size())
    throw std::invalid_argument("setVelocities: " + std::to_string(velocities.size()) + " velocities for " +
                                std::to_string(state().size()) + " points");
  pieces_.front()->state().velocities = velocities;
  saveGoodState();
}

std::size_t Simulation::elementCount() const { return piece().elementCount(); }
std::size_t Simulation::invertedElements() const { return piece().invertedElements(); }
double Simulation::elasticEnergy() const { return piece().elasticEnergy(); }
SlimeMetrics Simulation::metrics() const {
  if (pieces_.size() == 1) return piece().metrics();
  SlimeMetrics metrics;
  metrics.kineticEnergy = 0.0;
  double volume = 0.0, restVolume = 0.0;
  for (const std::unique_ptr<Piece>& piece : pieces_) {
    const SlimeMetrics own = piece->metrics();
    metrics.kineticEnergy += own.kineticEnergy;
    metrics.maxSpeed = std::max(metrics.maxSpeed, own.maxSpeed);
    volume += piece->volume();
    restVolume += piece->restVolume();
  }
  metrics.volumeRatio = volume / restVolume;
  measureShape(surfaces(), metrics);
  return metrics;
}

std::vector<EnclosedSolid> Simulation::pieceSolids() const {
  std::vector<EnclosedSolid> solids;
  for (const std::unique_ptr<Piece>& piece : pieces_) solids.push_back(enclosedSolid(piece->surface()));
  return solids;
}

const SlimeBody& Simulation::body() const {
  static const SlimeBody none;
  const auto* membrane = dynamic_cast<const MembranePiece*>(&piece());
  return membrane ? membrane->body() : none;
}
const BulkBody& Simulation::bulkBody() const {
  static const BulkBody none;
  const auto* bulk = dynamic_cast<const BulkPiece*>(&piece());
  return bulk ? bulk->body() : none;
}
const FloorAdhesion& Simulation::adhesion() const {
  static const FloorAdhesion none;
  const auto* bulk = dynamic_cast<const BulkPiece*>(&piece());
  return bulk ? bulk->adhesion() : none;
}

std::size_t Simulation::checkedHand(int hand) {
  if (hand < 0 || hand >= kHands)
    throw std::invalid_argument("hand " + std::to_string(hand) + " does not exist; hands are 0 and 1");
  return static_cast<std::size_t>(hand);
}

bool Simulation::grab(const glm::dvec3& point, double radius, int which) {
  checkedHand(which);
  release(which);
  return handPiece(which).grab(point, radius, which);
}

void Simulation::dragTo(const glm::dvec3& target, int which) { handPiece(which).dragTo(target, static_cast<int>(checkedHand(which))); }
glm::dvec3 Simulation::grabbedPoint(int which) const { return handPiece(which).grabbedPoint(static_cast<int>(checkedHand(which))); }
void Simulation::release(int which) { handPiece(which).release(static_cast<int>(checkedHand(which))); }

void Simulation::releaseAll() {
  for (int i = 0; i < kHands; ++i) release(i);
}

bool Simulation::grabbing(int which) const { return hand(which).holding; }
bool Simulation::anyGrabbing() const {
  return std::any_of(pieces_.begin(), pieces_.end(), [](const std::unique_ptr<Piece>& piece) { return piece->anyGrabbing(); });
}
glm::dvec3 Simulation::grabTarget(int which) const { return hand(which).target; }
glm::dvec3 Simulation::handForce(int which) const { return hand(which).force; }
const std::vector<std::uint32_t>& Simulation::grabbedIndices(int which) const { return hand(which).nodes; }

}  // namespace slime

#include "core/simulation/simulation.h"

#include "core/integrators/divergence.h"
#include "core/simulation/integrator_choice.h"
#include "core/geometry/level_of_detail.h"
#include "core/bulk/piece_surface.h"
#include "core/bulk/surface_embedding.h"
#include "core/hands/grab.h"
#include "core/simulation/merging.h"
#include "core/simulation/tearing.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <stdexcept>
#include <utility>

namespace slime {
namespace {

// A tear's or a merge's cost: wall-clock and the thread's CPU milliseconds since construction.
class TopologyTimer {
 public:
  double milliseconds() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wall_).count();
  }
  double cpuMilliseconds() const { return threadCpuMilliseconds() - cpu_; }

 private:
  static double threadCpuMilliseconds() {
    timespec now{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return 1e3 * static_cast<double>(now.tv_sec) + 1e-6 * static_cast<double>(now.tv_nsec);
  }
  std::chrono::steady_clock::time_point wall_ = std::chrono::steady_clock::now();
  double cpu_ = threadCpuMilliseconds();
};

}  // namespace
namespace {

constexpr int kGoodStateInterval = 8;   // steps between saved good states
constexpr int kMaxRefinement = 64;      // the guard doubles substeps after a rollback, up to this
constexpr int kCleanStepsToCoarsen = 500;  // after this many steps with no rollback it halves them again
// The guard's speed limit follows the hands (issue 45 item 5): a hand's target that moves at v may
// fling the points it holds past v (the spring overshoots, a light slime whips), so the limit is
// kHandSpeedFactor times the fastest hand's speed when that is over kAbsurdSpeed. The speed is
// remembered with time constant kHandSpeedMemory, long enough for a slime flung at the hand's speed to
// be stopped by the hand or the floor's friction (a 10 g slime pulled at 16 N stops from 100 m/s in
// 60 ms), so a state the hands made fast is not taken for a divergence; a blow-up grows without bound
// within a few steps and still passes any such limit.
constexpr double kHandSpeedFactor = 2.0;
constexpr double kHandSpeedMemory = 0.25;  // s
// Steps between tearing checks (a pass over the tetrahedra's elastic stretch: 8 ms against the tens
// of milliseconds a strand takes to snap).
constexpr int kTearInterval = 8;
// Steps between a tear's two halves (its drawn surfaces, then its pieces): a 60 Hz viewer frame holds
// about 17 steps of 1 ms, so the halves fall mostly in different frames.
constexpr int kTearStageSteps = 2 * kTearInterval;

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
      goodStep_(other.goodStep_),
      handPiece_(other.handPiece_),
      slimeRestVolume_(other.slimeRestVolume_),
      drawnSpacing_(other.drawnSpacing_),
      tears_(other.tears_),
      merges_(other.merges_),
      touchingFor_(other.touchingFor_),
      pendingTear_(other.pendingTear_),
      lastTopologyMilliseconds_(other.lastTopologyMilliseconds_),
      lastTopologyCpuMilliseconds_(other.lastTopologyCpuMilliseconds_),
      handSpeed_(other.handSpeed_) {
  std::copy(std::begin(other.handHeld_), std::end(other.handHeld_), std::begin(handHeld_));
  std::copy(std::begin(other.handTarget_), std::end(other.handTarget_), std::begin(handTarget_));
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
  handSpeed_ = 0.0;
  for (bool& held : handHeld_) held = false;
  handPiece_.fill(0);
  tears_ = merges_ = 0;
  touchingFor_.clear();
  pendingTear_.reset();
  slimeRestVolume_ = 0.0;
  for (const std::unique_ptr<Piece>& piece : pieces_) slimeRestVolume_ += piece->restVolume();
  // A drawn surface made afresh is extracted on a grid of twice the drawn icosphere's edge (marching
  // tetrahedra leave about four vertices per icosphere vertex at one edge), no finer than R/8 (the
  // grid's cost grows as its inverse cube, the smooth map's as its inverse square).
  drawnSpacing_ = std::max(2.0 * meanEdgeLength(pieces_.front()->surface()), settings_.slime.radius / 8.0);
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
                        settings.slime.plastic != settings_.slime.plastic ||
                        settings.slime.yieldStretch != settings_.slime.yieldStretch ||
                        settings.slime.flowTime != settings_.slime.flowTime ||
                        settings.slime.recoveryTime != settings_.slime.recoveryTime ||
                        settings.slime.damage != settings_.slime.damage ||
                        settings.slime.damageStretch != settings_.slime.damageStretch ||
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

double Simulation::speedLimit() {
  double fastest = 0.0;
  for (int hand = 0; hand < kHands; ++hand) {
    const bool holding = grabbing(hand);
    const glm::dvec3 target = holding ? grabTarget(hand) : glm::dvec3(0.0);
    if (holding && handHeld_[hand]) fastest = std::max(fastest, glm::length(target - handTarget_[hand]) / settings_.sim.dt);
    handHeld_[hand] = holding;
    handTarget_[hand] = target;
  }
  handSpeed_ = std::max(fastest, handSpeed_ * std::exp(-settings_.sim.dt / kHandSpeedMemory));
  return std::max(kAbsurdSpeed, kHandSpeedFactor * handSpeed_);
}

void Simulation::step() {
  const double speedLimit = this->speedLimit();
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
    const std::string what = findDivergence(piece->state(), speedLimit);
    if (!what.empty()) {
      rollBack(what);
      return;
    }
  }
  if (refinement_ > 1 && ++cleanSteps_ >= kCleanStepsToCoarsen) {
    refinement_ /= 2;
    cleanSteps_ = 0;
  }
  if (!settings_.slime.tearing) pendingTear_.reset();  // switched off half-way
  if (settings_.slime.tearing && stepCount_ % kTearInterval == 0 && tearPieces()) return;
  if (settings_.slime.mergeTime > 0.0 && pieces_.size() > 1 && !pendingTear_ && stepCount_ % kTearInterval == 0 && mergePieces())
    return;
  if (stepCount_ % kGoodStateInterval == 0) saveGoodState();
}

bool Simulation::mergePieces() {
  const std::size_t count = pieces_.size();
  touchingFor_.resize(count * count, 0.0);
  const double interval = kTearInterval * settings_.sim.dt;
  for (std::size_t i = 0; i < count; ++i)
    for (std::size_t j = i + 1; j < count; ++j) {
      auto* a = dynamic_cast<BulkPiece*>(pieces_[i].get());
      auto* b = dynamic_cast<BulkPiece*>(pieces_[j].get());
      if (a == nullptr || b == nullptr) continue;
      double& touching = touchingFor_[i * count + j];
      touching = touchingNodes(a->body(), b->body(), drawnSpacing_) >= kTouchingNodes ? touching + interval : 0.0;
      if (touching < settings_.slime.mergeTime - 1e-9) continue;
      const TopologyTimer timer;
      std::array<int, kHands> handFrom{};
      const double support = kSmoothSupportSteps * settings_.slime.radius / std::ldexp(1.0, settings_.slime.resolution);
      std::unique_ptr<BulkPiece> merged = a->mergedWith(*b, drawnSpacing_, drawnSpacing_, support, handFrom);
      if (merged == nullptr) {  // their drawn surfaces do not meet: touching again for a whole mergeTime first
        touching = -settings_.slime.mergeTime;
        continue;
      }
      pieces_[i] = std::move(merged);
      pieces_.erase(pieces_.begin() + static_cast<std::ptrdiff_t>(j));
      for (std::size_t& piece : handPiece_) {
        if (piece == j) piece = i;
        else if (piece > j) --piece;
      }
      pieces_[i]->rebuildModels(settings_, integrator_);
      ++merges_;
      touchingFor_.clear();
      selfContact_.forget();  // its contacts name the pieces' old vertices
      saveGoodState();
      lastTopologyMilliseconds_ = timer.milliseconds();
      lastTopologyCpuMilliseconds_ = timer.cpuMilliseconds();
      return true;
    }
  return false;
}

bool Simulation::tearPieces() {
  if (pendingTear_) {
    if (stepCount_ < pendingTear_->dueStep) return false;
    const TopologyTimer timer;
    PendingTear pending = std::move(*pendingTear_);
    pendingTear_.reset();
    const std::size_t p = pending.piece;
    auto* bulk = dynamic_cast<BulkPiece*>(pieces_[p].get());
    std::array<int, kHands> handPart{};
    const double support = kSmoothSupportSteps * settings_.slime.radius / std::ldexp(1.0, settings_.slime.resolution);
    std::vector<std::unique_ptr<BulkPiece>> parts = bulk->split(pending.surfaces, support, handPart);
    // Part 0 takes the torn piece's place; the others follow the last piece.
    const std::size_t firstNew = pieces_.size();
    for (int hand = 0; hand < kHands; ++hand)
      if (handPiece_[hand] == p && handPart[hand] >= 0)
        handPiece_[hand] = handPart[hand] == 0 ? p : firstNew + static_cast<std::size_t>(handPart[hand]) - 1;
    pieces_[p] = std::move(parts[0]);
    for (std::size_t k = 1; k < parts.size(); ++k) pieces_.push_back(std::move(parts[k]));
    pieces_[p]->rebuildModels(settings_, integrator_);
    for (std::size_t k = firstNew; k < pieces_.size(); ++k) pieces_[k]->rebuildModels(settings_, integrator_);
    ++tears_;
    touchingFor_.clear();
    selfContact_.forget();  // its contacts name the pieces' old vertices
    saveGoodState();  // the guard never rolls back across a tear
    // The dearer of the tear's two steps.
    lastTopologyMilliseconds_ = std::max(pending.milliseconds, timer.milliseconds());
    lastTopologyCpuMilliseconds_ = std::max(pending.cpuMilliseconds, timer.cpuMilliseconds());
    return true;
  }
  for (std::size_t p = 0; p < pieces_.size(); ++p) {
    auto* bulk = dynamic_cast<BulkPiece*>(pieces_[p].get());
    if (bulk == nullptr) continue;
    // A seam just fused is not torn: its welded elements start far from their rest (the window's press
    // back tore the merged slime again 50-80 ms after the merge, in 1 of 4 runs, into crumpled shards),
    // and the seam is given the time the pieces took to fuse to set.
    if (bulk->secondsSinceMerge() < settings_.slime.mergeTime) continue;
    const TopologyTimer timer;
    const TearPlan plan = planTear(bulk->body(), settings_.slime.tearStretch, settings_.slime.smallestPiece * slimeRestVolume_);
    if (plan.parts < 2) continue;
    if (pieces_.size() - 1 + plan.parts > static_cast<std::size_t>(settings_.slime.maxPieces)) continue;
    BulkPiece::SplitSurfaces surfaces = bulk->splitSurfaces(plan, drawnSpacing_);
    if (surfaces.surfaces.empty()) continue;
    pendingTear_ = PendingTear{p, std::move(surfaces), stepCount_ + kTearStageSteps, timer.milliseconds(),
                               timer.cpuMilliseconds()};
    return false;  // torn at the second half
  }
  return false;
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
  pendingTear_.reset();  // planned on a state the guard rejected
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
double Simulation::restVolume() const {
  double sum = 0.0;
  for (const std::unique_ptr<Piece>& piece : pieces_) sum += piece->restVolume();
  return sum;
}
double Simulation::volume() const {
  double sum = 0.0;
  for (const std::unique_ptr<Piece>& piece : pieces_) sum += piece->volume();
  return sum;
}
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

bool Simulation::grab(const glm::dvec3& point, double radius, int which, Grip grip) {
  checkedHand(which);
  release(which);
  // The piece whose drawn surface passes nearest to the point (the first of equals).
  std::size_t nearest = 0;
  if (pieces_.size() > 1) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t p = 0; p < pieces_.size(); ++p) {
      const Piece& piece = *pieces_[p];
      const double distance = glm::length(nearestSurfacePoint(piece.drawnPositions(), piece.drawnTriangles(), point) - point);
      if (distance < best) {
        best = distance;
        nearest = p;
      }
    }
  }
  handPiece_[which] = nearest;
  return handPiece(which).grab(point, radius, which, grip);
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

#include "core/simulation/bulk_piece.h"

#include "core/bulk/element_pass.h"
#include "core/bulk/piece_surface.h"
#include "core/bulk/sub_body.h"
#include "core/simulation/merging.h"
#include "core/geometry/enclosed_solid.h"
#include "core/contact/floor_contact.h"
#include "core/geometry/volume.h"
#include "core/hands/grab.h"
#include "core/integrators/stability.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace slime {
namespace {

constexpr double kExactDamperStepFactor = 12.0;  // see largestStableStep
// Steps between the Maxwell branches' flow updates (exact over the interval for the strain at its end;
// 4 ms against relaxation times of 10 ms and more). Every step it cost a quarter of the step. The explicit
// step's interval also follows τ (maxwellFlowInterval, viscoelastic.h), never below this.
constexpr int kRelaxInterval = 4;
// An explicit substep moves no node farther than this share of the body's shortest rest edge
// (a collision's CFL rule: the stability bound of largestStableStep is for small vibrations, and a
// landing at 4.4 m/s pushed the lowest layer 4.4 mm — 40 % of an element — into the floor in one
// 1 ms substep, which inverted elements and made the guard roll back twice).
constexpr double kTravelPerSubstep = 0.25;
// Steps between estimates of the body's highest frequency while a hand holds it or it is still
// stretched (beginStep): 41 force evaluations, a fifth of a step's forces a step every 200 steps;
// every 50 took 19 % of a held slime's physics (perf, drag_top_in_circles_6s).
// Drawn vertices whose smooth map is fitted per step after a tear or merge (about 13 µs each on F25.17):
// a 1,900-vertex surface in 60 steps, a few ms of each viewer frame instead of 25 ms in one.
constexpr std::size_t kSmoothFitVerticesPerStep = 32;
constexpr int kFrequencyInterval = 200;
// A merged piece rounds up (endStep) every this many steps, for this many flow times τ_p (e^−8: done).
constexpr int kRoundingInterval = 8;
constexpr double kRoundingFlowTimes = 8.0;

// Sets every drawn vertex below the floor (z < 0) on it. The physics holds the element map's vertices
// on the floor (resolveDrawnFloorContact); the smooth map that places the drawn surface differs by
// millimetres (most at the contact's rim and under a press) and may dip under it: drawn on the floor.
void liftOntoFloor(std::vector<glm::dvec3>& drawn) {
  for (glm::dvec3& p : drawn) p.z = std::max(p.z, 0.0);
}

}  // namespace

BulkPiece::BulkPiece(BulkBody body, double slimeRestVolume)
    : body_(std::move(body)), slimeRestVolume_(slimeRestVolume > 0.0 ? slimeRestVolume : body_.restVolume) {
  adhesion_.reset(body_.mesh.surface, body_.mesh.surfaceNodes);
}

void BulkPiece::applyMaterial(const SlimeSettings& slime) {
  SlimeSettings own = slime;  // slime.mass is the whole slime's: a torn piece takes its share
  if (body_.restVolume != slimeRestVolume_) own.mass = slime.mass * body_.restVolume / slimeRestVolume_;
  applyBulkMaterial(body_, own);
}

BulkPiece::SplitSurfaces BulkPiece::splitSurfaces(const TearPlan& plan, double spacing) const {
  SplitSurfaces made;
  made.surfaces = splitDrawnSurface(surface(), body_, plan.partOf, plan.parts, spacing);
  for (const TriangleMesh& drawn : made.surfaces)
    if (drawn.triangles.empty()) return {};  // a part outside the drawn surface: no tear
  made.plan = plan;
  made.reference = body_.state.positions;
  // Each part's drawn surface encloses its body as the whole one's did (the drawn surface stands proud
  // of the body's faces by about 2 %): moved along its normals to that volume (split).
  made.drawnShare = enclosedSolid(surface()).volume / volume();
  return made;
}

std::vector<std::unique_ptr<BulkPiece>> BulkPiece::split(const SplitSurfaces& made, double support, std::array<int, kHands>& handPart) {
  if (projectiveActive_) projective_.storeMaxwell(body_);  // the live Maxwell states are the solver's
  const TearPlan& plan = made.plan;
  const double density = body_.totalMass / body_.restVolume;
  std::vector<std::unique_ptr<BulkPiece>> pieces;
  std::vector<std::vector<std::uint32_t>> newOfOld(plan.parts);
  std::array<std::size_t, kHands> mostHeld{};
  handPart.fill(-1);
  for (std::uint32_t part = 0; part < plan.parts; ++part) {
    std::vector<std::uint32_t> tetrahedra, partNode, order;
    for (std::uint32_t e = 0; e < plan.partOf.size(); ++e)
      if (plan.partOf[e] == part) tetrahedra.push_back(e);
    BulkBody body = assembleBody(partsOf(body_, tetrahedra, partNode), settings_.slime, density, body_.mesh.shellLevel, order);
    std::vector<glm::dvec3> reference(order.size());
    for (std::uint32_t i = 0; i < order.size(); ++i) reference[i] = made.reference[partNode[order[i]]];
    TriangleMesh drawn = made.surfaces[part];
    offsetToVolume(drawn, made.drawnShare * enclosedVolume(reference, body.mesh.surface));
    carryDrawnSurface(body, std::move(drawn), support, reference);
    auto piece = std::make_unique<BulkPiece>(std::move(body), slimeRestVolume_);
    piece->settings_ = settings_;
    piece->drawnVolumeShare_ = made.drawnShare;
    std::vector<std::uint32_t> source(order.size());
    newOfOld[part].assign(body_.state.positions.size(), kNoNode);
    for (std::uint32_t i = 0; i < order.size(); ++i) {
      source[i] = partNode[order[i]];
      newOfOld[part][source[i]] = i;
    }
    piece->adhesion_.carryOver(adhesion_, source);
    for (int which = 0; which < kHands; ++which) {
      if (!hands_[which].holding) continue;
      std::size_t held = 0;
      for (std::uint32_t node : hands_[which].spring.nodes) held += newOfOld[part][node] != kNoNode;
      if (held > mostHeld[which]) {
        mostHeld[which] = held;
        handPart[which] = static_cast<int>(part);
      }
    }
    pieces.push_back(std::move(piece));
  }
  for (int which = 0; which < kHands; ++which)
    if (handPart[which] >= 0) pieces[handPart[which]]->takeHand(which, hands_[which], newOfOld[handPart[which]]);
  return pieces;
}

std::unique_ptr<BulkPiece> BulkPiece::mergedWith(BulkPiece& other, double weldDistance, double spacing, double support,
                                                  std::array<int, kHands>& handFrom) {
  if (projectiveActive_) projective_.storeMaxwell(body_);
  if (other.projectiveActive_) other.projective_.storeMaxwell(other.body_);
  const SurfaceView surfaces[2] = {surface(), other.surface()};
  const double drawnVolume = enclosedSolid(surfaces[0]).volume + enclosedSolid(surfaces[1]).volume;
  const double bodyVolume = volume() + other.volume();
  const BulkBody* bodies[2] = {&body_, &other.body_};
  TriangleMesh drawn = mergedDrawnSurface(bodies, surfaces, spacing, settings_.slime.level);
  if (drawn.triangles.empty()) return nullptr;
  std::vector<std::uint32_t> bOf, order;
  const double density = (body_.totalMass + other.body_.totalMass) / (body_.restVolume + other.body_.restVolume);
  BodyParts parts = weldedParts(body_, other.body_, weldDistance, bOf);
  rebaseRestTowardBall(parts);  // the merged slime rounds up like one never torn (roundingLeft_)
  BulkBody body = assembleBody(parts, settings_.slime, density, body_.mesh.shellLevel, order);
  offsetToVolume(drawn, drawnVolume / bodyVolume * enclosedVolume(body.state.positions, body.mesh.surface));
  carryDrawnSurface(body, std::move(drawn), support, std::vector<glm::dvec3>(body.state.positions));
  auto piece = std::make_unique<BulkPiece>(std::move(body), slimeRestVolume_);
  piece->settings_ = settings_;
  piece->drawnVolumeShare_ = drawnVolume / bodyVolume;
  piece->roundingLeft_ = kRoundingFlowTimes * settings_.slime.flowTime;
  piece->sinceMerge_ = 0.0;
  // Where each new node came from, in this piece and in the other.
  const std::size_t ownNodes = body_.state.positions.size();
  std::vector<std::uint32_t> ownSource(order.size(), FloorAdhesion::kNoSource), otherSource(order.size(), FloorAdhesion::kNoSource);
  std::vector<std::uint32_t> newOfOwn(ownNodes, kNoNode), newOfOther(other.body_.state.positions.size(), kNoNode);
  std::vector<std::uint32_t> newOfPart(order.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) {
    newOfPart[order[i]] = i;
    if (order[i] < ownNodes) {
      ownSource[i] = order[i];
      newOfOwn[order[i]] = i;
    }
  }
  for (std::uint32_t j = 0; j < bOf.size(); ++j) {
    if (bOf[j] == kNoNode) continue;
    newOfOther[j] = newOfPart[bOf[j]];
    if (bOf[j] >= ownNodes) otherSource[newOfPart[bOf[j]]] = j;
  }
  piece->adhesion_.carryOver(adhesion_, ownSource);
  piece->adhesion_.carryOver(other.adhesion_, otherSource);
  handFrom.fill(-1);
  for (int which = 0; which < kHands; ++which) {
    if (hands_[which].holding) {
      piece->takeHand(which, hands_[which], newOfOwn);
      handFrom[which] = 0;
    } else if (other.hands_[which].holding) {
      piece->takeHand(which, other.hands_[which], newOfOther);
      handFrom[which] = 1;
    }
  }
  return piece;
}

void BulkPiece::takeHand(int which, const Hand& from, const std::vector<std::uint32_t>& newOfOld) {
  Hand hand = from;
  MouseSpring& spring = hand.spring;
  std::vector<std::pair<std::uint32_t, std::size_t>> kept;  // (new node, k in the old spring)
  for (std::size_t k = 0; k < from.spring.nodes.size(); ++k)
    if (newOfOld[from.spring.nodes[k]] != kNoNode) kept.emplace_back(newOfOld[from.spring.nodes[k]], k);
  std::sort(kept.begin(), kept.end());
  spring.nodes.clear();
  spring.offsets.clear();
  spring.shares.clear();
  spring.lowest.clear();
  double shares = 0.0;
  for (const auto& [node, k] : kept) shares += from.spring.shares[k];
  for (const auto& [node, k] : kept) {
    spring.nodes.push_back(node);
    spring.offsets.push_back(from.spring.offsets[k]);
    spring.shares.push_back(from.spring.shares[k] / shares);
    spring.lowest.push_back(from.spring.lowest[k]);
  }
  hand.nodes = spring.nodes;
  hand.holding = !spring.nodes.empty();
  hands_[which] = std::move(hand);
}

std::unique_ptr<Piece> BulkPiece::clone() const {
  auto copy = std::make_unique<BulkPiece>(*this);
  copy->bindAccelerations();
  return copy;
}

void BulkPiece::bindAccelerations() {
  accelerationField_ = [this](const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& v,
                              std::vector<glm::dvec3>& a) { accelerations(x, v, a); };
}

void BulkPiece::rebuildModels(const Settings& settings, Integrator integrator) {
  settings_ = settings;
  integrator_ = integrator;
  // The Maxwell state moves between the projective solver's stretches U_v and the body's metrics G_v.
  if (projectiveActive_) projective_.storeMaxwell(body_);
  projectiveActive_ = integrator_ == Integrator::Projective || integrator_ == Integrator::ProjectiveMidpoint;
  if (projectiveActive_) {
    projective_.loadMaxwell(body_);
    projective_.invalidate();
  }
  bindAccelerations();
  highestFrequency_ = restFrequency_ = bulkHighestFrequency(body_, scratch_);
  deformedFrequency_ = false;
  // symplectic_euler integrates the dampers exactly; the explicit methods feel their rate.
  dampingRate_ = bulkHighestDampingRate(body_);
  highestDampingRate_ = integrator_ == Integrator::SymplecticEuler ? 0.0 : dampingRate_;
  scratch_.decayStep = -1.0;
  shortestEdge_ = std::numeric_limits<double>::infinity();
  for (const glm::u32vec2& e : body_.edges)
    shortestEdge_ = std::min(shortestEdge_, glm::length(body_.mesh.positions[e.y] - body_.mesh.positions[e.x]));
}

double BulkPiece::largestStableStep() const {
  const double step = Piece::largestStableStep();
  // The exact dampers are a contraction pair by pair, but one pair after another between the
  // kicks not unconditionally stable: on the lightest slime (slime.mass=0.01, Gershgorin rate 7.3e4/s),
  // colour after colour (edge_colours.h), 0.2 ms held and 0.225 ms rolled back, so the step is capped
  // at kExactDamperStepFactor / rate = 12 / rate (0.164 ms there; no cap at the defaults: 4.4 ms).
  if (integrator_ == Integrator::SymplecticEuler && dampingRate_ > 0.0)
    return std::min(step, kExactDamperStepFactor / dampingRate_);
  return step;
}

int BulkPiece::travelSubstepsNeeded() const {
  if (projectiveActive_) return 1;
  double fastest = 0.0;
  for (const glm::dvec3& v : body_.state.velocities) fastest = std::max(fastest, glm::dot(v, v));
  const double travel = std::sqrt(fastest) * settings_.sim.dt;
  return static_cast<int>(std::min(std::ceil(travel / (kTravelPerSubstep * shortestEdge_)), 1.0e4));
}

void BulkPiece::beginStep(const StepContext& context) {
  travelSubsteps_ = travelSubstepsNeeded();
  // The explicit step limit 2/ω_max follows the shape. A stretched body's thinner elements raise ω (×1.5
  // in a 5× strand, issue 29): the estimate runs every 200 steps while held or deformed. An inverted
  // element's volumetric stress raises it within steps (flung and slammed at resolution 3: J to −2.5, ω
  // 2,400 → 13,000 /s in 20 steps, a rollback): it runs every step that one meets a body fast enough for
  // the travel rule (a landing's J stays above 0.1).
  const bool explicitStep = context.automaticSubsteps && !projectiveActive_;
  const bool invertedAndFast =
      explicitStep && travelSubsteps_ > 1 && invertedBulkElements(body_, body_.state.positions) > 0;
  if (invertedAndFast ||
      (explicitStep && (anyGrabbing() || deformedFrequency_) && context.stepCount % kFrequencyInterval == 0)) {
    const double now = bulkHighestFrequencyAt(body_, body_.state.positions, scratch_);
    highestFrequency_ = std::max(restFrequency_, now);
    deformedFrequency_ = now > restFrequency_;
  }
  // Each mouse target moves to where dragTo put it over this step.
  for (Hand& hand : hands_) {
    if (!hand.holding) continue;
    hand.spring.targetVelocity = (hand.pendingTarget - hand.spring.target) / settings_.sim.dt;
    hand.spring.target = hand.pendingTarget;
  }
}

// a = (internal forces + mouse spring) / m + g; pinned nodes (w = 0) do not move.
void BulkPiece::accelerations(const std::vector<glm::dvec3>& x, const std::vector<glm::dvec3>& v,
                              std::vector<glm::dvec3>& a) {
  bulkInternalForces(body_, x, v, a);
  for (Hand& hand : hands_)
    if (hand.holding) hand.force = addMouseSpringForces(hand.spring, x, v, a);
  const glm::dvec3 gravity{0.0, 0.0, -settings_.sim.gravity};
  const std::vector<double>& w = body_.state.inverseMasses;
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = w[i] > 0.0 ? a[i] * w[i] + gravity : glm::dvec3(0.0);
}

// symplectic_euler: v += h a(x), the dampers exactly, x += h v; explicit_euler and rk4 integrate the
// same accelerations, dampers included, through integrators.h. Then the floor on every node and the
// volume projection, which leaves the nodes on the floor where they are (projective's: on the drawn
// surface's floor; the drawn surface's own contact follows once per step, in endStep).
void BulkPiece::substep(double h) {
  ParticleState& state = body_.state;
  // The sticky floor reads a stuck node's pull from the kick-drift step's Δx = h²F/m; projective's implicit step
  // is not that, and holding its nodes back made it roll back (21 times in a two-hand pull at 6000 Pa): no adhesion.
  // projective_midpoint holds its stuck nodes inside the solve instead (ProjectiveStep::adhesion).
  const double adhesion = projectiveActive_ ? 0.0 : settings_.slime.adhesion;
  const double friction = settings_.slime.friction;
  bool floorDone = false;  // the floor contact on every node, fused with the drift below
  if (adhesion > 0.0) adhesion_.beginSubstep(state);
  switch (integrator_) {
    case Integrator::ExplicitEuler: explicitEulerStep(state, h, accelerationField_, integratorScratch_); break;
    case Integrator::Rk4: rk4Step(state, h, accelerationField_, integratorScratch_); break;
    case Integrator::Projective:
    case Integrator::ProjectiveMidpoint: {
      ProjectiveStep options;
      options.h = h;
      options.iterations = settings_.sim.iterations;
      if (integrator_ == Integrator::ProjectiveMidpoint) {
        options.theta = kMidpointTheta;
        options.adhesion = settings_.slime.adhesion;
      }
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
      const glm::dvec3 force = projective_.step(body_, scratch_, options);
      if (first != nullptr) first->force = force;
      break;
    }
    default: {
      // Kick with every force but the dampers, the dampers exactly (dampEdges), then drift.
      std::vector<glm::dvec3>& a = scratch_.forces;
      bulkInternalForces(body_, state.positions, state.velocities, a, false);
      for (Hand& hand : hands_)
        if (hand.holding && hand.spring.grip == Grip::Pinch)
          hand.force = addMouseSpringForces(hand.spring, state.positions, state.velocities, a);
      const glm::dvec3 gravity{0.0, 0.0, -settings_.sim.gravity};
      for (std::size_t i = 0; i < state.size(); ++i) {
        const double w = state.inverseMasses[i];
        if (w != 0.0) state.velocities[i] += h * (a[i] * w + gravity);
      }
      // A fist's springs, each as stiff as ten elements, by backward Euler after the kick (explicitly they
      // would need a step under 2√(m/k) of a node).
      for (Hand& hand : hands_)
        if (hand.holding && hand.spring.grip == Grip::Fist)
          hand.force = applyMouseSpringImplicitly(hand.spring, state.positions, state.inverseMasses, h, state.velocities);
      dampEdges(body_, h, scratch_, state);
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
  projectBulkVolume(body_, h, scratch_, state, projectiveActive_ ? &projective_.floorHeights() : nullptr);
  if (adhesion > 0.0) adhesion_.endSubstep(state, body_.mesh.surface, body_.freeInverseMasses, adhesion, h);
}

void BulkPiece::endStep(const StepContext& context) {
  sinceMerge_ += settings_.sim.dt;
  // projective flows its Maxwell branches every substep; the body's metrics follow as a copy.
  const int flowInterval = projectiveActive_
                               ? kRelaxInterval
                               : bulkFlowInterval(settings_.slime, settings_.sim.dt, kRelaxInterval);
  if (context.stepCount % flowInterval == 0) {
    if (projectiveActive_) {
      projective_.storeMaxwell(body_);
      projective_.flowLongTerm(body_, flowInterval * settings_.sim.dt);
    } else {
      relaxBulk(body_, flowInterval * settings_.sim.dt);
    }
  }
  // A merged piece's long-term rest shape flows to its reference, a ball (rebaseRestTowardBall), over the
  // material's flow time τ_p.
  if (roundingLeft_ > 0.0 && context.stepCount % kRoundingInterval == 0) {
    const double dt = kRoundingInterval * settings_.sim.dt;
    relaxLongTermTowardReference(body_, -std::expm1(-dt / settings_.slime.flowTime));
    if (projectiveActive_) projective_.loadPlastic(body_);
    roundingLeft_ -= dt;
  }
  const bool touching = resolveDrawnFloorContact(body_, settings_.slime.friction) > 0;
  // The floor's rolling resistance acts on the bulk slime too: Coulomb friction lets a ball roll,
  // and the bulk's own viscosity barely slows a bun rolling on its patch (a yanked slime rolled 3 m).
  if (context.stepCount % kRollingInterval == 0)
    dampTurningOnFloor(body_.state, settings_.slime.rolling, kRollingInterval * settings_.sim.dt, touching);
  // A drawn surface made afresh by a tear or a merge: its smooth map is fitted over the next steps.
  continueSmoothFit(body_.embedding, kSmoothFitVerticesPerStep);
  drawnStale_ = true;
}

void BulkPiece::saveGoodState() {
  if (projectiveActive_) projective_.storeMaxwell(body_);
  goodState_ = body_.state;
  goodMaxwell_ = body_.maxwell;
}

void BulkPiece::rollBack() {
  body_.state = goodState_;
  body_.maxwell = goodMaxwell_;
  refreshMaxwellForceMaps(body_);  // M follows B_v (element_pass.h)
  if (projectiveActive_) projective_.loadMaxwell(body_);
  drawnStale_ = true;
}

ContactBody BulkPiece::contactBody() {
  drawnStale_ = true;
  ContactBody contact;
  contact.state = &body_.state;
  contact.restNodes = body_.mesh.positions;
  contact.surface = body_.mesh.surface;
  contact.drawnTriangles = body_.drawn.triangles;
  contact.carriers = body_.embedding.nodes;
  contact.weights = body_.embedding.weights;
  contact.verticesOfSurfaceTriangle = body_.embedding.verticesOfSurfaceTriangle;
  return contact;
}

const std::vector<glm::dvec3>& BulkPiece::drawnPositions() const {
  if (drawnStale_) {
    placeEmbedded(body_.embedding, body_.state.positions, drawnPositions_);
    // A torn piece's smooth map is fitted over fewer nodes than the ball's (a small piece lies within one
    // support): a recoil that is far from affine moved its drawn surface off its body's volume (a piece
    // of 3 % of the slime lost 40 % of its drawn volume in 0.1 s). It keeps its share, as at the tear.
    if (drawnVolumeShare_ > 0.0) {
      drawnMesh_.positions.swap(drawnPositions_);
      drawnMesh_.triangles = body_.drawn.triangles;
      offsetToVolume(drawnMesh_, drawnVolumeShare_ * volume());
      drawnPositions_.swap(drawnMesh_.positions);
    }
    liftOntoFloor(drawnPositions_);  // the smooth map may dip under the floor the element map rests on
    drawnStale_ = false;
  }
  return drawnPositions_;
}

double BulkPiece::volume() const { return enclosedVolume(body_.state.positions, body_.mesh.surface); }

bool BulkPiece::grab(const glm::dvec3& point, double radius, int index, Grip grip) {
  Hand& hand = hands_[index];
  // The drawn surface point nearest to `point`, and the body's nodes within `radius` of it (or,
  // when none is that close, the nodes that carry the nearest drawn vertex). The surface as the
  // element map places it, as the floor contact sees it (the physics never evaluates the smooth map,
  // which differs by millimetres: a press grabbed through the smooth map left the body flat in
  // BulkTorture's press_top_to_the_floor, aspect 0.48 against 0.66, where main's grab recovers).
  std::vector<glm::dvec3> drawn;
  placeByElements(body_.embedding, body_.state.positions, drawn);
  const glm::dvec3 surface = nearestSurfacePoint(drawn, body_.drawn.triangles, point);
  const ParticleState& state = body_.state;
  std::vector<std::uint32_t> nodes = pointsWithinRadius(state.positions, surface, radius);
  if (nodes.empty()) {
    std::uint32_t nearest = 0;
    for (std::uint32_t i = 1; i < drawn.size(); ++i)
      if (glm::length(drawn[i] - surface) < glm::length(drawn[nearest] - surface)) nearest = i;
    const Tetrahedron& t = body_.embedding.nodes[nearest];
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
    mass += 1.0 / body_.freeInverseMasses[i];
  }
  spring.nodes = nodes;
  spring.target = surface;
  spring.grip = grip;
  if (grip == Grip::Fist) {  // each node by itself: its stiffness and a damping for a node of the mean mass
    spring.stiffness = kFistNodeStiffness;
    mass /= static_cast<double>(nodes.size());
  }
  spring.damping = kMouseDampingRatio * 2.0 * std::sqrt(spring.stiffness * mass);
  spring.maxForce = settings_.sim.handForce;
  hand.pendingTarget = surface;
  hand.holding = true;
  hand.nodes = std::move(nodes);
  hand.target = surface;
  hand.radius = radius;
  return true;
}

}  // namespace slime

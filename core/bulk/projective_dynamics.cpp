#include "core/bulk/eigen.h"  // first: see its header
#include "core/bulk/projective_dynamics.h"

#include "core/bulk/element_pass.h"
#include "core/contact/floor_adhesion.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>

namespace slime {
namespace {

constexpr int kContactRounds = 4;          // active-set rounds of the floor per global solve
// Columns A⁻¹e_i kept for floor nodes, at most this many doubles in all (64 MB): resolution 3 keeps
// every node's, resolution 4 about 350; a node past the budget is put on the floor after the solve.
constexpr std::size_t kColumnBudget = std::size_t{8} << 20;

}  // namespace

struct ProjectiveSolver::Contact {
  Eigen::LLT<Eigen::MatrixXd> llt;
};

ProjectiveSolver::ProjectiveSolver() : contactFactor_(std::make_unique<Contact>()) {}
ProjectiveSolver::~ProjectiveSolver() = default;
ProjectiveSolver::ProjectiveSolver(const ProjectiveSolver& other)
    : blocks_(other.blocks_), contactFactor_(std::make_unique<Contact>()) {}
ProjectiveSolver& ProjectiveSolver::operator=(const ProjectiveSolver& other) {
  if (this != &other) {
    blocks_ = other.blocks_;
    factor_ = ProjectiveFactor{};
    contactFactor_ = std::make_unique<Contact>();
    factoredStep_ = -1.0;
  }
  return *this;
}

void ProjectiveSolver::reset(const BulkBody& body) {
  blocks_.assign(body.restBlocks.size(), ProjectiveBlock{});
  for (ProjectiveBlock& block : blocks_)
    for (std::size_t lane = 0; lane < kTetLanes; ++lane) block.rotation[0][lane] = 1.0;
  loadMaxwell(body);
  factoredStep_ = -1.0;
}

namespace {

// √G of a symmetric positive metric through its eigenvectors, less I (projective_local.h's stretches), in
// kSymmetricEntry's order (a zero lane past the last tetrahedron gives −I).
void storeRootLessIdentity(const Eigen::Matrix3d& g, ProjectiveReal (&out)[6][kTetLanes], std::size_t lane) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(g);
  const Eigen::Vector3d roots = eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  const Eigen::Matrix3d u = eigen.eigenvectors() * roots.asDiagonal() * eigen.eigenvectors().transpose();
  for (int r = 0; r < 3; ++r)
    for (int c = r; c < 3; ++c) out[kSymmetricEntry[r][c]][lane] = static_cast<ProjectiveReal>(u(r, c) - (r == c ? 1.0 : 0.0));
}

}  // namespace

void ProjectiveSolver::loadMaxwell(const BulkBody& body) {
  if (blocks_.size() != body.restBlocks.size()) {
    reset(body);
    return;
  }
  for (std::size_t block = 0; block < blocks_.size(); ++block)
    for (std::size_t lane = 0; lane < kTetLanes; ++lane) {
      Eigen::Matrix3d g;
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) g(r, c) = body.maxwell[block].metric[3 * c + r][lane];
      // U_v = √G_v, kept as U_v − I (projective_local.h).
      storeRootLessIdentity(g, blocks_[block].maxwellStretch, lane);
    }
  loadPlastic(body);
}

void ProjectiveSolver::loadPlastic(const BulkBody& body) {
  plastic_ = false;
  if (blocks_.size() != body.maxwell.size()) return;
  for (std::size_t block = 0; block < blocks_.size(); ++block)
    for (std::size_t lane = 0; lane < kTetLanes; ++lane) {
      const ElementReal(&metric)[6][kTetLanes] = body.maxwell[block].plastic;
      bool identity = true;
      for (int e = 0; e < 6; ++e) identity = identity && metric[e][lane] == (e < 3 ? 1 : 0);
      if (identity) {
        for (int e = 0; e < 6; ++e) blocks_[block].plasticStretch[e][lane] = 0;
        continue;
      }
      plastic_ = true;
      Eigen::Matrix3d g;
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) g(r, c) = metric[kSymmetricEntry[r][c]][lane];
      storeRootLessIdentity(g, blocks_[block].plasticStretch, lane);
    }
}

void ProjectiveSolver::flowLongTerm(BulkBody& body, double dt) {
  const PlasticFlow flow = plasticFlowOver(body.material, dt);
  if (flow.flow <= 0.0 && !plastic_) return;
  if (blocks_.size() != body.maxwell.size()) return;
  plasticBefore_.resize(body.maxwell.size());
  for (std::size_t block = 0; block < blocks_.size(); ++block)
    std::copy(&body.maxwell[block].plastic[0][0], &body.maxwell[block].plastic[0][0] + 6 * kTetLanes, &plasticBefore_[block][0][0]);
  relaxElements(body, 1.0, flow, false);
  // U_p = √G_p again only where the flow moved G_p (an eigensolver a tetrahedron).
  for (std::size_t block = 0; block < blocks_.size(); ++block)
    for (std::size_t lane = 0; lane < kTetLanes; ++lane) {
      const ElementReal(&metric)[6][kTetLanes] = body.maxwell[block].plastic;
      bool moved = false;
      for (int e = 0; e < 6; ++e) moved = moved || metric[e][lane] != plasticBefore_[block][e][lane];
      if (!moved) continue;
      plastic_ = true;
      Eigen::Matrix3d g;
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) g(r, c) = metric[kSymmetricEntry[r][c]][lane];
      storeRootLessIdentity(g, blocks_[block].plasticStretch, lane);
    }
}

void ProjectiveSolver::storeMaxwell(BulkBody& body) const {
  if (blocks_.size() != body.maxwell.size()) return;
  for (std::size_t block = 0; block < blocks_.size(); ++block)
    for (std::size_t lane = 0; lane < kTetLanes; ++lane) {
      glm::dmat3 u;
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) u[c][r] = blocks_[block].maxwellStretch[kSymmetricEntry[r][c]][lane] + (r == c ? 1.0 : 0.0);
      const glm::dmat3 g = u * u;
      const double det = glm::determinant(g);
      const glm::dmat3 b = det > 0.0 ? glm::inverse(g) : glm::dmat3(1.0);
      for (int entry = 0; entry < 9; ++entry) {
        body.maxwell[block].metric[entry][lane] = det > 0.0 ? g[entry / 3][entry % 3] : (entry % 4 == 0 ? 1.0 : 0.0);
        body.maxwell[block].inverse[entry][lane] = b[entry / 3][entry % 3];
      }
    }
  refreshMaxwellForceMaps(body, false);  // the explicit step's forces read M (element_pass.h)
}

void ProjectiveSolver::factor(const BulkBody& body, double h) {
  const ViscoelasticMaterial& m = body.material;
  const std::size_t n = body.state.size();
  factor_.factor(n, projectiveMatrix(body, h, masses_));
  columnOf_.assign(n, -1);
  columns_.clear();
  factoredContact_.clear();
  factoredStep_ = h;
  factoredShear_ = m.longTermShear + m.maxwellShear;
  factoredLambda_ = m.lameLambda;
  factoredInverseMasses_ = body.state.inverseMasses;
  ++factorisations_;
}

// Targets p_e of every tetrahedron at the current positions, summed into targets_ as w_e D_eᵀ p_e.
// `flow`: the Maxwell rest stretch flows towards this shape first (once per step).
void ProjectiveSolver::localStep(const BulkBody& body, double h, bool flow) {
  const ViscoelasticMaterial& m = body.material;
  const bool flows = flow && m.maxwellShear > 0.0;
  projectiveTargets(body, flows, flows ? -std::expm1(-h / m.relaxationTime) : 0.0, plastic_, blocks_, quads_, targets_);
}

void ProjectiveSolver::keepColumns(const std::vector<std::uint32_t>& nodes) {
  std::uint32_t batch[4];
  std::size_t count = 0;
  const auto solveBatch = [&] {
    std::vector<double>* out[4];
    for (std::size_t k = 0; k < count; ++k) out[k] = &columns_[static_cast<std::size_t>(columnOf_[batch[k]])];
    factor_.columns(batch, count, out);
    count = 0;
  };
  for (const std::uint32_t node : nodes) {
    int& index = columnOf_[node];
    if (index >= 0) continue;
    if ((columns_.size() + 1) * columnOf_.size() > kColumnBudget) break;
    index = static_cast<int>(columns_.size());
    columns_.emplace_back();
    batch[count++] = node;
    if (count == 4) solveBatch();
  }
  if (count > 0) solveBatch();
}

// The floor as a constraint of the global solve: minimise ½ zᵀAz − bᵀz subject to z_i ≥ f_i, f_i the
// floor under node i (0, or where the drawn surface touches it: drawnFloorHeights, bulk_body.h). With
// z0 = A⁻¹b the free solve and C the active set, z = z0 + Σ_{c∈C} λ_c A⁻¹e_c with (A⁻¹)_CC λ = f_C − z0_C,
// so that z_C = f_C and λ_c (N) is the floor's reaction on node c. Active-set rounds: a node with λ < 0
// (the floor pulling) leaves C, a node still below the floor joins it. The columns A⁻¹e_c are kept
// until the matrix changes, and the small dense factor while C does not change (a slime at rest).
void ProjectiveSolver::holdOnFloor(const std::vector<double>& inverseMasses, const std::vector<double>& floor) {
  const std::size_t n = solved_.size();
  reaction_.assign(n, 0.0);
  freeZ_.resize(n);
  for (std::size_t i = 0; i < n; ++i) freeZ_[i] = solved_[i].z;
  // A stuck node (the sticky floor) is in the active set from the start: its contact holds it down
  // against a pull, λ ≥ −holds_[i], where a plain contact only pushes, λ ≥ 0.
  const bool sticky = !holds_.empty();
  const auto hold = [&](std::size_t i) { return sticky ? holds_[i] : 0.0; };
  contact_.clear();
  for (std::size_t i = 0; i < n; ++i)
    if (inverseMasses[i] > 0.0 && (freeZ_[i] < floor[i] || hold(i) > 0.0)) contact_.push_back(static_cast<std::uint32_t>(i));
  keepColumns(contact_);
  std::erase_if(contact_, [&](std::uint32_t i) { return columnOf_[i] < 0; });
  if (contact_.empty()) return;
  Eigen::VectorXd lambda;
  heldZ_ = freeZ_;
  for (int round = 0; round < kContactRounds && !contact_.empty(); ++round) {
    const std::size_t k = contact_.size();
    if (contact_ != factoredContact_) {
      Eigen::MatrixXd s(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(k));
      for (std::size_t b = 0; b < k; ++b) {
        const std::vector<double>& col = columns_[static_cast<std::size_t>(columnOf_[contact_[b]])];
        for (std::size_t a = 0; a < k; ++a) s(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) = col[contact_[a]];
      }
      contactFactor_->llt.compute(s);
      factoredContact_ = contact_;
    }
    Eigen::VectorXd rhs(static_cast<Eigen::Index>(k));
    for (std::size_t a = 0; a < k; ++a) rhs(static_cast<Eigen::Index>(a)) = floor[contact_[a]] - freeZ_[contact_[a]];
    lambda = contactFactor_->llt.solve(rhs);
    heldZ_ = freeZ_;
    for (std::size_t b = 0; b < k; ++b) {
      const double l = lambda(static_cast<Eigen::Index>(b));
      const std::vector<double>& col = columns_[static_cast<std::size_t>(columnOf_[contact_[b]])];
      for (std::size_t i = 0; i < n; ++i) heldZ_[i] += l * col[i];
    }
    // The next active set: keep the pushed nodes (and the stuck ones pulled less than they hold), add
    // the ones still below.
    std::vector<std::uint32_t> next;
    next.reserve(k);
    bool changed = false;
    inContact_.assign(n, 0);
    for (std::size_t b = 0; b < k; ++b) {
      inContact_[contact_[b]] = 1;
      if (lambda(static_cast<Eigen::Index>(b)) > -hold(contact_[b])) next.push_back(contact_[b]);
      else changed = true;
    }
    below_.clear();
    for (std::size_t i = 0; i < n; ++i)
      if (inverseMasses[i] > 0.0 && !(heldZ_[i] >= floor[i] - 1e-12) && !inContact_[i]) below_.push_back(static_cast<std::uint32_t>(i));
    keepColumns(below_);
    for (const std::uint32_t i : below_) {
      if (columnOf_[i] < 0) continue;  // past the column budget
      next.push_back(i);
      changed = true;
    }
    if (!changed) {
      for (std::size_t b = 0; b < k; ++b) {
        reaction_[contact_[b]] = lambda(static_cast<Eigen::Index>(b));
        heldZ_[contact_[b]] = floor[contact_[b]];
      }
      break;
    }
    std::sort(next.begin(), next.end());
    if (round + 1 == kContactRounds || next.empty()) {
      // Out of rounds: the last solve's pushed nodes keep their reactions; the rest is put on the
      // floor after the solve (step()).
      for (std::size_t b = 0; b < k; ++b)
        if (lambda(static_cast<Eigen::Index>(b)) > -hold(contact_[b])) reaction_[contact_[b]] = lambda(static_cast<Eigen::Index>(b));
      if (next.empty()) heldZ_ = freeZ_;
      break;
    }
    contact_ = std::move(next);
  }
  for (std::size_t i = 0; i < n; ++i) solved_[i].z = heldZ_[i];
}

glm::dvec3 ProjectiveSolver::step(BulkBody& body, BulkScratch& scratch, const ProjectiveStep& options) {
  const double h = options.h;
  const double theta = options.theta;
  const double solveStep = theta * h;  // the backward Euler step the forces are solved over
  ParticleState& state = body.state;
  const std::size_t n = state.size();
  if (blocks_.size() != body.restBlocks.size()) reset(body);
  const ViscoelasticMaterial& m = body.material;
  if (factoredStep_ != solveStep || factoredShear_ != m.longTermShear + m.maxwellShear || factoredLambda_ != m.lameLambda ||
      factoredInverseMasses_ != state.inverseMasses)
    factor(body, solveStep);
  dampEdges(body, h, scratch, state);
  // The mouse spring, node by node backward Euler on m (v' − v)/h = s_k (k (t_k − x − h v') + c (v_t − v')),
  // then the whole hand's force limited as addMouseSpringForces does.
  glm::dvec3 hand(0.0);
  if (options.mouse != nullptr && !options.mouse->nodes.empty()) {
    const MouseSpring& mouse = *options.mouse;
    std::vector<glm::dvec3>& change = scratch.positions;  // velocity changes, reused scratch
    change.assign(mouse.nodes.size(), glm::dvec3(0.0));
    for (std::size_t k = 0; k < mouse.nodes.size(); ++k) {
      const std::uint32_t i = mouse.nodes[k];
      const double w = state.inverseMasses[i];
      if (w <= 0.0) continue;
      const double mass = 1.0 / w, stiffness = nodeShare(mouse, k) * mouse.stiffness,
                   damping = nodeShare(mouse, k) * mouse.damping;
      const glm::dvec3 v = state.velocities[i];
      const glm::dvec3 next =
          (mass / h * v + stiffness * (springTarget(mouse, k) - state.positions[i]) + damping * springTargetVelocity(mouse, k)) /
          (mass / h + stiffness * h + damping);
      change[k] = next - v;
      hand += mass * change[k] / h;
    }
    const double magnitude = glm::length(hand);
    const double scale = magnitude > mouse.maxForce ? mouse.maxForce / magnitude : 1.0;
    for (std::size_t k = 0; k < mouse.nodes.size(); ++k) state.velocities[mouse.nodes[k]] += scale * change[k];
    hand *= scale;
  }
  drawnFloorHeights(body, floor_);
  const std::vector<double>& floor = floor_;
  stickyHolds(body, options.adhesion);
  start_.resize(n);
  predicted_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {  // one pass, not a loop and two copies
    const glm::dvec3 x = state.positions[i];
    start_[i] = x;
    predicted_[i] = x + solveStep * state.velocities[i] + (state.inverseMasses[i] > 0.0 ? solveStep * solveStep : 0.0) * options.gravity;
    state.positions[i] = predicted_[i];
  }
  // The solve's floor: x_θ's that puts x_{n+1} on f_i ((1 − θ) z_n + θ f_i; f_i itself for backward Euler).
  const bool midpoint = theta != 1.0;
  if (midpoint) {
    thetaFloor_.resize(n);
    for (std::size_t i = 0; i < n; ++i) thetaFloor_[i] = (1.0 - theta) * start_[i].z + theta * floor[i];
  }
  for (int iteration = 0; iteration < std::max(1, options.iterations); ++iteration) {
    localStep(body, h, iteration == 0);
    for (std::size_t i = 0; i < n; ++i) targets_[i] += masses_[i] * predicted_[i];  // the right-hand side
    factor_.solve(targets_, solved_);
    holdOnFloor(state.inverseMasses, midpoint ? thetaFloor_ : floor);
    for (std::size_t i = 0; i < n; ++i) state.positions[i] = state.inverseMasses[i] > 0.0 ? solved_[i] : predicted_[i];
  }
  // x_{n+1} = x_n + (x_θ − x_n)/θ; a node the solve held on the floor ends exactly on it.
  if (midpoint)
    for (std::size_t i = 0; i < n; ++i) {
      glm::dvec3& x = state.positions[i];
      x = start_[i] + (x - start_[i]) / theta;
      if (state.inverseMasses[i] > 0.0 && reaction_[i] != 0.0) x.z = floor[i];
    }
  // Friction: a node the floor held with the reaction N has its slide across the floor undone up to
  // the Coulomb limit μ N θh²/m (the slide μ N moves the mass m in a step h, θh² for x_{n+1} = x_n +
  // h v_n + θh² a); a stuck node up to (μ max(N, 0) + σ(t)A_i) θh²/m; a node the solve missed (past the
  // column budget, or the active set's last round) is put on the floor and its slide undone up to
  // μ × depth (as xpbd.h; the same limit with N = m depth/h²).
  const bool sticky = !holds_.empty();
  for (std::size_t i = 0; i < n; ++i) {
    glm::dvec3& x = state.positions[i];
    if (state.inverseMasses[i] == 0.0) continue;
    double limit = 0.0;
    const double hold = sticky && reaction_[i] != 0.0 ? holds_[i] : 0.0;
    if (x.z < floor[i]) {
      limit = options.friction * (floor[i] - x.z);
      x.z = floor[i];
    } else if (reaction_[i] > 0.0 || hold > 0.0) {
      limit = (options.friction * std::max(reaction_[i], 0.0) + hold) * solveStep * h * state.inverseMasses[i];
    } else {
      continue;
    }
    const glm::dvec2 slide(x.x - start_[i].x, x.y - start_[i].y);
    const double length = glm::length(slide);
    const double undo = length <= limit ? 1.0 : limit / length;
    x.x -= undo * slide.x;
    x.y -= undo * slide.y;
  }
  // v_{n+1} from x_{n+1} = x_n + h ((1 − θ) v_n + θ v_{n+1}). A node on the floor (held by the solve,
  // stuck, or put there) ends as backward Euler ends it, v = (x_{n+1} − x_n)/h, so it lands and stays;
  // so does a node the hand holds, whose spring is backward Euler's (above): the midpoint rule's end
  // velocity 2 v̄ − v_n, a yanked node's twice the hand's speed, tripped the guard's speed limit
  // (173 m/s against 157 in a 1 m yank in 10 ms of a 10 g slime).
  if (midpoint) {
    drivenByHand_.assign(n, 0);
    if (options.mouse != nullptr)
      for (const std::uint32_t i : options.mouse->nodes) drivenByHand_[i] = 1;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (state.inverseMasses[i] <= 0.0) continue;
    const glm::dvec3 average = (state.positions[i] - start_[i]) / h;
    const bool endsAsBackwardEuler =
        !midpoint || reaction_[i] != 0.0 || state.positions[i].z <= floor[i] || drivenByHand_[i];
    state.velocities[i] = endsAsBackwardEuler ? average : (average - (1.0 - theta) * state.velocities[i]) / theta;
  }
  updateSticky(state.positions, h);
  return hand;
}

std::size_t ProjectiveSolver::stuckCount() const {
  return static_cast<std::size_t>(std::count(stuck_.begin(), stuck_.end(), 1));
}

void ProjectiveSolver::stickyHolds(const BulkBody& body, double strength) {
  const std::size_t n = body.state.size();
  if (strength <= 0.0) {
    holds_.clear();
    return;
  }
  if (stuck_.size() != n) {
    stuck_.assign(n, 0);
    left_.assign(n, 0);
    age_.assign(n, 0.0);
  }
  // A_i: a third of the floor-facing (projected) area of its surface triangles (floor_adhesion.h).
  area_.assign(n, 0.0);
  const std::vector<glm::dvec3>& x = body.state.positions;
  for (const Triangle& t : body.mesh.surface) {
    if (t.x >= n || t.y >= n || t.z >= n) continue;
    const glm::dvec3 normal = glm::cross(x[t.y] - x[t.x], x[t.z] - x[t.x]);  // 2 A n̂
    const double downward = std::max(0.0, -normal.z) / 6.0;
    area_[t.x] += downward;
    area_[t.y] += downward;
    area_[t.z] += downward;
  }
  holds_.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i)
    if (stuck_[i]) holds_[i] = adhesionGrownShare(age_[i]) * strength * area_[i];
}

void ProjectiveSolver::updateSticky(const std::vector<glm::dvec3>& positions, double h) {
  if (holds_.empty()) {
    stuck_.clear();  // adhesion 0 (or switched off): no contact is kept
    return;
  }
  for (std::size_t i = 0; i < holds_.size(); ++i) {
    if (stuck_[i]) {
      if (reaction_[i] != 0.0) {
        age_[i] += h;
        continue;
      }
      stuck_[i] = 0;  // pulled off past its hold: the active set let it go
      left_[i] = 1;
      ++peeled_;
    } else if (left_[i]) {
      if (positions[i].z > floor_[i] + 2.0 * kAdhesionContactBand) left_[i] = 0;
    } else if (reaction_[i] > 0.0 && area_[i] > 0.0) {
      stuck_[i] = 1;  // a surface node the floor pushed: caught where it landed
      age_[i] = 0.0;
    }
  }
}

}  // namespace slime

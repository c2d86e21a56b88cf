// The bulk body's unconditionally stable integrator (sim.integrator=projective): backward Euler
// solved by projective dynamics (Bouaziz, Martin, Liu, Kavan & Pauly, "Projective Dynamics: Fusing
// Constraint Projections for Fast Simulation", SIGGRAPH 2014) with the global matrix factored once
// (Eigen's SimplicialLDLT) and one or a few local/global iterations per step.
//
// Each tetrahedron's energy is written as a distance to a target, E_e = w_e/2 ‖F − p_e‖² with a
// constant weight, so that the global matrix A = M/h² + Σ w_e D_eᵀD_e (D_e x = F) never changes:
//   w_e = V0 (2μ + 3λ),   p_e = (μ∞ R + μ1 R U_v + (3λ/2) p_V) / (μ + 3λ/2),
// R the rotation of F (F = R U, found by Müller, Bender, Chentanez & Macklin 2016, "A robust method
// to extract the rotational part of deformations", warm-started from the last step), U_v the Maxwell
// branch's rest stretch and μ = μ∞ + μ1. At small strain this is linear elasticity with shear
// modulus μ and Lamé λ, the same as the explicit integrators' stable neo-Hookean material
// (viscoelastic.h): μ∞‖F − R‖² ≈ μ∞ ε:ε, μ1‖F − R U_v‖² ≈ μ1 (ε − ε_v):(ε − ε_v), and
// (3λ/2)‖F − p_V‖² ≈ λ/2 (tr ε)², with p_V the volume target: one Newton step from F onto det = 1,
// p_V = F + (1 − J) cof F / ‖cof F‖², which stays within ‖F − R‖ of F (R lies on det = 1 too), or R
// itself for an inverted element (J ≤ 0) or where the step would go farther. So every target stays
// at a bounded distance from its F: the earlier p_V = F J^(−1/3) (and its extension (2 + J)/3 past
// J = 0.01) grew without bound for an element pressed flat or inverted, and each such element was
// pushed further in, step after step (pressed through to the floor: J = −6000, 21 rollbacks).
// The standard linear solid is kept: the Maxwell branch's rest stretch U_v flows towards the current
// stretch U = sym(RᵀF) every step, U_v ← U + (U_v − U) exp(−h/τ), then U_v ← U_v / det(U_v)^(1/3) (at
// small strain ε_v' = (ε − ε_v)/τ, as the explicit integrators' metric flow). U_v² is the metric G_v
// of bulk_body.h's MaxwellBlock; storeMaxwell / loadMaxwell move between the two.
//
// One step h: the seed's edge dampers exactly (dampEdges, a contraction), the mouse spring
// implicitly node by node (with the hand's force limit), the inertial prediction y = x + h v + h² g,
// then `iterations` local steps (targets p_e, projective_local.h, in float lanes) and global
// solves A x = M y/h² + Σ w_e D_eᵀ p_e with the floor z_i ≥ f_i a constraint of each solve (an active
// set; holdOnFloor in the .cpp), then Coulomb friction on the held nodes' slide up to μ × the floor's
// reaction; v = (x − x_start)/h. f_i is where the drawn surface touches the floor under node i
// (drawnFloorHeights, bulk_body.h): a correction after the solve, as the drawn surface's contact was,
// is undone by the next solve through the whole matrix A, so the rest balanced a phantom force A Δ
// and depended on sim.iterations. The Simulation's volume projection after the step is still such a
// correction (docs/physics.md).
// Each iteration lowers the step's objective, so no step length makes it blow up; what a long step
// costs is numerical damping (backward Euler's ζ ≈ hω/2 for a mode ω; see docs/physics.md).
#pragma once

#include "core/bulk/bulk_body.h"
#include "core/bulk/projective_factor.h"
#include "core/bulk/projective_local.h"
#include "core/hands/grab.h"

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

namespace slime {

// θ of the step (sim.integrator=projective_midpoint: θ = ½, kMidpointTheta). The forces are taken at
// x_θ = x_n + θh v_n + (θh)² (g + F(x_θ)/m), the same minimisation as backward Euler over the step θh
// (the matrix A = M/(θh)² + Σ w DᵀD, factored once), and the step ends at
//   v_{n+1} = v_n + (v_θ − v_n)/θ,  v_θ = (x_θ − x_n)/(θh),   x_{n+1} = x_n + h ((1 − θ) v_n + θ v_{n+1}),
// so x_{n+1} = x_n + (x_θ − x_n)/θ. θ = 1 is backward Euler (the projective step, ζ ≈ ωh/2); θ = ½ is the
// implicit midpoint rule, which on a linear oscillator keeps the energy exactly (ζ = 0) at any step
// and shortens the period by a factor of about 1 + (ωh)²/12. Between them, ζ ≈ (θ − ½) ωh.
// A node the floor holds (or the sticky floor keeps), or the hand holds, ends the step as backward Euler
// ends it, v_{n+1} = (x_{n+1} − x_n)/h: a landing stops, it does not bounce back as the midpoint rule would.
constexpr double kMidpointTheta = 0.5;

struct ProjectiveStep {
  double h = 0.001;               // s
  int iterations = 1;             // local/global iterations
  double theta = 1.0;             // 1: backward Euler; ½: implicit midpoint (above)
  glm::dvec3 gravity{0.0, 0.0, -9.81};
  double friction = 0.0;          // Coulomb μ of the floor
  // The sticky floor inside the solve (slime.adhesion, Pa; 0 = none): a surface node held on the floor
  // sticks, and its contact then holds a pull up to σ(t)·A_i (floor_adhesion.h's strength, ageing and
  // floor-facing area) inside the active set, a bound on the reaction −σ(t)A_i ≤ λ_i instead of 0 ≤ λ_i;
  // across the floor its slide is held up to the same force more than the friction's.
  double adhesion = 0.0;
  const MouseSpring* mouse = nullptr;  // null: nothing grabbed
};

class ProjectiveSolver {
 public:
  ProjectiveSolver();
  ~ProjectiveSolver();
  // A copy keeps the per-element state and factors again on its first step.
  ProjectiveSolver(const ProjectiveSolver& other);
  ProjectiveSolver& operator=(const ProjectiveSolver& other);
  // Sizes the per-element state for `body` and takes U_v = √G_v from its Maxwell metrics, R = I.
  void reset(const BulkBody& body);
  // U_v = √G_v from the body's metrics (after a rollback or a switch from another integrator).
  void loadMaxwell(const BulkBody& body);
  // G_v = U_v², B_v = G_v⁻¹ into the body (for its energy, a rollback, another integrator).
  void storeMaxwell(BulkBody& body) const;
  // U_p = √G_p from the body's long-term branches (loadMaxwell does it too).
  void loadPlastic(const BulkBody& body);
  // The long-term branches' plastic flow over dt on the body (relaxElements, at its positions), then U_p.
  void flowLongTerm(BulkBody& body, double dt);
  // One step; returns the hand's force, N (zero when nothing is grabbed).
  glm::dvec3 step(BulkBody& body, BulkScratch& scratch, const ProjectiveStep& step);
  // Forget the factorisation (after a material change); the next step factors again.
  void invalidate() { factoredStep_ = -1.0; }
  int factorisations() const { return factorisations_; }
  // Per node, the floor the last step held it above, m (drawnFloorHeights, bulk_body.h).
  const std::vector<double>& floorHeights() const { return floor_; }
  // The sticky floor's nodes stuck after the last step (ProjectiveStep::adhesion), and those peeled since reset.
  std::size_t stuckCount() const;
  std::size_t peeledCount() const { return peeled_; }

 private:
  void factor(const BulkBody& body, double h);
  // The floor inside the global solve: z of solved_ with the active set of floor nodes held at their floor.
  // A stuck node (holds_[i] > 0) stays in the active set while its reaction is above −holds_[i].
  void holdOnFloor(const std::vector<double>& inverseMasses, const std::vector<double>& floor);
  // holds_: per node, what its sticky contact holds this step, N (σ(t)·A_i; 0 where not stuck).
  void stickyHolds(const BulkBody& body, double strength);
  // After the step: a node the floor pushed sticks, a stuck one pulled past its hold has peeled.
  void updateSticky(const std::vector<glm::dvec3>& positions, double h);
  // Computes the columns A⁻¹e_i of `nodes` not kept yet, four per solve, while the budget lasts
  // (columnOf_ stays −1 for a node past it).
  void keepColumns(const std::vector<std::uint32_t>& nodes);
  void localStep(const BulkBody& body, double h, bool flow);

  std::vector<ProjectiveBlock> blocks_;
  bool plastic_ = false;  // some U_p is not I
  std::vector<std::array<std::array<ElementReal, kTetLanes>, 6>> plasticBefore_;  // G_p before a flow
  NodeQuads quads_;  // the local step's node copies
  ProjectiveFactor factor_;
  double factoredStep_ = -1.0;
  double factoredShear_ = 0.0, factoredLambda_ = 0.0;
  std::vector<double> factoredInverseMasses_;
  int factorisations_ = 0;
  std::vector<double> masses_;             // m_i/h² on the diagonal (pinned: a huge mass)
  std::vector<glm::dvec3> start_, predicted_, targets_;  // x at the step's start, y, Σ w Dᵀp per node
  std::vector<glm::dvec3> solved_;
  std::vector<double> floor_;  // per node, the floor under it this step (drawnFloorHeights)
  // Floor contact in the solve (holdOnFloor): columns A⁻¹e_i of the nodes that touched the floor
  // since the last factorisation, the active set, its reactions (N) and the factor of (A⁻¹)_CC.
  std::vector<int> columnOf_;                 // node → index into columns_, −1 none
  std::vector<std::vector<double>> columns_;
  std::vector<std::uint32_t> contact_, factoredContact_, below_;
  std::vector<double> reaction_, freeZ_, heldZ_;
  std::vector<char> inContact_;  // per node, whether it is in this round's active set
  // The sticky floor (ProjectiveStep::adhesion): per node, stuck, peeled and not yet off the floor
  // (it sticks again only after rising above 2 kAdhesionContactBand), time in contact (s), hold (N).
  std::vector<char> stuck_, left_, peeledNow_;
  std::vector<double> age_, holds_, area_;
  std::size_t peeled_ = 0;
  // θ's midpoint floor: per node, (1 − θ) z_n + θ f_i, so that x_{n+1} = x_n + (x_θ − x_n)/θ ends on f_i.
  std::vector<double> thetaFloor_;
  std::vector<char> drivenByHand_;  // per node, held by the step's hand (its velocity ends as backward Euler's)
  struct Contact;  // the dense Cholesky factor of (A⁻¹)_CC (Eigen)
  std::unique_ptr<Contact> contactFactor_;
};

}  // namespace slime

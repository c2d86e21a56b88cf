// The slime as a bulk viscoelastic body (slime.model=bulk, the default): mass points through the
// volume of a tetrahedral ball (tet_mesh.h), each tetrahedron a standard linear solid
// (viscoelastic.h), the seed's dampers along every edge, a whole-body volume term, gravity, floor
// contact and the mouse spring. The drawn icosphere rides on it (surface_embedding.h), so the drawn
// level no longer sets the physics cost.
//
// Settings in SI units and how the seed's sliders map onto them:
//  - mass (kg) gives the density ρ = mass / V0, spread to the nodes by a quarter of each tetrahedron;
//  - modulus G (Pa) is the instantaneous shear modulus μ∞ + μ1 (the seed's "stiffness" slider);
//    longTerm = μ∞ / G; relaxation = τ (s); poisson = ν of each element (Lamé λ = 2Gν/(1 − 2ν));
//  - viscosity η (Pa·s) sets the seed's damper along every edge, k_d = η V_e / l_e², V_e the edge's
//    share of its tetrahedra's volume (the seed's "damping" slider), so the body's viscosity does not
//    depend on the resolution.
// Linear tetrahedra lock when each element is made nearly incompressible, so elements have ν = 0.4
// by default, and the whole body's volume is held exactly instead by one constraint, V = V0, projected
// after every substep (XPBD with zero compliance, Macklin et al. 2016: Δx_i = −C w_i ∇_i V / Σ w|∇V|²,
// with the velocity following the correction). A stiff pressure force would need several substeps
// per step; the projection costs one pass over the surface. The n = 2 modes that Lamb's oracle checks
// keep the volume, so it leaves them alone.
#pragma once

#include "core/geometry/icosphere.h"
#include "core/geometry/particle_state.h"
#include "core/settings/settings.h"
#include "core/bulk/edge_colours.h"
#include "core/bulk/element_real.h"
#include "core/bulk/surface_embedding.h"
#include "core/bulk/tet_mesh.h"
#include "core/bulk/viscoelastic.h"

#include <glm/mat3x3.hpp>

#include <algorithm>
#include <vector>

namespace slime {

// The force loop takes the tetrahedra kTetLanes at a time, one per vector lane: a few vector
// registers' worth, so that the stores that gather a block have left before its arithmetic reads them.
constexpr std::size_t kTetLanes = 64;

// The rest data of kTetLanes tetrahedra with each matrix entry's lanes side by side (structure of
// arrays within the block), entry [3·column + row], in ElementReal (element_real.h). Lanes past the
// last tetrahedron hold zeros.
struct TetBlock {
  alignas(64) ElementReal restInverse[9][kTetLanes] = {};  // Dm⁻¹
  alignas(64) ElementReal forceMap[9][kTetLanes] = {};     // −V0 Dm⁻ᵀ
  // The element pass's own (element_pass.h): the four nodes, K_p = −V0 Dm⁻¹ B_p Dm⁻ᵀ (six entries,
  // tet_lanes.h's kSymmetricEntry; K0 = −V0 Dm⁻¹Dm⁻ᵀ until the long-term branch yields, and refreshed
  // when its G_p flows) and 1/det Dm; node 0 and zeros past the last tetrahedron.
  alignas(64) std::uint32_t nodes[4][kTetLanes] = {};
  alignas(64) ElementReal stiffnessMap[6][kTetLanes] = {};
  alignas(64) ElementReal volumeScale[kTetLanes] = {};
};

// The rest states that flow, of a block's tetrahedra, laid out as TetBlock; identity at rest: the Maxwell
// branches' (viscoelastic.h's MaxwellRest) and the long-term branches' plastic rest metric G_p. (One
// struct, so that the guard's saved states keep both.)
struct MaxwellBlock {
  alignas(64) ElementReal inverse[9][kTetLanes] = {};  // B_v
  alignas(64) ElementReal metric[9][kTetLanes] = {};   // G_v = B_v⁻¹, which the flow blends
  alignas(64) ElementReal plastic[6][kTetLanes] = {};  // G_p (six entries, tet_lanes.h's kSymmetricEntry)
};

// M = −V0 Dm⁻¹ B_v Dm⁻ᵀ of a block's tetrahedra (six entries, element_pass.h), which follows B_v: kept
// apart from MaxwellBlock so that the guard's saved states do not copy it (refreshed on a rollback).
struct MaxwellMapBlock {
  alignas(64) ElementReal forceMap[6][kTetLanes] = {};
};

struct BulkBody {
  TetMesh mesh;                           // at rest at slime.position
  ParticleState state;
  std::vector<double> freeInverseMasses;  // inverse masses when nothing pins a node
  std::vector<TetRest> rest;              // per tetrahedron
  std::vector<TetBlock> restBlocks;       // the same by kTetLanes, for the force loop
  std::vector<MaxwellBlock> maxwell;      // per block of kTetLanes tetrahedra, B_v and G_v
  std::vector<MaxwellMapBlock> maxwellMaps;  // M per block, from maxwell (refreshMaxwellForceMaps)
  std::vector<glm::u32vec2> edges;        // every tetrahedron edge once
  std::vector<double> edgeDamping;        // k_d per edge, N·s/m
  EdgeColours edgeColours;                // the order dampEdges takes the edges in
  ViscoelasticMaterial material;
  double restVolume = 0.0;                // V0 of the tetrahedral ball, m³
  double totalMass = 0.0;                 // kg
  TriangleMesh drawn;                     // the drawn icosphere at rest
  SurfaceEmbedding embedding;             // how it rides on the body
  // The points the floor holds up (resolveDrawnFloorContact, drawnFloorHeights): the element map of the
  // icosphere of level floorContactLevel(mesh.shellLevel), whatever finer slime.level draws. Empty where
  // they are the drawn vertices themselves: the drawn level is that level, or coarser than the shells (the
  // drawn vertices are nodes), or a piece made afresh by a tear or a merge (its drawn surface is on a grid
  // of a spacing that the drawn level barely changes).
  SurfaceEmbedding floorPoints;
};

// The icosphere level of the floor's points (BulkBody::floorPoints): two levels finer than the body's
// shells (16 points a surface triangle), at most kFloorContactLevel, the default drawn level. Read
// through the element map every step, the drawn vertices over the contact patch made a step at level 6
// cost 2.0× one at level 4 (AMD EPYC family 25 model 17), though the body is the same; with a level of
// its own the physics is the same at every drawn level. A finer drawn surface shows the smooth map,
// which is set on the floor where it dips under it when placed (bulk_piece.cpp's liftOntoFloor). At
// resolution 1, level 4's 64 points a surface triangle kept a slammed rk4 slime from settling back in
// 7 s (aspect 0.61 against 0.67 at level 3's; BulkTorture's fling_up_and_slam).
constexpr int kFloorContactLevel = 4;
inline int floorContactLevel(int shellLevel) {
  return std::max(shellLevel, std::min(shellLevel + 2, kFloorContactLevel));
}

BulkBody buildBulkBody(const SlimeSettings& slime);

// B_v of one tetrahedron.
glm::dmat3 maxwellInverse(const BulkBody& body, std::size_t tetrahedron);
// G_p and B_p = G_p⁻¹ of one tetrahedron's long-term branch (the identity until it yields).
glm::dmat3 plasticMetric(const BulkBody& body, std::size_t tetrahedron);
glm::dmat3 plasticInverse(const BulkBody& body, std::size_t tetrahedron);
// The long-term branch's damage D of one tetrahedron (viscoelastic.h's damageOfTrace; 0 without slime.damage).
double damage(const BulkBody& body, std::size_t tetrahedron);

// The elastic stretch of one tetrahedron's long-term branch at `positions`: F = Ds·Dm⁻¹ measured against
// its flowed rest shape U_p, as the isochoric uniaxial stretch with the same deviatoric elastic stress
// (viscoelastic.h's equivalentStretch of deviatoricStretchMeasure(F, B_p); 1 at rest, the yield stretch
// where it yields). What has flowed is not in it: a strand drawn out slowly has flowed and is barely
// stretched elastically; one pulled fast is.
double elasticStretch(const BulkBody& body, const std::vector<glm::dvec3>& positions, std::size_t tetrahedron);

// Live material changes that keep the geometry: mass, modulus, longTerm, relaxation, poisson, viscosity.
void applyBulkMaterial(BulkBody& body, const SlimeSettings& slime);

// Scratch for the forces (sized on first use, no allocation per step after that).
struct BulkScratch {
  std::vector<glm::dvec3> forces;
  // Per edge in dampEdges' order (BulkBody::edgeColours): its two nodes and 1 − exp(−k_d (w_i + w_j) h)
  // for the step decayStep.
  std::vector<glm::u32vec2> dampedPairs;
  std::vector<double> edgeDecay;
  double decayStep = -1.0;
  std::vector<glm::dvec3> volumeGradient;
  std::vector<glm::dvec3> positions;  // the frequency estimate's displaced shape
};

// Internal forces at (x, v): elastic and Maxwell stresses and the edge dampers. No gravity, no
// contact, no volume (projectBulkVolume). `forces` is resized and overwritten.
void bulkInternalForces(const BulkBody& body, const std::vector<glm::dvec3>& positions,
                        const std::vector<glm::dvec3>& velocities, std::vector<glm::dvec3>& forces,
                        bool dampers = true);

// The seed's dampers integrated exactly pair by pair, as symplectic_euler does for the membrane: the
// relative velocity of each edge's ends along the edge decays by exp(−k_d (w_i + w_j) h), the two
// ends sharing the change by their inverse masses (momentum kept). A contraction for any h; with the
// kicks between passes the step is capped (Simulation::largestStableStep). The pairs are taken colour
// after colour (edge_colours.h), each seeing the velocities the earlier ones left. Call after the kick.
void dampEdges(const BulkBody& body, double h, BulkScratch& scratch, ParticleState& state);

// Moves the surface nodes so the body's volume is its rest volume again (one projection along ∇V)
// and the velocity of that move over h. Nodes lying on the floor are held by it and stay: z ≤ 0, or
// z ≤ floor[i] given the floor under each node (drawnFloorHeights, for the projective solver, which
// holds its nodes there).
void projectBulkVolume(const BulkBody& body, double h, BulkScratch& scratch, ParticleState& state,
                       const std::vector<double>* floor = nullptr);

// Elastic energy of both branches, J.
double bulkElasticEnergy(const BulkBody& body, const std::vector<glm::dvec3>& positions);

// How many tetrahedra are inverted or flat (det Ds ≤ 0) at `positions`: a healthy body has none; a
// press that drives nodes through the material under them inverts some (docs/physics.md, known limits).
std::size_t invertedBulkElements(const BulkBody& body, const std::vector<glm::dvec3>& positions);

// The Maxwell branches' flow and the long-term branches' plastic flow (viscoelastic.h) over dt.
void relaxBulk(BulkBody& body, double dt);

// Steps between relaxBulk's flows for the explicit step: maxwellFlowInterval for the shorter of the Maxwell
// branch's τ and (when the long-term branch yields) its flow time τ_p.
int bulkFlowInterval(const SlimeSettings& slime, double dt, int fewest);

// Lifts every floor point (BulkBody::floorPoints: points of the drawn sphere, by the element map) that
// went below the floor back onto it by moving the nodes that carry it with positive weight in proportion
// to w_j / m_j, and takes away those nodes' downward speed with Coulomb friction on their sliding (a
// position-level contact on the drawn surface, where a person sees it; the nodes it holds sit just above
// the floor, where the nodes' own contact never acts). Returns how many floor points touched. (Its lifts squeeze the body by up to 1 % while it lands; the next substep's volume
// projection gives that back. Projecting again right here, as shape or as speed, kept the resting
// body from settling.)
std::size_t resolveDrawnFloorContact(BulkBody& body, double friction);

// How many floor points the two above read at the body's state: those over the surface triangles that
// may touch the floor. The same at every drawn level (tests hold the physics to it).
std::size_t floorPointsNearFloor(const BulkBody& body);

// The drawn surface's floor as a floor under each node, for a solver that holds its nodes on the floor
// inside its solve (projective_dynamics.h). Each floor point v rests on the node j it follows most
// (its largest element-map weight φ_j): j may go down to z_j − z_v / φ_j (z_v the point's height),
// where it alone would put v on the floor; never below 0. A point on the floor holds its node where
// it is. Only that node: holding every node with a positive weight held the rim of the contact patch
// up (a 20 kPa slime rested 1.0 mm too tall, 78.3 mm against 77.1 explicit); what the other nodes do
// to v, the drawn contact after the step (resolveDrawnFloorContact) still sees to. `heights` is
// resized to the body's nodes.
void drawnFloorHeights(const BulkBody& body, std::vector<double>& heights);

// ω_max of the undamped linearised body (power iteration on finite differences of the forces) and
// the dampers' highest rate (Gershgorin bound), for the explicit step limit.
double bulkHighestFrequency(const BulkBody& body, BulkScratch& scratch, int iterations = 40);
// The same about the shape `at` (the body's current one): a stretched element is thinner across,
// so its highest frequency rises (ω ∝ 1/thickness); the step limit follows it under the hands.
double bulkHighestFrequencyAt(const BulkBody& body, const std::vector<glm::dvec3>& at, BulkScratch& scratch,
                              int iterations = 40);
double bulkHighestDampingRate(const BulkBody& body);

}  // namespace slime

// The bulk body's element pass (issue 27): every tetrahedron's elastic and Maxwell nodal forces in one
// sweep, kLaneWidth tetrahedra at a time, gathered from and scattered to padded node copies
// (x, y, z, 0 in one vector) so that a tetrahedron's corners are one load each and its shape Ds never
// goes through memory; and the Maxwell branches' flow, which refreshes the map M the forces use.
// The stress is viscoelastic.h's, rewritten on Ds (tet_lanes.h's shapeForceLanes): the same forces
// to rounding.
#pragma once

#include "core/bulk/bulk_body.h"

#include <glm/vec3.hpp>

#include <vector>

namespace slime {

// The per-block data the pass reads (TetBlock's nodes, stiffnessMap, volumeScale), from the body's
// tetrahedra and restBlocks' restInverse and forceMap; then every block's M (refreshMaxwellForceMaps).
void fillElementBlocks(BulkBody& body);

// M = −V0 Dm⁻¹ B_v Dm⁻ᵀ of every block from its B_v, and (longTermToo) K_p = −V0 Dm⁻¹ B_p Dm⁻ᵀ from its
// G_p: after anything that sets them other than relaxElements (building the body, the projective
// solver's storeMaxwell, which sets only B_v, the guard's rollback). G_p = I gives K0 exactly.
void refreshMaxwellForceMaps(BulkBody& body, bool longTermToo = true);

// Elastic and Maxwell nodal forces at x, in ElementReal lanes (element_real.h) summed in double;
// `forces` is resized and overwritten.
void elementForces(const BulkBody& body, const std::vector<glm::dvec3>& x, std::vector<glm::dvec3>& forces);
// The same in double lanes from the same stored data: for finite differences of the forces (the
// frequency estimate moves the nodes by ~1e-10 m, below float's rounding of an edge).
void elementForcesInDouble(const BulkBody& body, const std::vector<glm::dvec3>& x, std::vector<glm::dvec3>& forces);

// The Maxwell branches' flow with decay = exp(−Δt/τ) at the body's positions (relaxMaxwellBranch per
// tetrahedron, tet_lanes.h's relaxLanes), then M; and the long-term branches' plastic flow (`plastic`,
// relaxLongTermBranch, tet_lanes.h's flowLongTermLanes), then K_p where any lane flowed.
// `maxwellToo` false: the plastic flow alone (the projective solver flows its Maxwell branches itself).
void relaxElements(BulkBody& body, double decay, const PlasticFlow& plastic = {}, bool maxwellToo = true);

}  // namespace slime

// Bulk bodies made from other bodies' tetrahedra, for tearing and merging (issue 42 items 4 and 5):
// the tetrahedra keep their rest data (Dm⁻¹, V0) and their Maxwell branches' flowed rest states, the
// nodes their positions, velocities and mass density, and everything derived from the tetrahedra is
// built again: the node numbering (the new surface's nodes first, as projectBulkVolume expects), the
// surface (the faces of one tetrahedron only, wound outwards), the element blocks, the edges, their
// dampers and colours, the rest volume Σ V0 and the masses. The drawn surface is the caller's (made
// afresh in the current configuration) and is carried by the new body from there (carryDrawnSurface).
#pragma once

#include "core/bulk/bulk_body.h"
#include "core/geometry/icosphere.h"
#include "core/settings/settings.h"

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace slime {

// A body's content before it is laid out: nodes (rest position, state) and tetrahedra over them, each
// with its rest data and its Maxwell branch's rest state.
struct BodyParts {
  std::vector<glm::dvec3> restPositions, positions, velocities;
  std::vector<double> inverseMasses;  // as the state had them (0: pinned)
  std::vector<Tetrahedron> tetrahedra;
  std::vector<TetRest> rest;
  std::vector<MaxwellRest> maxwell;
  std::vector<glm::dmat3> plastic;  // the long-term branch's rest metric G_p (plasticMetric), per tetrahedron
};

// The parts of `body` made of its tetrahedra `tetrahedra` (ascending), the nodes they use in the
// body's order; partNode[k] is the body's node of part node k.
BodyParts partsOf(const BulkBody& body, std::span<const std::uint32_t> tetrahedra, std::vector<std::uint32_t>& partNode);

// The faces of exactly one of `tetrahedra`, wound counter-clockwise seen from outside, each with its
// tetrahedron, in a fixed order (by the face's sorted nodes).
std::vector<std::pair<Triangle, std::uint32_t>> boundaryFaces(const std::vector<Tetrahedron>& tetrahedra);

// Lays `parts` out as a body of mass density `density` (kg/m³; slime's other material settings).
// order[i] is the part node that became node i (surface nodes first, each group in the parts' order).
// The drawn surface is left empty (carryDrawnSurface).
BulkBody assembleBody(const BodyParts& parts, const SlimeSettings& slime, double density, int shellLevel,
                      std::vector<std::uint32_t>& order);

// The rest shape of `parts` derived again as a ball (a merge: a torn piece pressed back keeps its share
// of the old ball as its rest shape and would stand out of the merged slime as a nub). The nodes as they
// are now are mapped about the tetrahedra's centroid c by the affine map that makes their second moment
// isotropic, y = S^(−1/2) (x − c), then radially onto a sphere, x* = y/ρ(y/|y|), where ρ(d) is the
// farthest node's distance along the direction d (the largest per cell of a latitude–longitude grid,
// smoothed, interpolated); each tetrahedron's new reference is its image there scaled to keep its
// volume V0 (so the volume is the body's, exactly), and its long-term and Maxwell rest metrics are carried
// into it, G' = Aᵀ G A with A = Dm Dm'⁻¹ (det 1): the stress now is what it was. Letting G_p flow to the
// identity (relaxLongTermTowardReference) then rounds the body up toward the ball. A tetrahedron whose
// image is inverted (a part of the body folded back on itself about c) keeps its reference.
void rebaseRestTowardBall(BodyParts& parts);

// G_p ← (G_p + w (I − G_p)) / det^(1/3) for every tetrahedron of `body` (w in [0, 1]), then its long-term
// force maps K_p (element_pass.h): the long-term branch's rest shape flows a share w of the way to the
// tetrahedron's reference.
void relaxLongTermTowardReference(BulkBody& body, double w);

// Gives `body` the drawn surface `drawn`, made where the body's nodes were at `reference` (its node
// numbering; the current positions, or those of a few steps before, as a tear spread over two steps
// made its surfaces): the smooth map over those node positions, support `support` m (surface_embedding.h:
// exact for affine motion from any reference), and the element map into the tetrahedron under the
// nearest surface face there.
void carryDrawnSurface(BulkBody& body, TriangleMesh drawn, double support, const std::vector<glm::dvec3>& reference);

}  // namespace slime

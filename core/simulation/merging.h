// Pieces pressed together fuse (issue 42 item 5). Two bulk pieces touch when at least kTouchingNodes
// of their surface nodes lie within a weld distance of the other's (a node grid, only when their boxes
// overlap: cheap, and blind to the self-contact that holds touching surfaces a small gap apart). Touching
// for slime.mergeTime without a break, they become one piece: the tetrahedra of both, the surface nodes
// of one welded to the nearest of the other where each is the other's nearest within the weld distance
// (the pair meets half-way). Welding moves a node by at most half the weld distance, so each tetrahedron
// that holds a welded node has its rest shape pulled back through its deformation gradient before the
// weld, D_m' = F⁻¹ D_s' (its stress is as before: the weld adds none); its Maxwell state is kept. The
// merged rest shape is then derived again as a ball (sub_body.h's rebaseRestTowardBall), and the drawn
// surface is the two bodies' union, blurred, which closes the seam (piece_surface.h).
#pragma once

#include "core/bulk/bulk_body.h"
#include "core/bulk/sub_body.h"

#include <cstdint>
#include <vector>

namespace slime {

constexpr std::size_t kTouchingNodes = 3;

// How many surface nodes of `a` lie within `distance` of a surface node of `b`.
std::size_t touchingNodes(const BulkBody& a, const BulkBody& b, double distance);

// The parts of a and b as one body, welded within `weldDistance`; source[i] says where part node i came
// from: i < a's nodes is a's node i, the rest b's node (i − a's nodes); welded b nodes are gone (bOf[j]
// gives b's node j's part node).
BodyParts weldedParts(const BulkBody& a, const BulkBody& b, double weldDistance, std::vector<std::uint32_t>& bOf);

}  // namespace slime

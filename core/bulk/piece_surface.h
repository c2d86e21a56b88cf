// Drawn surfaces made afresh when pieces tear or merge (core/geometry/surface_extraction.h's grid
// surfaces), in the current configuration, for carryDrawnSurface (sub_body.h) to embed:
//  - split: each part's surface is the old drawn surface's inside intersected with the region nearer
//    that part's tetrahedra than any other's (each grid point takes the part of the tetrahedron it lies
//    in, points in none the part of their nearest labelled neighbour); the part's indicator is blurred
//    so that the cut is round, not stepped. Away from the cut the surface is the old one's zero level.
//  - merge: the union of the pieces' bodies, blurred, which fills the crease where they touch, drawn
//    as the drawn icosphere moved along its rays onto it (a small torn piece's own drawn surface is
//    crumpled: its union with the other kept that as the seam).
// The grid spacing is about the old drawn surface's mean edge; Taubin's smoothing follows.
#pragma once

#include "core/bulk/bulk_body.h"
#include "core/geometry/icosphere.h"
#include "core/geometry/surface_view.h"

#include <cstdint>
#include <span>
#include <vector>

namespace slime {

// The drawn surface of each of `parts` parts of `body` (at its current positions), `partOf` per
// tetrahedron, cut from `drawn`, the body's drawn surface now. `spacing`, m: the grid's.
std::vector<TriangleMesh> splitDrawnSurface(const SurfaceView& drawn, const BulkBody& body,
                                            const std::vector<std::uint32_t>& partOf, std::uint32_t parts,
                                            double spacing);

// One closed surface around the union of `bodies`' tetrahedra, blurred over a few spacings of `spacing`
// (which rounds the seam); `surfaces`, their drawn surfaces, bound the grid. Where the union is
// star-shaped about its centroid it is the drawn icosphere of `level` moved along its rays onto the
// union (as regular as a slime never torn), else the grid's surface nets. Empty when the bodies do not
// meet as one.
TriangleMesh mergedDrawnSurface(std::span<const BulkBody* const> bodies, std::span<const SurfaceView> surfaces, double spacing,
                                int level);

// Moves every vertex of the closed surface `mesh` along its normal by one distance, so that it encloses
// `volume` (m³; two Newton steps on V(δ) ≈ V + A δ).
void offsetToVolume(TriangleMesh& mesh, double volume);

// The mean edge length of a surface, m.
double meanEdgeLength(const SurfaceView& surface);

}  // namespace slime

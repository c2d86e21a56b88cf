// Where a bulk piece tears (issue 42 item 4). Every few steps the most stretched tetrahedron is found by
// its elastic stretch (core/bulk/elastic_stretch.h, which depends on the rate); past slime.tearStretch
// the piece is cut there: through that tetrahedron, across its principal direction, the plane
// separates the tetrahedra that straddle it and are themselves stretched (a flood fill from the seed
// over shared faces: the thin section, not the whole body that the plane crosses), and the faces
// between them on opposite sides are cut. The pieces are then the connected components of the
// tetrahedra over the faces left. A cut that leaves one component (the crack has not yet run across)
// waits for more stretch; a component smaller than slime.smallestPiece of the slime stays joined to its
// largest neighbour across the cut. With slime.damage a damaged tetrahedron tears at a smaller elastic
// stretch (elastic_stretch.h's tearMeasure, 1 where it tears): the seed is the one nearest to tearing, a
// damaged seed cut across its total stretch, and the crack takes straddling tetrahedra past
// kCrackStretchShare of that measure (without damage the same elements as before). Serial and in a fixed
// order: the same tear for the same state on any number of threads.
#pragma once

#include "core/bulk/bulk_body.h"

#include <cstdint>
#include <vector>

namespace slime {

// A straddling tetrahedron joins the crack when its elastic stretch is past this share of the way
// from 1 to slime.tearStretch (with damage: its tear measure past this share).
constexpr double kCrackStretchShare = 0.2;

struct TearPlan {
  double stretch = 1.0;               // the largest elastic stretch found past slime.tearStretch (else 1)
  std::uint32_t parts = 0;            // pieces the cut leaves: under 2 means no tear
  std::vector<std::uint32_t> partOf;  // per tetrahedron, its piece (0..parts−1, by its first tetrahedron)
};

// The tear of `body` at its state now: no parts when its largest elastic stretch is under
// `tearStretch` or the cut does not separate it. `smallestVolume` (m³, rest) is the least a piece holds.
TearPlan planTear(const BulkBody& body, double tearStretch, double smallestVolume);

}  // namespace slime

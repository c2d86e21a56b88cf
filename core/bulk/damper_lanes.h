// The seed's exact edge dampers (dampEdges, bulk_body.h) four pairs at a time, one per vector lane.
// The edges of one colour (edge_colours.h) share no node, so four of them can be read, changed and
// written back together: the same contraction per pair, the same order of colours, the same
// arithmetic per pair as the pair-by-pair loop (to the rounding of fused multiply-adds).
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <vector>

namespace slime {

// Four pairs of one colour: their nodes and their decay 1 − exp(−k_d (w_i + w_j) h). A colour whose
// size is not a multiple of four is padded with pairs on the spare node (index nodeCount, at rest,
// w = 0), whose change is zero.
struct DamperQuad {
  alignas(32) double decay[4] = {};
  std::uint32_t first[4] = {};
  std::uint32_t second[4] = {};
};

struct DamperLanes {
  std::vector<DamperQuad> quads;       // colour after colour
  std::vector<std::uint32_t> colours;  // colour c is quads[colours[c], colours[c + 1])
  std::size_t nodeCount = 0;
};

// `pairs` and `decay` in the dampers' order, `starts` the colours' bounds in it (colour c is
// [starts[c], starts[c + 1])); no two pairs of a colour may share a node.
DamperLanes packDamperLanes(const std::vector<glm::u32vec2>& pairs, const std::vector<double>& decay,
                            const std::vector<std::uint32_t>& starts, std::size_t nodeCount);

// Δv_i = w_i a ((v_j − v_i)·d) d, Δv_j = −w_j a ((v_j − v_i)·d) d, a = decay/(|d|² (w_i + w_j)), d = x_j −
// x_i, quad after quad; a pair with w_i + w_j = 0 or |d| = 0 is left alone.
void dampPairLanes(const DamperLanes& lanes, const std::vector<glm::dvec3>& positions,
                   std::vector<glm::dvec3>& velocities, const std::vector<double>& inverseMasses);

}  // namespace slime

// A colouring of the bulk body's edges such that no two edges of one colour share a node (a proper
// edge colouring, greedy: each edge in turn takes the lowest colour neither of its ends has yet, so at
// most 2Δ − 1 colours for the highest node degree Δ; deterministic for a given edge list). The seed's
// dampers are integrated pair by pair (dampEdges, bulk_body.h); taken colour after colour, the pairs of
// one colour touch disjoint nodes, so their updates do not wait on each other and the processor runs
// them side by side, where the edges' own order (sorted by first node) chains every pair through the
// velocity of a shared node.
#pragma once

#include <glm/vec2.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace slime {

struct EdgeColours {
  std::vector<std::uint32_t> order;   // edge indices, colour after colour, by index within a colour
  std::vector<std::uint32_t> starts;  // colour c is order[starts[c] .. starts[c + 1])
  std::size_t count() const { return starts.empty() ? 0 : starts.size() - 1; }
};

// `edges` index nodes 0..nodeCount−1; an edge whose two ends are the same node is refused
// (std::invalid_argument), as is an index out of range.
EdgeColours colourEdges(const std::vector<glm::u32vec2>& edges, std::size_t nodeCount);

}  // namespace slime

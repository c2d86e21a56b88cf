#include "core/bulk/edge_colours.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace slime {

EdgeColours colourEdges(const std::vector<glm::u32vec2>& edges, std::size_t nodeCount) {
  // used[node] holds one bit per colour, in 64-bit words grown as colours are added.
  std::vector<std::vector<std::uint64_t>> used(nodeCount);
  std::vector<std::uint32_t> colour(edges.size());
  std::uint32_t colours = 0;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const std::uint32_t i = edges[e].x, j = edges[e].y;
    if (i >= nodeCount || j >= nodeCount || i == j)
      throw std::invalid_argument("colourEdges: edge " + std::to_string(e) + " (" + std::to_string(i) + ", " +
                                  std::to_string(j) + ") is not two distinct nodes below " +
                                  std::to_string(nodeCount));
    std::vector<std::uint64_t>& a = used[i];
    std::vector<std::uint64_t>& b = used[j];
    std::uint32_t c = 0;
    for (std::size_t word = 0;; ++word) {
      const std::uint64_t taken = (word < a.size() ? a[word] : 0) | (word < b.size() ? b[word] : 0);
      if (taken != ~std::uint64_t{0}) {
        c = static_cast<std::uint32_t>(64 * word + __builtin_ctzll(~taken));
        break;
      }
    }
    const std::size_t word = c / 64;
    if (a.size() <= word) a.resize(word + 1, 0);
    if (b.size() <= word) b.resize(word + 1, 0);
    a[word] |= std::uint64_t{1} << (c % 64);
    b[word] |= std::uint64_t{1} << (c % 64);
    colour[e] = c;
    colours = std::max(colours, c + 1);
  }
  EdgeColours result;
  result.starts.assign(colours + 1, 0);
  for (std::uint32_t c : colour) ++result.starts[c + 1];
  for (std::uint32_t c = 0; c < colours; ++c) result.starts[c + 1] += result.starts[c];
  result.order.resize(edges.size());
  std::vector<std::uint32_t> next(result.starts.begin(), result.starts.end() - 1);
  for (std::size_t e = 0; e < edges.size(); ++e) result.order[next[colour[e]]++] = static_cast<std::uint32_t>(e);
  return result;
}

}  // namespace slime

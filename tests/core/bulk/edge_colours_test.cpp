// The dampers' edge colouring (edge_colours.h): every edge once, no two edges of a colour sharing a
// node, the same colouring every time.
#include "core/bulk/edge_colours.h"
#include "core/bulk/bulk_body.h"
#include "core/settings/settings_io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

namespace slime {
namespace {

TEST(EdgeColours, TheDefaultBodysEdgesOnceEachNoColourSharingANode) {
  const BulkBody body = buildBulkBody(defaultSettings().slime);
  const EdgeColours& colours = body.edgeColours;
  ASSERT_EQ(colours.order.size(), body.edges.size());
  std::vector<std::uint32_t> sorted = colours.order;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t e = 0; e < sorted.size(); ++e) ASSERT_EQ(sorted[e], e) << "edge taken twice or never";
  std::vector<std::size_t> lastColour(body.mesh.positions.size(), colours.count());
  for (std::size_t c = 0; c < colours.count(); ++c) {
    for (std::uint32_t k = colours.starts[c]; k < colours.starts[c + 1]; ++k) {
      const glm::u32vec2 edge = body.edges[colours.order[k]];
      ASSERT_NE(lastColour[edge.x], c) << "node " << edge.x << " twice in colour " << c;
      ASSERT_NE(lastColour[edge.y], c) << "node " << edge.y << " twice in colour " << c;
      lastColour[edge.x] = lastColour[edge.y] = c;
    }
  }
  // Most edges fall in a few large colours (the pairs the processor can overlap).
  EXPECT_GT(colours.starts[8], body.edges.size() / 2);
  const BulkBody again = buildBulkBody(defaultSettings().slime);
  EXPECT_EQ(again.edgeColours.order, colours.order);
  EXPECT_EQ(again.edgeColours.starts, colours.starts);
}

TEST(EdgeColours, AStarNeedsOneColourPerEdgeAndMoreThan64Work) {
  std::vector<glm::u32vec2> star;
  for (std::uint32_t leaf = 1; leaf <= 70; ++leaf) star.push_back({0, leaf});
  const EdgeColours colours = colourEdges(star, 71);
  EXPECT_EQ(colours.count(), 70u);
  for (std::size_t c = 0; c < 70; ++c) EXPECT_EQ(colours.order[c], c);
}

TEST(EdgeColours, RefusesALoopOrANodeOutOfRange) {
  EXPECT_THROW(colourEdges({{2, 2}}, 3), std::invalid_argument);
  EXPECT_THROW(colourEdges({{0, 3}}, 3), std::invalid_argument);
}

}  // namespace
}  // namespace slime

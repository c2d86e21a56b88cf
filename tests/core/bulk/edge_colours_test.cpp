// The dampers' edge colouring (edge_colours.h): every edge once, no two edges of a colour sharing a
// node, the same colouring every time. And the dampers taken four pairs of a colour at a time
// (damper_lanes.h, dampEdges): the same velocities as the pair-by-pair loop in the colours' order, to
// rounding, with every node moving and three held (w = 0, two of them one edge's ends); each colour padded with pairs on the spare
// node; bad packing refused. (Here rather than in a file of their own: a new test file shifts the unity
// batches and put floor_contact_test.cpp's own Tetrahedron beside tet_mesh.h's.)
#include "core/bulk/edge_colours.h"
#include "core/bulk/bulk_body.h"
#include "core/bulk/damper_lanes.h"
#include "core/settings/settings_io.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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

// dampEdges' loop before the lanes: pair after pair in the colours' order.
void dampPairByPair(const BulkBody& body, double h, ParticleState& state) {
  const std::vector<double>& w = state.inverseMasses;
  for (std::uint32_t s : body.edgeColours.order) {
    const std::uint32_t i = body.edges[s].x, j = body.edges[s].y;
    const double decay = 1.0 - std::exp(-body.edgeDamping[s] * (w[i] + w[j]) * h);
    const double inverseMassSum = w[i] + w[j];
    if (inverseMassSum <= 0.0) continue;
    const glm::dvec3 d = state.positions[j] - state.positions[i];
    const double lengthSquared = glm::dot(d, d);
    if (lengthSquared <= 0.0) continue;
    const double share = decay / (lengthSquared * inverseMassSum);
    const double relativeSpeed = glm::dot(state.velocities[j] - state.velocities[i], d);
    state.velocities[i] += (w[i] * share * relativeSpeed) * d;
    state.velocities[j] -= (w[j] * share * relativeSpeed) * d;
  }
}

TEST(DamperLanes, FourPairsAtATimeGiveThePairByPairVelocities) {
  BulkBody body = buildBulkBody(defaultSettings().slime);
  ParticleState& state = body.state;
  for (std::size_t i = 0; i < state.size(); ++i) {
    const double a = static_cast<double>(i);
    state.velocities[i] = glm::dvec3(std::sin(1.3 * a), std::cos(0.7 * a), 0.5 * std::sin(0.31 * a * a));
    state.positions[i] += 0.002 * glm::dvec3(std::cos(2.1 * a), std::sin(0.9 * a), std::cos(0.17 * a * a));
  }
  // Held by a hand: node 7, and both ends of edge 0 (a pair with w_i + w_j = 0, which is skipped).
  const std::uint32_t heldA = body.edges[0].x, heldB = body.edges[0].y;
  state.inverseMasses[7] = state.inverseMasses[heldA] = state.inverseMasses[heldB] = 0.0;
  const glm::dvec3 held = state.velocities[7], heldVelocityA = state.velocities[heldA];
  ParticleState reference = state;
  const double h = 0.001;
  BulkScratch scratch;
  for (int pass = 0; pass < 3; ++pass) {
    dampEdges(body, h, scratch, state);
    dampPairByPair(body, h, reference);
  }
  double largest = 0.0;
  for (std::size_t i = 0; i < state.size(); ++i) {
    largest = std::max(largest, glm::length(reference.velocities[i]));
    for (int c = 0; c < 3; ++c)
      ASSERT_NEAR(state.velocities[i][c], reference.velocities[i][c], 1e-12) << "node " << i << " component " << c;
  }
  EXPECT_GT(largest, 0.1);
  EXPECT_EQ(state.velocities[7], held);
  EXPECT_EQ(state.velocities[heldA], heldVelocityA);
  EXPECT_EQ(state.positions, reference.positions);
}

TEST(DamperLanes, PadsEachColourWithPairsOnTheSpareNode) {
  // Colour 0: three pairs; colour 1: five pairs. Two quads and two quads.
  const std::vector<glm::u32vec2> pairs = {{0, 1}, {2, 3}, {4, 5}, {1, 2}, {3, 4}, {5, 6}, {7, 8}, {9, 0}};
  const std::vector<double> decay = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8};
  const DamperLanes lanes = packDamperLanes(pairs, decay, {0, 3, 8}, 10);
  ASSERT_EQ(lanes.quads.size(), 3u);
  EXPECT_EQ(lanes.colours, (std::vector<std::uint32_t>{0, 1, 3}));
  EXPECT_EQ(lanes.quads[0].first[2], 4u);
  EXPECT_EQ(lanes.quads[0].first[3], 10u);
  EXPECT_EQ(lanes.quads[0].second[3], 10u);
  EXPECT_EQ(lanes.quads[0].decay[3], 0.0);
  EXPECT_EQ(lanes.quads[2].first[0], 9u);
  EXPECT_EQ(lanes.quads[2].decay[0], 0.8);
  EXPECT_EQ(lanes.quads[2].first[1], 10u);
  // The spare pairs change nothing: two nodes at rest next to moving ones stay at rest.
  std::vector<glm::dvec3> x(10), v(10, glm::dvec3(0.0));
  for (std::size_t i = 0; i < 10; ++i) x[i] = glm::dvec3(0.01 * static_cast<double>(i), 0.0, 0.0);
  v[4] = glm::dvec3(1.0, 0.0, 0.0);
  std::vector<double> w(10, 1.0);
  dampPairLanes(lanes, x, v, w);
  // Pair (4, 5) in colour 0 shares 0.3 of the relative speed, then (3, 4) and (5, 6) in colour 1.
  EXPECT_NEAR(v[4].x, 1.0 - 0.15 - 0.5 * 0.5 * 0.85 - 0.0, 1e-14);
  EXPECT_EQ(v[0], glm::dvec3(0.0));
  EXPECT_EQ(v[8], glm::dvec3(0.0));
}

TEST(DamperLanes, RefusesMismatchedPacking) {
  EXPECT_THROW(packDamperLanes({{0, 1}}, {0.1, 0.2}, {0, 1}, 2), std::invalid_argument);
  EXPECT_THROW(packDamperLanes({{0, 1}}, {0.1}, {0, 2}, 2), std::invalid_argument);
  const DamperLanes lanes = packDamperLanes({{0, 1}}, {0.1}, {0, 1}, 2);
  std::vector<glm::dvec3> x(3), v(3);
  EXPECT_THROW(dampPairLanes(lanes, x, v, std::vector<double>(3, 1.0)), std::invalid_argument);
}

}  // namespace
}  // namespace slime

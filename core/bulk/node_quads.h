// The tetrahedron passes' node copies (element_pass.h's forces and flow, projective_local.h's targets):
// every node's x, y, z and a zero in one 32-byte vector, so that a tetrahedron's corner is one load and
// its nodal sums one add; the gather of kLanesOf<Real> tetrahedra's Ds = [x1 − x0, x2 − x0, x3 − x0]
// (differences in double, then rounded to Real) and the scatter of their nodal sums (in double).
#pragma once

#include "core/bulk/bulk_body.h"
#include "core/bulk/tet_lanes.h"

#include <glm/vec3.hpp>

#include <cstring>
#include <vector>

namespace slime {

// One node's x, y, z and a zero, in one 32-byte vector.
using Quad = double __attribute__((vector_size(4 * sizeof(double))));

// The padded copies.
struct NodeQuads {
  std::vector<Quad> positions;
  std::vector<Quad> forces;
};
// The element pass's, per thread (a simulation steps on one thread; benches may run several at once).
inline NodeQuads& nodeQuads() {
  thread_local NodeQuads quads;
  return quads;
}

inline void copyToQuads(const std::vector<glm::dvec3>& x, std::vector<Quad>& quads) {
  quads.resize(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) quads[i] = Quad{x[i].x, x[i].y, x[i].z, 0.0};
}

// Asks for `bytes` from `p` one 64-byte line at a time (a block's arrays ahead of their use: a block of
// the flow reads 42 rows of 512 bytes, more streams than the hardware prefetcher follows, so each new
// line was a demand miss once the blocks no longer fit in L2; resolution 3's flow ran at 4× resolution
// 2's cost per tetrahedron).
// Only for bodies whose blocks outgrow L2 (resolution 3 has 260 blocks, resolution 2 35, whose passes
// ran no faster with it: ~2 extra loads a tetrahedron for lines already cached).
constexpr std::size_t kPrefetchFromBlocks = 128;
template <int Write>
[[gnu::always_inline]] inline void prefetchBytes(const void* p, std::size_t bytes) {
  const char* c = static_cast<const char*>(p);
  for (std::size_t offset = 0; offset < bytes; offset += 64) __builtin_prefetch(c + offset, Write, 3);
}

// Four tetrahedra's vectors (x, y, z, ·) into x, y and z of the four.
[[gnu::always_inline]] inline void transposeIn(const Quad& a, const Quad& b, const Quad& c, const Quad& d, Quad& x,
                                               Quad& y, Quad& z) {
  const Quad t0 = __builtin_shufflevector(a, b, 0, 4, 2, 6);  // a0 b0 a2 b2
  const Quad t1 = __builtin_shufflevector(a, b, 1, 5, 3, 7);  // a1 b1 a3 b3
  const Quad t2 = __builtin_shufflevector(c, d, 0, 4, 2, 6);
  const Quad t3 = __builtin_shufflevector(c, d, 1, 5, 3, 7);
  x = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
  y = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
  z = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
}
// And back: x, y, z of four tetrahedra into their vectors (x, y, z, 0).
[[gnu::always_inline]] inline void transposeOut(const Quad& x, const Quad& y, const Quad& z, Quad (&out)[4]) {
  const Quad zero{};
  const Quad t0 = __builtin_shufflevector(x, y, 0, 4, 2, 6);     // x0 y0 x2 y2
  const Quad t1 = __builtin_shufflevector(x, y, 1, 5, 3, 7);     // x1 y1 x3 y3
  const Quad t2 = __builtin_shufflevector(z, zero, 0, 4, 2, 6);  // z0 0 z2 0
  const Quad t3 = __builtin_shufflevector(z, zero, 1, 5, 3, 7);  // z1 0 z3 0
  out[0] = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
  out[1] = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
  out[2] = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
  out[3] = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
}
// Four Reals to and from a Quad.
template <class Real>
[[gnu::always_inline]] inline void storeQuad(Real* p, const Quad& q) {
  using RealQuad = typename VectorOf<Real, 4 * sizeof(Real)>::type;
  const RealQuad v = __builtin_convertvector(q, RealQuad);
  std::memcpy(p, &v, sizeof v);
}
template <class Real>
[[gnu::always_inline]] inline Quad loadQuad(const Real* p) {
  using RealQuad = typename VectorOf<Real, 4 * sizeof(Real)>::type;
  RealQuad v;
  std::memcpy(&v, p, sizeof v);
  return __builtin_convertvector(v, Quad);
}

// Ds = [x1 − x0, x2 − x0, x3 − x0] of kLanesOf<Real> tetrahedra from offset `o`, lanes [3·column + row]:
// the differences in double (positions far from the origin keep their edges' digits), then rounded to Real.
template <class Real>
[[gnu::always_inline]] inline void gatherLanes(const TetBlock& block, const std::vector<Quad>& x, std::size_t o,
                                               LanesOf<Real> (&ds)[9]) {
  if constexpr (kLanesOf<Real> == 4) {  // four doubles (AVX2): straight into the lanes
    Quad edge[3][4];
    for (std::size_t l = 0; l < 4; ++l) {
      const Quad origin = x[block.nodes[0][o + l]];
      for (int c = 0; c < 3; ++c) edge[c][l] = x[block.nodes[c + 1][o + l]] - origin;
    }
    for (int c = 0; c < 3; ++c)
      transposeIn(edge[c][0], edge[c][1], edge[c][2], edge[c][3], ds[3 * c], ds[3 * c + 1], ds[3 * c + 2]);
    return;
  }
  alignas(64) Real entries[9][kLanesOf<Real>];
  for (std::size_t g = 0; g < kLanesOf<Real>; g += 4) {
    Quad edge[3][4];
    for (std::size_t l = 0; l < 4; ++l) {
      const Quad origin = x[block.nodes[0][o + g + l]];
      for (int c = 0; c < 3; ++c) edge[c][l] = x[block.nodes[c + 1][o + g + l]] - origin;
    }
    for (int c = 0; c < 3; ++c) {
      Quad xyz[3];
      transposeIn(edge[c][0], edge[c][1], edge[c][2], edge[c][3], xyz[0], xyz[1], xyz[2]);
      for (int r = 0; r < 3; ++r) storeQuad(&entries[3 * c + r][g], xyz[r]);
    }
  }
  for (int e = 0; e < 9; ++e) ds[e] = loadLanes<Real>(entries[e]);
}

// Adds H's columns to nodes 1..3 and minus their sum to node 0, in double (lanes past the last
// tetrahedron hold zero forces on node 0).
template <class Real>
[[gnu::always_inline]] inline void scatterLanes(const TetBlock& block, const LanesOf<Real> (&h)[9], std::size_t o,
                                                std::vector<Quad>& forces) {
  alignas(64) Real entries[9][kLanesOf<Real>];
  for (int e = 0; e < 9; ++e) storeLanes<Real>(entries[e], h[e]);
  for (std::size_t g = 0; g < kLanesOf<Real>; g += 4) {
    Quad columns[3][4];
    for (int c = 0; c < 3; ++c) {
      if constexpr (kLanesOf<Real> == 4)  // four doubles (AVX2): straight from the lanes
        transposeOut(h[3 * c], h[3 * c + 1], h[3 * c + 2], columns[c]);
      else
        transposeOut(loadQuad(&entries[3 * c][g]), loadQuad(&entries[3 * c + 1][g]), loadQuad(&entries[3 * c + 2][g]),
                     columns[c]);
    }
    for (std::size_t l = 0; l < 4; ++l) {
      forces[block.nodes[1][o + g + l]] += columns[0][l];
      forces[block.nodes[2][o + g + l]] += columns[1][l];
      forces[block.nodes[3][o + g + l]] += columns[2][l];
      forces[block.nodes[0][o + g + l]] -= columns[0][l] + columns[1][l] + columns[2][l];
    }
  }
}

// Ds of all kTetLanes tetrahedra of `block` into `shape` ([3·column + row][lane]), for a pass that reads
// them as arrays (element_pass.h's flow, projective_local.h): the differences in double, then rounded.
template <class Real>
[[gnu::always_inline]] inline void gatherBlock(const TetBlock& block, const std::vector<Quad>& x,
                                               Real (&shape)[9][kTetLanes]) {
  for (std::size_t g = 0; g < kTetLanes; g += 4) {
    Quad edge[3][4];
    for (std::size_t l = 0; l < 4; ++l) {
      const Quad origin = x[block.nodes[0][g + l]];
      for (int c = 0; c < 3; ++c) edge[c][l] = x[block.nodes[c + 1][g + l]] - origin;
    }
    for (int c = 0; c < 3; ++c) {
      Quad xyz[3];
      transposeIn(edge[c][0], edge[c][1], edge[c][2], edge[c][3], xyz[0], xyz[1], xyz[2]);
      for (int r = 0; r < 3; ++r) storeQuad(&shape[3 * c + r][g], xyz[r]);
    }
  }
}

// And the nodal sums of all kTetLanes tetrahedra of `block` from arrays: H's columns ([3·column + row][lane])
// added to nodes 1..3 and minus their sum to node 0, in double.
template <class Real>
[[gnu::always_inline]] inline void scatterBlock(const TetBlock& block, const Real (&h)[9][kTetLanes],
                                                std::vector<Quad>& forces) {
  for (std::size_t g = 0; g < kTetLanes; g += 4) {
    Quad columns[3][4];
    for (int c = 0; c < 3; ++c)
      transposeOut(loadQuad(&h[3 * c][g]), loadQuad(&h[3 * c + 1][g]), loadQuad(&h[3 * c + 2][g]), columns[c]);
    for (std::size_t l = 0; l < 4; ++l) {
      forces[block.nodes[1][g + l]] += columns[0][l];
      forces[block.nodes[2][g + l]] += columns[1][l];
      forces[block.nodes[3][g + l]] += columns[2][l];
      forces[block.nodes[0][g + l]] -= columns[0][l] + columns[1][l] + columns[2][l];
    }
  }
}

}  // namespace slime

// One node's 3-vector padded to four doubles (x, y, z, and a zero or a spare value) in one 32-byte
// vector, and the 4×4 transposes that turn four nodes' quads into x, y, z lanes and back: how the
// element pass (element_pass.cpp) and the dampers (damper_lanes.cpp) gather and scatter nodes.
#pragma once

namespace slime {

using Quad = double __attribute__((vector_size(4 * sizeof(double))));

// Four quads (x, y, z, ·) into x, y and z lanes.
[[gnu::always_inline]] inline void transposeIn(const Quad& a, const Quad& b, const Quad& c, const Quad& d,
                                               Quad& x, Quad& y, Quad& z) {
  const Quad t0 = __builtin_shufflevector(a, b, 0, 4, 2, 6);  // a0 b0 a2 b2
  const Quad t1 = __builtin_shufflevector(a, b, 1, 5, 3, 7);  // a1 b1 a3 b3
  const Quad t2 = __builtin_shufflevector(c, d, 0, 4, 2, 6);
  const Quad t3 = __builtin_shufflevector(c, d, 1, 5, 3, 7);
  x = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
  y = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
  z = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
}

// The same with the fourth entries as a fourth lane vector w.
[[gnu::always_inline]] inline void transposeIn(const Quad& a, const Quad& b, const Quad& c, const Quad& d,
                                               Quad& x, Quad& y, Quad& z, Quad& w) {
  const Quad t0 = __builtin_shufflevector(a, b, 0, 4, 2, 6);
  const Quad t1 = __builtin_shufflevector(a, b, 1, 5, 3, 7);
  const Quad t2 = __builtin_shufflevector(c, d, 0, 4, 2, 6);
  const Quad t3 = __builtin_shufflevector(c, d, 1, 5, 3, 7);
  x = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
  y = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
  z = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
  w = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
}

// And back: x, y, z lanes into four quads (x, y, z, 0).
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

}  // namespace slime

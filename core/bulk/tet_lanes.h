// The bulk body's per-element arithmetic written once for a whole vector of tetrahedra (GCC/Clang vector
// extensions, no intrinsics): the nodal forces H = P·(−V0 Dm⁻ᵀ) of the stress (viscoelastic.h's
// firstPiolaStress) and the Maxwell branches' flow (relaxMaxwellBranch), kLanesOf<Real> tetrahedra per
// instruction (Real: ElementReal for the step, element_real.h; double for the frequency estimate). GCC left the per-lane glm loops scalar on an AVX2 processor (perf, issue 27: the force loop
// was 51 % of a step and the flow 14 %, all vmulsd/vfmaddsd), so the lanes are spelt out here.
// Entries are stored [3·column + row][lane] as in TetBlock (bulk_body.h). The same operations in the same
// order for every lane, so the result does not depend on where a tetrahedron sits in its block.
#pragma once

#include "core/bulk/element_real.h"

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace slime {

// One vector register: 64 bytes with AVX-512, 32 with AVX2 (and two SSE2 registers without it).
#if defined(__AVX512F__)
constexpr std::size_t kVectorBytes = 64;
#else
constexpr std::size_t kVectorBytes = 32;
#endif
// The lanes of one register of `Real`: the step's arithmetic is in ElementReal (bulk_body.h), the
// frequency estimate's finite differences in double (element_pass.h).
template <class Real>
constexpr std::size_t kLanesOf = kVectorBytes / sizeof(Real);
// A vector of `Bytes` bytes of T (a member typedef: GCC drops vector_size on an alias template's type).
template <class T, std::size_t Bytes>
struct VectorOf {
  typedef T type __attribute__((vector_size(Bytes)));
};
template <class Real>
using LanesOf = typename VectorOf<Real, kVectorBytes>::type;
using Lanes = LanesOf<ElementReal>;
constexpr std::size_t kLaneWidth = kLanesOf<ElementReal>;

// kLanesOf<Real> values from `p` (of any stored type), converted to Real.
template <class Real, class Stored>
[[gnu::always_inline]] inline LanesOf<Real> loadLanes(const Stored* p) {
  using StoredLanes = typename VectorOf<Stored, kLanesOf<Real> * sizeof(Stored)>::type;
  StoredLanes v;
  std::memcpy(&v, p, sizeof v);
  return __builtin_convertvector(v, LanesOf<Real>);
}
template <class Real, class Stored>
[[gnu::always_inline]] inline void storeLanes(Stored* p, const LanesOf<Real>& v) {
  using StoredLanes = typename VectorOf<Stored, kLanesOf<Real> * sizeof(Stored)>::type;
  const StoredLanes stored = __builtin_convertvector(v, StoredLanes);
  std::memcpy(p, &stored, sizeof stored);
}

// x^(−1/3) per lane for x in [2^−126, 2^126] (cube_root.h's method with a single-precision first guess,
// since AVX2 has no 64-bit integer ↔ double conversion): the float bit trick (3.4 %), then fourth-order
// steps r ← r (1 + e/3 + 2e²/9 + 14e³/81), e = 1 − x r³ (3.4 % → 1e-5 → 1e-19 → rounding: three in
// double, two in float), within a few ulp. Lanes outside that range give meaningless values; the caller
// masks them.
template <class Real>
[[gnu::always_inline]] inline void inverseCubeRootLanes(const LanesOf<Real>& x, LanesOf<Real>& root) {
  using FloatLanes = typename VectorOf<float, kLanesOf<Real> * sizeof(float)>::type;
  using Int32Lanes = typename VectorOf<std::int32_t, kLanesOf<Real> * sizeof(float)>::type;
  using Lanes = LanesOf<Real>;
  const Lanes low = x < Real(0x1p-126) ? Lanes{} + Real(0x1p-126) : x;
  const Lanes clamped = low > Real(0x1p126) ? Lanes{} + Real(0x1p126) : low;
  const FloatLanes single = __builtin_convertvector(clamped, FloatLanes);
  Int32Lanes bits;
  std::memcpy(&bits, &single, sizeof bits);
  // 2^23 (127·4/3 − 0.066) − bits/3, as kInverseCubeRootGuessBits is for double (cube_root.h).
  const FloatLanes third = __builtin_convertvector(bits, FloatLanes) * (1.0f / 3.0f);
  const Int32Lanes guessBits = 0x54a237fa - __builtin_convertvector(third, Int32Lanes);
  FloatLanes guess;
  std::memcpy(&guess, &guessBits, sizeof guess);
  Lanes r = __builtin_convertvector(guess, Lanes);
  constexpr int steps = sizeof(Real) == sizeof(float) ? 2 : 3;
  for (int step = 0; step < steps; ++step) {
    const Lanes e = Real(1) - clamped * (r * r * r);
    r += r * e * (Real(1.0 / 3.0) + e * (Real(2.0 / 9.0) + e * Real(14.0 / 81.0)));
  }
  root = r;
}

// F = Ds Dm⁻¹ of kLanesOf<Real> tetrahedra from offset `o`, column-major (f[3c + r] = F_rc).
template <class Real, class Shape, class Stored, std::size_t N>
[[gnu::always_inline]] inline void deformationGradientLanes(const Shape (&shape)[9][N], const Stored (&restInverse)[9][N],
                                                            std::size_t o, LanesOf<Real> (&f)[9]) {
  using Lanes = LanesOf<Real>;
  Lanes ds[9];
  for (int e = 0; e < 9; ++e) ds[e] = loadLanes<Real>(&shape[e][o]);
  for (int c = 0; c < 3; ++c) {
    const Lanes d0 = loadLanes<Real>(&restInverse[3 * c][o]), d1 = loadLanes<Real>(&restInverse[3 * c + 1][o]),
                d2 = loadLanes<Real>(&restInverse[3 * c + 2][o]);
    for (int r = 0; r < 3; ++r) f[3 * c + r] = ds[r] * d0 + ds[3 + r] * d1 + ds[6 + r] * d2;
  }
}

// Nodal forces of kLanesOf<Real> tetrahedra from offset `o` of a block's [9][kTetLanes] arrays:
//   F = Ds Dm⁻¹,  P = μ∞ F + λ'(J − α) cof F + μ1 (F B_v − cof F),  H = P · forceMap
// (viscoelastic.h; μ1 = 0 leaves the Maxwell term out).
template <class Real, class Stored, std::size_t N>
[[gnu::always_inline]] inline void stressForceLanes(double longTermShear, double maxwellShear, double lambdaPrime,
                                                     double restVolumeRatio, const Stored (&shape)[9][N],
                                                     const Stored (&restInverse)[9][N], const Stored (&forceMap)[9][N],
                                                     const Stored (&maxwellInverse)[9][N], std::size_t o,
                                                     Stored (&forces)[9][N]) {
  using Lanes = LanesOf<Real>;
  Lanes f[9];
  deformationGradientLanes<Real>(shape, restInverse, o, f);
  // cof F: columns f1×f2, f2×f0, f0×f1.
  Lanes cof[9];
  for (int c = 0; c < 3; ++c) {
    const int a = 3 * ((c + 1) % 3), b = 3 * ((c + 2) % 3);
    cof[3 * c + 0] = f[a + 1] * f[b + 2] - f[a + 2] * f[b + 1];
    cof[3 * c + 1] = f[a + 2] * f[b + 0] - f[a + 0] * f[b + 2];
    cof[3 * c + 2] = f[a + 0] * f[b + 1] - f[a + 1] * f[b + 0];
  }
  const Lanes j = f[0] * cof[0] + f[1] * cof[1] + f[2] * cof[2];
  const Lanes volumetric = Real(lambdaPrime) * (j - Real(restVolumeRatio));
  Lanes p[9];
  for (int e = 0; e < 9; ++e) p[e] = Real(longTermShear) * f[e] + volumetric * cof[e];
  if (maxwellShear > 0.0) {
    for (int c = 0; c < 3; ++c) {
      const Lanes b0 = loadLanes<Real>(&maxwellInverse[3 * c][o]), b1 = loadLanes<Real>(&maxwellInverse[3 * c + 1][o]),
                  b2 = loadLanes<Real>(&maxwellInverse[3 * c + 2][o]);
      for (int r = 0; r < 3; ++r)
        p[3 * c + r] += Real(maxwellShear) * (f[r] * b0 + f[3 + r] * b1 + f[6 + r] * b2 - cof[3 * c + r]);
    }
  }
  for (int c = 0; c < 3; ++c) {
    const Lanes m0 = loadLanes<Real>(&forceMap[3 * c][o]), m1 = loadLanes<Real>(&forceMap[3 * c + 1][o]),
                m2 = loadLanes<Real>(&forceMap[3 * c + 2][o]);
    for (int r = 0; r < 3; ++r) storeLanes<Real>(&forces[3 * c + r][o], p[r] * m0 + p[3 + r] * m1 + p[6 + r] * m2);
  }
}

// The same nodal forces from Ds itself, without forming F (issue 27, the element pass): with
// S = −V0 Dm⁻¹ (μ∞ I + μ1 B_v) Dm⁻ᵀ (symmetric) and cof(F)·(−V0 Dm⁻ᵀ) = −V0 det(Dm⁻¹) cof(Ds) = −cof(Ds)/6
// (cof(AB) = cof A cof B, V0 = det Dm / 6),
//   H = P·(−V0 Dm⁻ᵀ) = Ds·S + k cof(Ds),  k = (μ1 − λ'(J − α))/6,  J = det(Ds)/det(Dm).
// S = μ∞ K0 + μ1 M with K0 = −V0 Dm⁻¹Dm⁻ᵀ (TetBlock::stiffnessMap) and M = −V0 Dm⁻¹ B_v Dm⁻ᵀ
// (MaxwellBlock::forceMap, refreshed when B_v flows), six entries each in kSymmetricEntry's order;
// `volumeScale` is 1/det(Dm). Ds and H are lanes [3·column + row]; 6 + 1 loads instead of 27.
constexpr int kSymmetricEntry[3][3] = {{0, 3, 4}, {3, 1, 5}, {4, 5, 2}};  // (row, column) → 00 11 22 01 02 12

template <class Real, class Stored, std::size_t N>
[[gnu::always_inline]] inline void shapeForceLanes(double longTermShear, double maxwellShear, double lambdaPrime,
                                                    double restVolumeRatio, const LanesOf<Real> (&ds)[9],
                                                    const Stored (&stiffnessMap)[6][N],
                                                    const Stored (&maxwellMap)[6][N], const Stored (&volumeScale)[N],
                                                    std::size_t o, LanesOf<Real> (&h)[9]) {
  using Lanes = LanesOf<Real>;
  Lanes s[6];
  for (int e = 0; e < 6; ++e) s[e] = Real(longTermShear) * loadLanes<Real>(&stiffnessMap[e][o]);
  if (maxwellShear > 0.0)
    for (int e = 0; e < 6; ++e) s[e] += Real(maxwellShear) * loadLanes<Real>(&maxwellMap[e][o]);
  Lanes cof[9];  // columns d1×d2, d2×d0, d0×d1 of Ds
  for (int c = 0; c < 3; ++c) {
    const int a = 3 * ((c + 1) % 3), b = 3 * ((c + 2) % 3);
    cof[3 * c + 0] = ds[a + 1] * ds[b + 2] - ds[a + 2] * ds[b + 1];
    cof[3 * c + 1] = ds[a + 2] * ds[b + 0] - ds[a + 0] * ds[b + 2];
    cof[3 * c + 2] = ds[a + 0] * ds[b + 1] - ds[a + 1] * ds[b + 0];
  }
  const Lanes j = (ds[0] * cof[0] + ds[1] * cof[1] + ds[2] * cof[2]) * loadLanes<Real>(&volumeScale[o]);
  const Lanes k = (Real(maxwellShear) - Real(lambdaPrime) * (j - Real(restVolumeRatio))) * Real(1.0 / 6.0);
  for (int c = 0; c < 3; ++c) {
    const Lanes s0 = s[kSymmetricEntry[0][c]], s1 = s[kSymmetricEntry[1][c]], s2 = s[kSymmetricEntry[2][c]];
    for (int r = 0; r < 3; ++r) h[3 * c + r] = ds[r] * s0 + ds[3 + r] * s1 + ds[6 + r] * s2 + k * cof[3 * c + r];
  }
}

// Dm⁻¹·B·forceMap = −V0 Dm⁻¹ B Dm⁻ᵀ (symmetric, six entries as above) of kLanesOf<Real> tetrahedra from
// offset `o`: shapeForceLanes' K0 (B = I, `inverse` null) or M (B = B_v).
template <class Real, class Stored, std::size_t N>
[[gnu::always_inline]] inline void congruenceLanes(const Stored (&restInverse)[9][N], const Stored (&forceMap)[9][N],
                                                    const Stored (*inverse)[N], std::size_t o, Stored (&out)[6][N]) {
  using Lanes = LanesOf<Real>;
  Lanes t[9];  // B·forceMap
  for (int e = 0; e < 9; ++e) t[e] = loadLanes<Real>(&forceMap[e][o]);
  if (inverse != nullptr) {
    Lanes b[9];
    for (int e = 0; e < 9; ++e) b[e] = loadLanes<Real>(&inverse[e][o]);
    Lanes bt[9];
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) bt[3 * c + r] = b[r] * t[3 * c] + b[3 + r] * t[3 * c + 1] + b[6 + r] * t[3 * c + 2];
    for (int e = 0; e < 9; ++e) t[e] = bt[e];
  }
  for (int r = 0; r < 3; ++r)
    for (int c = r; c < 3; ++c) {
      const Lanes value = loadLanes<Real>(&restInverse[r][o]) * t[3 * c] +
                          loadLanes<Real>(&restInverse[3 + r][o]) * t[3 * c + 1] +
                          loadLanes<Real>(&restInverse[6 + r][o]) * t[3 * c + 2];
      storeLanes<Real>(&out[kSymmetricEntry[r][c]][o], value);
    }
}

// The Maxwell flow of kLanesOf<Real> tetrahedra from offset `o` (viscoelastic.h's relaxMaxwellBranch):
// G = C + (G_v − C)·decay, C = FᵀF; G_v ← G det(G)^(−1/3), B_v ← adj(G) det(G)^(−2/3). A lane whose det(G)
// is not in [2^−126, 2^126] (inverted, or its volume changed 10^19-fold) keeps its rest state.
template <class Real, class Shape, class Stored, std::size_t N>
[[gnu::always_inline]] inline void relaxLanes(const Shape (&shape)[9][N], const Stored (&restInverse)[9][N],
                                               double decay, std::size_t o, Stored (&metric)[9][N],
                                               Stored (&inverse)[9][N]) {
  using Lanes = LanesOf<Real>;
  Lanes f[9];
  deformationGradientLanes<Real>(shape, restInverse, o, f);
  const auto dot = [&](int a, int b) { return f[3 * a] * f[3 * b] + f[3 * a + 1] * f[3 * b + 1] + f[3 * a + 2] * f[3 * b + 2]; };
  const Lanes c00 = dot(0, 0), c11 = dot(1, 1), c22 = dot(2, 2), c01 = dot(0, 1), c02 = dot(0, 2), c12 = dot(1, 2);
  const Real memory = Real(decay);
  const auto blend = [&](const Lanes& c, int entry) { return c + (loadLanes<Real>(&metric[entry][o]) - c) * memory; };
  const Lanes m00 = blend(c00, 0), m11 = blend(c11, 4), m22 = blend(c22, 8);
  const Lanes m01 = blend(c01, 3), m02 = blend(c02, 6), m12 = blend(c12, 7);
  const Lanes a00 = m11 * m22 - m12 * m12, a11 = m00 * m22 - m02 * m02, a22 = m00 * m11 - m01 * m01;
  const Lanes a01 = m02 * m12 - m01 * m22, a02 = m01 * m12 - m02 * m11, a12 = m01 * m02 - m00 * m12;
  const Lanes det = m00 * a00 + m01 * a01 + m02 * a02;
  Lanes scale;
  inverseCubeRootLanes<Real>(det, scale);
  const Lanes inverseScale = scale * scale;
  const auto flows = (det >= Real(0x1p-126)) & (det <= Real(0x1p126));  // per lane, all bits set where it flows
  const Lanes metricFlowed[9] = {m00, m01, m02, m01, m11, m12, m02, m12, m22};
  const Lanes inverseFlowed[9] = {a00, a01, a02, a01, a11, a12, a02, a12, a22};
  for (int e = 0; e < 9; ++e) {
    storeLanes<Real>(&metric[e][o], flows ? metricFlowed[e] * scale : loadLanes<Real>(&metric[e][o]));
    storeLanes<Real>(&inverse[e][o], flows ? inverseFlowed[e] * inverseScale : loadLanes<Real>(&inverse[e][o]));
  }
}

// x^(−1/2) per lane for x in [2^−126, 2^126]: the float bit trick 0x5f3759df − bits/2 (3.4 %), then Newton
// steps r ← r (3 − x r²)/2 (3.4 % → 2e-3 → 5e-6 → 3e-11 → rounding: three in float, four in double). Lanes
// outside that range give meaningless values; the caller masks them.
template <class Real>
[[gnu::always_inline]] inline void inverseSquareRootLanes(const LanesOf<Real>& x, LanesOf<Real>& root) {
  using FloatLanes = typename VectorOf<float, kLanesOf<Real> * sizeof(float)>::type;
  using Int32Lanes = typename VectorOf<std::int32_t, kLanesOf<Real> * sizeof(float)>::type;
  using Lanes = LanesOf<Real>;
  const Lanes low = x < Real(0x1p-126) ? Lanes{} + Real(0x1p-126) : x;
  const Lanes clamped = low > Real(0x1p126) ? Lanes{} + Real(0x1p126) : low;
  const FloatLanes single = __builtin_convertvector(clamped, FloatLanes);
  Int32Lanes bits;
  std::memcpy(&bits, &single, sizeof bits);
  const Int32Lanes guessBits = 0x5f3759df - (bits >> 1);
  FloatLanes guess;
  std::memcpy(&guess, &guessBits, sizeof guess);
  Lanes r = __builtin_convertvector(guess, Lanes);
  constexpr int steps = sizeof(Real) == sizeof(float) ? 3 : 4;
  for (int step = 0; step < steps; ++step) r = r * (Real(1.5) - Real(0.5) * clamped * (r * r));
  root = r;
}

// B_p = adj(G_p)/det(G_p) per lane (viscoelastic.h's plasticInverseOf), G_p as six entries in
// kSymmetricEntry's order, B_p as nine ([3·column + row]); G_p = I gives I exactly, and a lane of zeros
// (past the last tetrahedron) gives zeros.
template <class Real>
[[gnu::always_inline]] inline void plasticInverseOfLanes(const LanesOf<Real> (&m)[6], LanesOf<Real> (&inverse)[9]) {
  using Lanes = LanesOf<Real>;
  const Lanes a00 = m[1] * m[2] - m[5] * m[5], a11 = m[0] * m[2] - m[4] * m[4], a22 = m[0] * m[1] - m[3] * m[3];
  const Lanes a01 = m[4] * m[5] - m[3] * m[2], a02 = m[3] * m[5] - m[4] * m[1], a12 = m[3] * m[4] - m[0] * m[5];
  const Lanes det = m[0] * a00 + m[3] * a01 + m[4] * a02;
  const Lanes scale = Real(1) / (det > Real(0) ? det : Lanes{} + Real(1));
  const Lanes entries[9] = {a00, a01, a02, a01, a11, a12, a02, a12, a22};
  for (int e = 0; e < 9; ++e) inverse[e] = entries[e] * scale;
}

// The same from and to a block's arrays, for kLanesOf<Real> tetrahedra from offset `o`.
template <class Real, class Stored, std::size_t N>
[[gnu::always_inline]] inline void plasticInverseLanes(const Stored (&metric)[6][N], std::size_t o, Stored (&inverse)[9][N]) {
  LanesOf<Real> m[6], b[9];
  for (int e = 0; e < 6; ++e) m[e] = loadLanes<Real>(&metric[e][o]);
  plasticInverseOfLanes<Real>(m, b);
  for (int e = 0; e < 9; ++e) storeLanes<Real>(&inverse[e][o], b[e]);
}

// The long-term branch's flow of kLanesOf<Real> tetrahedra from offset `o` (viscoelastic.h's
// relaxLongTermBranch): with C̄ = det(C)^(−1/3) C, A = C̄ B_p and s² = 3/2 (tr A² − (tr A)²/3),
// G = G_p + w (C̄ − G_p) + r (I − G_p), w = flow (1 − s_y/s) where s > s_y, r = recovery elsewhere;
// G_p ← G det(G)^(−1/3). Only lanes that flow, or recover from a G_p that is not I, are written (so that a
// body that never yields keeps G_p = I bit for bit); a lane whose det C or det G is not in [2^−126, 2^126]
// keeps its G_p. Returns whether any lane was written.
template <class Real, class Shape, class Stored, std::size_t N>
[[gnu::always_inline]] inline bool flowLongTermLanes(const Shape (&shape)[9][N], const Stored (&restInverse)[9][N],
                                                      double yieldMeasure, double flow, double recovery, std::size_t o,
                                                      Stored (&metric)[6][N]) {
  using Lanes = LanesOf<Real>;
  Lanes f[9];
  deformationGradientLanes<Real>(shape, restInverse, o, f);
  const auto dot = [&](int a, int b) { return f[3 * a] * f[3 * b] + f[3 * a + 1] * f[3 * b + 1] + f[3 * a + 2] * f[3 * b + 2]; };
  const Lanes c00 = dot(0, 0), c11 = dot(1, 1), c22 = dot(2, 2), c01 = dot(0, 1), c02 = dot(0, 2), c12 = dot(1, 2);
  const Lanes detC = c00 * (c11 * c22 - c12 * c12) + c01 * (c02 * c12 - c01 * c22) + c02 * (c01 * c12 - c02 * c11);
  Lanes iso;
  inverseCubeRootLanes<Real>(detC, iso);
  const Lanes cb[6] = {c00 * iso, c11 * iso, c22 * iso, c01 * iso, c02 * iso, c12 * iso};  // C̄, kSymmetricEntry order
  Lanes g[6];
  for (int e = 0; e < 6; ++e) g[e] = loadLanes<Real>(&metric[e][o]);
  Lanes b[9];
  plasticInverseOfLanes<Real>(g, b);
  // A = C̄ B_p: A_rc = Σ_k C̄_rk B_kc.
  Lanes a[9];
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r)
      a[3 * c + r] = cb[kSymmetricEntry[r][0]] * b[3 * c] + cb[kSymmetricEntry[r][1]] * b[3 * c + 1] +
                     cb[kSymmetricEntry[r][2]] * b[3 * c + 2];
  const Lanes trace = a[0] + a[4] + a[8];
  Lanes traceOfSquare = Lanes{};
  for (int c = 0; c < 3; ++c)
    for (int r = 0; r < 3; ++r) traceOfSquare += a[3 * c + r] * a[3 * r + c];
  const Lanes squared = Real(1.5) * (traceOfSquare - trace * trace * Real(1.0 / 3.0));  // s²
  const Real yieldSquared = Real(yieldMeasure * yieldMeasure);
  const auto yields = squared > yieldSquared;
  Lanes inverseMeasure;
  inverseSquareRootLanes<Real>(yields ? squared : Lanes{} + Real(1), inverseMeasure);
  const Lanes w = yields ? Real(flow) * (Real(1) - Real(yieldMeasure) * inverseMeasure) : Lanes{};
  const Lanes r = yields ? Lanes{} : Lanes{} + Real(recovery);
  const Lanes identity[6] = {Lanes{} + Real(1), Lanes{} + Real(1), Lanes{} + Real(1), Lanes{}, Lanes{}, Lanes{}};
  Lanes m[6];
  for (int e = 0; e < 6; ++e) m[e] = g[e] + w * (cb[e] - g[e]) + r * (identity[e] - g[e]);
  const Lanes det = m[0] * (m[1] * m[2] - m[5] * m[5]) + m[3] * (m[4] * m[5] - m[3] * m[2]) +
                    m[4] * (m[3] * m[5] - m[4] * m[1]);
  Lanes scale;
  inverseCubeRootLanes<Real>(det, scale);
  const auto inRange = (det >= Real(0x1p-126)) & (det <= Real(0x1p126)) & (detC >= Real(0x1p-126)) & (detC <= Real(0x1p126));
  const auto notIdentity = (g[0] != Real(1)) | (g[1] != Real(1)) | (g[2] != Real(1)) | (g[3] != Real(0)) |
                           (g[4] != Real(0)) | (g[5] != Real(0));
  const auto active = inRange & ((w > Real(0)) | ((r > Real(0)) & notIdentity));
  bool any = false;
  for (std::size_t lane = 0; lane < kLanesOf<Real>; ++lane) any |= active[lane] != 0;
  if (!any) return false;
  for (int e = 0; e < 6; ++e) storeLanes<Real>(&metric[e][o], active ? m[e] * scale : g[e]);
  return true;
}

}  // namespace slime

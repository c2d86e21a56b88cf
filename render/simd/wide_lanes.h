// N floats computed together, written once for every width: GCC's vector extensions (+ − × ÷,
// comparisons giving masks, `mask ? a : b`) with the few operations they lack (rounding, square root,
// fused multiply-add, a mask's bits) for N = 8 (AVX2) and N = 16 (AVX-512). The floor's pattern and
// shading use them so that the pixels outside the slime's reach can be shaded 16 at a time where the
// processor has AVX-512 and 8 at a time where it has AVX2, with the same result in every lane:
// each operation is one IEEE operation per lane, and the build contracts nothing (-std=c++20
// without GNU extensions: no multiply-add unless asked for).
#pragma once

#if defined(__AVX2__) && defined(__FMA__)
#define SLIME_WIDE_LANES 1
#include <immintrin.h>

#include <cstdint>
#include <cstring>

namespace slime {

template <int N>
struct Wide {
  typedef float F __attribute__((vector_size(4 * N)));         // N floats
  typedef std::int32_t I __attribute__((vector_size(4 * N)));  // N integers; also a comparison's mask (−1 or 0)
  typedef std::uint32_t U __attribute__((vector_size(4 * N)));
};

// The widest the build has: 16 with AVX-512 (SLIME_WIDE_LANES_16), else 8.
#if defined(__AVX512F__)
#define SLIME_WIDE_LANES_16 1
constexpr int kWidestLanes = 16;
#else
constexpr int kWidestLanes = 8;
#endif

template <class F>
inline F splat(float value) {
  return F{} + value;
}
template <class F>
inline F loadLanes(const float* values) {
  F lanes;
  std::memcpy(&lanes, values, sizeof lanes);
  return lanes;
}
template <class F>
inline void storeLanes(float* values, F lanes) {
  std::memcpy(values, &lanes, sizeof lanes);
}
// a < b ? a : b and a > b ? a : b lane by lane (a NaN in either gives b, as minps and maxps).
template <class F>
inline F minLanes(F a, F b) {
  return a < b ? a : b;
}
template <class F>
inline F maxLanes(F a, F b) {
  return a > b ? a : b;
}
template <class F>
inline F absLanes(F a) {
  return a < 0.0f ? -a : a;
}

// ⌊x⌋, the nearest integer (ties to even), √x and a·b + c rounded once, lane by lane.
inline Wide<8>::F floorLanes(Wide<8>::F x) {
  return (Wide<8>::F)_mm256_round_ps((__m256)x, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
}
inline Wide<8>::F nearestLanes(Wide<8>::F x) {
  return (Wide<8>::F)_mm256_round_ps((__m256)x, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
}
inline Wide<8>::F sqrtLanes(Wide<8>::F x) { return (Wide<8>::F)_mm256_sqrt_ps((__m256)x); }
inline Wide<8>::F fmaLanes(Wide<8>::F a, Wide<8>::F b, Wide<8>::F c) {
  return (Wide<8>::F)_mm256_fmadd_ps((__m256)a, (__m256)b, (__m256)c);
}
// Lane i of a mask as bit i.
inline unsigned maskBits(Wide<8>::I mask) { return static_cast<unsigned>(_mm256_movemask_ps((__m256)mask)); }

#if defined(SLIME_WIDE_LANES_16)
// (The zero-masked forms: GCC 12 warns that the plain ones read an uninitialised vector.)
inline Wide<16>::F floorLanes(Wide<16>::F x) {
  return (Wide<16>::F)_mm512_maskz_roundscale_ps(0xFFFF, (__m512)x, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
}
inline Wide<16>::F nearestLanes(Wide<16>::F x) {
  return (Wide<16>::F)_mm512_maskz_roundscale_ps(0xFFFF, (__m512)x, _MM_FROUND_TO_NEAREST_INT | _MM_FROUND_NO_EXC);
}
inline Wide<16>::F sqrtLanes(Wide<16>::F x) { return (Wide<16>::F)_mm512_maskz_sqrt_ps(0xFFFF, (__m512)x); }
inline Wide<16>::F fmaLanes(Wide<16>::F a, Wide<16>::F b, Wide<16>::F c) {
  return (Wide<16>::F)_mm512_fmadd_ps((__m512)a, (__m512)b, (__m512)c);
}
inline unsigned maskBits(Wide<16>::I mask) {
  return static_cast<unsigned>(_mm512_cmpneq_epi32_mask((__m512i)mask, _mm512_setzero_si512()));
}
#endif

// e^x lane by lane: Cephes' expf (range reduction by ln 2, a degree-5 polynomial; within 2 ulp of
// libm's expf over [−87, 0], where the tracer uses it: absorption and haze).
template <class F>
inline F expLanes(F x) {
  using I = decltype(x < x);
  const F v = maxLanes(x, splat<F>(-87.0f));
  const F n = nearestLanes(v * 1.44269504088896341f);
  F r = v - n * 0.693359375f;
  r = r - n * -2.12194440e-4f;
  F p = splat<F>(1.9875691500e-4f);
  p = fmaLanes(p, r, splat<F>(1.3981999507e-3f));
  p = fmaLanes(p, r, splat<F>(8.3334519073e-3f));
  p = fmaLanes(p, r, splat<F>(4.1665795894e-2f));
  p = fmaLanes(p, r, splat<F>(1.6666665459e-1f));
  p = fmaLanes(p, r, splat<F>(5.0000001201e-1f));
  p = fmaLanes(p, r * r, r + 1.0f);
  const I scale = (__builtin_convertvector(n, I) + 127) << 23;
  return p * (F)scale;
}

}  // namespace slime
#endif

// Eight floats computed together: `Lanes` and its mask `LaneMask` read like scalar arithmetic and
// compile to AVX2 vector instructions where the build has them (else to loops over eight floats), so
// the tracer's per-ray formulas can be written once and run for a packet of rays at a time.
// Every operation is one IEEE operation per lane, rounded as its scalar counterpart (no fused
// multiply-adds unless asked for), so a result equals the scalar formula's bit for bit.
#pragma once

#include "render/simd/wide_lanes.h"

#include <glm/vec3.hpp>

#include <cmath>

#if defined(__AVX2__)
#include <immintrin.h>
#endif

namespace slime {

#if defined(__AVX2__)

struct LaneMask {
  __m256 bits;
  friend LaneMask operator&&(LaneMask a, LaneMask b) { return {_mm256_and_ps(a.bits, b.bits)}; }
  friend LaneMask operator||(LaneMask a, LaneMask b) { return {_mm256_or_ps(a.bits, b.bits)}; }
  friend LaneMask operator!(LaneMask a) { return {_mm256_xor_ps(a.bits, _mm256_castsi256_ps(_mm256_set1_epi32(-1)))}; }
  bool operator[](int i) const { return (_mm256_movemask_ps(bits) >> i) & 1; }
  unsigned mask() const { return static_cast<unsigned>(_mm256_movemask_ps(bits)); }  // lane i: bit i
};

struct Lanes {
  __m256 v;
  Lanes() : v(_mm256_setzero_ps()) {}
  Lanes(float all) : v(_mm256_set1_ps(all)) {}  // a scalar stands for all eight lanes
  explicit Lanes(__m256 lanes) : v(lanes) {}
  static Lanes load(const float* values) { return Lanes(_mm256_loadu_ps(values)); }
  void store(float* values) const { _mm256_storeu_ps(values, v); }
  float operator[](int i) const {
    alignas(32) float values[8];
    _mm256_store_ps(values, v);
    return values[i];
  }
  friend Lanes operator+(Lanes a, Lanes b) { return Lanes(_mm256_add_ps(a.v, b.v)); }
  friend Lanes operator-(Lanes a, Lanes b) { return Lanes(_mm256_sub_ps(a.v, b.v)); }
  friend Lanes operator*(Lanes a, Lanes b) { return Lanes(_mm256_mul_ps(a.v, b.v)); }
  friend Lanes operator/(Lanes a, Lanes b) { return Lanes(_mm256_div_ps(a.v, b.v)); }
  friend Lanes operator-(Lanes a) { return Lanes(_mm256_xor_ps(a.v, _mm256_set1_ps(-0.0f))); }
  friend LaneMask operator<(Lanes a, Lanes b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_LT_OQ)}; }
  friend LaneMask operator<=(Lanes a, Lanes b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_LE_OQ)}; }
  friend LaneMask operator>(Lanes a, Lanes b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_GT_OQ)}; }
  friend LaneMask operator>=(Lanes a, Lanes b) { return {_mm256_cmp_ps(a.v, b.v, _CMP_GE_OQ)}; }
};

inline Lanes sqrt(Lanes a) { return Lanes(_mm256_sqrt_ps(a.v)); }
// a > b ? a : b and a < b ? a : b (a NaN in either gives b).
inline Lanes max(Lanes a, Lanes b) { return Lanes(_mm256_max_ps(a.v, b.v)); }
inline Lanes min(Lanes a, Lanes b) { return Lanes(_mm256_min_ps(a.v, b.v)); }
// mask ? a : b, lane by lane.
inline Lanes select(LaneMask mask, Lanes a, Lanes b) { return Lanes(_mm256_blendv_ps(b.v, a.v, mask.bits)); }

#else

// r.lane(i) = f(a[i], b[i]) for each of the eight lanes.
template <typename Result, typename Argument, typename F>
Result eachLane(const Argument& a, const Argument& b, F f) {
  Result r;
  for (int i = 0; i < 8; ++i) r.lane(i) = f(a[i], b[i]);
  return r;
}

struct LaneMask {
  bool bits[8] = {};
  friend LaneMask operator&&(LaneMask a, LaneMask b) { return eachLane<LaneMask>(a, b, [](bool x, bool y) { return x && y; }); }
  friend LaneMask operator||(LaneMask a, LaneMask b) { return eachLane<LaneMask>(a, b, [](bool x, bool y) { return x || y; }); }
  friend LaneMask operator!(LaneMask a) { return eachLane<LaneMask>(a, a, [](bool x, bool) { return !x; }); }
  bool operator[](int i) const { return bits[i]; }
  bool& lane(int i) { return bits[i]; }
  unsigned mask() const {  // lane i: bit i
    unsigned result = 0;
    for (int i = 0; i < 8; ++i) result |= static_cast<unsigned>(bits[i]) << i;
    return result;
  }
};

struct Lanes {
  float v[8] = {};
  Lanes() = default;
  Lanes(float all) {  // a scalar stands for all eight lanes
    for (float& x : v) x = all;
  }
  static Lanes load(const float* values) {
    Lanes r;
    for (int i = 0; i < 8; ++i) r.v[i] = values[i];
    return r;
  }
  void store(float* values) const {
    for (int i = 0; i < 8; ++i) values[i] = v[i];
  }
  float operator[](int i) const { return v[i]; }
  float& lane(int i) { return v[i]; }
  friend Lanes operator+(Lanes a, Lanes b) { return eachLane<Lanes>(a, b, [](float x, float y) { return x + y; }); }
  friend Lanes operator-(Lanes a, Lanes b) { return eachLane<Lanes>(a, b, [](float x, float y) { return x - y; }); }
  friend Lanes operator*(Lanes a, Lanes b) { return eachLane<Lanes>(a, b, [](float x, float y) { return x * y; }); }
  friend Lanes operator/(Lanes a, Lanes b) { return eachLane<Lanes>(a, b, [](float x, float y) { return x / y; }); }
  friend Lanes operator-(Lanes a) { return eachLane<Lanes>(a, a, [](float x, float) { return -x; }); }
  friend LaneMask operator<(Lanes a, Lanes b) { return eachLane<LaneMask>(a, b, [](float x, float y) { return x < y; }); }
  friend LaneMask operator<=(Lanes a, Lanes b) { return eachLane<LaneMask>(a, b, [](float x, float y) { return x <= y; }); }
  friend LaneMask operator>(Lanes a, Lanes b) { return eachLane<LaneMask>(a, b, [](float x, float y) { return x > y; }); }
  friend LaneMask operator>=(Lanes a, Lanes b) { return eachLane<LaneMask>(a, b, [](float x, float y) { return x >= y; }); }
};

inline Lanes sqrt(Lanes a) { return eachLane<Lanes>(a, a, [](float x, float) { return std::sqrt(x); }); }
inline Lanes max(Lanes a, Lanes b) { return eachLane<Lanes>(a, b, [](float x, float y) { return x > y ? x : y; }); }
inline Lanes min(Lanes a, Lanes b) { return eachLane<Lanes>(a, b, [](float x, float y) { return x < y ? x : y; }); }
inline Lanes select(LaneMask mask, Lanes a, Lanes b) {
  Lanes r;
  for (int i = 0; i < 8; ++i) r.v[i] = mask[i] ? a[i] : b[i];
  return r;
}

#endif

// e^x lane by lane: expLanes (render/simd/wide_lanes.h) where the build has AVX2 and FMA, else libm's.
inline Lanes exp(Lanes x) {
#if defined(SLIME_WIDE_LANES)
  return Lanes((__m256)expLanes((Wide<8>::F)x.v));
#else
  float values[8];
  x.store(values);
  for (float& value : values) value = std::exp(value);
  return Lanes::load(values);
#endif
}

// Three components of eight vectors.
struct Lanes3 {
  Lanes x, y, z;
};
inline Lanes dot(const Lanes3& a, const Lanes3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Lanes3 operator*(Lanes s, const Lanes3& a) { return {s * a.x, s * a.y, s * a.z}; }
inline Lanes3 operator+(const Lanes3& a, const Lanes3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Lanes3 operator-(const Lanes3& a, const Lanes3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Lanes3 operator-(const Lanes3& a) { return {-a.x, -a.y, -a.z}; }
inline Lanes3 select(LaneMask mask, const Lanes3& a, const Lanes3& b) {
  return {select(mask, a.x, b.x), select(mask, a.y, b.y), select(mask, a.z, b.z)};
}

// Eight vectors back in memory, read one at a time.
struct StoredLanes3 {
  explicit StoredLanes3(const Lanes3& lanes) {
    lanes.x.store(x);
    lanes.y.store(y);
    lanes.z.store(z);
  }
  glm::vec3 operator[](int i) const { return {x[i], y[i], z[i]}; }
  float x[8], y[8], z[8];
};

}  // namespace slime

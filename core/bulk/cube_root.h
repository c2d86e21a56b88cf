// x^(−1/3) in double precision, within 1 ulp of the correctly rounded value (over the unit test's
// samples glibc's std::cbrt was up to 3 ulps off, 1/std::cbrt up to 5), for the Maxwell branch's
// volume normalisation G_v / det^(1/3), B_v · det^(−2/3) (viscoelastic.h), where glibc's cbrt and
// its frexp/scalbn took as long as the rest of the flow. No division: a guess from the exponent
// divided by three, two fourth-order steps of the series r (1 − e)^(−1/3) = r (1 + e/3 + 2e²/9 +
// 14e³/81 + …), e = 1 − x r³ (3.4 % → 1e-5 → 1e-19), then one Newton step with e found to the last
// bit (r³ split into two doubles by fma), which leaves only the final rounding.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace slime {

// The bits of a positive double are nearly 2^52 (log2 x + 1023), so 2^52 · 1023·4/3 − bits/3 is
// nearly x^(−1/3); the offset 0.066·2^52 below that makes its worst error smallest (3.4 %).
constexpr std::uint64_t kInverseCubeRootGuessBits = 0x553ef1a9fbe76c00;

// x^(−1/3) for any positive finite x, subnormals too. No branch and no call, so a loop over
// elements vectorises (the guess divides the bits by three in double, which vector units can).
inline double inverseCubeRootOfPositive(double x) {
  const bool subnormal = x < std::numeric_limits<double>::min();
  const double scaled = subnormal ? x * 0x1p54 : x;  // then x^(−1/3) = scaled^(−1/3) · 2^18
  const double bitsOverThree =
      static_cast<double>(static_cast<std::int64_t>(std::bit_cast<std::uint64_t>(scaled))) * (1.0 / 3.0);
  double r = std::bit_cast<double>(kInverseCubeRootGuessBits -
                                   static_cast<std::uint64_t>(static_cast<std::int64_t>(bitsOverThree)));
  for (int step = 0; step < 2; ++step) {
    const double e = 1.0 - scaled * (r * r * r);
    r += r * e * (1.0 / 3.0 + e * (2.0 / 9.0 + e * (14.0 / 81.0)));
  }
  const double square = r * r;
  const double squareLow = std::fma(r, r, -square);
  const double cube = square * r;
  const double cubeLow = std::fma(square, r, -cube) + squareLow * r;
  const double e = std::fma(-scaled, cube, 1.0) - scaled * cubeLow;
  const double root = std::fma(r * e, 1.0 / 3.0, r);
  return subnormal ? root * 0x1p18 : root;
}

// x^(−1/3) for any x: zero, negative, infinite and NaN arguments take the library's 1/std::cbrt.
inline double inverseCubeRoot(double x) {
  if (!(x > 0.0 && x <= std::numeric_limits<double>::max())) return 1.0 / std::cbrt(x);
  return inverseCubeRootOfPositive(x);
}

}  // namespace slime

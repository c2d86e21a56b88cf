// The tensile tests' oracle, written from the formula, independently of the bench's tensileClosedForm:
// the standard linear solid's nominal stress under a constant strain rate ε̇ (issue 29, item 5),
//   σ = E∞·ε + E₁·ε̇·τ·(1 − exp(−ε / (ε̇·τ))),   E∞ = 2μ∞(1 + ν), E₁ = 2μ₁(1 + ν).
#pragma once

#include "core/settings/settings.h"

#include <cmath>

namespace slime::fixture {

inline double standardLinearSolidStress(const SlimeSettings& s, double strain, double rate) {
  const double eInfinity = 2.0 * s.modulus * s.longTerm * (1.0 + s.poisson);
  const double eMaxwell = 2.0 * s.modulus * (1.0 - s.longTerm) * (1.0 + s.poisson);
  return eInfinity * strain + eMaxwell * rate * s.relaxation * (1.0 - std::exp(-strain / (rate * s.relaxation)));
}

}  // namespace slime::fixture

// The divergence guard's test: a state is bad when any position or velocity is NaN/inf, or a point
// moves faster than an absurd speed (the slime dropped from 10 cm lands at about 1.4 m/s).
#pragma once

#include "core/geometry/particle_state.h"

#include <string>

namespace slime {

constexpr double kAbsurdSpeed = 50.0;  // m/s

// Empty when the state is sound, otherwise what diverged, e.g. "NaN position at vertex 17".
std::string findDivergence(const ParticleState& state, double absurdSpeed = kAbsurdSpeed);

}  // namespace slime

// How small a step each integrator needs on this slime. The highest angular frequency ω_max of the
// undamped linearised system M⁻¹K (springs with their geometric stiffness at the rest shape) is
// found by power iteration; the damper's highest rate c_max by Gershgorin's bound on M⁻¹C.
// Stability limits on the test equation x'' + c x' + ω² x = 0:
//   symplectic Euler (and the seed's update, which is the same map):  h² ω² + 2 h c < 4,
//     i.e. h < 4 / (c + √(c² + 4 ω²))  (= 2/ω undamped);
//   rk4: |h λ| below ≈ 2.8 on both axes, so h < 2.78 / (ω + c);
//   xpbd with one pass per substep is stable for any h but its springs soften unless h ω ≲ 2:
//     it uses the undamped symplectic bound for accuracy;
//   implicit Euler: any h.
#pragma once

#include "core/integrators/integrators.h"
#include "core/geometry/particle_state.h"
#include "core/membrane/springs.h"

#include <vector>

namespace slime {

constexpr double kStabilitySafety = 0.8;  // fraction of the predicted limit actually used

// ω_max of M⁻¹K for the springs at `positions` (power iteration, deterministic start).
double highestFrequency(const SpringSet& springs, const std::vector<glm::dvec3>& positions,
                        const std::vector<double>& inverseMasses, int iterations = 60);

// Gershgorin bound of the explicit damper's highest rate, max_i w_i Σ_{s∋i} 2 k_d/|x_s|.
double highestDampingRate(const SpringSet& springs, const std::vector<glm::dvec3>& positions,
                          const std::vector<double>& inverseMasses, double damping);

// The largest step with which `integrator` stays stable (infinity for implicit Euler).
double largestStableStep(Integrator integrator, double omega, double dampingRate);

}  // namespace slime

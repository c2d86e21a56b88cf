// The local step of the bulk body's projective dynamics (projective_dynamics.h): every tetrahedron's
// target p_e = (μ∞ R + μ1 R U_v + (3λ/2) p_V) / (μ + 3λ/2) at the current positions, summed per node as
// w_e D_eᵀ p_e for the global solve's right-hand side, with the Maxwell rest stretch U_v flowing towards
// the current stretch first (once per step).
// The arithmetic runs in ElementReal lanes (element_real.h: 16 floats with AVX-512, 4 doubles on AVX2),
// as the explicit integrators' element pass does: the per-element state (R's quaternion, U_v) is stored
// in ElementReal, the corners are gathered and the sums scattered in double (node_quads.h).
#pragma once

#include "core/bulk/bulk_body.h"
#include "core/bulk/node_quads.h"

#include <glm/vec3.hpp>

#include <vector>

namespace slime {

// Per block of kTetLanes tetrahedra: the rotation of F as a unit quaternion (w, x, y, z; warm start
// of the next polar decomposition) and the Maxwell rest stretch as U_v − I (symmetric: 00, 11, 22, 01,
// 02, 12): a step's flow moves U_v by ~1e-6, which float keeps in U_v − I but rounds away in U_v
// (a relaxed twist stopped recovering at 0.1 % of it).
struct ProjectiveBlock {
  alignas(64) ElementReal rotation[4][kTetLanes] = {};
  alignas(64) ElementReal maxwellStretch[6][kTetLanes] = {};
};

// Σ_e w_e D_eᵀ p_e per node into `targets` (resized and overwritten), with w_e = V0 (2μ + 3λ) and
// D_e x = F, R found from each block's warm start (which it updates). `flows`: U_v ← U_v + (U − U_v)·flow,
// det U_v = 1 first (U = sym(RᵀF), flow = 1 − exp(−h/τ)). `quads`: scratch.
void projectiveTargets(const BulkBody& body, bool flows, double flow, std::vector<ProjectiveBlock>& blocks,
                       NodeQuads& quads, std::vector<glm::dvec3>& targets);

}  // namespace slime

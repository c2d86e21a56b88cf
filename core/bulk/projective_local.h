// The local step of the bulk body's projective dynamics (projective_dynamics.h): every tetrahedron's
// target p_e = (μ∞ R U_p + μ1 R U_v + (3λ/2) p_V) / (μ + 3λ/2) at the current positions, summed per node as
// w_e D_eᵀ p_e for the global solve's right-hand side, with the Maxwell rest stretch U_v flowing towards
// the current stretch first (once per step).
// The arithmetic runs in float lanes (16 with AVX-512, 8 with AVX2), the per-element state (R's quaternion,
// U_v − I) is stored in float, the corners are gathered and the sums scattered in double (node_quads.h),
// as the explicit integrators' element pass does in ElementReal (element_real.h).
#pragma once

#include "core/bulk/bulk_body.h"
#include "core/bulk/node_quads.h"

#include <glm/vec3.hpp>

#include <vector>

namespace slime {

// The local step's precision. Float on both kinds of processor, unlike ElementReal: its ~450 operations a
// tetrahedron outweigh the conversions at the gather and the scatter that made float lose on AVX2 for the
// element pass (docs/performance.md, issue 27, branch pdlocal: built for x86-64-v3, 8 float lanes took the
// local step 1.7× faster than 4 double lanes).
using ProjectiveReal = float;

// Per block of kTetLanes tetrahedra: the rotation of F as a unit quaternion (w, x, y, z; warm start
// of the next polar decomposition) and the Maxwell rest stretch as U_v − I (symmetric, in tet_lanes.h's
// kSymmetricEntry order: 00, 11, 22, 01, 02, 12): a step's flow moves U_v by ~1e-6, which float keeps in
// U_v − I but rounds away in U_v (a relaxed twist stopped recovering at 0.1 % of it).
// The long-term branch's plastic rest stretch U_p = √G_p (viscoelastic.h) is kept the same way, as
// U_p − I; its flow is the body's (relaxElements), which the solver reads back (loadPlastic).
struct ProjectiveBlock {
  alignas(64) ProjectiveReal rotation[4][kTetLanes] = {};
  alignas(64) ProjectiveReal maxwellStretch[6][kTetLanes] = {};
  alignas(64) ProjectiveReal plasticStretch[6][kTetLanes] = {};
};

// Σ_e w_e D_eᵀ p_e per node into `targets` (resized and overwritten), with w_e = V0 (2μ + 3λ) and
// p_e's long-term part μ∞ R U_p (R alone while `plastic` is false: every U_p is I), and
// D_e x = F, R found from each block's warm start (which it updates). `flows`: U_v ← U_v + (U − U_v)·flow,
// det U_v = 1 first (U = sym(RᵀF), flow = 1 − exp(−h/τ)). `quads`: scratch.
void projectiveTargets(const BulkBody& body, bool flows, double flow, bool plastic, std::vector<ProjectiveBlock>& blocks,
                       NodeQuads& quads, std::vector<glm::dvec3>& targets);

}  // namespace slime

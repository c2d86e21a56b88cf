// How far each tetrahedron is stretched elastically, the tearing criterion (issue 42 item 4): the
// largest principal stretch of the Maxwell branch's elastic part, F_e = F·U_v⁻¹ (U_v² = G_v, the
// branch's flowed rest metric). Its squares are the eigenvalues of F_e F_eᵀ = F B_v Fᵀ (symmetric, in
// the current configuration, its eigenvectors the principal directions now), the same as those of
// B_v·C. Pulled fast, the branch has no time to flow and the elastic stretch is the total one; pulled
// slowly, it flows (relaxation τ) and stays small where the rate is low: the criterion depends on the
// rate, as a slime's snapping does. With no Maxwell branch (slime.longTerm = 1) it is the total stretch.
// This one function is what tearing reads; a flow of the elastic branch (necking) changes what it
// should return, not its callers.
#pragma once

#include "core/bulk/bulk_body.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <vector>

namespace slime {

// λ_max² of F B_v Fᵀ of tetrahedron `tetrahedron` at positions `x`; its unit principal direction in
// `direction` when not null.
double elasticStretchSquared(const BulkBody& body, const std::vector<glm::dvec3>& x, std::size_t tetrahedron,
                             glm::dvec3* direction = nullptr);

struct MostStretched {
  std::size_t tetrahedron = 0;
  double stretch = 1.0;  // the largest principal elastic stretch
};

// The tetrahedron with the largest elastic stretch at the body's positions (the first of equals), among
// those stretched at least `atLeast`; none (stretch 1, tetrahedron 0) when no element is. An element whose
// tr(F B_v Fᵀ), a bound on λ_max², is under atLeast² or under the largest λ_max² so far is not solved
// (the check runs every few steps; at rest all the traces are 3).
MostStretched mostStretchedElement(const BulkBody& body, double atLeast = 0.0);

// How near a tetrahedron is to tearing, 1 where it tears: q = (λ_e − 1) / ((λ_tear − 1)(1 − D)), λ_e its elastic
// stretch above and D its long-term branch's damage (bulk_body.h's damage; 0 without slime.damage, where q ≥ 1
// is λ_e ≥ λ_tear). A strand drawn out slowly flows, so λ_e stays small, but where it has flowed past the damage
// stretch its crosslinks break (D → 1) and it tears at a smaller and smaller elastic stretch: broken through
// (D = 1), at any. Infinite where D = 1 and λ_e > 1.
double tearMeasure(const BulkBody& body, const std::vector<glm::dvec3>& x, std::size_t tetrahedron, double tearStretch);

// The damaged tetrahedron (D > 0) with the largest tear measure at the body's positions, among those with q ≥ 1;
// none (measure 0) without damage or when no damaged element tears.
struct MostTorn {
  std::size_t tetrahedron = 0;
  double measure = 0.0;
};
MostTorn mostTornDamagedElement(const BulkBody& body, double tearStretch);

// The largest eigenvalue of a symmetric 3×3 matrix (trigonometric closed form, Smith 1961) and, when
// `direction` is not null, its unit eigenvector.
double largestSymmetricEigenvalue(const glm::dmat3& m, glm::dvec3* direction = nullptr);

}  // namespace slime

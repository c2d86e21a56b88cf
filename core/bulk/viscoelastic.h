// The slime's material: a standard linear solid (Zener) in finite strain, per tetrahedron.
// An elastic branch (shear modulus μ∞) remembers the round rest shape, so the ball always comes back;
// a Maxwell branch (modulus μ1, viscosity η1 = μ1·τ) has a rest state that flows towards the current
// shape with relaxation time τ; a volumetric term keeps each element's volume (Lamé λ).
//
// Energy density, with F = Ds·Dm⁻¹, C = FᵀF, J = det F and B_v the inverse of the Maxwell branch's
// rest metric G_v (symmetric, det G_v = 1):
//   Ψ = μ∞/2 (tr C − 3) + λ'/2 (J − α)²  +  μ1/2 (tr(C·B_v) − 3) − μ1 (J − 1),   α = 1 + μ∞/λ'
// (stable neo-Hookean, Smith, de Goes & Kim 2018; Macklin & Müller 2021). Each branch is free of
// stress at its own rest state: the elastic one at F = I, the Maxwell one at F = U_v (U_v² = G_v),
// however far it has flowed. Its first Piola stress is
//   P = μ∞ F + λ'(J − α) cof F + μ1 (F B_v − cof F),
// and at small strain it is linear elasticity with shear modulus μ = μ∞ + μ1 and Lamé λ = λ' − μ.
// The Maxwell branch's flow (once per step Δt, exact for a strain held over the step):
//   G_v ← C + (G_v − C)·exp(−Δt/τ), then G_v ← G_v / det(G_v)^(1/3)  (the flow keeps the volume)
// which at small strain is ε_v' = (ε − ε_v)/τ, the standard linear solid; under a constant shear
// stress its creep has the time constant τ_c = τ (μ∞ + μ1)/μ∞.
//
// The long-term branch's rest shape yields (a Bingham-like viscoplastic flow, for strands that neck):
// its energy is μ∞/2 (tr(C·B_p) − 3) with B_p = G_p⁻¹ the inverse of a plastic rest metric G_p
// (symmetric, det 1, the identity at the start), free of stress at F = U_p. G_p flows towards the
// isochoric C̄ = J^(−2/3) C only while the branch's deviatoric elastic stretch passes a yield:
//   s = √(3/2 |dev(C̄·B_p)|²)   (an isochoric uniaxial stretch u: s = u² − 1/u, the Cauchy stress / μ∞),
//   Ġ_p = (1 − s_y/s)₊ (C̄ − G_p)/τ_p, kept at det G_p = 1,
// which for a uniaxial elastic stretch u is d ln u/dt = −(s − s_y)/(3 τ_p): Bingham's law in extension,
// ε̇_p = (σ − σ_y)/(3 η_p) with σ = μ∞ s, σ_y = μ∞ s_y and η_p = μ∞ τ_p. Below the yield G_p recovers
// towards the identity with time τ_r (the ball comes back over seconds; τ_r = 0: never). Held at a
// stretch λ above the yield, the elastic stretch decays from λ to u_y in closed form
// (plasticHoldTime). Nothing flows below the yield, so a body that never reaches it is the standard
// linear solid above, bit for bit.
#pragma once

#include "core/bulk/cube_root.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <vector>

namespace slime {

struct ViscoelasticMaterial {
  double longTermShear = 0.0;  // μ∞, Pa
  double maxwellShear = 0.0;   // μ1, Pa (0: purely elastic)
  double lameLambda = 0.0;     // λ of the linearised material, Pa
  double relaxationTime = 1.0; // τ, s
  bool plastic = false;        // the long-term branch's rest shape flows above the yield
  double yieldStretch = 2.0;   // u_y: the isochoric uniaxial elastic stretch at which it yields
  double plasticFlowTime = 1.0;  // τ_p, s: η_p = μ∞ τ_p
  double recoveryTime = 0.0;   // τ_r, s: G_p's return to the identity below the yield (0: none)
  double damageStretch = 0.0;  // λ_d: the plastic stretch past which the long-term branch breaks (0: never)
};

// Lamé λ for a shear modulus and a Poisson ratio: 2 μ ν / (1 − 2ν).
double lameLambdaFor(double shearModulus, double poisson);

// The creep time constant τ (μ∞ + μ1)/μ∞ of the material under a constant shear stress.
double creepTimeConstant(const ViscoelasticMaterial& material);

// One tetrahedron's rest data.
struct TetRest {
  glm::dmat3 restInverse{1.0};  // Dm⁻¹, Dm = [x1−x0, x2−x0, x3−x0] at rest
  double volume = 0.0;          // V0, m³
  glm::dmat3 forceMap{0.0};     // −V0 Dm⁻ᵀ: the nodal forces on nodes 1..3 are the columns of P·forceMap
};

TetRest makeTetRest(const glm::dvec3& x0, const glm::dvec3& x1, const glm::dvec3& x2, const glm::dvec3& x3);

// Deformation gradient F = Ds Dm⁻¹ of a tetrahedron at positions x0..x3.
inline glm::dmat3 deformationGradient(const TetRest& rest, const glm::dvec3& x0, const glm::dvec3& x1,
                                      const glm::dvec3& x2, const glm::dvec3& x3) {
  return glm::dmat3(x1 - x0, x2 - x0, x3 - x0) * rest.restInverse;
}

// cof F = ∂J/∂F: columns f1×f2, f2×f0, f0×f1 for F's columns f0, f1, f2.
inline glm::dmat3 cofactor(const glm::dmat3& f) {
  return glm::dmat3(glm::cross(f[1], f[2]), glm::cross(f[2], f[0]), glm::cross(f[0], f[1]));
}

// λ' = λ + μ∞ + μ1 and α = 1 + μ∞/λ' of the energy above.
inline double volumetricModulus(const ViscoelasticMaterial& m) { return m.lameLambda + m.longTermShear + m.maxwellShear; }
inline double restVolumeRatio(const ViscoelasticMaterial& m) { return 1.0 + m.longTermShear / volumetricModulus(m); }

// First Piola–Kirchhoff stress P of the material at F with the Maxwell inverse rest metric B_v.
inline glm::dmat3 firstPiolaStress(const ViscoelasticMaterial& material, const glm::dmat3& f,
                                   const glm::dmat3& maxwellInverse) {
  const double lambdaPrime = volumetricModulus(material);
  const glm::dmat3 cof = cofactor(f);
  const double j = glm::dot(f[0], cof[0]);
  glm::dmat3 p = material.longTermShear * f + (lambdaPrime * (j - restVolumeRatio(material))) * cof;
  if (material.maxwellShear > 0.0) p += material.maxwellShear * (f * maxwellInverse - cof);
  return p;
}

// The same with the long-term branch's inverse rest metric B_p: μ∞ F B_p in place of μ∞ F.
inline glm::dmat3 firstPiolaStress(const ViscoelasticMaterial& material, const glm::dmat3& f,
                                   const glm::dmat3& maxwellInverse, const glm::dmat3& plasticInverse) {
  return firstPiolaStress(material, f, maxwellInverse) + material.longTermShear * (f * plasticInverse - f);
}

// Energy density Ψ at F with B_v (and B_p), J/m³.
double energyDensity(const ViscoelasticMaterial& material, const glm::dmat3& f, const glm::dmat3& maxwellInverse);
double energyDensity(const ViscoelasticMaterial& material, const glm::dmat3& f, const glm::dmat3& maxwellInverse,
                     const glm::dmat3& plasticInverse);

// The yield measure s_y = u_y² − 1/u_y of a yield stretch u_y (s of an isochoric uniaxial stretch).
inline double yieldMeasure(double yieldStretch) { return yieldStretch * yieldStretch - 1.0 / yieldStretch; }

// The long-term branch's deviatoric elastic stretch s = √(3/2 (tr A² − (tr A)²/3)), A = C̄·B_p.
double deviatoricStretchMeasure(const glm::dmat3& f, const glm::dmat3& plasticInverse);

// The isochoric uniaxial stretch u ≥ 1 with u² − 1/u = s: s as a stretch (the yield stretch's scale).
double equivalentStretch(double measure);

// One flow of the long-term branch: the weights over Δt and the yield.
struct PlasticFlow {
  double yieldMeasure = 0.0;  // s_y
  double flow = 0.0;          // 1 − exp(−Δt/τ_p)
  double recovery = 0.0;      // 1 − exp(−Δt/τ_r), 0 without recovery
};
PlasticFlow plasticFlowOver(const ViscoelasticMaterial& material, double dt);

// B_p = G_p⁻¹ = adj(G_p)/det(G_p) of a plastic rest metric (the form tet_lanes.h's lanes use).
glm::dmat3 plasticInverseOf(const glm::dmat3& metric);

// The long-term branch's flow over Δt at F: G = G_p + w (C̄ − G_p) + r (I − G_p) with
// w = flow·(1 − s_y/s) above the yield (s > s_y) and r = recovery below it, then G_p = G det(G)^(−1/3).
// An element whose G is not positive keeps its G_p. (tet_lanes.h's flowLongTermLanes is the same per lane.)
glm::dmat3 relaxLongTermBranch(const glm::dmat3& f, const glm::dmat3& metric, const PlasticFlow& flow);

// The plastic stretch of a flowed rest metric: the isochoric uniaxial stretch λ ≥ 1 with the same trace,
// λ² + 2/λ = tr G_p (1 for G_p = I).
double plasticStretchOfTrace(double trace);

// The long-term branch's damage D of a flowed rest metric with trace tr G_p: 0 until its plastic stretch λ_p
// passes λ_d, then (λ_p − λ_d)/λ_d, 1 (broken through) from 2 λ_d; always 0 when λ_d = 0. The branch's stress
// is (1 − D) times its undamaged one (the element pass scales K_p), and tearing reads D (elastic_stretch.h).
double damageOfTrace(double trace, double damageStretch);

// The closed form of a bar held at a constant isochoric uniaxial stretch λ (F = diag(λ, λ^−½, λ^−½)) above
// the yield: the time its elastic stretch takes to decay from u0 (= λ at the hold's start, G_p = I) to u
// (u_y < u ≤ u0) under d ln u/dt = −(u² − 1/u − s_y)/(3 τ_p):
//   t = 3 τ_p ∫_u^u0 dv / (v³ − s_y v − 1) = 3 τ_p ∫_u^u0 dv / ((v − u_y)(v² + u_y v + 1/u_y)),
// in partial fractions (a logarithm and, as 4/u_y − u_y² is positive or negative, an arctangent or a
// logarithm). Its stress is μ∞ (u² − 1/u), decaying to the yield stress μ∞ s_y.
double plasticHoldTime(double yieldStretch, double flowTime, double u0, double u);

// The Maxwell branch's rest state: its metric G_v and the inverse B_v that the stress uses, kept
// together so that the flow inverts once (B_v = (G/s)⁻¹ = s·G⁻¹ after the blend G, s = det G^(1/3)).
struct MaxwellRest {
  glm::dmat3 metric{1.0};   // G_v, symmetric, det 1
  glm::dmat3 inverse{1.0};  // B_v = G_v⁻¹
};

// The Maxwell branch's flow over Δt (decay = exp(−Δt/τ)): the new rest state for the current F.
// An inverted element (det ≤ 0 after the blend) keeps its rest state this step. Inline and without
// branches or calls, so that bulk_body.cpp's loop over a block of elements vectorises.
inline MaxwellRest relaxMaxwellBranch(const glm::dmat3& f, const MaxwellRest& rest, double decay) {
  // G = C + (G_v − C)·decay with C = FᵀF (C_ij = f_i·f_j for F's columns), all symmetric: six entries.
  const glm::dmat3& g = rest.metric;
  const double c00 = glm::dot(f[0], f[0]), c11 = glm::dot(f[1], f[1]), c22 = glm::dot(f[2], f[2]);
  const double c01 = glm::dot(f[0], f[1]), c02 = glm::dot(f[0], f[2]), c12 = glm::dot(f[1], f[2]);
  const double m00 = c00 + (g[0][0] - c00) * decay, m11 = c11 + (g[1][1] - c11) * decay;
  const double m22 = c22 + (g[2][2] - c22) * decay, m01 = c01 + (g[0][1] - c01) * decay;
  const double m02 = c02 + (g[0][2] - c02) * decay, m12 = c12 + (g[1][2] - c12) * decay;
  // Its adjugate (cofactors) and determinant.
  const double a00 = m11 * m22 - m12 * m12, a11 = m00 * m22 - m02 * m02, a22 = m00 * m11 - m01 * m01;
  const double a01 = m02 * m12 - m01 * m22, a02 = m01 * m12 - m02 * m11, a12 = m01 * m02 - m00 * m12;
  const double det = m00 * a00 + m01 * a01 + m02 * a02;
  // G_v = G·det^(−1/3) and B_v = G_v⁻¹ = adj G · det^(1/3)/det = adj G · det^(−2/3). (An infinite det,
  // from an element already blown up, gives NaN, which the divergence guard catches.)
  const double scale = inverseCubeRootOfPositive(det);
  const double inverseScale = scale * scale;
  const glm::dmat3 metric = glm::dmat3(m00, m01, m02, m01, m11, m12, m02, m12, m22) * scale;
  const glm::dmat3 inverse = glm::dmat3(a00, a01, a02, a01, a11, a12, a02, a12, a22) * inverseScale;
  // An inverted element keeps its rest state this step (chosen entry by entry, which vectorises).
  const bool flows = det > 0.0;
  MaxwellRest flowed;
  for (int column = 0; column < 3; ++column)
    for (int row = 0; row < 3; ++row) {
      flowed.metric[column][row] = flows ? metric[column][row] : rest.metric[column][row];
      flowed.inverse[column][row] = flows ? inverse[column][row] : rest.inverse[column][row];
    }
  return flowed;
}

// Steps between the Maxwell branches' flow updates for the explicit step (issue 27): up to τ/60 (10 steps
// of 1 ms at the default τ = 0.6 s), never fewer than `fewest` and at most 16. A flow is exact over its
// interval for the strain at its end, so it lags the strain by up to one interval, an error ~ interval/τ:
// the measured creep time at the default changed by under 1 % (docs/performance.md, issue 27's element pass).
int maxwellFlowInterval(double relaxationTime, double dt, int fewest);

}  // namespace slime

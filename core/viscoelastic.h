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
#pragma once

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

// Energy density Ψ at F with B_v, J/m³.
double energyDensity(const ViscoelasticMaterial& material, const glm::dmat3& f, const glm::dmat3& maxwellInverse);

// The Maxwell branch's rest state: its metric G_v and the inverse B_v that the stress uses, kept
// together so that the flow inverts once (B_v = (G/s)⁻¹ = s·G⁻¹ after the blend G, s = det G^(1/3)).
struct MaxwellRest {
  glm::dmat3 metric{1.0};   // G_v, symmetric, det 1
  glm::dmat3 inverse{1.0};  // B_v = G_v⁻¹
};

// The Maxwell branch's flow over Δt (decay = exp(−Δt/τ)): the new rest state for the current F.
// An inverted element (det ≤ 0 after the blend) keeps its rest state this step.
MaxwellRest relaxMaxwellBranch(const glm::dmat3& f, const MaxwellRest& rest, double decay);

}  // namespace slime

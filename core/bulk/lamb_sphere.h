// Free vibrations of a homogeneous, isotropic elastic sphere (Lamb 1882), the oracle for the bulk
// body. Dimensionless frequency η = ωR/c_s, c_s = √(G/ρ) the shear wave speed.
//  - Torsional modes of degree n: (n − 1) j_n(η) − η j_(n+1)(η) = 0 (no dependence on ν);
//    n = 2: η = 2.5011, 7.136, 10.515.
//  - Spheroidal modes of degree n: the displacement u = ∇φ + ∇×∇×(x ψ), φ = A j_n(αr) Y_n,
//    ψ = B j_n(βr) Y_n (α = ω/c_p, β = ω/c_s), i.e. u = U(r) Y r̂ + V(r) ∇_s Y with
//    U = A f' + B n(n+1) g/r and V = A f/r + B (g/r + g'); a stress-free surface, σ_rr = σ_rθ = 0
//    at r = R, is a 2×2 homogeneous system whose determinant vanishes at the mode frequencies
//    (spheroidalDeterminant). It depends on the Poisson ratio ν through c_p/c_s = √(2(1−ν)/(1−2ν)).
// j_n is the spherical Bessel function of the first kind (std::sph_bessel).
#pragma once

#include <glm/vec3.hpp>

namespace slime {

// (n − 1) j_n(η) − η j_(n+1)(η).
double torsionalCharacteristic(int degree, double eta);

// The 2×2 boundary determinant of the spheroidal modes of degree n at η for Poisson ratio ν.
double spheroidalDeterminant(int degree, double eta, double poisson);

// The lowest root above `from` of the torsional (spheroidal = false) or spheroidal characteristic
// function, found by scanning in steps of 0.01 and bisecting the first sign change.
double lambRoot(int degree, bool spheroidal, double poisson, double from = 0.5);

// The mode shapes at the point x (relative to the centre) of a ball of radius R, for degree 2 and
// azimuthal order 0 (axis z), unnormalised; η from lambRoot.
glm::dvec3 torsionalModeShape(const glm::dvec3& x, double radius, double eta);
glm::dvec3 spheroidalModeShape(const glm::dvec3& x, double radius, double eta, double poisson);

}  // namespace slime

// The pure arithmetic of the modal oracles on plain per-node arrays, shared by `slime bench material`
// (bench_modes, bench_damping) and the peers (app/bench/peers/, which link no Simulation): Lamb's n = 2
// mode shape at a body's rest nodes, the mode's amplitude by mass-weighted projection, and the
// frequency and damping ratio fitted to the sampled amplitude.
#pragma once

#include <glm/vec3.hpp>

#include <vector>

namespace slime {

// Takes the rigid motion out of per-node vectors (as velocities, or as forces per unit mass):
// afterwards Σ m u = 0 and Σ m (X − c) × u = 0, so a mode shape starts no drift or spin and a load
// pushes and turns the body as a whole by nothing.
void removeRigidMotion(const std::vector<double>& masses, const std::vector<glm::dvec3>& rest,
                       std::vector<glm::dvec3>& vectors);

// Lamb's n = 2 mode shape (axis z) at the rest nodes of a ball of `radius` about `centre`, its largest
// value 1, rigid motion removed; η from lambRoot (core/bulk/lamb_sphere.h).
std::vector<glm::dvec3> lambModeShape(const std::vector<glm::dvec3>& rest, const std::vector<double>& masses,
                                      const glm::dvec3& centre, double radius, bool spheroidal, double eta,
                                      double poisson);

// The least-squares a of u − origin ≈ a ψ in the mass norm, Σ m (u − origin)·ψ / Σ m ψ·ψ (origin:
// none, or the rest positions). Of positions it is the mode's amplitude (m, where ψ is largest), of
// velocities its rate ȧ.
double massProjection(const std::vector<glm::dvec3>& u, const std::vector<glm::dvec3>* origin,
                      const std::vector<glm::dvec3>& shape, const std::vector<double>& masses);

// The frequency of a sampled signal from its zero crossings (linear interpolation between samples):
// (crossings − 1) / (2 (last − first)); 0 with fewer than three crossings.
double zeroCrossingFrequency(const std::vector<double>& t, const std::vector<double>& y);

// The damping ratio of a mode sampled as amplitude a and rate ȧ: its energy E = ω²a² + ȧ² decays as
// exp(−2ζωt), so ζ = −slope(ln E) / (2ω), the slope a least-squares fit over the samples.
double energyDampingRatio(const std::vector<double>& t, const std::vector<double>& amplitude,
                          const std::vector<double>& rate, double omega);

}  // namespace slime

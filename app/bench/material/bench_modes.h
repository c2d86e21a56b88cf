// The free elastic ball and its n = 2 modes (Lamb 1882), shared by `slime bench material`'s oracles:
// Lamb's frequencies, creep and recovery, energy drift, and the integrators' numerical damping.
#pragma once

#include "core/simulation/simulation.h"
#include "app/bench/material/modal_fit.h"
#include "core/settings/settings.h"

#include <glm/vec3.hpp>

#include <vector>

namespace slime {

// A free, undamped, weightless ball: the elastic limit Lamb's oracle is about (longTerm = 1, no
// viscosity, no gravity) at `resolution`, its centre at least a diameter above the floor.
Settings elasticBall(const Settings& base, int resolution);

// Lamb's n = 2 mode shape (axis z) at the body's rest nodes, its largest value 1, rigid motion removed.
std::vector<glm::dvec3> modeShape(const Simulation& simulation, bool spheroidal, double eta);

// The mode's amplitude in the current state: the least-squares a of x − X ≈ a ψ in the mass norm,
// Σ m (x − X)·ψ / Σ m ψ·ψ (m; with ψ's largest value 1, the displacement where the mode moves most).
double modalAmplitude(const Simulation& simulation, const std::vector<glm::dvec3>& shape);

// The same projection of the velocities: the mode's rate ȧ, m/s.
double modalVelocity(const Simulation& simulation, const std::vector<glm::dvec3>& shape);

// f = η √(G/ρ) / (2πR), ρ = mass / volume of the tetrahedral ball, Hz.
double lambTheoryHz(const Simulation& simulation, double eta);

}  // namespace slime

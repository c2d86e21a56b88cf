// sim.integrator=auto, the default: which integrator steps the slime (issue 27).
//
// symplectic_euler keeps the slime's jiggle (numerical damping ζ ~ 1e-5, Lamb's frequencies within
// 1–4 %), but its substeps grow as √(G/ρ): a 100 kPa slime needs 7 a millisecond, a 100 kPa one of
// 10 g needs 34. projective (backward Euler) costs the same whatever the material, and damps a mode ω by
// ζ ≈ ωh/2. So auto takes projective where that damping cannot be seen: for a bulk slime whose slowest
// jiggle, Lamb's torsional n = 2 mode of the rest ball (lamb_sphere.h), is faster than half the
// viewer's 60 frames a second (Nyquist: a faster swing cannot be shown, only aliased); everywhere else
// symplectic_euler. Projective has no sticky floor yet, so auto keeps symplectic_euler where the floor's
// adhesion σ_a could still be seen: a stuck patch strains the body by about σ_a / G, and under a tenth
// (kUnseenAdhesionStrain) it neither pulls a strand nor spreads the base. The default slime jiggles at
// 10.9 Hz; a modulus above about 9 kPa, or a mass below about 35 g, crosses 30 Hz; with the default
// adhesion (8,000 Pa) auto takes projective from 80 kPa up (a 10 g slime at 1200 Pa stays explicit: its
// sticky floor stretches it when it is dragged).
// projective_midpoint (the implicit midpoint rule on projective's factorisation) is not chosen: at the
// guide's accuracy (Lamb's n = 2 modes within 5 %, numerical damping ≤ 0.02, rest height within 2 %) it
// needs about 10 local/global iterations a step, and measured at resolution 2 (docs/physics.md) it cost
// more than symplectic_euler wherever both met it: 0.19–0.20 ms per simulated ms at 8 ms against 0.08–0.09
// at the default slime, 4.3–5.2 against 1.7 at 100 kPa (1 ms: the stiff slime's ωh must stay near 0.6).
#pragma once

#include "core/integrators/integrators.h"
#include "core/settings/settings.h"

namespace slime {

// Half of 60 frames a second: the fastest swing a display at that rate can show.
constexpr double kShownJiggleHz = 30.0;
// The strain σ_a / G under which the sticky floor's pull on a slime cannot be seen.
constexpr double kUnseenAdhesionStrain = 0.1;

// Lamb's torsional n = 2 frequency, Hz, of the rest ball: η c_s / (2πR), c_s = √(G/ρ) with the
// instantaneous modulus G and ρ the mass over the ball's volume.
double slowestJiggleHz(const SlimeSettings& slime);

// sim.integrator, with "auto" resolved as above; another name is parsed as it is (parseIntegrator).
Integrator chooseIntegrator(const Settings& settings);

}  // namespace slime

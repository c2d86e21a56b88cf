// The tensile test of `slime bench material` (issue 29, item 5), as a rheometer would run it:
//  (a) a bar of the slime's material stretched at a constant strain rate ε̇, at three rates: a uniform
//      bar (one material point, its ends pulled apart, its sides free: F = diag(1 + ε, b, b) with b
//      found so that the lateral stress is zero) through the bulk body's own stress (firstPiolaStress)
//      and Maxwell flow (relaxMaxwellBranch), one flow per step as the body does. Its nominal stress
//      against strain is checked at small strain against the standard linear solid's closed form
//        σ = E∞·ε + E₁·ε̇·τ·(1 − exp(−ε / (ε̇·τ))),   E∞ = 2μ∞(1 + ν), E₁ = 2μ₁(1 + ν).
//      Not the tetrahedral cylinder the issue names: a uniform bar strains uniformly, so one point is
//      the whole bar (the ends' clamping, which a cylinder of elements would add, is left out).
//  (b) the slime itself, pulled apart by two hands at three speeds (each hand at half the speed, in
//      opposite directions, at mid-height): the hands' pull against the extension of the held parts.
#pragma once

#include "app/bench/bench_report.h"
#include "core/bulk/viscoelastic.h"
#include "core/settings/settings.h"

#include <nlohmann/json.hpp>

#include <vector>

namespace slime {

struct TensileOptions {
  std::vector<double> strainRates{0.05, 0.5, 5.0};  // 1/s: ε̇τ = 0.03, 0.3, 3 at the default τ = 0.6 s
  double maxStrain = 0.3;          // the bar is stretched to this engineering strain
  double checkStrain = 0.05;       // ... and checked against the closed form up to this one
  int barSteps = 3000;             // steps per bar run (the Maxwell flow once per step)
  std::vector<double> pullSpeeds{0.05, 0.1, 0.2};  // m/s, the hands' speed apart
  double pullExtension = 0.05;     // m, how far apart the hands move
  double settleSeconds = 1.0;      // the slime rests on the floor this long before the hands take it
};

// The material of the scene's slime, as the bulk body builds it (bulk_body.cpp).
ViscoelasticMaterial materialOf(const SlimeSettings& slime);

// The standard linear solid's nominal stress at strain ε under a constant strain rate (the formula above).
double tensileClosedForm(double strain, double strainRate, const SlimeSettings& slime);

// One bar run: nominal axial stress (Pa) at each strain in `strains` (ascending, from 0).
struct BarRun {
  std::vector<double> strains, stresses, lateralStretches;
};
BarRun stretchBar(const ViscoelasticMaterial& material, double strainRate, double maxStrain, int steps);

// Runs (a) and (b); rows of the bar series go to `bar` (rate, strain, stress, closed form) and of the
// pulls to `pull` (speed, extension, force). Returns the figures as JSON.
nlohmann::json runTensileBench(const Settings& settings, const TensileOptions& options, CsvTable& bar, CsvTable& pull);

}  // namespace slime

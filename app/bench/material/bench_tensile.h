// The tensile test of `slime bench material` (issue 29, item 5), as a rheometer would run it:
//  (a) a bar of the slime's material stretched at a constant strain rate ε̇, at three rates: a small
//      tetrahedral cylinder, its ends held and moved apart (bench_tensile_bar.h: the bulk body's own
//      elements, solved quasi-statically), its nominal stress against the strain of its middle half (an
//      extensometer's) checked at small strain against the standard linear solid's closed form
//        σ = E∞·ε + E₁·ε̇·τ·(1 − exp(−ε / (ε̇·τ))),   E∞ = 2μ∞(1 + ν), E₁ = 2μ₁(1 + ν);
//      beside it the reference: the uniform bar as one material point (F = diag(1 + ε, b, b) with b
//      found so that the lateral stress is zero, firstPiolaStress and relaxMaxwellBranch once per step),
//      which is what the cylinder's middle is when its ends' clamping does not reach it.
//  (b) the slime itself, pulled apart by two hands at three speeds (each hand at half the speed, in
//      opposite directions, at mid-height): the hands' pull against the extension of the held parts.
#pragma once

#include "app/bench/report/bench_report.h"
#include "app/bench/material/bench_tensile_bar.h"
#include "core/bulk/viscoelastic.h"
#include "core/settings/settings.h"

#include <nlohmann/json.hpp>

#include <vector>

namespace slime {

struct TensileOptions {
  std::vector<double> strainRates{0.05, 0.5, 5.0};  // 1/s: ε̇τ = 0.03, 0.3, 3 at the default τ = 0.6 s
  double maxStrain = 0.3;          // the bar is stretched to this engineering strain
  double checkStrain = 0.05;       // ... and checked against the closed form up to this one
  int barSteps = 3000;             // steps per uniform-point run (the Maxwell flow once per step)
  int meshedSteps = 300;           // steps per meshed-bar run (each a quasi-static balance, then the flow)
  MeshedBarOptions meshed;         // the cylinder: 1 cm radius, 8 cm long (4 diameters), 2 rings, 16 layers
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

// The columns of runTensileBench's tables.
CsvTable tensilePointTable();   // strain_rate, strain, stress_pa, closed_form_pa, lateral_stretch
CsvTable tensileMeshedTable();  // strain_rate, strain, gauge_strain, stress_pa, closed_form_pa, middle_width
CsvTable tensilePullTable();    // speed_m_s, extension_m, force_n

// Runs (a) and (b); rows of the uniform point go to `bar`, of the meshed cylinder to `meshed` (the
// closed form there at the gauge's strain and mean rate) and of the pulls to `pull`. Returns the
// figures as JSON.
nlohmann::json runTensileBench(const Settings& settings, const TensileOptions& options, CsvTable& bar,
                               CsvTable& meshed, CsvTable& pull);

}  // namespace slime

// `slime bench material`: the bulk body's material against oracles no one here wrote
// (docs/material.md).
//  - Lamb (1882): a free elastic ball (longTerm = 1, viscosity 0, no gravity, no floor) started in its
//    n = 2 torsional or spheroidal mode; the frequency of its modal coordinate against
//    f = η √(G/ρ) / (2πR), ρ = mass / volume of the tetrahedral ball, for each resolution.
//  - Creep and recovery of the whole body under a constant twist (a body force along the n = 2
//    torsional mode shape: isochoric, so only the shear modulus answers and the standard linear solid's
//    closed form holds for the whole body): the time constant against τ_c = τ (μ∞ + μ1)/μ∞.
//  - Energy drift of a free body in a large spheroidal oscillation with every dissipation off.
//  - The range of volume / rest volume over each run.
//  - The tensile test (bench_tensile.h): a bar at three strain rates against the standard linear
//    solid's closed form, and the slime pulled apart by two hands at three speeds.
//  - The integrators' numerical damping of Lamb's modes against the step (bench_damping.h).
#pragma once

#include "app/bench/material/bench_damping.h"
#include "app/bench/material/bench_tensile.h"
#include "app/bench/material/modal_fit.h"
#include "app/bench/report/bench_report.h"
#include "core/settings/settings.h"

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace slime {

struct MaterialBenchOptions {
  std::vector<int> resolutions{1, 2, 3};  // Lamb runs
  double lambPeriods = 8.0;               // simulated periods of the theoretical frequency per Lamb run
  double lambSpeed = 0.005;               // m/s, the largest initial speed of a Lamb run (small: linear)
  int creepResolution = 0;                // 0: the scene's slime.resolution
  double twistLoad = 0.75;                // m/s², the twist's body force per unit mass at its largest
  double settleSeconds = 1.0;             // elastic settling (Maxwell branch frozen) before creep and recovery
  double creepSeconds = 8.0;              // under load, then as long again unloaded
  bool recovery = true;                   // the unloaded half too
  double settleViscosity = 100.0;         // Pa·s: the dampers while the body settles (slime.viscosity's largest)
  bool automaticSubsteps = true;          // off: the creep runs at exactly sim.dt / sim.substeps (bench_front.h)
  double energySeconds = 10.0;
  double energySpeed = 0.1;               // m/s, the largest initial speed of the energy run (20× Lamb's)
  TensileOptions tensile;
  DampingOptions damping;
  std::string jsonFile;
  // FILE: the Lamb table; FILE_creep: the creep and recovery series; FILE_tensile: the uniform bar's
  // stress against strain; FILE_tensile_bar: the meshed cylinder's; FILE_pull: the two hands' force against extension; FILE_damping: the integrators'
  // numerical damping of Lamb's modes against the step.
  std::string csvFile;

  static MaterialBenchOptions quick();  // resolutions 1–2 and short runs (CI)
};

nlohmann::json runMaterialBench(const Settings& settings, const MaterialBenchOptions& options);

// Creep under a constant twist, then (options.recovery) recovery with the twist removed, at the
// scene's resolution (or options.creepResolution), integrator and step: {"creep": {material_tau_s,
// measured_tau_s, error, ...}, "recovery": ...} (docs/material.md). `series` gets the fitted series.
// A rollback of the divergence guard shows as "rollbacks" in both; with automaticSubsteps off the run
// stops at the first.
nlohmann::json measureCreep(const Settings& scene, const MaterialBenchOptions& options, CsvTable& series);

// y(t) ≈ asymptote + (initial − asymptote)·exp(−t/tau), least squares: for each τ the model is linear
// in (asymptote, initial − asymptote); τ by golden-section search on the residual over [tauLow, tauHigh].
struct ExponentialFit {
  double asymptote = 0.0;
  double initial = 0.0;
  double tau = 0.0;
  double rms = 0.0;  // root-mean-square residual, in y's units
};
ExponentialFit fitExponential(const std::vector<double>& t, const std::vector<double>& y, double tauLow,
                              double tauHigh);

}  // namespace slime

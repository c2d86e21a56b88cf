#include "app/bench/material/bench_material.h"

#include "app/bench/material/bench_damping.h"
#include "app/bench/material/bench_modes.h"
#include "app/bench/report/bench_report.h"
#include "app/bench/report/bench_timing.h"
#include "core/bulk/lamb_sphere.h"
#include "core/simulation/simulation.h"
#include "core/bulk/viscoelastic.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

namespace slime {
namespace {

using nlohmann::json;

constexpr double kFrozenRelaxation = 1000.0; // s: slime.relaxation's largest value, the Maxwell branch frozen
constexpr int kSeriesInterval = 10;         // steps between the creep series' samples
constexpr double kFitTauLow = 0.01, kFitTauHigh = 100.0;  // s

// The smallest and largest volume / rest volume seen over a run.
struct VolumeRange {
  double low = std::numeric_limits<double>::infinity();
  double high = -std::numeric_limits<double>::infinity();
  void add(const Simulation& simulation) {
    const double ratio = simulation.volume() / simulation.restVolume();
    low = std::min(low, ratio);
    high = std::max(high, ratio);
  }
  json toJson() const { return {{"min", low}, {"max", high}}; }
};

json lambRun(const Settings& base, int resolution, bool spheroidal, const MaterialBenchOptions& options) {
  Simulation simulation(elasticBall(base, resolution));
  const double eta = lambRoot(2, spheroidal, simulation.settings().slime.poisson);
  const double theory = lambTheoryHz(simulation, eta);
  const std::vector<glm::dvec3> shape = modeShape(simulation, spheroidal, eta);
  std::vector<glm::dvec3> velocities(shape.size());
  for (std::size_t i = 0; i < shape.size(); ++i) velocities[i] = options.lambSpeed * shape[i];
  simulation.setVelocities(velocities);

  VolumeRange volume;
  std::vector<double> times, amplitudes;
  const double seconds = options.lambPeriods / theory;
  const Stopwatch watch;
  while (simulation.time() < seconds) {
    simulation.step();
    times.push_back(simulation.time());
    amplitudes.push_back(modalAmplitude(simulation, shape));
    volume.add(simulation);
  }
  const double measured = zeroCrossingFrequency(times, amplitudes);
  const double largest = *std::max_element(amplitudes.begin(), amplitudes.end());
  return {{"mode", spheroidal ? "spheroidal_n2" : "torsional_n2"},
          {"resolution", resolution},
          {"nodes", simulation.state().size()},
          {"tetrahedra", simulation.elementCount()},
          {"eta", eta},
          {"density_kg_m3", simulation.settings().slime.mass / simulation.bulkBody().restVolume},
          {"theory_hz", theory},
          {"measured_hz", measured},
          {"error", measured / theory - 1.0},
          {"seconds", seconds},
          {"amplitude_mm", largest * 1e3},
          {"substeps", simulation.substepsPerStep()},
          {"wall_s", watch.milliseconds() * 1e-3},
          {"divergences", simulation.divergences().size()},
          {"volume_ratio", volume.toJson()}};
}

// Adds a constant force per unit mass over one step as the impulse it gives (v += a dt).
void push(Simulation& simulation, const std::vector<glm::dvec3>& acceleration, double scale) {
  std::vector<glm::dvec3> velocities = simulation.state().velocities;
  const double dt = simulation.settings().sim.dt;
  for (std::size_t i = 0; i < velocities.size(); ++i) velocities[i] += (scale * dt) * acceleration[i];
  simulation.setVelocities(velocities);
}

// The material switched between frozen (relaxation at its largest, strong dampers: the body settles
// elastically) and flowing (the scene's relaxation time and viscosity: the slime as it is).
void setPhase(Simulation& simulation, const Settings& scene, double settleViscosity, bool frozen) {
  Settings settings = simulation.settings();
  settings.slime.relaxation = frozen ? kFrozenRelaxation : scene.slime.relaxation;
  settings.slime.viscosity = frozen ? settleViscosity : scene.slime.viscosity;
  simulation.applySettings(settings);
}

struct PhaseRecord {
  std::vector<double> times, amplitudes;
  VolumeRange volume;
};

// Runs `seconds` with the twist load times scale(t) (t from the phase's start), sampling the twist
// every kSeriesInterval steps.
template <typename Scale>
PhaseRecord runPhase(Simulation& simulation, const std::vector<glm::dvec3>& load, Scale scale,
                     const std::vector<glm::dvec3>& shape, double seconds, bool stopAtRollback) {
  PhaseRecord record;
  const double start = simulation.time();
  const std::int64_t firstStep = simulation.stepCount();
  record.times.push_back(0.0);
  record.amplitudes.push_back(modalAmplitude(simulation, shape));
  const std::size_t rollbacks = simulation.divergences().size();
  while (simulation.time() - start < seconds - 0.5 * simulation.settings().sim.dt) {
    const double factor = scale(simulation.time() - start);
    if (factor != 0.0) push(simulation, load, factor);
    simulation.step();
    if (stopAtRollback && simulation.divergences().size() > rollbacks) break;
    record.volume.add(simulation);
    if ((simulation.stepCount() - firstStep) % kSeriesInterval == 0) {
      record.times.push_back(simulation.time() - start);
      record.amplitudes.push_back(modalAmplitude(simulation, shape));
    }
  }
  return record;
}

// Creep under a constant twist, then recovery with the twist removed. Before each, the body settles
// elastically with the Maxwell branch frozen, so the flowing phase starts from the standard linear
// solid's initial state (the instantaneous elastic response, no Maxwell flow yet) with nothing left
// swinging; then the relaxation time is switched to the scene's (applySettings keeps the Maxwell state)
// and the twist's amplitude a(t) fitted with a∞ + (a0 − a∞) exp(−t/τ).
}  // namespace

json measureCreep(const Settings& scene, const MaterialBenchOptions& options, CsvTable& series) {
  Settings settings = scene;
  settings.slime.model = "bulk";
  if (options.creepResolution > 0) settings.slime.resolution = options.creepResolution;
  settings.slime.level = std::max(settings.slime.resolution, 2);
  settings.sim.gravity = 0.0;
  settings.slime.position.z = std::max(settings.slime.position.z, 2.0 * settings.slime.radius);
  settings.slime.relaxation = kFrozenRelaxation;
  settings.slime.viscosity = options.settleViscosity;
  Simulation simulation(settings);
  simulation.setAutomaticSubsteps(options.automaticSubsteps);
  const bool stop = !options.automaticSubsteps;

  // The load: a body force along the n = 2 torsional mode (top and bottom twisted opposite ways about
  // z; no net force or torque). Its response is isochoric, so the non-relaxing volume terms take no part.
  const double eta = lambRoot(2, false, settings.slime.poisson);
  const std::vector<glm::dvec3> shape = modeShape(simulation, false, eta);
  std::vector<glm::dvec3> load(shape.size());
  for (std::size_t i = 0; i < shape.size(); ++i) load[i] = options.twistLoad * shape[i];

  ViscoelasticMaterial material = simulation.bulkBody().material;
  material.relaxationTime = scene.slime.relaxation;
  const double tauC = creepTimeConstant(material);
  const double longTerm = scene.slime.longTerm;

  // While frozen the load comes on (and goes off) smoothly over the first half of the settling, so
  // it hardly sets the body swinging, and the dampers take what it does.
  const double ramp = 0.5 * options.settleSeconds;
  auto rampUp = [ramp](double t) { return t < ramp ? 0.5 * (1.0 - std::cos(std::numbers::pi * t / ramp)) : 1.0; };
  auto rampDown = [&rampUp](double t) { return 1.0 - rampUp(t); };
  auto constant = [](double value) { return [value](double) { return value; }; };

  const Stopwatch watch;
  const double settle = options.settleViscosity;
  const PhaseRecord loading = runPhase(simulation, load, rampUp, shape, options.settleSeconds, stop);
  const double elastic = loading.amplitudes.back();  // a0 = σ/G0 in the twist's units
  const double settleSpeed = simulation.metrics().maxSpeed;
  setPhase(simulation, scene, settle, false);
  const PhaseRecord creep = runPhase(simulation, load, constant(1.0), shape, options.creepSeconds, stop);
  const bool recover = options.recovery && !(stop && !simulation.divergences().empty());
  setPhase(simulation, scene, settle, true);
  const PhaseRecord unloading =
      recover ? runPhase(simulation, load, rampDown, shape, options.settleSeconds, stop) : PhaseRecord{};
  setPhase(simulation, scene, settle, false);
  const PhaseRecord recovery =
      recover ? runPhase(simulation, load, constant(0.0), shape, options.creepSeconds, stop) : PhaseRecord{};

  // Normalised by a0: the closed form is creep 1/L − (1/L − 1) e^(−t/τc) (L = μ∞/G) and, after the
  // elastic part a0 springs back, recovery (creep(t1) − 1) e^(−t/τc).
  auto normalised = [elastic](std::vector<double> values) {
    for (double& v : values) v /= elastic;
    return values;
  };
  const std::vector<double> creepRatio = normalised(creep.amplitudes), recoveryRatio = normalised(recovery.amplitudes);
  const ExponentialFit creepFit = fitExponential(creep.times, creepRatio, kFitTauLow, kFitTauHigh);
  const ExponentialFit recoveryFit = fitExponential(recovery.times, recoveryRatio, kFitTauLow, kFitTauHigh);
  const double creepEnd = options.creepSeconds;
  auto closedCreep = [&](double t) { return 1.0 / longTerm - (1.0 / longTerm - 1.0) * std::exp(-t / tauC); };
  auto closedRecovery = [&](double t) { return (closedCreep(creepEnd) - 1.0) * std::exp(-t / tauC); };

  json creepSeries = json::array(), recoverySeries = json::array();
  for (std::size_t k = 0; k < creep.times.size(); ++k) {
    const double t = creep.times[k];
    const double fit = creepFit.asymptote + (creepFit.initial - creepFit.asymptote) * std::exp(-t / creepFit.tau);
    series.add({"creep", t, creepRatio[k], fit, closedCreep(t), creepFit.tau, tauC});
    if (k % 5 == 0) creepSeries.push_back({{"t_s", t}, {"twist", creepRatio[k]}, {"closed_form", closedCreep(t)}});
  }
  for (std::size_t k = 0; k < recovery.times.size(); ++k) {
    const double t = recovery.times[k];
    const double fit = recoveryFit.asymptote + (recoveryFit.initial - recoveryFit.asymptote) * std::exp(-t / recoveryFit.tau);
    series.add({"recovery", creepEnd + t, recoveryRatio[k], fit, closedRecovery(t), recoveryFit.tau, tauC});
    if (k % 5 == 0)
      recoverySeries.push_back({{"t_s", creepEnd + t}, {"twist", recoveryRatio[k]}, {"closed_form", closedRecovery(t)}});
  }
  VolumeRange volume = loading.volume;
  for (const VolumeRange* v : {&creep.volume, &unloading.volume, &recovery.volume}) {
    volume.low = std::min(volume.low, v->low);
    volume.high = std::max(volume.high, v->high);
  }
  const json common = {{"resolution", settings.slime.resolution},
                       {"nodes", simulation.state().size()},
                       {"load", "body force along the n=2 torsional mode, m/s^2 at its largest"},
                       {"load_m_s2", options.twistLoad},
                       {"elastic_twist_mm", elastic * 1e3},
                       {"settle_s", options.settleSeconds},
                       {"settle_max_speed_m_s", settleSpeed},
                       {"relaxation_s", scene.slime.relaxation},
                       {"long_term", longTerm},
                       {"wall_s", watch.milliseconds() * 1e-3},
                       {"simulated_s", simulation.time()},
                       {"substeps", simulation.substepsPerStep()},
                       {"rollbacks", simulation.divergences().size()},
                       {"volume_ratio", volume.toJson()}};
  json creepJson = {{"material_tau_s", tauC},
                    {"measured_tau_s", creepFit.tau},
                    {"error", creepFit.tau / tauC - 1.0},
                    {"start_ratio", creepFit.initial},
                    {"final_ratio_fit", creepFit.asymptote},
                    {"final_ratio_material", 1.0 / longTerm},
                    {"fit_rms", creepFit.rms},
                    {"seconds", options.creepSeconds},
                    {"units", "twist / elastic twist a0"},
                    {"series", creepSeries}};
  creepJson.update(common);
  json recoveryJson = {{"material_tau_s", tauC},
                       {"measured_tau_s", recoveryFit.tau},
                       {"error", recoveryFit.tau / tauC - 1.0},
                       {"start_ratio", recoveryFit.initial},
                       {"start_ratio_material", closedRecovery(0.0)},
                       {"final_ratio_fit", recoveryFit.asymptote},
                       {"fit_rms", recoveryFit.rms},
                       {"seconds", options.creepSeconds},
                       {"series", recoverySeries}};
  recoveryJson.update(common);
  if (!recover) recoveryJson = nullptr;
  return {{"creep", creepJson}, {"recovery", recoveryJson}};
}

namespace {

// Total energy, kinetic + elastic (less the elastic energy at rest), of a free body in a large
// spheroidal n = 2 oscillation with every dissipation off. Symplectic Euler's stored velocities are
// half a substep h behind its positions, so kinetic + elastic energy as stored (what metrics() gives)
// wobbles by about ωh/2 about a constant; the energy with the velocity at the positions' time,
// v + (h/2)·a, which the next step's velocity change gives (exactly with one substep), wobbles by
// O((ωh)²) only. The drift is the change of the mean energy from the first second to the last.
json energyRun(const Settings& scene, const MaterialBenchOptions& options) {
  Simulation simulation(elasticBall(scene, scene.slime.resolution));
  const double restEnergy = simulation.elasticEnergy();
  const double eta = lambRoot(2, true, simulation.settings().slime.poisson);
  const std::vector<glm::dvec3> shape = modeShape(simulation, true, eta);
  std::vector<glm::dvec3> velocities(shape.size());
  for (std::size_t i = 0; i < shape.size(); ++i) velocities[i] = options.energySpeed * shape[i];
  simulation.setVelocities(velocities);
  const std::vector<double>& w = simulation.bulkBody().freeInverseMasses;
  const double initial = simulation.metrics().kineticEnergy;
  const int substeps = simulation.substepsPerStep();

  VolumeRange volume;
  double largestStored = 0.0, largestCentred = 0.0, largestAmplitude = 0.0;
  const double window = std::min(1.0, 0.1 * options.energySeconds);  // s, averaged at either end
  double firstSum = 0.0, lastSum = 0.0;
  int firstCount = 0, lastCount = 0;
  std::vector<glm::dvec3> before = simulation.state().velocities;
  double elastic = simulation.elasticEnergy() - restEnergy, stored = initial;
  const Stopwatch watch;
  while (simulation.time() < options.energySeconds - 0.5 * simulation.settings().sim.dt) {
    const double time = simulation.time();
    simulation.step();
    // The energy at `time`, with the velocity there.
    const std::vector<glm::dvec3>& after = simulation.state().velocities;
    double kinetic = 0.0;
    for (std::size_t i = 0; i < after.size(); ++i) {
      const glm::dvec3 v = before[i] + (after[i] - before[i]) / (2.0 * substeps);
      kinetic += 0.5 * glm::dot(v, v) / w[i];
    }
    largestCentred = std::max(largestCentred, std::abs(kinetic + elastic - initial));
    largestStored = std::max(largestStored, std::abs(stored - initial));
    if (time < window) {
      firstSum += stored;
      ++firstCount;
    }
    if (time >= options.energySeconds - window) {
      lastSum += stored;
      ++lastCount;
    }
    before = after;
    elastic = simulation.elasticEnergy() - restEnergy;
    stored = simulation.metrics().kineticEnergy + elastic;
    largestAmplitude = std::max(largestAmplitude, std::abs(modalAmplitude(simulation, shape)));
    volume.add(simulation);
  }
  return {{"mode", "spheroidal_n2"},
          {"resolution", simulation.settings().slime.resolution},
          {"nodes", simulation.state().size()},
          {"seconds", options.energySeconds},
          {"initial_speed_m_s", options.energySpeed},
          {"amplitude_mm", largestAmplitude * 1e3},
          {"initial_energy_j", initial},
          {"final_energy_j", stored},
          {"drift", (lastSum / lastCount - firstSum / firstCount) / initial},
          {"drift_window_s", window},
          {"max_deviation", largestCentred / initial},
          {"max_deviation_stored", largestStored / initial},
          {"substeps", substeps},
          {"wall_s", watch.milliseconds() * 1e-3},
          {"volume_ratio", volume.toJson()}};
}

double squaredResidual(const std::vector<double>& t, const std::vector<double>& y, double tau,
                       ExponentialFit& fit) {
  // y ≈ c + d e, e = exp(−t/τ): the normal equations of (c, d).
  const double n = static_cast<double>(t.size());
  double se = 0.0, see = 0.0, sy = 0.0, sey = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double e = std::exp(-t[k] / tau);
    se += e;
    see += e * e;
    sy += y[k];
    sey += e * y[k];
  }
  const double determinant = n * see - se * se;
  const double d = determinant != 0.0 ? (n * sey - se * sy) / determinant : 0.0;
  const double c = (sy - d * se) / n;
  double sum = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double r = y[k] - c - d * std::exp(-t[k] / tau);
    sum += r * r;
  }
  fit.asymptote = c;
  fit.initial = c + d;
  fit.tau = tau;
  fit.rms = std::sqrt(sum / n);
  return sum;
}

}  // namespace

MaterialBenchOptions MaterialBenchOptions::quick() {
  MaterialBenchOptions options;
  options.resolutions = {1, 2};
  options.lambPeriods = 3.0;
  options.settleSeconds = 0.5;
  options.creepSeconds = 2.0;
  options.energySeconds = 1.0;
  options.tensile.barSteps = 1000;
  options.tensile.meshedSteps = 100;
  options.tensile.settleSeconds = 0.5;
  options.damping.resolution = 1;
  options.damping.steps = {0.001, 0.004};
  options.damping.projectiveIterations = {1, 3, 10};
  options.damping.periods = 3.0;
  return options;
}

ExponentialFit fitExponential(const std::vector<double>& t, const std::vector<double>& y, double tauLow,
                              double tauHigh) {
  ExponentialFit fit;
  if (t.size() < 3 || t.size() != y.size()) return fit;
  // Golden-section search on log τ.
  const double golden = (std::sqrt(5.0) - 1.0) / 2.0;
  double a = std::log(tauLow), b = std::log(tauHigh);
  double c = b - golden * (b - a), d = a + golden * (b - a);
  ExponentialFit scratch;
  double fc = squaredResidual(t, y, std::exp(c), scratch), fd = squaredResidual(t, y, std::exp(d), scratch);
  for (int iteration = 0; iteration < 100 && b - a > 1e-10; ++iteration) {
    if (fc < fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - golden * (b - a);
      fc = squaredResidual(t, y, std::exp(c), scratch);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + golden * (b - a);
      fd = squaredResidual(t, y, std::exp(d), scratch);
    }
  }
  squaredResidual(t, y, std::exp(0.5 * (a + b)), fit);
  return fit;
}

json runMaterialBench(const Settings& settings, const MaterialBenchOptions& options) {
  const Stopwatch watch;
  CsvTable lambTable{{"mode", "resolution", "nodes", "theory_hz", "measured_hz", "ratio"}, {}};
  json lamb = json::array();
  std::printf("Lamb n=2 modes (free elastic ball; theory f = eta sqrt(G/rho) / (2 pi R))\n");
  std::printf("%-14s %4s %6s %10s %12s %8s %17s\n", "mode", "res", "nodes", "theory Hz", "measured Hz", "error",
              "volume ratio");
  for (int resolution : options.resolutions) {
    for (bool spheroidal : {false, true}) {
      json run = lambRun(settings, resolution, spheroidal, options);
      std::printf("%-14s %4d %6zu %10.3f %12.3f %+7.2f%% %8.6f..%.6f\n", run["mode"].get<std::string>().c_str(),
                  resolution, run["nodes"].get<std::size_t>(), run["theory_hz"].get<double>(),
                  run["measured_hz"].get<double>(), 100.0 * run["error"].get<double>(),
                  run["volume_ratio"]["min"].get<double>(), run["volume_ratio"]["max"].get<double>());
      std::fflush(stdout);
      lambTable.add({run["mode"], resolution, run["nodes"], run["theory_hz"], run["measured_hz"],
                     run["measured_hz"].get<double>() / run["theory_hz"].get<double>()});
      lamb.push_back(std::move(run));
    }
  }

  CsvTable creepTable{{"phase", "t_s", "measured", "fit", "closed_form", "measured_tau_s", "material_tau_s"}, {}};
  const json creep = measureCreep(settings, options, creepTable);
  const json& c = creep["creep"];
  const json& r = creep["recovery"];
  std::printf("\nCreep under a constant twist (resolution %d), twist / elastic twist fitted a_inf + (a0 - a_inf) exp(-t/tau)\n",
              c["resolution"].get<int>());
  std::printf("  creep:    tau %.4f s (material tau_c %.4f s, %+.2f%%), a0 %.4f, a_inf %.4f (material %.4f), rms %.2e\n",
              c["measured_tau_s"].get<double>(), c["material_tau_s"].get<double>(), 100.0 * c["error"].get<double>(),
              c["start_ratio"].get<double>(), c["final_ratio_fit"].get<double>(), c["final_ratio_material"].get<double>(),
              c["fit_rms"].get<double>());
  std::printf("  recovery: tau %.4f s (%+.2f%%), start %.4f (material %.4f), end %.4f, rms %.2e\n",
              r["measured_tau_s"].get<double>(), 100.0 * r["error"].get<double>(), r["start_ratio"].get<double>(),
              r["start_ratio_material"].get<double>(), r["final_ratio_fit"].get<double>(), r["fit_rms"].get<double>());
  std::printf("  elastic twist %.4f mm, volume ratio %.6f..%.6f\n", c["elastic_twist_mm"].get<double>(),
              c["volume_ratio"]["min"].get<double>(), c["volume_ratio"]["max"].get<double>());
  std::fflush(stdout);

  const json energy = energyRun(settings, options);
  std::printf("\nEnergy, free spheroidal oscillation (resolution %d, %.1f mm), no dissipation, %.1f s:\n",
              energy["resolution"].get<int>(), energy["amplitude_mm"].get<double>(), energy["seconds"].get<double>());
  std::printf("  drift %+.4f%% (mean of the last %.1f s vs the first), largest deviation %.4f%% (time-centred)"
              " / %.4f%% (stored velocities), volume ratio %.6f..%.6f\n",
              100.0 * energy["drift"].get<double>(), energy["drift_window_s"].get<double>(), 100.0 * energy["max_deviation"].get<double>(),
              100.0 * energy["max_deviation_stored"].get<double>(), energy["volume_ratio"]["min"].get<double>(),
              energy["volume_ratio"]["max"].get<double>());

  CsvTable barTable = tensilePointTable(), meshedTable = tensileMeshedTable(), pullTable = tensilePullTable();
  const json tensile = runTensileBench(settings, options.tensile, barTable, meshedTable, pullTable);
  CsvTable dampingTable;
  const json damping = runDampingBench(settings, options.damping, dampingTable);

  const SlimeSettings& slime = settings.slime;
  json report = {{"machine", machineJson()},
                 {"material",
                  {{"modulus_pa", slime.modulus},
                   {"long_term", slime.longTerm},
                   {"relaxation_s", slime.relaxation},
                   {"poisson", slime.poisson},
                   {"mass_kg", slime.mass},
                   {"radius_m", slime.radius},
                   {"dt_s", settings.sim.dt},
                   {"integrator", settings.sim.integrator}}},
                 {"lamb", lamb},
                 {"creep", creep["creep"]},
                 {"recovery", creep["recovery"]},
                 {"energy_drift", energy},
                 {"tensile", tensile},
                 {"numerical_damping", damping},
                 {"wall_s", watch.milliseconds() * 1e-3}};
  if (!options.jsonFile.empty()) writeJsonFile(report, options.jsonFile);
  if (!options.csvFile.empty()) {
    writeCsvFile(lambTable, options.csvFile);
    writeCsvFile(creepTable, siblingCsvPath(options.csvFile, "creep"));
    writeCsvFile(barTable, siblingCsvPath(options.csvFile, "tensile"));
    writeCsvFile(meshedTable, siblingCsvPath(options.csvFile, "tensile_bar"));
    writeCsvFile(pullTable, siblingCsvPath(options.csvFile, "pull"));
    writeCsvFile(dampingTable, siblingCsvPath(options.csvFile, "damping"));
  }
  return report;
}

}  // namespace slime

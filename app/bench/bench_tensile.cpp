#include "app/bench/bench_tensile.h"

#include "core/scene/simulation.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace slime {
namespace {

using nlohmann::json;

constexpr double kHandRadiusFraction = 0.35;  // of the slime's radius: the viewer's grab (interaction.h)
constexpr int kPullSamples = 100;             // rows of each pull's series

// The lateral stress P_yy of the bar at axial stretch a and lateral stretch b (F = diag(a, b, b)).
double lateralStress(const ViscoelasticMaterial& material, double a, double b, const glm::dmat3& maxwellInverse) {
  const glm::dmat3 f(a, 0.0, 0.0, 0.0, b, 0.0, 0.0, 0.0, b);
  return firstPiolaStress(material, f, maxwellInverse)[1][1];
}

// Linear interpolation of y at x in a series with ascending x; NaN outside it.
double interpolate(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  for (std::size_t k = 1; k < xs.size(); ++k)
    if (xs[k - 1] <= x && x <= xs[k]) {
      const double span = xs[k] - xs[k - 1];
      return span > 0.0 ? ys[k - 1] + (ys[k] - ys[k - 1]) * (x - xs[k - 1]) / span : ys[k];
    }
  return std::numeric_limits<double>::quiet_NaN();
}

// One pull of the settled slime by two hands moving apart at `speed`, both grabbing at mid-height on
// opposite sides along x.
json pullRun(const Simulation& settled, double speed, const TensileOptions& options, CsvTable& table) {
  Simulation simulation = settled;
  const Settings& settings = simulation.settings();
  const SlimeMetrics before = simulation.metrics();
  glm::dvec3 centre(0.0);
  for (const glm::dvec3& p : simulation.positions()) centre += p;
  centre /= static_cast<double>(simulation.positions().size());
  const double reach = 2.0 * settings.slime.radius;
  const double radius = kHandRadiusFraction * settings.slime.radius;
  simulation.grab(centre - glm::dvec3(reach, 0.0, 0.0), radius, 0);
  simulation.grab(centre + glm::dvec3(reach, 0.0, 0.0), radius, 1);
  const glm::dvec3 start0 = simulation.grabbedPoint(0), start1 = simulation.grabbedPoint(1);
  const glm::dvec3 axis = glm::normalize(glm::dvec3(start1.x - start0.x, start1.y - start0.y, 0.0));
  const double startSeparation = glm::dot(start1 - start0, axis);
  const double dt = settings.sim.dt;
  const int steps = static_cast<int>(std::ceil(options.pullExtension / speed / dt));
  const int every = std::max(1, steps / kPullSamples);
  std::vector<double> extensions{0.0}, forces{0.0};
  double lowVolume = 1.0, highVolume = 1.0;
  for (int k = 1; k <= steps; ++k) {
    const double half = 0.5 * speed * k * dt;
    simulation.dragTo(start0 - half * axis, 0);
    simulation.dragTo(start1 + half * axis, 1);
    simulation.step();
    if (k % every != 0 && k != steps) continue;
    const double extension = glm::dot(simulation.grabbedPoint(1) - simulation.grabbedPoint(0), axis) - startSeparation;
    // The tension: each hand's pull along its own direction, averaged over the two hands.
    const double force = 0.5 * (glm::dot(simulation.handForce(1), axis) - glm::dot(simulation.handForce(0), axis));
    extensions.push_back(extension);
    forces.push_back(force);
    const double ratio = simulation.volume() / simulation.restVolume();
    lowVolume = std::min(lowVolume, ratio);
    highVolume = std::max(highVolume, ratio);
    table.add({speed, extension, force});
  }
  const SlimeMetrics after = simulation.metrics();
  return {{"speed_m_s", speed},
          {"seconds", steps * dt},
          {"hand_separation_m", startSeparation},
          {"extensions_m", extensions},
          {"forces_n", forces},
          {"final_extension_m", extensions.back()},
          {"final_force_n", forces.back()},
          {"width_before_m", before.width},
          {"width_after_m", after.width},
          {"divergences", simulation.divergences().size()},
          {"volume_ratio", {{"min", lowVolume}, {"max", highVolume}}}};
}

}  // namespace

ViscoelasticMaterial materialOf(const SlimeSettings& slime) {
  ViscoelasticMaterial material;
  material.longTermShear = slime.longTerm * slime.modulus;
  material.maxwellShear = (1.0 - slime.longTerm) * slime.modulus;
  material.lameLambda = lameLambdaFor(slime.modulus, slime.poisson);
  material.relaxationTime = slime.relaxation;
  return material;
}

double tensileClosedForm(double strain, double strainRate, const SlimeSettings& slime) {
  const double youngLongTerm = 2.0 * slime.longTerm * slime.modulus * (1.0 + slime.poisson);
  const double youngMaxwell = 2.0 * (1.0 - slime.longTerm) * slime.modulus * (1.0 + slime.poisson);
  const double rateTau = strainRate * slime.relaxation;
  return youngLongTerm * strain + youngMaxwell * rateTau * (1.0 - std::exp(-strain / rateTau));
}

BarRun stretchBar(const ViscoelasticMaterial& material, double strainRate, double maxStrain, int steps) {
  BarRun run;
  const double dt = maxStrain / strainRate / steps;
  const double decay = std::exp(-dt / material.relaxationTime);
  MaxwellRest rest;
  for (int k = 0; k <= steps; ++k) {
    const double strain = maxStrain * k / steps;
    const double a = 1.0 + strain;
    // The sides are free: the lateral stretch b with P_yy = 0, by bisection (P_yy grows with b).
    double low = 0.2, high = 2.0;
    for (int iteration = 0; iteration < 60; ++iteration) {
      const double middle = 0.5 * (low + high);
      (lateralStress(material, a, middle, rest.inverse) > 0.0 ? high : low) = middle;
    }
    const double b = 0.5 * (low + high);
    const glm::dmat3 f(a, 0.0, 0.0, 0.0, b, 0.0, 0.0, 0.0, b);
    run.strains.push_back(strain);
    run.stresses.push_back(firstPiolaStress(material, f, rest.inverse)[0][0]);  // nominal: force / rest area
    run.lateralStretches.push_back(b);
    rest = relaxMaxwellBranch(f, rest, decay);  // the flow over the step to the next strain
  }
  return run;
}

json runTensileBench(const Settings& settings, const TensileOptions& options, CsvTable& bar, CsvTable& pull) {
  const SlimeSettings& slime = settings.slime;
  const ViscoelasticMaterial material = materialOf(slime);
  json bars = json::array();
  std::printf("\nTensile test (a): a uniform bar of the material at a constant strain rate, nominal stress\n"
              "against the standard linear solid  E_inf e + E_1 rate tau (1 - exp(-e / (rate tau)))\n");
  std::printf("%10s %8s %14s %14s %16s\n", "rate 1/s", "rate*tau", "stress@5% Pa", "closed form Pa", "max error <=5%");
  for (double rate : options.strainRates) {
    const BarRun run = stretchBar(material, rate, options.maxStrain, options.barSteps);
    double worst = 0.0;
    for (std::size_t k = 0; k < run.strains.size(); ++k) {
      const double closed = tensileClosedForm(run.strains[k], rate, slime);
      bar.add({rate, run.strains[k], run.stresses[k], closed, run.lateralStretches[k]});
      if (run.strains[k] > 0.0 && run.strains[k] <= options.checkStrain + 1e-12)
        worst = std::max(worst, std::abs(run.stresses[k] - closed) / closed);
    }
    const double atCheck = interpolate(run.strains, run.stresses, options.checkStrain);
    const double closedAtCheck = tensileClosedForm(options.checkStrain, rate, slime);
    std::printf("%10.3f %8.3f %14.2f %14.2f %+15.2f%%\n", rate, rate * slime.relaxation, atCheck, closedAtCheck,
                100.0 * worst);
    bars.push_back({{"strain_rate", rate},
                    {"rate_tau", rate * slime.relaxation},
                    {"stress_at_check_pa", atCheck},
                    {"closed_form_at_check_pa", closedAtCheck},
                    {"stress_at_max_pa", run.stresses.back()},
                    {"max_relative_error", worst}});
  }

  // (b) the slime, settled on the floor, then pulled apart at each speed from the same state.
  Settings scene = settings;
  Simulation settled(scene);
  for (int k = 0; k < static_cast<int>(std::lround(options.settleSeconds / scene.sim.dt)); ++k) settled.step();
  json pulls = json::array();
  std::printf("\nTensile test (b): the slime pulled apart by two hands at mid-height (settled %.1f s first)\n",
              options.settleSeconds);
  std::printf("%10s %14s %14s %14s %12s\n", "speed m/s", "extension mm", "force N", "width mm", "divergences");
  for (double speed : options.pullSpeeds) {
    json run = pullRun(settled, speed, options, pull);
    std::printf("%10.3f %14.2f %14.3f %14.1f %12zu\n", speed, 1000.0 * run["final_extension_m"].get<double>(),
                run["final_force_n"].get<double>(), 1000.0 * run["width_after_m"].get<double>(),
                run["divergences"].get<std::size_t>());
    pulls.push_back(std::move(run));
  }
  // Faster pulls need more force: each pull's force at one extension all of them reached.
  double common = std::numeric_limits<double>::infinity();
  for (const json& run : pulls) common = std::min(common, run["final_extension_m"].get<double>());
  common *= 0.5;
  for (json& run : pulls)
    run["force_at_common_extension_n"] =
        interpolate(run["extensions_m"].get<std::vector<double>>(), run["forces_n"].get<std::vector<double>>(), common);
  std::printf("  force at %.1f mm of extension:", 1000.0 * common);
  for (const json& run : pulls) std::printf(" %.3f N (%.2f m/s)", run["force_at_common_extension_n"].get<double>(),
                                            run["speed_m_s"].get<double>());
  std::printf("\n");
  return {{"bar", bars},
          {"check_strain", options.checkStrain},
          {"max_strain", options.maxStrain},
          {"pulls", pulls},
          {"common_extension_m", common}};
}

}  // namespace slime

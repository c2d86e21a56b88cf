#include "app/bench/material/bench_tensile.h"

#include "core/simulation/simulation.h"

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

CsvTable tensilePointTable() { return {{"strain_rate", "strain", "stress_pa", "closed_form_pa", "lateral_stretch"}, {}}; }
CsvTable tensileMeshedTable() {
  return {{"strain_rate", "strain", "gauge_strain", "stress_pa", "closed_form_pa", "middle_width"}, {}};
}
CsvTable tensilePullTable() { return {{"speed_m_s", "extension_m", "force_n"}, {}}; }

json runTensileBench(const Settings& settings, const TensileOptions& options, CsvTable& bar, CsvTable& meshed,
                     CsvTable& pull) {
  const SlimeSettings& slime = settings.slime;
  const ViscoelasticMaterial material = materialOf(slime);
  json bars = json::array();
  MeshedBarOptions twiceAsLong = options.meshed;
  twiceAsLong.length *= 2.0;
  twiceAsLong.segments *= 2;
  std::printf("\nTensile test (a): a tetrahedral cylinder of the material, its ends held and pulled apart at a\n"
              "constant strain rate (quasi-static), nominal stress against the strain of its middle half, and the\n"
              "standard linear solid  E_inf e + E_1 rate tau (1 - exp(-e / (rate tau)))  at that strain and rate\n");
  std::printf("%9s %8s %13s %13s %14s %14s %14s %14s\n", "rate 1/s", "rate*tau", "gauge err<=5%", "grips err@5%",
              "grips 2x long", "point err<=5%", "stress@5% Pa", "closed form Pa");
  for (double rate : options.strainRates) {
    // The uniform material point: the reference for the cylinder's middle.
    const BarRun point = stretchBar(material, rate, options.maxStrain, options.barSteps);
    double pointWorst = 0.0;
    for (std::size_t k = 0; k < point.strains.size(); ++k) {
      const double closed = tensileClosedForm(point.strains[k], rate, slime);
      bar.add({rate, point.strains[k], point.stresses[k], closed, point.lateralStretches[k]});
      const double error = k == 0 ? 0.0 : point.stresses[k] / closed - 1.0;
      if (point.strains[k] > 0.0 && point.strains[k] <= options.checkStrain + 1e-12 &&
          std::abs(error) > std::abs(pointWorst))
        pointWorst = error;
    }
    // The meshed cylinder: the gauge's strain and its mean rate since the start (the gauge strains a
    // little faster than the grips, whose clamping holds the ends' lateral contraction).
    const MeshedBarRun run = stretchMeshedBar(material, rate, options.maxStrain, options.meshedSteps, options.meshed);
    double gaugeWorst = 0.0;
    for (std::size_t k = 0; k < run.strains.size(); ++k) {
      const double gauge = run.gaugeStrains[k];
      const double closed = k == 0 ? 0.0 : tensileClosedForm(gauge, rate * gauge / run.strains[k], slime);
      meshed.add({rate, run.strains[k], gauge, run.stresses[k], closed, run.middleWidths[k]});
      const double error = k == 0 ? 0.0 : run.stresses[k] / closed - 1.0;  // the signed error of largest size
      if (k > 0 && gauge <= options.checkStrain + 1e-12 && std::abs(error) > std::abs(gaugeWorst)) gaugeWorst = error;
    }
    const double closedAtCheck = tensileClosedForm(options.checkStrain, rate, slime);
    const double gripStress = interpolate(run.strains, run.stresses, options.checkStrain);
    const int longSteps = std::max(1, static_cast<int>(std::lround(options.meshedSteps * options.checkStrain / options.maxStrain)));
    const MeshedBarRun longer = stretchMeshedBar(material, rate, options.checkStrain, longSteps, twiceAsLong);
    const double gripLonger = longer.stresses.back();
    std::printf("%9.3f %8.3f %+12.2f%% %+12.2f%% %+13.2f%% %+13.2f%% %14.2f %14.2f\n", rate, rate * slime.relaxation,
                100.0 * gaugeWorst, 100.0 * (gripStress / closedAtCheck - 1.0), 100.0 * (gripLonger / closedAtCheck - 1.0),
                100.0 * pointWorst, gripStress, closedAtCheck);
    bars.push_back({{"strain_rate", rate},
                    {"rate_tau", rate * slime.relaxation},
                    {"closed_form_at_check_pa", closedAtCheck},
                    {"meshed_max_relative_error", gaugeWorst},
                    {"meshed_stress_at_check_pa", gripStress},
                    {"meshed_gauge_strain_at_check", interpolate(run.strains, run.gaugeStrains, options.checkStrain)},
                    {"meshed_grip_error_at_check", gripStress / closedAtCheck - 1.0},
                    {"meshed_twice_as_long_grip_error_at_check", gripLonger / closedAtCheck - 1.0},
                    {"meshed_stress_at_max_pa", run.stresses.back()},
                    {"meshed_middle_width_at_max", run.middleWidths.back()},
                    {"meshed_smallest_volume_ratio", run.smallestVolumeRatio},
                    {"meshed_newton_iterations", run.newtonIterations},
                    {"meshed_factorisations", run.factorisations},
                    {"stress_at_check_pa", interpolate(point.strains, point.stresses, options.checkStrain)},
                    {"stress_at_max_pa", point.stresses.back()},
                    {"max_relative_error", pointWorst}});
  }
  const CylinderMesh cylinder =
      makeCylinderTetMesh(options.meshed.radius, options.meshed.length, options.meshed.rings, options.meshed.segments);
  std::printf("  cylinder: %zu nodes, %zu tetrahedra, %.1f mm long, %.1f mm radius, cross-section %.1f mm^2\n",
              cylinder.mesh.positions.size(), cylinder.mesh.tetrahedra.size(), 1000.0 * cylinder.length,
              1000.0 * cylinder.radius, 1e6 * cylinder.crossSection);

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
          {"cylinder",
           {{"nodes", cylinder.mesh.positions.size()},
            {"tetrahedra", cylinder.mesh.tetrahedra.size()},
            {"length_m", cylinder.length},
            {"radius_m", cylinder.radius},
            {"rings", options.meshed.rings},
            {"segments", options.meshed.segments},
            {"cross_section_m2", cylinder.crossSection},
            {"steps", options.meshedSteps}}},
          {"check_strain", options.checkStrain},
          {"max_strain", options.maxStrain},
          {"pulls", pulls},
          {"common_extension_m", common}};
}

}  // namespace slime

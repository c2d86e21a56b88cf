// `slime bench physics`: what the slime's physics costs, where each integrator blows up, and how
// accurate each is for its cost, for the bulk body (slime.model=bulk, the default) beside the seed's
// membrane (slime.model=membrane) and the peers.
//  - cost: CPU ms per simulated second of the drop-and-grab (bench_trajectory_error.h: landing, floor
//    contact, a grab and a drag, with the automatic substeps the program uses) for the bulk body at
//    each drawn level and at each simulation resolution, the membrane at each level, Bullet's
//    btSoftBody measured here (peers/bullet_ball, when built) and Jolt's soft body quoted (SPEC §9);
//  - stability map (bench_stability.h): the largest stable dt against the bulk modulus for each bulk
//    integrator, beside Simulation::largestStableStep; the membrane's against spring stiffness;
//  - accuracy against cost (bench_trajectory_error.h): each integrator over several substeps against a
//    much smaller-step RK4 reference, and which integrator is cheapest for a given accuracy;
//  - roundness at rest of the settled default ball.
// Every figure is only as good as the machine is quiet: CPU time, medians, and the load average are
// written beside them.
#pragma once

#include "core/settings/settings.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace slime {

struct PhysicsBenchOptions {
  std::vector<int> levels{3, 4, 5, 6};             // drawn levels of the cost table (bulk, membrane, Bullet)
  std::vector<int> resolutions{1, 2, 3};           // bulk resolutions of the cost table, at the base level
  std::vector<std::string> integrators;            // empty: all five (the bulk body takes its three of them)
  double secondsPerMeasurement = 1.0;              // wall seconds of repeats per cost figure (at least one run)
  int stabilityLevel = 4;                          // drawn level of the stability maps (none if < 0)
  std::vector<double> moduli{50, 100, 200, 500, 1000, 2000, 5000, 1e4, 2e4, 5e4, 1e5};  // bulk map, Pa
  std::vector<double> stiffnesses{10, 20, 40, 80, 160, 320, 640, 1280};  // membrane map, k_e in N/m
  bool membrane = true;                            // the membrane's stability map and accuracy runs too
  int accuracyLevel = 4;                           // drawn level of the accuracy runs (none if < 0)
  std::vector<double> steps{5e-5, 1e-4, 2e-4, 5e-4, 1e-3, 2e-3, 5e-3};  // substeps h of the accuracy runs, s
  double settleSeconds = 2.0;                      // roundness at rest after this long (none if <= 0)
  std::string bulletProgram;                       // peers/bullet_ball; empty: next to this program, if built
  double bulletTetsSeconds = 2.0;                  // simulated seconds of peers/bullet_tets a resolution (0: skip)
  std::string jsonFile;
  std::string csvFile;
};

nlohmann::json runPhysicsBench(const Settings& settings, const PhysicsBenchOptions& options);

// The settings of one physics run: the model, level, integrator and step given, one substep,
// everything else as `base`.
Settings physicsSettings(const Settings& base, const std::string& model, int level, const std::string& integrator,
                         double dt);

// The integrators of `requested` that the bulk body runs (symplectic_euler, explicit_euler, rk4).
std::vector<std::string> bulkIntegrators(const std::vector<std::string>& requested);

// Which integrator reaches each RMS error target most cheaply, from accuracy runs of one model
// (entries with "integrator", "stable", "finished", "rms_error_mm", "cpu_s_per_simulated_s"). With
// `runnableOnly`, only the runs whose substep the program's automatic substeps would allow
// ("within_predicted_limit": h ≤ kStabilitySafety × Simulation::largestStableStep()) count.
nlohmann::json cheapestForAccuracy(const nlohmann::json& runs, const std::vector<double>& targetsMillimetres,
                                   bool runnableOnly = false);

}  // namespace slime

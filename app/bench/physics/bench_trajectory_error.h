// Two fixed scenarios of 0.5 s, both with a grab, a drag and a release:
//  - the drop and grab: the ball falls 2 cm onto the floor, its top is grabbed at 0.2 s and pulled up
//    3 cm and sideways 1 cm over 0.15 s, released at 0.4 s. It has landing, floor contact and a grab:
//    `slime bench physics` times it, with the program's automatic substeps, for the cost table;
//  - the pinch in the air: the ball, high above the floor, is pinched at its top at t = 0 (so every
//    run grabs the same points), droops from the pinch, is pulled the same way from 0.2 s and released
//    at 0.4 s. No contact: the accuracy runs use it, because the contact's decisions (which points
//    touch, stick or slip, which the grab takes) make the landing's trajectory no smooth function of
//    the step, and the bench measures that spread too (accuracy.<model>.landing).
// The error of a run is the distance of every drawn vertex from where a reference run puts it (RK4
// with a much smaller substep), sampled every 10 ms: its RMS over vertices and samples, and its
// maximum. The cost is CPU seconds (of the whole process, every thread) per simulated second. A run
// takes exactly the substep h it is given (automatic substeps off), unless it is the program's own
// setting (automatic substeps on): a run that blows up has no error, only the mark "unstable".
#pragma once

#include "core/settings/settings.h"

#include <glm/vec3.hpp>

#include <string>
#include <vector>

namespace slime {

constexpr double kScenarioSeconds = 0.5;     // s
constexpr double kSampleInterval = 0.01;     // s
constexpr double kGrabTime = 0.2;            // s, when the top is grabbed
constexpr double kMaxRunCpuSeconds = 40.0;   // a run slower than this is stopped and marked "too slow"

// CPU seconds used so far by every thread of this process (CLOCK_PROCESS_CPUTIME_ID): what a run
// costs on a machine shared with other jobs, which wall-clock time is not.
double processCpuSeconds();

struct Trajectory {
  std::vector<std::vector<glm::dvec3>> samples;  // drawn positions every kSampleInterval, from t = 0
  bool stable = true;
  bool finished = true;     // false: stopped at its CPU limit
  double wallSeconds = 0.0;
  double cpuSeconds = 0.0;  // process CPU time of the run
  double simulatedSeconds = 0.0;
  long steps = 0;
  int substeps = 1;         // substeps per step at the end of the run
  std::size_t simulatedPoints = 0;
  std::size_t drawnVertices = 0;
};

struct DropAndGrabOptions {
  bool inTheAir = false;           // true: the pinch in the air instead of the drop and grab
  bool automaticSubsteps = false;  // true: as many substeps as stability needs (the program's way)
  double maxCpuSeconds = kMaxRunCpuSeconds;  // stopped there (finished = false)
  bool keepSamples = true;  // false (timing only): the drawn surface is still placed every 10 ms, not kept
};

// Runs the drop-and-grab (or the pinch in the air) with steps of settings.sim.dt (which must divide kSampleInterval), each of
// settings.sim.substeps substeps unless options.automaticSubsteps.
Trajectory runDropAndGrab(const Settings& settings, const DropAndGrabOptions& options = {});

// The settings of a run whose substep is h: steps of `programStep` (the program's sim.dt) split into
// programStep / h substeps when h divides it, else steps of h with one substep. Throws when neither fits.
Settings withSubstep(Settings settings, double h, double programStep);

struct TrajectoryError {
  double rmsMillimetres = 0.0;
  double maxMillimetres = 0.0;
  double rmsBeforeGrabMillimetres = 0.0;  // over the samples before kGrabTime: the drop and the landing
};

TrajectoryError compareTrajectories(const Trajectory& run, const Trajectory& reference);

}  // namespace slime

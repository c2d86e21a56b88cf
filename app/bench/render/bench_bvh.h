// BVH update cost and the trace time after it, on a slime deformed by the physics: the ball settles
// on the floor, its top is grabbed and pulled up 5 cm (a grab-and-stretch), and every displayed
// frame (60 Hz) the BVH is either refitted (built once on the round ball) or rebuilt from scratch
// at LOW, MEDIUM or HIGH quality. At the most stretched frame the recorded slime queries of that
// frame are replayed through each BVH: does refitting slow tracing down as the slime deforms?
#pragma once

#include "app/bench/report/bench_progress.h"
#include "app/bench/report/bench_report.h"
#include "core/geometry/icosphere.h"
#include "core/settings/settings.h"

#include <glm/vec3.hpp>

#include <nlohmann/json.hpp>

#include <vector>

namespace slime {

struct BvhBenchOptions {
  int level = 4;
  int width = 734, height = 564;
  int replays = 10;  // timed replays of the frame's queries per method
  int threads = 0;   // 0: all cores
};

// The default slime handled as a person does: dropped from just above the floor, landed and settled
// for kStretchSettleSeconds, then grabbed at its top and pulled up 5 cm over 0.3 s and held 0.1 s. Its
// drawn surface at every displayed frame, kStretchFrameSeconds apart (frame 0: the start), into the
// positions of `frames`; its triangles into `triangles`.
constexpr double kStretchFrameSeconds = 1.0 / 60.0;
constexpr double kStretchSettleSeconds = 0.4;
constexpr double kStretchPullSeconds = 0.3;  // the pull after it (then held 0.1 s)
void stretchTrajectory(Settings settings, std::vector<std::vector<glm::dvec3>>& frames, std::vector<Triangle>& triangles);

// One JSON entry per update method; also appends rows to `table` (columns set by makeBvhTable).
nlohmann::json runBvhBench(const Settings& settings, const BvhBenchOptions& options, BenchProgress& progress,
                           CsvTable& table);

CsvTable makeBvhTable();

}  // namespace slime

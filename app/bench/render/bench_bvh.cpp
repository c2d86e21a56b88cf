#include "app/bench/render/bench_bvh.h"

#include "app/bench/render/bench_embree_replay.h"
#include "app/bench/render/bench_ray_log.h"
#include "app/bench/report/bench_timing.h"
#include "core/simulation/simulation.h"

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace slime {
namespace {

using nlohmann::json;

constexpr double kFrameSeconds = kStretchFrameSeconds;  // one displayed frame
constexpr double kSettleSeconds = kStretchSettleSeconds;  // the ball lands and settles before the grab
constexpr double kStretchSeconds = kStretchPullSeconds;     // the top is pulled up over this time...
constexpr double kHoldSeconds = 0.1;          // ...then held
constexpr double kStretchHeight = 0.05;       // m, the pull (more than half the ball's diameter)

// Bounding box extents (height / width) say how far the stretched slime is from round.
double aspectOf(const std::vector<glm::dvec3>& positions) {
  glm::dvec3 low(1e300), high(-1e300);
  for (const glm::dvec3& p : positions) {
    low = glm::min(low, p);
    high = glm::max(high, p);
  }
  const double width = std::max(high.x - low.x, high.y - low.y);
  return width > 0.0 ? (high.z - low.z) / width : 0.0;
}

double medianReplayMs(const EmbreeReplay& replay, const RayLog& log, int threads, int count) {
  replay.replay(log, threads);  // warm-up
  std::vector<double> samples;
  for (int i = 0; i < count; ++i) samples.push_back(replay.replay(log, threads).totalMs());
  return summarize(samples).median;
}

}  // namespace

void stretchTrajectory(Settings settings, std::vector<std::vector<glm::dvec3>>& frames, std::vector<Triangle>& triangles) {
  const double radius = settings.slime.radius;
  settings.slime.position = glm::dvec3(settings.slime.position.x, settings.slime.position.y, radius + 0.005);
  Simulation simulation(settings);
  triangles = simulation.triangles();
  frames.assign(1, simulation.positions());
  double nextFrame = kFrameSeconds;
  const auto runUntil = [&](double end, const auto& beforeStep) {
    while (simulation.time() < end - 1e-12) {
      beforeStep();
      simulation.step();
      if (simulation.time() + 1e-12 >= nextFrame) {
        frames.push_back(simulation.positions());
        nextFrame += kFrameSeconds;
      }
    }
  };
  runUntil(kSettleSeconds, [] {});
  // The grab takes the top of the slime as it has settled (a sagging slime's top is well below the
  // ball's), and the hand rises steadily, then holds.
  const std::vector<glm::dvec3>& settled = simulation.positions();
  const glm::dvec3 top = *std::max_element(settled.begin(), settled.end(),
                                           [](const glm::dvec3& a, const glm::dvec3& b) { return a.z < b.z; });
  if (!simulation.grab(top, 0.6 * radius)) throw std::runtime_error("bench stretch: the grab at the slime's top found no surface");
  const double start = simulation.time();
  runUntil(kSettleSeconds + kStretchSeconds + kHoldSeconds, [&] {
    const double pulled = std::min(1.0, (simulation.time() - start) / kStretchSeconds);
    simulation.dragTo(top + glm::dvec3(0.0, 0.0, pulled * kStretchHeight));
  });
}

CsvTable makeBvhTable() {
  return CsvTable{{"level", "faces", "method", "build_ms", "update_ms", "update_ms_max", "trace_round_ms",
                   "trace_deformed_ms", "trace_deformed_over_high"},
                  {}};
}

json runBvhBench(const Settings& baseSettings, const BvhBenchOptions& options, BenchProgress& progress, CsvTable& table) {
  Settings settings = baseSettings;
  settings.slime.level = options.level;
  settings.slime.shape = "mesh";
  const std::string label = "bvh level " + std::to_string(options.level);
  std::vector<Triangle> triangles;
  progress.advance(0.0, label + ": simulating the stretch");
  std::vector<std::vector<glm::dvec3>> frames;
  stretchTrajectory(settings, frames, triangles);
  progress.advance(10.0, label + ": recording rays");
  const std::vector<glm::dvec3>& round = frames.front();
  const std::vector<glm::dvec3>& stretched = frames.back();
  // The queries of the first (round, in the air) and the last (stretched) frame.
  const RayLog roundLog = recordSlimeQueries(settings, round, triangles, options.width, options.height);
  const RayLog stretchedLog = recordSlimeQueries(settings, stretched, triangles, options.width, options.height);
  progress.advance(4.0, label);

  json entries = json::array();
  double highTraceMs = 0.0;
  for (const BvhUpdate method : {BvhUpdate::RebuildHigh, BvhUpdate::RebuildMedium, BvhUpdate::RebuildLow, BvhUpdate::Refit}) {
    EmbreeReplay replay(options.threads, method);
    std::vector<double> builds;
    for (int i = 0; i < 3; ++i) builds.push_back(replay.build(round, triangles));
    const double traceRoundMs = medianReplayMs(replay, roundLog, options.threads, options.replays);
    std::vector<double> updates;
    for (std::size_t f = 1; f < frames.size(); ++f) updates.push_back(replay.update(frames[f]));
    const double traceDeformedMs = medianReplayMs(replay, stretchedLog, options.threads, options.replays);
    if (method == BvhUpdate::RebuildHigh) highTraceMs = traceDeformedMs;
    const TimingSummary update = summarize(updates);
    json entry = {{"level", options.level},
                  {"faces", triangles.size()},
                  {"method", bvhUpdateName(method)},
                  {"build_ms", summarize(builds).median},
                  {"update_ms", update.median},
                  {"update", toJson(update)},
                  {"frames", frames.size() - 1},
                  {"trace_round_ms", traceRoundMs},
                  {"trace_deformed_ms", traceDeformedMs},
                  {"trace_deformed_over_high", highTraceMs > 0.0 ? traceDeformedMs / highTraceMs : 0.0},
                  {"deformed_aspect", aspectOf(stretched)},
                  {"queries_deformed", stretchedLog.queries()}};
    table.add({options.level, triangles.size(), bvhUpdateName(method), entry["build_ms"], update.median, update.max,
               traceRoundMs, traceDeformedMs, entry["trace_deformed_over_high"]});
    entries.push_back(std::move(entry));
    progress.advance(4.0, label + ": " + bvhUpdateName(method));
  }
  return entries;
}

}  // namespace slime

// `slime bench render`: ray-tracing throughput of the renderer against what bounds it, at
// 734×564, depth 3, per subdivision level and thread count, measured in one run:
//  - the full frame (Renderer::render): ms/frame (median, min, max) and rays by kind;
//  - the limit: the same slime queries replayed through Embree alone (no shading, no floor);
//  - the seed's algorithm (render.backend=brute: bounding sphere + every triangle) where it finishes;
//  - the headline: the frame where the slime deforms and the camera moves (every pixel traced) at
//    734×564 and 1280×720, level 4, beside the Embree-only replay of that frame's queries;
//  - BVH refit vs rebuild at LOW/MEDIUM/HIGH on a slime stretched by the physics (bench_bvh.h).
#pragma once

#include "core/geometry/icosphere.h"
#include "core/settings/settings.h"

#include <nlohmann/json.hpp>

#include <string>
#include <utility>
#include <vector>

namespace slime {

struct RenderBenchOptions {
  std::vector<int> levels{0, 1, 2, 3, 4, 5, 6};
  std::vector<int> threads;        // empty: 1 and all cores
  int frames = 15;                 // timed frames per configuration
  int warmup = 2;                  // untimed frames first
  int width = 734;
  int height = 564;
  int depth = 3;
  int bruteMaxLevel = 4;           // the seed's algorithm at levels 0..this (-1: none)
  int bruteSamples = 3;            // timed brute-force frames at least (after one warm-up); below 3 the
                                   // headline is labelled a quick, indicative figure
  std::vector<int> bvhLevels{4, 6};  // levels of the refit-vs-rebuild measurement (empty: none)
  // The headline (issue 15): the deforming frame at these sizes, level headlineLevel, beside the
  // Embree-only replay of its queries (empty: none).
  std::vector<std::pair<int, int>> headlineSizes{{734, 564}, {1280, 720}};
  int headlineLevel = 4;
  std::string jsonFile;
  std::string csvFile;
};

// Runs everything, writes the JSON/CSV files the options name, prints a summary table; returns the report.
nlohmann::json runRenderBench(const Settings& settings, const RenderBenchOptions& options);

// The undeformed slime of `level` resting on the floor (centre at height radius) below its start position.
TriangleMesh restingSlime(const SlimeSettings& slime, int level);

}  // namespace slime

// What `slime bench physics --front` writes (bench_front.h): a line per point, the guide's accuracy at
// each resolution, and the files: front.json, front.md (the table), and per error front_<error>.dat,
// .gp and .png (gnuplot: cost against the error, each integrator's and peer's points, our Pareto front).
#pragma once

#include "core/settings/settings.h"

#include <nlohmann/json.hpp>

#include <string>

namespace slime {

// The errors a front point has, in chart order, with their labels and the guide's bound (0: none).
struct FrontError {
  const char* key;     // in a point's "errors"
  const char* label;   // the chart's axis
  double guideBound;
};
inline constexpr FrontError kFrontErrors[] = {
    {"torsional", "Lamb's n = 2 torsional frequency, relative error", 0.05},
    {"spheroidal", "Lamb's n = 2 spheroidal frequency, relative error", 0.05},
    {"damping", "numerical damping ratio of the n = 2 modes (the larger)", 0.02},
    {"creep", "creep time constant, relative error", 0.0},
    {"rest_height", "rest height against the static solve, relative error", 0.02}};

// One line: the point, its cost, its errors, its rollbacks, whether it meets the guide's accuracy.
std::string frontRowText(const nlohmann::json& point);

// Per resolution: the cheapest of our points at the guide's accuracy, the program's default (the scene's
// integrator at its automatic substeps) and the first's cost as a share of the second's.
nlohmann::json guideSummary(const nlohmann::json& points, const Settings& scene);
void printGuide(const nlohmann::json& guide);

// Issue 45's test of the peers: for each stable peer point, the cheapest of our points at the same
// resolution with no larger error on any oracle the peer is measured on (Lamb's two modes, the damping,
// the rest height; creep is ours alone), and its cost as a share of the peer's (the aim: at most 0.5).
nlohmann::json peerDominance(const nlohmann::json& ours, const nlohmann::json& peers);
void printPeerDominance(const nlohmann::json& dominance);

// front.json, front.md and the charts into `directory` (made if missing). The charts need gnuplot on
// the PATH; without it the report says "charts": "not drawn".
void writeFrontFiles(nlohmann::json& report, const std::string& directory);

}  // namespace slime

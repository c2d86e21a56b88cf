#include "app/bench/physics/bench_front_report.h"

#include "app/bench/physics/bench_front.h"
#include "app/bench/report/bench_report.h"
#include "core/simulation/integrator_choice.h"

#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>

extern char** environ;

namespace slime {
namespace {

using nlohmann::json;

constexpr double kSmallestChartedError = 1e-6;  // the log axis's floor: a smaller error is drawn there

std::string formatNumber(const char* pattern, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

std::string stepText(const json& point) {
  if (point["step_ms"].is_string()) return point["step_ms"];
  return formatNumber("%g", point["step_ms"].get<double>());
}

std::string iterationsText(const json& point) {
  return point.contains("iterations") && point["iterations"].is_number() ? std::to_string(point["iterations"].get<int>())
                                                                          : "-";
}

std::string errorText(const json& errors, const char* key) {
  if (!errors.contains(key) || !errors[key].is_number()) return "-";
  const double value = errors[key];
  return std::string(key) == "damping" ? formatNumber("%.2e", value) : formatNumber("%.2f%%", 100.0 * value);
}

double pointCost(const json& point) {
  return point.contains("cost_ms_per_ms") && point["cost_ms_per_ms"].is_number() ? point["cost_ms_per_ms"].get<double>()
                                                                                : std::numeric_limits<double>::infinity();
}

// A series of a chart: our integrator's name, or "jolt" / "bullet".
std::string seriesName(const json& point) { return point.contains("peer") ? point["peer"].get<std::string>() : point["integrator"].get<std::string>(); }

// Every point of ours and the peers', each with "peer" set on the peers'.
json allPoints(const json& report) {
  json points = report["points"];
  for (const json& peer : report["peers"]) {
    if (!peer.contains("points")) continue;
    for (json point : peer["points"]) {
      point["peer"] = peer.value("peer", peer["program"].get<std::string>());
      point["integrator"] = point["peer"];
      points.push_back(point);
    }
  }
  return points;
}

void writeTable(const json& points, const std::string& path) {
  std::ofstream file(path);
  file << "| who | resolution | integrator | step ms | iterations | cost ms/ms | torsional | spheroidal | damping ratio "
          "| creep | rest height | rollbacks | guide | note |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const json& point : points) {
    const json& errors = point["errors"];
    file << "| " << (point.contains("peer") ? point["peer"].get<std::string>() : "slime") << " | "
         << point["resolution"].get<int>() << " | " << point["integrator"].get<std::string>() << " | " << stepText(point)
         << " | " << iterationsText(point) << " | "
         << (std::isfinite(pointCost(point)) ? formatNumber("%.4g", pointCost(point)) : "-") << " | " << errorText(errors, "torsional")
         << " | " << errorText(errors, "spheroidal") << " | " << errorText(errors, "damping") << " | "
         << errorText(errors, "creep") << " | " << errorText(errors, "rest_height") << " | "
         << (point.contains("rollbacks") ? std::to_string(point["rollbacks"].get<long>()) : "-") << " | "
         << (point.value("guide", false) ? "yes" : "") << " | "
         << (point.value("stable", true) ? "" : point.value("note", std::string("diverged"))) << " |\n";
  }
}

bool runGnuplot(const std::string& script) {
  std::vector<const char*> argv{"gnuplot", script.c_str(), nullptr};
  pid_t child = 0;
  if (posix_spawnp(&child, "gnuplot", nullptr, nullptr, const_cast<char* const*>(argv.data()), environ) != 0)
    return false;
  int status = 0;
  return waitpid(child, &status, 0) == child && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

// The chart of one error: a data block per series (error, cost, point type by resolution), then the
// Pareto front of our points.
bool writeChart(const json& points, const FrontError& error, const std::string& directory, const std::string& title) {
  const std::string stem = directory + "/front_" + error.key;
  std::map<std::string, std::vector<const json*>> bySeries;
  std::vector<std::string> order;
  std::vector<std::pair<double, double>> ours;
  std::vector<const json*> oursPoints;
  int unstable = 0, unmeasured = 0;
  for (const json& point : points) {
    if (!point.value("stable", true)) {
      ++unstable;
      continue;
    }
    if (!point["errors"][error.key].is_number() || !std::isfinite(pointCost(point))) {
      ++unmeasured;
      continue;
    }
    const std::string name = seriesName(point);
    if (!bySeries.count(name)) order.push_back(name);
    bySeries[name].push_back(&point);
    if (!point.contains("peer")) {
      ours.emplace_back(point["errors"][error.key].get<double>(), pointCost(point));
      oursPoints.push_back(&point);
    }
  }
  std::ofstream data(stem + ".dat");
  const auto charted = [](double value) { return std::max(value, kSmallestChartedError); };
  const int pointTypes[] = {0, 4, 6, 8, 12};  // resolution 1..4: square, circle, triangle, diamond
  for (const std::string& name : order) {
    data << "# " << name << "\n";
    for (const json* point : bySeries[name]) {
      const int resolution = std::clamp((*point)["resolution"].get<int>(), 1, 4);
      data << charted((*point)["errors"][error.key].get<double>()) << " " << pointCost(*point) << " "
           << pointTypes[resolution] + (point->contains("peer") ? 1 : 0) << "\n";
    }
    data << "\n\n";
  }
  data << "# pareto\n";
  for (std::size_t k : paretoFront(ours)) data << charted(ours[k].first) << " " << ours[k].second << "\n";
  data.close();

  std::ofstream script(stem + ".gp");
  script << "set terminal pngcairo size 900,620 noenhanced\nset output '" << stem << ".png'\n"
         << "set logscale xy\nset format x '%g'\nset format y '%g'\nset grid\n"
         << "set xlabel \"" << error.label << "\"\nset ylabel 'cost: ms of one core per simulated ms (landing included)'\n"
         << "set title \"" << title << (unstable > 0 ? " (" + std::to_string(unstable) + " unstable points not drawn)" : "")
         << "\"\nset key outside right\n";
  if (error.guideBound > 0.0)
    script << "set arrow from " << error.guideBound << ", graph 0 to " << error.guideBound
           << ", graph 1 nohead dashtype 2 lc 'gray40'\nset label 'guide' at " << error.guideBound
           << ", graph 0.97 offset 0.5,0 tc 'gray40'\n";
  // Each series in its colour, the resolution as the point's shape (filled: a peer's); the key draws
  // one entry per series and per resolution.
  script << "plot ";
  for (std::size_t k = 0; k < order.size(); ++k)
    script << "'" << stem << ".dat' index " << k << " using 1:2:3 with points pt variable ps 1.3 lw 1.5 lc " << k + 1
           << " notitle, NaN with points pt 7 lc " << k + 1 << " title '" << order[k] << "', ";
  for (int resolution = 1; resolution <= 4; ++resolution)
    script << "NaN with points pt " << pointTypes[resolution] << " lc 'black' title 'resolution " << resolution << "', ";
  script << "'" << stem << ".dat' index " << order.size()
         << " using 1:2 with steps lc 'black' lw 1.5 title 'Pareto front (ours)'\n";
  script.close();
  (void)unmeasured;
  return runGnuplot(stem + ".gp");
}

}  // namespace

std::string frontRowText(const json& point) {
  std::string text = "res " + std::to_string(point["resolution"].get<int>()) + "  " + point["integrator"].get<std::string>() +
                     "  step " + stepText(point) + " ms  it " + iterationsText(point) + "  ";
  if (!point.value("stable", true) && !point.contains("modes")) return text + point.value("note", std::string("unstable"));
  text += formatNumber("cost %.4g ms/ms", pointCost(point));
  const json& errors = point["errors"];
  text += "  torsional " + errorText(errors, "torsional") + "  spheroidal " + errorText(errors, "spheroidal") +
          "  zeta " + errorText(errors, "damping") + "  creep " + errorText(errors, "creep") + "  rest " +
          errorText(errors, "rest_height") + "  rollbacks " + std::to_string(point.value("rollbacks", 0L));
  if (point.value("guide", false)) text += "  [guide's accuracy]";
  if (!point.value("stable", true)) text += "  (" + point.value("note", std::string("unstable")) + ")";
  return text;
}

json guideSummary(const json& points, const Settings& scene) {
  std::set<int> resolutions;
  for (const json& point : points) resolutions.insert(point["resolution"].get<int>());
  json summary = json::array();
  for (int resolution : resolutions) {
    Settings settings = scene;
    settings.slime.model = "bulk";
    settings.slime.resolution = resolution;
    const std::string defaultIntegrator = integratorName(chooseIntegrator(settings));
    const json* cheapest = nullptr;
    const json* fallback = nullptr;
    for (const json& point : points) {
      if (point["resolution"].get<int>() != resolution) continue;
      if (point.value("guide", false) && (cheapest == nullptr || pointCost(point) < pointCost(*cheapest))) cheapest = &point;
      if (point["integrator"] == defaultIntegrator && point["step_ms"] == "auto") fallback = &point;
    }
    json entry = {{"resolution", resolution}, {"default_integrator", defaultIntegrator},
                  {"default", fallback != nullptr ? json({{"step_ms", "auto"}, {"cost_ms_per_ms", (*fallback)["cost_ms_per_ms"]},
                                                          {"guide", (*fallback).value("guide", false)}})
                                                  : json()},
                  {"cheapest", nullptr}};
    if (cheapest != nullptr) {
      entry["cheapest"] = {{"integrator", (*cheapest)["integrator"]}, {"step_ms", (*cheapest)["step_ms"]},
                           {"iterations", (*cheapest)["iterations"]}, {"cost_ms_per_ms", (*cheapest)["cost_ms_per_ms"]},
                           {"errors", (*cheapest)["errors"]}};
      if (fallback != nullptr && std::isfinite(pointCost(*fallback)))
        entry["share_of_default"] = pointCost(*cheapest) / pointCost(*fallback);
    }
    summary.push_back(entry);
  }
  return summary;
}

void printGuide(const json& guide) {
  std::printf("\nThe guide's accuracy (Lamb's n = 2 modes within 5 %%, numerical damping ratio <= 0.02, rest height "
              "within 2 %% of the static solve), the cheapest point of ours:\n");
  for (const json& entry : guide) {
    const int resolution = entry["resolution"];
    if (entry["cheapest"].is_null()) {
      std::printf("  resolution %d: no point meets it\n", resolution);
      continue;
    }
    const json& best = entry["cheapest"];
    std::printf("  resolution %d: %s, step %s ms, iterations %s: %.4g ms per simulated ms", resolution,
                best["integrator"].get<std::string>().c_str(), stepText(best).c_str(), iterationsText(best).c_str(),
                best["cost_ms_per_ms"].get<double>());
    if (entry.contains("share_of_default"))
      std::printf(" (%.2f x the default, %s at its automatic substeps, %.4g)", entry["share_of_default"].get<double>(),
                  entry["default_integrator"].get<std::string>().c_str(),
                  entry["default"]["cost_ms_per_ms"].get<double>());
    std::printf("\n");
  }
  std::fflush(stdout);
}

json peerDominance(const json& ours, const json& peers) {
  static constexpr const char* kShared[] = {"torsional", "spheroidal", "damping", "rest_height"};
  const auto error = [](const json& point, const char* key) {
    const json& errors = point["errors"];
    return errors.contains(key) && errors[key].is_number() ? errors[key].get<double>() : std::numeric_limits<double>::infinity();
  };
  json rows = json::array();
  int stable = 0, met = 0;
  for (const json& peer : peers) {
    if (!peer.contains("points")) continue;
    for (const json& point : peer["points"]) {
      if (!point.value("stable", false)) continue;
      ++stable;
      const json* best = nullptr;
      for (const json& candidate : ours) {
        if (candidate["resolution"] != point["resolution"] || !candidate.value("stable", false)) continue;
        const bool noWorse = std::all_of(std::begin(kShared), std::end(kShared),
                                         [&](const char* key) { return error(candidate, key) <= error(point, key); });
        if (noWorse && (best == nullptr || pointCost(candidate) < pointCost(*best))) best = &candidate;
      }
      json row = {{"peer", peer.value("peer", std::string("?"))}, {"resolution", point["resolution"]},
                  {"step_ms", point["step_ms"]}, {"iterations", point["iterations"]}, {"cost_ms_per_ms", point["cost_ms_per_ms"]},
                  {"ours", nullptr}, {"share", nullptr}};
      if (best != nullptr) {
        const double share = pointCost(*best) / pointCost(point);
        row["ours"] = {{"integrator", (*best)["integrator"]}, {"step_ms", (*best)["step_ms"]},
                       {"iterations", (*best)["iterations"]}, {"cost_ms_per_ms", (*best)["cost_ms_per_ms"]}};
        row["share"] = share;
        if (share <= 0.5) ++met;
      }
      rows.push_back(row);
    }
  }
  return {{"stable_peer_points", stable}, {"beaten_at_half_cost", met}, {"points", rows}};
}

void printPeerDominance(const json& dominance) {
  std::printf("\nPeers: %d of %d stable peer points have a point of ours at least as accurate on every oracle they share "
              "(Lamb's two modes, damping, rest height) at no more than half their cost:\n",
              dominance["beaten_at_half_cost"].get<int>(), dominance["stable_peer_points"].get<int>());
  for (const json& row : dominance["points"]) {
    std::printf("  %-6s res %d  step %5s ms  it %s  %.4g ms/ms: ", row["peer"].get<std::string>().c_str(),
                row["resolution"].get<int>(), stepText(row).c_str(), iterationsText(row).c_str(), pointCost(row));
    if (row["ours"].is_null()) {
      std::printf("no point of ours is as accurate on all four\n");
      continue;
    }
    const json& ours = row["ours"];
    std::printf("%s step %s ms it %s, %.4g ms/ms (%.2f x)%s\n", ours["integrator"].get<std::string>().c_str(),
                stepText(ours).c_str(), iterationsText(ours).c_str(), pointCost(ours), row["share"].get<double>(),
                row["share"].get<double>() <= 0.5 ? "" : "  MISSED");
  }
  std::fflush(stdout);
}

void writeFrontFiles(json& report, const std::string& directory) {
  std::filesystem::create_directories(directory);
  const json points = allPoints(report);
  writeTable(points, directory + "/front.md");
  const std::string processor = report["machine"].value("cpu", std::string("?"));
  json charts = json::array();
  bool drawn = true;
  for (const FrontError& error : kFrontErrors) {
    drawn = writeChart(points, error, directory, std::string("The front: ") + error.key + " (" + processor + ")") && drawn;
    charts.push_back(directory + "/front_" + error.key + ".png");
  }
  report["charts"] = drawn ? charts : json("not drawn: gnuplot is not on the PATH or failed");
  if (!drawn) std::printf("front     charts not drawn: gnuplot is not on the PATH or failed\n");
  writeJsonFile(report, directory + "/front.json");
  std::printf("front     wrote %s/front.json, front.md and the charts front_*.png\n", directory.c_str());
}

}  // namespace slime

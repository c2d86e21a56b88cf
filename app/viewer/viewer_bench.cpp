#include "app/viewer/viewer_bench.h"

#include "app/bench/report/bench_report.h"
#include "app/viewer/frame_log.h"
#include "app/viewer/viewer.h"
#include "core/settings/settings_io.h"
#include "core/simulation/scenario.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace slime {
namespace {

constexpr double kWindowSeconds = 3.0;  // the aim: at least kAimFps in every window this long
constexpr double kAimFps = 30.0;
constexpr double kLongestAimMs = 100.0;

// The aim for a phase's slow frames: the 95th percentile within max(1.5 × median, median + 8 ms).
double p95Allowance(const PhaseSummary& phase) { return std::max(1.5 * phase.medianMs, phase.medianMs + 8.0); }

// slime.tearing: the handled frames of one piece against those of several, without the frames that
// tore or merged, which are listed one by one (issue 42: "as smooth while the slime is handled").
bool handledWhole(const FrameRecord& frame) { return frame.grabbed && frame.pieces == 1 && frame.topologyMs == 0.0; }
bool handledInPieces(const FrameRecord& frame) { return frame.grabbed && frame.pieces > 1 && frame.topologyMs == 0.0; }

nlohmann::json timesJson(const PhaseSummary& times) {
  return {{"frames", times.frames},
          {"median_ms", times.medianMs},
          {"p95_ms", times.p95Ms},
          {"longest_ms", times.longestMs}};
}

// Prints and returns the pieces' table; null when nothing tore or merged.
nlohmann::json piecesTable(const std::vector<FrameRecord>& records, double afterSeconds) {
  if (records.empty() || records.back().tears + records.back().merges == 0) return nullptr;
  const PhaseSummary whole = summarizeFrameTimes(records, handledWhole, afterSeconds);
  const PhaseSummary pieces = summarizeFrameTimes(records, handledInPieces, afterSeconds);
  std::printf("handled    %7s %9s %8s %9s   (frames that tore or merged left out)\n", "frames", "median_ms", "p95_ms",
              "longest_ms");
  std::printf("%-10s %7lld %9.1f %8.1f %9.1f\n", "1 piece", static_cast<long long>(whole.frames), whole.medianMs,
              whole.p95Ms, whole.longestMs);
  std::printf("%-10s %7lld %9.1f %8.1f %9.1f\n", "pieces", static_cast<long long>(pieces.frames), pieces.medianMs,
              pieces.p95Ms, pieces.longestMs);
  nlohmann::json events = nlohmann::json::array();
  int tears = 0, merges = 0;
  for (std::size_t index = 0; index < records.size(); ++index) {
    const FrameRecord& frame = records[index];
    if (frame.tears == tears && frame.merges == merges) continue;
    const bool tore = frame.tears != tears, merged = frame.merges != merges;
    const char* what = tore && merged ? "tear+merge" : tore ? "tear" : "merge";
    std::printf("%-10s frame %zu at %.3f s simulated: %.1f ms, %.1f of them tearing and merging; pieces after: %d\n",
                what, index, frame.simulatedSeconds, frame.frameMs, frame.topologyMs, frame.pieces);
    events.push_back({{"what", what},
                      {"frame", index},
                      {"simulated_s", frame.simulatedSeconds},
                      {"frame_ms", frame.frameMs},
                      {"topology_ms", frame.topologyMs},
                      {"pieces", frame.pieces}});
    tears = frame.tears;
    merges = frame.merges;
  }
  return {{"handled_one_piece", timesJson(whole)}, {"handled_in_pieces", timesJson(pieces)}, {"events", events}};
}

}  // namespace

int runViewerBench(const Settings& settings, const ViewerBenchOptions& options) {
  ViewerOptions viewerOptions;
  viewerOptions.scenario = loadScenario(options.scenarioPath);
  double seconds = options.seconds;
  if (seconds <= 0.0) {
    double last = 0.0;
    for (const ScenarioEvent& event : viewerOptions.scenario->events)
      last = std::max(last, event.time + event.duration + event.hold);
    seconds = last + 6.0;
  }
  viewerOptions.quitAtSimulatedSeconds = seconds;
  viewerOptions.quitAtWallSeconds = options.wallSeconds > 0.0 ? options.wallSeconds : 2.0 * seconds + 30.0;
  viewerOptions.frameLogPath = options.csvPath.empty() ? "/dev/null" : options.csvPath;  // keeps the records
  Settings run = settings;
  run.camera.width = options.width;
  run.camera.height = options.height;
  HeadlessGl backend(options.width, options.height, options.api);
  backend.setRealTime(true);
  std::vector<FrameRecord> records;
  {
    Viewer viewer(backend, run, viewerOptions);
    std::printf("bench viewer: %dx%d, scenario %s, %.1f simulated s, headless %s in real time\n", options.width,
                options.height, options.scenarioPath.c_str(), seconds, nameOf(backend.api()));
    if (viewer.run() != 0) throw std::runtime_error("bench viewer: cannot write the frame log " + options.csvPath);
    records = viewer.frameRecords();
    if (viewer.simulation().time() + 1e-9 < seconds)
      std::printf("bench viewer: the wall-clock limit came first: simulated %.2f of %.1f s (%.2f of real time)\n",
                  viewer.simulation().time(), seconds,
                  viewer.stats().totalFrameMs > 0.0 ? viewer.simulation().time() / (viewer.stats().totalFrameMs / 1000.0) : 0.0);
  }
  const std::vector<PhaseSummary> phases = summarizePhases(records, options.afterSeconds);
  const FrameWindow slowest = slowestWindow(records, kWindowSeconds, options.afterSeconds);
  double longest = 0.0;
  for (const FrameRecord& record : records)
    if (record.endSeconds >= options.afterSeconds) longest = std::max(longest, record.frameMs);

  std::printf("%-10s %7s %7s %9s %8s %8s %9s %12s\n", "phase", "frames", "fps", "median_ms", "p95_ms", "p99_ms",
              "longest_ms", "p95_aim_ms");
  nlohmann::json table = nlohmann::json::array();
  for (const PhaseSummary& phase : phases) {
    const double fps = phase.seconds > 0.0 ? static_cast<double>(phase.frames) / phase.seconds : 0.0;
    const bool p95Met = phase.p95Ms <= p95Allowance(phase);
    std::printf("%-10s %7lld %7.1f %9.1f %8.1f %8.1f %9.1f %8.1f %-3s\n", nameOf(phase.phase),
                static_cast<long long>(phase.frames), fps, phase.medianMs, phase.p95Ms, phase.p99Ms, phase.longestMs,
                p95Allowance(phase), p95Met ? "met" : "MISSED");
    table.push_back({{"phase", nameOf(phase.phase)}, {"frames", phase.frames}, {"fps", fps},
                     {"median_ms", phase.medianMs}, {"p95_ms", phase.p95Ms}, {"p99_ms", phase.p99Ms},
                     {"longest_ms", phase.longestMs}, {"p95_aim_ms", p95Allowance(phase)}, {"p95_aim_met", p95Met}});
  }
  std::printf("slowest %.0f s window: %.1f fps from %.1f s (aim %.0f: %s); longest frame %.1f ms (aim %.0f: %s)\n",
              kWindowSeconds, slowest.fps, slowest.startSeconds, kAimFps, slowest.fps >= kAimFps ? "met" : "MISSED",
              longest, kLongestAimMs, longest <= kLongestAimMs ? "met" : "MISSED");
  const nlohmann::json pieces = piecesTable(records, options.afterSeconds);
  if (!options.jsonPath.empty()) {
    const nlohmann::json report = {{"machine", machineJson()},
                                   {"size", {options.width, options.height}},
                                   {"scenario", options.scenarioPath},
                                   {"simulated_seconds", seconds},
                                   {"after_seconds", options.afterSeconds},
                                   {"phases", table},
                                   {"slowest_window", {{"seconds", kWindowSeconds}, {"fps", slowest.fps},
                                                       {"start_s", slowest.startSeconds}}},
                                   {"longest_ms", longest},
                                   {"pieces", pieces}};
    std::ofstream file(options.jsonPath);
    file << report.dump(2) << "\n";
    if (!file) throw std::runtime_error("bench viewer: cannot write " + options.jsonPath);
  }
  return 0;
}

}  // namespace slime

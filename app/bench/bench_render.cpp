#include "app/bench/bench_render.h"

#include "app/bench/bench_bvh.h"
#include "app/bench/bench_embree_replay.h"
#include "app/bench/bench_progress.h"
#include "app/bench/bench_ray_log.h"
#include "app/bench/bench_report.h"
#include "app/bench/bench_timing.h"
#include "render/renderer.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <thread>

namespace slime {
namespace {

using nlohmann::json;

// SPEC §6: the seed's own measurement (734×564, depth 3, i7-10510U, 8 threads), ms/frame.
struct SeedFigure {
  int faces;
  double parallelMs, serialMs;
};
constexpr SeedFigure kSeedPublished[] = {
    {20, 233, 536}, {80, 739, 2099}, {320, 2788, 7283}, {1280, 10738, 31847}, {5120, 42253, 135596}};
// SPEC §9: the seed's program built and run on this kind of 2-core machine, 5,120 faces.
constexpr SeedFigure kSeedBuiltHere{5120, 114900, 140800};

// The brute-force tracer repeats frames until this much time has gone by (at least one frame).
constexpr double kBruteBudgetMs = 3000.0;

int faceCount(int level) { return 20 << (2 * level); }

struct FrameTiming {
  TimingSummary ms;
  RenderStats stats;  // of the last frame: ray counts are the same every frame
  double refitMs = 0.0;
};

// Still: the view of a person watching or dragging the slime (the renderer reuses what the slime
// cannot change). Moving: the camera turns by a thousandth of a degree every frame, as when orbiting,
// so every pixel is traced every frame.
enum class CameraMotion { Still, Moving };

// warmup untimed frames, then `frames` timed ones; updateSlime every frame as the viewer does.
FrameTiming timeFrames(Renderer& renderer, const Settings& stillSettings, const TriangleMesh& mesh, int warmup,
                       int frames, BenchProgress& progress, const std::string& what, double budgetMs = 0.0,
                       CameraMotion motion = CameraMotion::Still) {
  Settings settings = stillSettings;
  Image image;
  image.resize(settings.camera.width, settings.camera.height);
  std::vector<double> samples, refits;
  FrameTiming timing;
  double spent = 0.0;
  for (int frame = 0; frame < warmup + frames; ++frame) {
    if (motion == CameraMotion::Moving) settings.camera.yaw = stillSettings.camera.yaw + (frame % 2 ? 1e-3 : -1e-3);
    renderer.updateSlime(mesh.positions, mesh.triangles);
    const Stopwatch watch;
    timing.stats = renderer.render(settings, image);
    const double ms = watch.milliseconds();
    if (frame >= warmup) {
      samples.push_back(ms);
      refits.push_back(timing.stats.refitMs);
    }
    spent += ms;
    progress.advance(1.0, what);
    if (budgetMs > 0.0 && frame >= warmup && spent >= budgetMs) {
      progress.advance(warmup + frames - frame - 1, what);
      break;
    }
  }
  timing.ms = summarize(samples);
  timing.refitMs = summarize(refits).median;
  return timing;
}

json raysJson(const RenderStats& stats) {
  const RayCounts& r = stats.rays;
  return {{"primary", r.primary}, {"shadow", r.shadow}, {"reflection", r.reflection}, {"refraction", r.refraction},
          {"total", r.total()}, {"slime_queries", stats.slimeQueries}};
}

// Rays of each kind delivered per second of the whole frame, in millions.
json raysPerSecondJson(const RenderStats& stats, double ms) {
  const auto rate = [ms](std::uint64_t count) { return ms > 0.0 ? count / (ms * 1e3) : 0.0; };
  const RayCounts& r = stats.rays;
  return {{"primary", rate(r.primary)}, {"shadow", rate(r.shadow)}, {"reflection", rate(r.reflection)},
          {"refraction", rate(r.refraction)}};
}

void printRow(const json& c) {
  std::printf("%5d %7d %3d %9.2f %9.2f %9.2f %8.2f %9.2f %7.2f", c["level"].get<int>(), c["faces"].get<int>(),
              c["threads"].get<int>(), c["ms_per_frame"].get<double>(), c["moving_camera_ms_per_frame"].get<double>(),
              c["mrays_per_s"].get<double>(),
              c["limit_ms_per_frame"].get<double>(), c["limit_mqueries_per_s"].get<double>(),
              c["full_over_limit"].get<double>());
  if (c.contains("brute_ms_per_frame"))
    std::printf(" %11.1f %9.0f", c["brute_ms_per_frame"].get<double>(), c["speedup_over_brute"].get<double>());
  std::printf("\n");
}

}  // namespace

TriangleMesh restingSlime(const SlimeSettings& slime, int level) {
  return makeIcosphere(level, slime.radius, {slime.position.x, slime.position.y, slime.radius});
}

json runRenderBench(const Settings& baseSettings, const RenderBenchOptions& options) {
  Settings settings = baseSettings;
  settings.camera.width = options.width;
  settings.camera.height = options.height;
  settings.render.depth = options.depth;
  settings.render.backend = "embree";
  settings.slime.shape = "mesh";
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::vector<int> threads = options.threads;
  if (threads.empty()) threads = cores > 1 ? std::vector<int>{1, cores} : std::vector<int>{1};

  const int perConfiguration = options.warmup + options.frames;
  double total = 0.0;
  for (int level : options.levels) {
    total += 1.0 + threads.size() * (2.0 * perConfiguration + options.frames + 1.0);
    if (level <= options.bruteMaxLevel) total += 3.0;
  }
  total += 30.0 * options.bvhLevels.size();
  BenchProgress progress("bench render", total);

  json report = {{"bench", "render"},
                 {"width", options.width},
                 {"height", options.height},
                 {"depth", options.depth},
                 {"cores", cores},
                 {"frames", options.frames},
                 {"warmup", options.warmup},
                 {"scene", "default scene, undeformed slime resting on the floor"}};
  json configurations = json::array();
  CsvTable table{{"level", "faces", "threads", "ms_per_frame", "ms_min", "ms_max", "mrays_per_s", "rays_total",
                  "limit_ms_per_frame", "limit_mqueries_per_s", "full_over_limit", "brute_ms_per_frame",
                  "speedup_over_brute", "speedup_over_1_thread", "limit_speedup_over_1_thread",
                  "moving_camera_ms_per_frame"}, {}};

  for (int level : options.levels) {
    const std::string label = "level " + std::to_string(level);
    settings.slime.level = level;
    const TriangleMesh mesh = restingSlime(settings.slime, level);
    const RayLog log = recordSlimeQueries(settings, mesh.positions, mesh.triangles, options.width, options.height);
    progress.advance(1.0, label + ": recording rays");

    // The seed's algorithm, single-threaded by design, where it finishes in reasonable time.
    json brute;
    if (level <= options.bruteMaxLevel) {
      Settings bruteSettings = settings;
      bruteSettings.render.backend = "brute";
      Renderer renderer(bruteSettings);
      const FrameTiming timing = timeFrames(renderer, bruteSettings, mesh, 0, std::max(1, options.frames), progress,
                                            label + ": brute force", kBruteBudgetMs);
      brute = {{"ms_per_frame", timing.ms.median}, {"ms", toJson(timing.ms)}, {"threads", 1}};
      progress.advance(3.0, label);
    }

    for (int count : threads) {
      const std::string what = label + ", " + std::to_string(count) + " thread(s)";
      settings.render.threads = count;
      Renderer renderer(settings);
      const FrameTiming full = timeFrames(renderer, settings, mesh, options.warmup, options.frames, progress, what);
      Renderer movingRenderer(settings);
      const FrameTiming moving = timeFrames(movingRenderer, settings, mesh, options.warmup, options.frames, progress,
                                            what + ", moving camera", 0.0, CameraMotion::Moving);

      // The limit: the same queries through Embree alone, same thread count.
      EmbreeReplay replay(count, BvhUpdate::Refit);
      replay.build(mesh.positions, mesh.triangles);
      replay.replay(log, count);  // warm-up
      std::vector<double> limitMs, primaryMs, secondaryMs, shadowMs;
      for (int frame = 0; frame < options.frames; ++frame) {
        const ReplayTimes times = replay.replay(log, count);
        limitMs.push_back(times.totalMs());
        primaryMs.push_back(times.primaryMs);
        secondaryMs.push_back(times.secondaryMs);
        shadowMs.push_back(times.shadowMs);
        progress.advance(1.0, what + ": Embree-only limit");
      }
      const TimingSummary limit = summarize(limitMs);
      const double ms = full.ms.median;
      const auto mrate = [](double count, double milliseconds) { return milliseconds > 0.0 ? count / (milliseconds * 1e3) : 0.0; };
      json c = {{"level", level},
                {"faces", faceCount(level)},
                {"vertices", mesh.positions.size()},
                {"width", options.width},
                {"height", options.height},
                {"depth", options.depth},
                {"threads", count},
                {"ms_per_frame", ms},
                {"ms", toJson(full.ms)},
                {"reused_pixels", full.stats.reusedPixels},
                {"moving_camera_ms_per_frame", moving.ms.median},
                {"moving_camera", {{"ms", toJson(moving.ms)}, {"mrays_per_s", mrate(static_cast<double>(moving.stats.rays.total()), moving.ms.median)},
                                   {"rays", raysJson(moving.stats)}}},
                {"refit_ms", full.refitMs},
                {"mrays_per_s", mrate(static_cast<double>(full.stats.rays.total()), ms)},
                {"mrays_per_s_by_kind", raysPerSecondJson(full.stats, ms)},
                {"rays", raysJson(full.stats)},
                {"limit_ms_per_frame", limit.median},
                {"limit", {{"ms", toJson(limit)},
                           {"primary_ms", summarize(primaryMs).median},
                           {"secondary_ms", summarize(secondaryMs).median},
                           {"shadow_ms", summarize(shadowMs).median},
                           {"queries", {{"primary", RayLog::activeRays(log.primary)}, {"secondary", RayLog::activeRays(log.secondary)},
                                        {"shadow", RayLog::activeRays(log.shadow)}}},
                           {"mqueries_per_s_by_kind",
                            {{"primary", mrate(static_cast<double>(RayLog::activeRays(log.primary)), summarize(primaryMs).median)},
                             {"secondary", mrate(static_cast<double>(RayLog::activeRays(log.secondary)), summarize(secondaryMs).median)},
                             {"shadow", mrate(static_cast<double>(RayLog::activeRays(log.shadow)), summarize(shadowMs).median)}}}}},
                {"limit_mqueries_per_s", mrate(static_cast<double>(log.queries()), limit.median)},
                {"full_over_limit", limit.median > 0.0 ? ms / limit.median : 0.0}};
      if (!brute.is_null()) {
        c["brute_ms_per_frame"] = brute["ms_per_frame"];
        c["brute"] = brute;
        c["speedup_over_brute"] = ms > 0.0 ? brute["ms_per_frame"].get<double>() / ms : 0.0;
      }
      configurations.push_back(std::move(c));
    }
  }
  // Parallel speed-up over one thread of the same level, for the full frame and for the limit.
  for (json& c : configurations) {
    for (const json& single : configurations) {
      if (single["level"] != c["level"] || single["threads"].get<int>() != 1) continue;
      c["speedup_over_1_thread"] = single["ms_per_frame"].get<double>() / c["ms_per_frame"].get<double>();
      c["limit_speedup_over_1_thread"] = single["limit_ms_per_frame"].get<double>() / c["limit_ms_per_frame"].get<double>();
    }
    const auto optional = [&c](const char* key) { return c.contains(key) ? c[key] : json(); };
    table.add({c["level"], c["faces"], c["threads"], c["ms_per_frame"], c["ms"]["min"], c["ms"]["max"], c["mrays_per_s"],
               c["rays"]["total"], c["limit_ms_per_frame"], c["limit_mqueries_per_s"], c["full_over_limit"],
               optional("brute_ms_per_frame"), optional("speedup_over_brute"), optional("speedup_over_1_thread"),
               optional("limit_speedup_over_1_thread"), c["moving_camera_ms_per_frame"]});
  }
  report["configurations"] = configurations;

  CsvTable bvhTable = makeBvhTable();
  json bvh = json::array();
  for (int level : options.bvhLevels) {
    BvhBenchOptions bvhOptions;
    bvhOptions.level = level;
    bvhOptions.width = options.width;
    bvhOptions.height = options.height;
    bvhOptions.replays = std::max(3, options.frames);
    for (json& entry : runBvhBench(settings, bvhOptions, progress, bvhTable)) bvh.push_back(std::move(entry));
  }
  report["bvh"] = bvh;

  CsvTable seedTable{{"faces", "parallel_ms", "serial_ms", "source"}, {}};
  json seed = json::array();
  for (const SeedFigure& figure : kSeedPublished) {
    seed.push_back({{"faces", figure.faces}, {"parallel_ms", figure.parallelMs}, {"serial_ms", figure.serialMs},
                    {"source", "seed report, i7-10510U, 8 threads (SPEC 6)"}});
    seedTable.add({figure.faces, figure.parallelMs, figure.serialMs, "published"});
  }
  seed.push_back({{"faces", kSeedBuiltHere.faces}, {"parallel_ms", kSeedBuiltHere.parallelMs},
                  {"serial_ms", kSeedBuiltHere.serialMs}, {"source", "seed program built on a 2-core machine (SPEC 9)"}});
  seedTable.add({kSeedBuiltHere.faces, kSeedBuiltHere.parallelMs, kSeedBuiltHere.serialMs, "built_here"});
  report["seed"] = seed;
  progress.finish();

  std::printf("level   faces thr  ms/frame moving ms  Mrays/s  limit ms  Mqueries/s full/limit  brute ms  speed-up\n");
  for (const json& c : configurations) printRow(c);
  for (const json& b : bvh)
    std::printf("bvh level %d %-7s update %8.3f ms  trace round %7.2f ms  stretched %7.2f ms\n", b["level"].get<int>(),
                b["method"].get<std::string>().c_str(), b["update_ms"].get<double>(), b["trace_round_ms"].get<double>(),
                b["trace_deformed_ms"].get<double>());

  if (!options.jsonFile.empty()) writeJsonFile(report, options.jsonFile);
  if (!options.csvFile.empty()) {
    writeCsvFile(table, options.csvFile);
    writeCsvFile(bvhTable, siblingCsvPath(options.csvFile, "bvh"));
    writeCsvFile(seedTable, siblingCsvPath(options.csvFile, "seed"));
  }
  return report;
}

}  // namespace slime

#include "app/bench/render/bench_render.h"

#include "app/bench/render/bench_bvh.h"
#include "app/bench/render/bench_embree_replay.h"
#include "app/bench/report/bench_progress.h"
#include "app/bench/render/bench_ray_log.h"
#include "app/bench/report/bench_report.h"
#include "app/bench/report/bench_timing.h"
#include "render/trace/renderer.h"

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

// The brute-force tracer repeats frames until this much time has gone by (at least bruteSamples), after
// one untimed warm-up frame (caches, page faults, the floor texture).
constexpr double kBruteBudgetMs = 3000.0;
constexpr int kBruteWarmupFrames = 1;
// Fewer brute-force samples than this make the headline speed-up a quick, indicative figure.
constexpr int kFullModeBruteSamples = 3;

constexpr const char* kAllRaysNote =
    "every ray of the moving-camera frame (nothing reused), the analytic floor and sky rays included: most never "
    "reach Embree, so this is not comparable with embree_mqueries_per_s";

int faceCount(int level) { return 20 << (2 * level); }

// Still: the view of a person watching or dragging the slime (the renderer reuses what the slime
// cannot change). Moving: the camera turns by a thousandth of a degree every frame, as when orbiting,
// so every pixel is traced every frame. Deforming: the camera moves as in Moving and the slime takes
// the plan's shapes in turn (two frames of the physics pulling it up by its top), as while a person
// drags it: every pixel is traced and the BVH refitted every frame.
enum class CameraMotion { Still, Moving, Deforming };

struct FramePlan {
  int warmup = 0;          // untimed frames first
  int frames = 1;          // timed frames at most
  int minFrames = 1;       // timed frames at least, whatever the budget
  double budgetMs = 0.0;   // stop once the timed frames took this long (0: no budget)
  CameraMotion motion = CameraMotion::Still;
  // Deforming: the shapes the frames take in turn (without them, the still mesh every frame).
  const std::vector<TriangleMesh>* shapes = nullptr;
};

struct FrameTiming {
  TimingSummary ms;
  RenderStats stats;  // of the last frame: ray counts are the same every frame
  double refitMs = 0.0;
};

// The headline's deforming frames: the slime this long into stretchTrajectory (0.2 s into the pull).
constexpr double kHeadlinePullSeconds = kStretchSettleSeconds + 0.2;

// The plan's frames, updateSlime every frame as the viewer does. A deforming frame costs its refit too
// (the viewer refits before it traces); the others as before.
FrameTiming timeFrames(Renderer& renderer, const Settings& stillSettings, const TriangleMesh& mesh,
                       const FramePlan& plan, BenchProgress& progress, const std::string& what) {
  Settings settings = stillSettings;
  Image image;
  image.resize(settings.camera.width, settings.camera.height);
  std::vector<double> samples, refits;
  FrameTiming timing;
  double spent = 0.0;
  const std::vector<TriangleMesh> shapes =
      plan.motion == CameraMotion::Deforming && plan.shapes ? *plan.shapes : std::vector<TriangleMesh>{};
  for (int frame = 0; frame < plan.warmup + plan.frames; ++frame) {
    if (plan.motion != CameraMotion::Still) settings.camera.yaw = stillSettings.camera.yaw + (frame % 2 ? 1e-3 : -1e-3);
    const TriangleMesh& shape = shapes.empty() ? mesh : shapes[frame % 2];
    const Stopwatch refitWatch;
    renderer.updateSlime({shape});
    const double refitMs = refitWatch.milliseconds();
    const Stopwatch watch;
    timing.stats = renderer.render(settings, image);
    const double ms = watch.milliseconds() + (plan.motion == CameraMotion::Deforming ? refitMs : 0.0);
    progress.advance(1.0, what);
    if (frame < plan.warmup) continue;
    samples.push_back(ms);
    refits.push_back(timing.stats.refitMs);
    spent += ms;
    if (plan.budgetMs > 0.0 && static_cast<int>(samples.size()) >= plan.minFrames && spent >= plan.budgetMs) {
      progress.advance(plan.warmup + plan.frames - frame - 1, what);
      break;
    }
  }
  timing.ms = summarize(samples);
  timing.refitMs = summarize(refits).median;
  return timing;
}

// The handled frame (issue 28): the camera still and the slime pulled by the hand, one displayed
// frame (1/60 s) further each frame, back and forth through the pull; refit and traced as the viewer
// does it, into the same image and sRGB bytes every frame, so that the pixels outside the slime's
// footprint now and in the last frame are kept (Renderer::render's buffersKept).
FrameTiming timeHandledFrames(Renderer& renderer, const Settings& settings, const std::vector<TriangleMesh>& shapes,
                              int warmup, int frames, BenchProgress& progress, const std::string& what) {
  Image image;
  image.resize(settings.camera.width, settings.camera.height);
  std::vector<std::uint8_t> bytes;
  std::vector<double> samples, refits;
  FrameTiming timing;
  const int count = static_cast<int>(shapes.size()), period = std::max(1, 2 * count - 2);
  for (int frame = 0; frame < warmup + frames; ++frame) {
    const int phase = frame % period;
    const TriangleMesh& shape = shapes[count > 1 && phase >= count ? period - phase : std::min(phase, count - 1)];
    const Stopwatch watch;
    renderer.updateSlime({shape});
    timing.stats = renderer.render(settings, image, &bytes, /*buffersKept=*/frame > 0);
    const double ms = watch.milliseconds();
    progress.advance(1.0, what);
    if (frame < warmup) continue;
    samples.push_back(ms);
    refits.push_back(timing.stats.refitMs);
  }
  timing.ms = summarize(samples);
  timing.refitMs = summarize(refits).median;
  return timing;
}

double megaPerSecond(double count, double ms) { return ms > 0.0 ? count / (ms * 1e3) : 0.0; }

json raysJson(const RenderStats& stats) {
  const RayCounts& r = stats.rays;
  return {{"primary", r.primary}, {"shadow", r.shadow}, {"reflection", r.reflection}, {"refraction", r.refraction},
          {"total", r.total()}, {"slime_queries", stats.slimeQueries}};
}

// One kind of frame: its times, what it reused, its rays, and all its rays per second (every kind,
// the analytic floor and sky included), in millions.
json frameJson(const FrameTiming& timing, const char* what) {
  const RayCounts& r = timing.stats.rays;
  const double ms = timing.ms.median;
  const auto rate = [ms](std::uint64_t count) { return megaPerSecond(static_cast<double>(count), ms); };
  return {{"what", what},
          {"ms", toJson(timing.ms)},
          {"reused_pixels", timing.stats.reusedPixels},
          {"cached_floor_pixels", timing.stats.cachedFloorPixels},
          {"filled_pixels", timing.stats.filledPixels},
          {"traced_fill_pixels", timing.stats.tracedFillPixels},
          {"rays", raysJson(timing.stats)},
          {"all_mrays_per_s", rate(r.total())},
          {"all_mrays_per_s_by_kind",
           {{"primary", rate(r.primary)}, {"shadow", rate(r.shadow)}, {"reflection", rate(r.reflection)},
            {"refraction", rate(r.refraction)}}}};
}

// The configuration the headline quotes: the default scene's level if measured (else the last level),
// on the most threads.
const json* headlineConfiguration(const json& configurations, int preferredLevel) {
  bool preferredMeasured = false;
  for (const json& c : configurations) preferredMeasured |= c["level"].get<int>() == preferredLevel;
  const int level = preferredMeasured || configurations.empty() ? preferredLevel : configurations.back()["level"].get<int>();
  const json* best = nullptr;
  for (const json& c : configurations)
    if (c["level"].get<int>() == level && (!best || c["threads"].get<int>() > (*best)["threads"].get<int>())) best = &c;
  return best;
}

json headlineJson(const json& c, const RenderBenchOptions& options) {
  json headline = {{"level", c["level"]},
                   {"faces", c["faces"]},
                   {"threads", c["threads"]},
                   {"width", c["width"]},
                   {"height", c["height"]},
                   {"depth", c["depth"]},
                   {"embree_mqueries_per_s", c["embree_mqueries_per_s"]},
                   {"embree_queries", c["limit"]["queries"]["total"]},
                   {"embree_only_ms", c["limit_ms_per_frame"]},
                   {"embree_mqueries_per_s_counts",
                    "the moving-camera frame's slime queries (the ones that reach Embree), replayed through "
                    "Embree alone, per second of that replay"},
                   {"all_mrays_per_s", c["all_mrays_per_s"]},
                   {"all_rays", c["moving_camera"]["rays"]["total"]},
                   {"all_mrays_per_s_counts", kAllRaysNote},
                   {"still_camera_frame_ms", c["still_camera_frame_ms"]},
                   {"moving_camera_frame_ms", c["moving_camera_frame_ms"]},
                   {"statistic", "median"}};
  if (c.contains("brute_force")) {
    const json& brute = c["brute_force"];
    const int samples = brute["samples"].get<int>();
    const bool full = samples >= kFullModeBruteSamples;
    headline["speedup_over_brute_full_frame"] = {
        {"ratio", c["full_frame_speedup_over_brute"]},
        {"frame", "moving camera on both sides: every pixel traced, nothing reused from the last frame"},
        {"brute_force_frame_ms", brute["ms"]["median"]},
        {"brute_force_samples", samples},
        {"brute_force_warmup_frames", brute["warmup_frames"]},
        {"brute_force_threads", brute["threads"]},
        {"embree_frame_ms", c["moving_camera_frame_ms"]},
        {"embree_frame_samples", c["moving_camera"]["ms"]["samples"]},
        {"embree_warmup_frames", options.warmup},
        {"embree_threads", c["threads"]},
        {"mode", full ? "full" : "quick: fewer than 3 brute-force samples, an indicative figure only"}};
  }
  return headline;
}

void printRow(const json& c) {
  std::printf("%5d %7d %3d %9.2f %9.2f %12.2f %8.2f %12.2f %8.2f", c["level"].get<int>(), c["faces"].get<int>(),
              c["threads"].get<int>(), c["still_camera_frame_ms"].get<double>(),
              c["moving_camera_frame_ms"].get<double>(), c["all_mrays_per_s"].get<double>(),
              c["limit_ms_per_frame"].get<double>(), c["embree_mqueries_per_s"].get<double>(),
              c["moving_camera_frame_over_limit"].get<double>());
  if (c.contains("brute_force"))
    std::printf(" %10.1f [%2d] %9.0f", c["brute_force_frame_ms"].get<double>(), c["brute_force"]["samples"].get<int>(),
                c["full_frame_speedup_over_brute"].get<double>());
  std::printf("\n");
}

// The headline (issue 15) at one image size, level options.headlineLevel, `threads` threads: the
// still, moving and deforming frames and, measured in the same run right after them, the Embree-only
// replay of the deforming frame's own queries (the even frames' shape and view).
json measureHeadline(const Settings& base, int width, int height, int threads, const RenderBenchOptions& options,
                     BenchProgress& progress) {
  Settings settings = base;
  settings.camera.width = width;
  settings.camera.height = height;
  settings.render.threads = threads;
  settings.slime.level = options.headlineLevel;
  const std::string what = "headline " + std::to_string(width) + "x" + std::to_string(height);
  // The slime as the viewer shows it, from the physics: landed (the still and moving frames) and
  // two frames of it being pulled up by its top (the deforming frames, 1/60 s apart).
  std::vector<std::vector<glm::dvec3>> trajectory;
  TriangleMesh mesh;
  stretchTrajectory(settings, trajectory, mesh.triangles);
  const auto frameAt = [&](double seconds) {
    const auto index = std::min(trajectory.size() - 1, static_cast<std::size_t>(std::lround(seconds / kStretchFrameSeconds)));
    return TriangleMesh{trajectory[index], mesh.triangles};
  };
  mesh = frameAt(kStretchSettleSeconds);
  const std::vector<TriangleMesh> pulled{frameAt(kHeadlinePullSeconds), frameAt(kHeadlinePullSeconds + kStretchFrameSeconds)};
  std::vector<TriangleMesh> pulling;  // every displayed frame of the pull
  for (double t = kStretchSettleSeconds; t <= kStretchSettleSeconds + kStretchPullSeconds + 1e-9; t += kStretchFrameSeconds)
    pulling.push_back(frameAt(t));
  const auto plan = [&](CameraMotion motion) {
    FramePlan p;
    p.warmup = options.warmup;
    p.frames = options.frames;
    p.motion = motion;
    if (motion == CameraMotion::Deforming) p.shapes = &pulled;
    return p;
  };
  Renderer stillRenderer(settings);
  const FrameTiming still = timeFrames(stillRenderer, settings, mesh, plan(CameraMotion::Still), progress, what + ", still");
  Renderer movingRenderer(settings);
  const FrameTiming moving =
      timeFrames(movingRenderer, settings, mesh, plan(CameraMotion::Moving), progress, what + ", moving camera");
  // The deforming and the handled frame gather their caustics as the viewer's moving frames do (a
  // progressive map: one moving budget, Caustics::kMovingDivisor, each frame the shape changes), not
  // the finished map of a snapshot (16 budgets), which would be most of either frame since caustics
  // are on by default and would hide the tracing the ratio is about (issue 28 item 4).
  Renderer deformingRenderer(settings);
  deformingRenderer.setProgressiveCaustics(true);
  const FrameTiming deforming =
      timeFrames(deformingRenderer, settings, mesh, plan(CameraMotion::Deforming), progress, what + ", deforming");
  Renderer handledRenderer(settings);
  handledRenderer.setProgressiveCaustics(true);
  const FrameTiming handled =
      timeHandledFrames(handledRenderer, settings, pulling, options.warmup, options.frames, progress, what + ", handled");

  Settings view = settings;
  view.camera.yaw = settings.camera.yaw - 1e-3;  // timeFrames' even frames
  const TriangleMesh& shape = pulled[0];
  const RayLog log = recordSlimeQueries(view, shape.positions, shape.triangles, width, height);
  EmbreeReplay replay(threads, BvhUpdate::Refit);
  replay.build(shape.positions, shape.triangles);
  replay.replay(log, threads);  // warm-up
  std::vector<double> replayMs, primaryMs, secondaryMs, shadowMs, nonSupportingMs;
  for (int frame = 0; frame < options.frames; ++frame) {
    const ReplayTimes times = replay.replay(log, threads);
    replayMs.push_back(times.totalMs());
    primaryMs.push_back(times.primaryMs);
    secondaryMs.push_back(times.secondaryMs);
    shadowMs.push_back(times.shadowMs);
    nonSupportingMs.push_back(times.nonSupportingMs);
    progress.advance(1.0, what + ": Embree-only replay");
  }
  const TimingSummary limit = summarize(replayMs);
  const auto kind = [](const std::vector<RayPacket>& packets, const std::vector<double>& ms) {
    return json{{"queries", RayLog::activeRays(packets)}, {"ms", summarize(ms).median}};
  };
  const double ms = deforming.ms.median;
  return {{"width", width},
          {"height", height},
          {"level", options.headlineLevel},
          {"threads", threads},
          {"depth", options.depth},
          {"deforming_frame_ms", ms},
          {"deforming_frame", {{"ms", toJson(deforming.ms)}, {"refit_ms", deforming.refitMs}, {"rays", raysJson(deforming.stats)},
                               {"note", "refit + render; camera turned and slime reshaped every frame: every pixel traced"}}},
          {"handled_frame_ms", handled.ms.median},
          {"handled_frame", {{"ms", toJson(handled.ms)}, {"refit_ms", handled.refitMs}, {"reused_pixels", handled.stats.reusedPixels},
                             {"filled_pixels", handled.stats.filledPixels}, {"traced_fill_pixels", handled.stats.tracedFillPixels},
                             {"rays", raysJson(handled.stats)},
                             {"note", "refit + render as the viewer does it: camera still, the slime pulled 1/60 s further "
                                      "each frame, pixels outside its footprint kept from the last frame, inside it a checkerboard "
                                      "traced (render.checkerboard)"}}},
          {"handled_over_deforming", ms > 0.0 ? handled.ms.median / ms : 0.0},
          {"deforming_replay_ms", limit.median},
          {"deforming_replay", {{"ms", toJson(limit)},
                                {"queries", log.queries()},
                                {"by_kind", {{"primary", kind(log.primary, primaryMs)},
                                             {"secondary", kind(log.secondary, secondaryMs)},
                                             {"shadow", kind(log.shadow, shadowMs)},
                                             {"non_supporting", kind(log.nonSupporting, nonSupportingMs)}}}}},
          {"deforming_over_replay", limit.median > 0.0 ? ms / limit.median : 0.0},
          {"moving_camera_ms", moving.ms.median},
          {"still_ms", still.ms.median},
          {"aim_ms", width == 734 && height == 564 ? 16.7 : width == 1280 && height == 720 ? 33.0 : 0.0}};  // issue 15's aims
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

  FramePlan brutePlan;
  brutePlan.warmup = kBruteWarmupFrames;
  brutePlan.minFrames = std::max(1, options.bruteSamples);
  brutePlan.frames = std::max(brutePlan.minFrames, options.frames);
  brutePlan.budgetMs = kBruteBudgetMs;
  brutePlan.motion = CameraMotion::Moving;
  FramePlan stillPlan{options.warmup, options.frames, options.frames, 0.0, CameraMotion::Still};
  FramePlan movingPlan = stillPlan;
  movingPlan.motion = CameraMotion::Moving;

  const int perConfiguration = options.warmup + options.frames;
  double total = 0.0;
  for (int level : options.levels) {
    total += 1.0 + threads.size() * (2.0 * perConfiguration + options.frames);
    if (level <= options.bruteMaxLevel) total += brutePlan.warmup + brutePlan.frames;
  }
  total += 30.0 * options.bvhLevels.size();
  total += options.headlineSizes.size() * (4.0 * perConfiguration + options.frames);
  BenchProgress progress("bench render", total);

  json report = {{"bench", "render"},
                 {"width", options.width},
                 {"height", options.height},
                 {"depth", options.depth},
                 {"cores", cores},
                 {"machine", machineJson()},
                 {"frames", options.frames},
                 {"warmup", options.warmup},
                 {"brute_force_min_samples", brutePlan.minFrames},
                 {"brute_force_warmup_frames", brutePlan.warmup},
                 {"scene", "default scene, undeformed slime resting on the floor"}};
  // The headline first, on all the threads asked for (the most of them).
  const int headlineThreads = *std::max_element(threads.begin(), threads.end());
  json headline = json::array();
  for (const auto& [width, height] : options.headlineSizes)
    headline.push_back(measureHeadline(settings, width, height, headlineThreads, options, progress));
  report["interactive_headline"] = headline;  // issue 15: the deforming frame at each size, beside its replay
  json configurations = json::array();
  CsvTable table{{"level", "faces", "threads", "still_camera_frame_ms", "still_ms_min", "still_ms_max",
                  "moving_camera_frame_ms", "moving_ms_min", "moving_ms_max", "all_mrays_per_s", "all_rays",
                  "limit_ms_per_frame", "embree_mqueries_per_s", "embree_queries", "moving_camera_frame_over_limit",
                  "brute_force_frame_ms", "brute_force_samples", "full_frame_speedup_over_brute",
                  "still_camera_speedup_over_1_thread", "moving_camera_speedup_over_1_thread",
                  "limit_speedup_over_1_thread"}, {}};

  for (int level : options.levels) {
    const std::string label = "level " + std::to_string(level);
    settings.slime.level = level;
    const TriangleMesh mesh = restingSlime(settings.slime, level);
    const RayLog log = recordSlimeQueries(settings, mesh.positions, mesh.triangles, options.width, options.height);
    progress.advance(1.0, label + ": recording rays");

    // The seed's algorithm, single-threaded by design, where it finishes in reasonable time, on the
    // moving-camera frame (every pixel traced) that its speed-up is taken against.
    json brute;
    if (level <= options.bruteMaxLevel) {
      Settings bruteSettings = settings;
      bruteSettings.render.backend = "brute";
      Renderer renderer(bruteSettings);
      const FrameTiming timing = timeFrames(renderer, bruteSettings, mesh, brutePlan, progress, label + ": brute force");
      brute = frameJson(timing, "the seed's algorithm on the moving-camera frame: every pixel traced, one thread");
      brute["samples"] = timing.ms.samples;
      brute["warmup_frames"] = brutePlan.warmup;
      brute["threads"] = 1;
    }

    for (int count : threads) {
      const std::string what = label + ", " + std::to_string(count) + " thread(s)";
      settings.render.threads = count;
      Renderer renderer(settings);
      const FrameTiming still = timeFrames(renderer, settings, mesh, stillPlan, progress, what);
      Renderer movingRenderer(settings);
      const FrameTiming moving = timeFrames(movingRenderer, settings, mesh, movingPlan, progress, what + ", moving camera");

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
      const double movingMs = moving.ms.median;
      const auto queries = [](const std::vector<RayPacket>& packets) { return static_cast<double>(RayLog::activeRays(packets)); };
      json c = {{"level", level},
                {"faces", faceCount(level)},
                {"vertices", mesh.positions.size()},
                {"width", options.width},
                {"height", options.height},
                {"depth", options.depth},
                {"threads", count},
                {"still_camera_frame_ms", still.ms.median},
                {"moving_camera_frame_ms", movingMs},
                {"still_camera", frameJson(still, "still camera: pixels the slime cannot change are copied from the last frame")},
                {"moving_camera", frameJson(moving, "moving camera (turns 0.001 degree a frame): every pixel traced, nothing reused")},
                {"refit_ms", still.refitMs},
                {"embree_mqueries_per_s", megaPerSecond(static_cast<double>(log.queries()), limit.median)},
                {"all_mrays_per_s", megaPerSecond(static_cast<double>(moving.stats.rays.total()), movingMs)},
                {"all_mrays_per_s_counts", kAllRaysNote},
                {"limit_ms_per_frame", limit.median},
                {"limit", {{"ms", toJson(limit)},
                           {"primary_ms", summarize(primaryMs).median},
                           {"secondary_ms", summarize(secondaryMs).median},
                           {"shadow_ms", summarize(shadowMs).median},
                           {"queries", {{"primary", RayLog::activeRays(log.primary)}, {"secondary", RayLog::activeRays(log.secondary)},
                                        {"shadow", RayLog::activeRays(log.shadow)}, {"total", log.queries()}}},
                           {"embree_mqueries_per_s_by_kind",
                            {{"primary", megaPerSecond(queries(log.primary), summarize(primaryMs).median)},
                             {"secondary", megaPerSecond(queries(log.secondary), summarize(secondaryMs).median)},
                             {"shadow", megaPerSecond(queries(log.shadow), summarize(shadowMs).median)}}}}},
                {"moving_camera_frame_over_limit", limit.median > 0.0 ? movingMs / limit.median : 0.0}};
      if (!brute.is_null()) {
        c["brute_force_frame_ms"] = brute["ms"]["median"];
        c["brute_force"] = brute;
        c["full_frame_speedup_over_brute"] = movingMs > 0.0 ? brute["ms"]["median"].get<double>() / movingMs : 0.0;
      }
      configurations.push_back(std::move(c));
    }
  }
  // Parallel speed-up over one thread of the same level, for both frames and for the limit.
  for (json& c : configurations) {
    for (const json& single : configurations) {
      if (single["level"] != c["level"] || single["threads"].get<int>() != 1) continue;
      for (const char* frame : {"still_camera", "moving_camera"})
        c[std::string(frame) + "_speedup_over_1_thread"] =
            single[std::string(frame) + "_frame_ms"].get<double>() / c[std::string(frame) + "_frame_ms"].get<double>();
      c["limit_speedup_over_1_thread"] = single["limit_ms_per_frame"].get<double>() / c["limit_ms_per_frame"].get<double>();
    }
    const auto optional = [&c](const char* key) { return c.contains(key) ? c[key] : json(); };
    const json bruteSamples = c.contains("brute_force") ? c["brute_force"]["samples"] : json();
    table.add({c["level"], c["faces"], c["threads"], c["still_camera_frame_ms"], c["still_camera"]["ms"]["min"],
               c["still_camera"]["ms"]["max"], c["moving_camera_frame_ms"], c["moving_camera"]["ms"]["min"],
               c["moving_camera"]["ms"]["max"], c["all_mrays_per_s"], c["moving_camera"]["rays"]["total"],
               c["limit_ms_per_frame"], c["embree_mqueries_per_s"], c["limit"]["queries"]["total"],
               c["moving_camera_frame_over_limit"], optional("brute_force_frame_ms"), bruteSamples,
               optional("full_frame_speedup_over_brute"), optional("still_camera_speedup_over_1_thread"),
               optional("moving_camera_speedup_over_1_thread"), optional("limit_speedup_over_1_thread")});
  }
  report["configurations"] = configurations;
  if (const json* c = headlineConfiguration(configurations, baseSettings.slime.level)) report["headline"] = headlineJson(*c, options);

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

  if (!headline.empty())
    std::printf("headline  size       level thr  deforming ms  replay ms  deforming/replay  moving ms  still ms  handled ms  "
                "handled/deforming  aim ms\n");
  for (const json& h : headline)
    std::printf("          %4dx%-5d %5d %3d %13.2f %10.2f %17.2f %10.2f %9.2f %11.2f %18.2f %7.1f\n", h["width"].get<int>(),
                h["height"].get<int>(), h["level"].get<int>(), h["threads"].get<int>(), h["deforming_frame_ms"].get<double>(),
                h["deforming_replay_ms"].get<double>(), h["deforming_over_replay"].get<double>(),
                h["moving_camera_ms"].get<double>(), h["still_ms"].get<double>(), h["handled_frame_ms"].get<double>(),
                h["handled_over_deforming"].get<double>(), h["aim_ms"].get<double>());
  // "all M rays/s" counts the analytic floor and sky rays of the moving frame; "Embree Mq/s" only queries.
  std::printf("%5s %7s %3s %9s %9s %12s %8s %12s %8s %15s %9s\n", "level", "faces", "thr", "still ms", "moving ms",
              "all Mrays/s", "limit ms", "Embree Mq/s", "mov/lim", "brute ms [n]", "speed-up");
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
    CsvTable headlineTable{{"width", "height", "pixels", "level", "threads", "deforming_frame_ms", "deforming_replay_ms",
                            "deforming_over_replay", "moving_camera_ms", "still_ms", "handled_frame_ms",
                            "handled_over_deforming", "aim_ms"}, {}};
    for (const json& h : headline)
      headlineTable.add({h["width"], h["height"], h["width"].get<int>() * h["height"].get<int>(), h["level"], h["threads"],
                         h["deforming_frame_ms"], h["deforming_replay_ms"], h["deforming_over_replay"], h["moving_camera_ms"],
                         h["still_ms"], h["handled_frame_ms"], h["handled_over_deforming"], h["aim_ms"]});
    if (!headline.empty()) writeCsvFile(headlineTable, siblingCsvPath(options.csvFile, "headline"));
  }
  return report;
}

}  // namespace slime

// Not a timed test: run by hand to measure frame time and ray throughput (README figures).
//   SLIME_BENCH_THREADS=2 build/perf/tests/render_tests --gtest_also_run_disabled_tests
//     --gtest_filter='RenderBench.*'   (SLIME_BENCH_LEVEL=4: that level only; SLIME_BENCH_FRAMES=n)
#include "render_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace slime::testing {
namespace {

TEST(RenderBench, DISABLED_LevelsZeroToSixAt734x564) {
  const char* threadsText = std::getenv("SLIME_BENCH_THREADS");
  const char* framesText = std::getenv("SLIME_BENCH_FRAMES");
  const char* levelText = std::getenv("SLIME_BENCH_LEVEL");  // one level only (e.g. under callgrind)
  const int frames = framesText ? std::max(1, std::atoi(framesText)) : 15;
  const int firstLevel = levelText ? std::atoi(levelText) : 0, lastLevel = levelText ? firstLevel : 6;
  for (int level = firstLevel; level <= lastLevel; ++level) {
    Settings settings = smallScene(734, 564);
    settings.render.threads = threadsText ? std::atoi(threadsText) : 2;
    settings.slime.level = level;
    const TriangleMesh mesh = restingMesh(settings);
    Renderer renderer(settings);
    renderer.updateSlime({mesh});
    Image image;
    image.resize(settings.camera.width, settings.camera.height);
    renderer.render(settings, image);  // warm-up: thread pool, caches
    std::vector<double> times, cpuTimes;
    RenderStats stats;
    for (int frame = 0; frame < frames; ++frame) {
      const std::clock_t cpuStart = std::clock();
      renderer.updateSlime({mesh});
      stats = renderer.render(settings, image);
      times.push_back(stats.traceMs + stats.refitMs);
      cpuTimes.push_back(1e3 * static_cast<double>(std::clock() - cpuStart) / CLOCKS_PER_SEC);
    }
    std::sort(times.begin(), times.end());
    std::sort(cpuTimes.begin(), cpuTimes.end());
    const double median = times[times.size() / 2];
    // On a shared machine wall time suffers from other processes; CPU time per thread does not.
    std::printf("level %d: cpu %.2f ms per frame over all threads (%.2f ms per thread)\n", level,
                cpuTimes[cpuTimes.size() / 2], cpuTimes[cpuTimes.size() / 2] / settings.render.threads);
    const RayCounts& r = stats.rays;
    std::printf("level %d (%6zu faces): %7.2f ms/frame median of %d, all rays (floor and sky included) %5.1f M/s; rays %.3f M: primary %.3f, "
                "shadow %.3f, reflection %.3f, refraction %.3f; slime queries %.3f M; refit %.3f ms\n",
                level, mesh.triangles.size(), median, frames, static_cast<double>(r.total()) / median / 1e3,
                r.total() / 1e6, r.primary / 1e6, r.shadow / 1e6, r.reflection / 1e6, r.refraction / 1e6,
                stats.slimeQueries / 1e6, stats.refitMs);
  }
}

}  // namespace
}  // namespace slime::testing

namespace slime::testing {
namespace {

// The floor and sky alone: the cost of the pixels that never see the slime.
TEST(RenderBench, DISABLED_FloorOnlyAt734x564) {
  Settings settings = smallScene(734, 564);
  const char* threadsText = std::getenv("SLIME_BENCH_THREADS");
  settings.render.threads = threadsText ? std::atoi(threadsText) : 2;
  Renderer renderer(settings);
  renderer.updateSlime({});
  Image image;
  image.resize(settings.camera.width, settings.camera.height);
  renderer.render(settings, image);
  std::vector<double> cpuTimes;
  for (int frame = 0; frame < 9; ++frame) {
    const std::clock_t cpuStart = std::clock();
    renderer.render(settings, image);
    cpuTimes.push_back(1e3 * static_cast<double>(std::clock() - cpuStart) / CLOCKS_PER_SEC);
  }
  std::sort(cpuTimes.begin(), cpuTimes.end());
  std::printf("floor only: cpu %.2f ms per frame over all threads\n", cpuTimes[cpuTimes.size() / 2]);
}

}  // namespace
}  // namespace slime::testing

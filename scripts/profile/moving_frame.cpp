// Profiling driver (issue 15): the render bench's moving-camera frame (every pixel traced; the camera
// turns by 1e-3 degrees each frame), level 4, depth 3, nothing else in the process, so that a
// profiler sees only it. Not part of the CMake build; after a release build:
//   g++ -std=c++20 -O2 -g -march=native -I. -Ibuild/release/core scripts/profile/moving_frame.cpp \
//     build/release/app/bench/libslime_bench.a build/release/render/libslime_render.a \
//     build/release/core/libslime_core.a -lembree3 -ltbb -lstb -lpthread -o build/moving_frame
//   perf record -F 2000 build/moving_frame 40 734 564 2 && perf report --no-children --sort dso,symbol
// Arguments: frames, width, height, threads, [PNG of the last frame]. Prints the median wall and CPU
// (process, all threads) time per frame: CPU time is the steadier figure on a shared machine.
#include "app/bench/render/bench_bvh.h"
#include "core/geometry/icosphere.h"
#include "core/settings/settings_io.h"
#include "render/image/image_io.h"
#include "render/trace/renderer.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <vector>

using namespace slime;

namespace {

double processCpuMilliseconds() {
  timespec now;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return now.tv_sec * 1e3 + now.tv_nsec * 1e-6;
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const int frames = argc > 1 ? std::atoi(argv[1]) : 50;
  const int width = argc > 2 ? std::atoi(argv[2]) : 734, height = argc > 3 ? std::atoi(argv[3]) : 564;
  Settings settings = defaultSettings();
  settings.camera.width = width;
  settings.camera.height = height;
  settings.render.depth = std::getenv("SLIME_PROFILE_DEPTH") ? std::atoi(std::getenv("SLIME_PROFILE_DEPTH")) : 3;
  settings.render.threads = argc > 4 ? std::atoi(argv[4]) : 2;
  // SLIME_PROFILE_LEVEL=L: the slime drawn at level L (default 4).
  settings.slime.level = std::getenv("SLIME_PROFILE_LEVEL") ? std::atoi(std::getenv("SLIME_PROFILE_LEVEL")) : 4;
  // SLIME_PROFILE_DEFORMING=1: the headline's deforming frames (the physics' slime pulled by its top,
  // two frames 1/60 s apart, alternating), else the icosphere on the floor.
  const bool deforming = std::getenv("SLIME_PROFILE_DEFORMING") != nullptr;
  // SLIME_PROFILE_STILL=1: the camera holds still (pixels the slime cannot reach are copied), as in
  // the viewer while a person drags the slime.
  const bool still = std::getenv("SLIME_PROFILE_STILL") != nullptr;
  std::vector<TriangleMesh> shapes{makeIcosphere(settings.slime.level, settings.slime.radius,
                                                 {settings.slime.position.x, settings.slime.position.y, settings.slime.radius})};
  if (deforming) {
    std::vector<std::vector<glm::dvec3>> trajectory;
    std::vector<Triangle> triangles;
    settings.slime.shape = "mesh";
    stretchTrajectory(settings, trajectory, triangles);
    const auto at = [&](double seconds) {
      return TriangleMesh{trajectory[std::min(trajectory.size() - 1, static_cast<std::size_t>(std::lround(seconds * 60.0)))], triangles};
    };
    shapes = {at(0.6), at(0.6 + 1.0 / 60.0)};
    if (std::getenv("SLIME_PROFILE_ONE_SHAPE")) shapes.pop_back();
  }
  Renderer renderer(settings);
  Image image;
  image.resize(width, height);
  std::vector<std::uint8_t> bytes;
  std::vector<double> wallMs, cpuMs, refitMs, setupMs, busyMs;
  const double yaw = settings.camera.yaw;
  for (int frame = 0; frame < frames; ++frame) {
    if (!still) settings.camera.yaw = yaw + (frame % 2 ? 1e-3 : -1e-3);  // as bench render's moving camera
    const TriangleMesh& mesh = shapes[frame % shapes.size()];
    const auto refitStart = std::chrono::steady_clock::now();
    renderer.updateSlime({mesh});
    refitMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - refitStart).count());
    const auto start = std::chrono::steady_clock::now();
    const double cpuStart = processCpuMilliseconds();
    const RenderStats stats = renderer.render(settings, image, &bytes, true);
    cpuMs.push_back(processCpuMilliseconds() - cpuStart);
    wallMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    setupMs.push_back(stats.setupMs);
    busyMs.push_back(stats.busyMs);
    if (frame == 0)
      std::fprintf(stderr, "rays %llu, slime queries %llu, reused pixels %llu\n",
                   static_cast<unsigned long long>(stats.rays.total()), static_cast<unsigned long long>(stats.slimeQueries),
                   static_cast<unsigned long long>(stats.reusedPixels));
  }
  if (argc > 5) writePng(image, argv[5]);
  std::printf("median %.2f ms wall, %.2f ms CPU per frame (%d frames); refit %.2f, set-up %.2f, tiles %.2f ms (summed over the threads)\n",
              median(wallMs), median(cpuMs), frames, median(refitMs), median(setupMs), median(busyMs));
}

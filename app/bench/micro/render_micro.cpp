// Micro-benchmarks of the renderer: one 32×8 tile's worth of the default frame (a 32×8 image looking
// at the slime's centre) and one whole frame at a small size (160×120), level 4, one thread, and the
// refit of the slime's BVH after its vertices move; and the floor's pattern alone, looked up where
// the default view sees it (under and around the slime, pixel footprints of about half a millimetre).
#include "core/geometry/camera.h"
#include "core/geometry/icosphere.h"
#include "core/settings/settings_io.h"
#include "render/floor/floor_texture.h"
#include "render/trace/renderer.h"
#include "render/simd/wide_lanes.h"

#include <benchmark/benchmark.h>

namespace slime {
namespace {

Settings smallFrame(int width, int height) {
  Settings settings = defaultSettings();
  settings.camera.width = width;
  settings.camera.height = height;
  settings.render.threads = 1;
  return settings;
}

TriangleMesh restingMesh(const Settings& settings) {
  return makeIcosphere(settings.slime.level, settings.slime.radius, {0.0, 0.0, settings.slime.radius});
}

void renderImage(benchmark::State& state, int width, int height, double fov) {
  Settings settings = smallFrame(width, height);
  settings.camera.fov = fov;
  lookAt(settings.camera, settings.camera.position, {0.0, 0.0, settings.slime.radius});
  const TriangleMesh mesh = restingMesh(settings);
  Renderer renderer(settings);
  renderer.updateSlime({mesh});
  Image image;
  image.resize(width, height);
  std::uint64_t rays = 0;
  for (auto _ : state) rays += renderer.render(settings, image).rays.total();
  state.counters["rays/s"] = benchmark::Counter(static_cast<double>(rays), benchmark::Counter::kIsRate);
}

// A tile through the slime: the narrow field of view puts every pixel of the 32×8 image on it.
void renderTile(benchmark::State& state) { renderImage(state, 32, 8, 3.0); }
BENCHMARK(renderTile)->Unit(benchmark::kMicrosecond);

void renderSmallFrame(benchmark::State& state) { renderImage(state, 160, 120, 45.0); }
BENCHMARK(renderSmallFrame)->Unit(benchmark::kMillisecond);

void refitSlime(benchmark::State& state) {
  Settings settings = smallFrame(16, 16);
  settings.slime.level = static_cast<int>(state.range(0));
  TriangleMesh mesh = restingMesh(settings);
  Renderer renderer(settings);
  renderer.updateSlime({mesh});
  double wobble = 0.0;
  for (auto _ : state) {
    wobble = wobble > 0.0 ? -1e-4 : 1e-4;  // a small move so that the refit has work
    for (glm::dvec3& p : mesh.positions) p.z += wobble;
    renderer.updateSlime({mesh});
  }
}
BENCHMARK(refitSlime)->Arg(4)->Arg(6)->Unit(benchmark::kMicrosecond);

void floorAlbedo(benchmark::State& state) {
  FloorSettings floorSettings = defaultSettings().floor;
  const char* patterns[] = {"planks", "tiles", "checker"};
  floorSettings.pattern = patterns[state.range(0)];
  const FloorTexture floor(floorSettings);
  constexpr int kSide = 64;  // a 64 × 64 grid over 0.3 m × 0.3 m around the slime
  glm::vec3 sum(0.0f);
  for (auto _ : state) {
    for (int j = 0; j < kSide; ++j)
      for (int i = 0; i < kSide; ++i)
        sum += floor.albedo({-0.15f + 0.3f * i / kSide, -0.12f + 0.3f * j / kSide}, {4e-4f, 2.5e-4f});
  }
  benchmark::DoNotOptimize(sum);
  state.SetItemsProcessed(state.iterations() * kSide * kSide);
  state.SetLabel(patterns[state.range(0)]);
}
BENCHMARK(floorAlbedo)->DenseRange(0, 2)->Unit(benchmark::kMicrosecond);

// The planks N lookups at a time (FloorTexture::albedoLanes: 8 lanes with AVX2, 16 with AVX-512), on
// the same grid as floorAlbedo; items are lookups.
template <int N>
void floorAlbedoLanes(benchmark::State& state) {
  const FloorTexture floor(defaultSettings().floor);
  constexpr int kSide = 64;
  static_assert(kSide % N == 0, "whole runs of lanes along a row");
  float x[N], y[N], footprintX[N], footprintY[N], channels[3][N];
  bool active[N];
  for (int i = 0; i < N; ++i) {
    footprintX[i] = 4e-4f;
    footprintY[i] = 2.5e-4f;
    active[i] = true;
  }
  float sum = 0.0f;
  for (auto _ : state) {
    for (int j = 0; j < kSide; ++j) {
      for (int i0 = 0; i0 < kSide; i0 += N) {
        for (int i = 0; i < N; ++i) {
          x[i] = -0.15f + 0.3f * static_cast<float>(i0 + i) / kSide;
          y[i] = -0.12f + 0.3f * static_cast<float>(j) / kSide;
        }
        floor.albedoLanes<N>(x, y, footprintX, footprintY, active, channels);
        sum += channels[0][0];
      }
    }
  }
  benchmark::DoNotOptimize(sum);
  state.SetItemsProcessed(state.iterations() * kSide * kSide);
}
BENCHMARK(floorAlbedoLanes<8>)->Unit(benchmark::kMicrosecond);
#if defined(SLIME_WIDE_LANES_16)
BENCHMARK(floorAlbedoLanes<16>)->Unit(benchmark::kMicrosecond);
#endif

}  // namespace
}  // namespace slime

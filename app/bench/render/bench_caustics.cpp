#include "app/bench/render/bench_caustics.h"

#include "core/geometry/icosphere.h"
#include "render/caustics/caustic_map.h"
#include "render/caustics/photon_tracer.h"
#include "render/trace/embree_scene.h"
#include "render/trace/shading_parameters.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>

namespace slime {
namespace {

struct LensScene {
  SlimeGeometry geometry;
  EmbreeScene embree{0};
  ShadingParameters parameters;
  PhotonCone cone;
  FloorRegion region;
};

// The wavefront map (render/caustics/wavefront.h) of a grid of at most n vertices (side ⌊√n⌋ − 1),
// traced on all threads (chunks in order, as the renderer) and gathered.
CausticMap mapOf(const LensScene& scene, int photons, double& ms) {
  const auto start = std::chrono::steady_clock::now();
  const PhotonTracer tracer(scene.geometry, scene.embree, scene.parameters);
  const WavefrontGrid grid(std::max(2, static_cast<int>(std::sqrt(static_cast<double>(photons))) - 1), 1);
  constexpr std::uint64_t kChunk = 1024;
  const std::uint64_t vertices = grid.vertices(), chunks = (vertices + kChunk - 1) / kChunk;
  std::vector<std::vector<WavefrontVertex>> found(chunks);
  std::vector<PhotonTally> tallies(chunks);
  tbb::parallel_for(std::uint64_t{0}, chunks, [&](std::uint64_t c) {
    const std::uint64_t begin = c * kChunk;
    traceWavefront(tracer, scene.cone, grid, begin, std::min(kChunk, vertices - begin), found[c], tallies[c]);
  });
  std::vector<WavefrontVertex> traced;
  traced.reserve(vertices);
  for (const auto& f : found) traced.insert(traced.end(), f.begin(), f.end());
  CausticMap map;
  map.buildWavefront(grid, 0, traced, scene.cone, scene.region);
  ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return map;
}

}  // namespace

nlohmann::json runCausticsBench(const Settings& initial, const CausticsBenchOptions& options) {
  Settings settings = initial;
  LensScene scene;
  const double radius = settings.slime.radius, n = settings.slime.ior;
  const double focal = n * radius / (2.0 * (n - 1.0));  // the ball lens's f = nR / (2 (n − 1))
  const glm::dvec3 center{0.0, 0.0, focal};
  settings.slime.shape = "sphere";
  settings.slime.color = {1.0, 1.0, 1.0};
  settings.slime.absorption = 0.0;
  settings.slime.transmission = 1.0;
  settings.light.position = center + glm::dvec3(0.0, 0.0, 50.0);
  const TriangleMesh mesh = makeIcosphere(2, radius, center);
  const bool topology = scene.geometry.update(mesh.positions, mesh.triangles);
  scene.geometry.setAnalyticSphere(true, static_cast<float>(radius));
  scene.embree.update(scene.geometry, topology);
  scene.parameters = makeShadingParameters(settings, 100);
  scene.cone = photonCone(scene.geometry, scene.parameters.lightPosition);
  scene.region = shadowRegion(scene.cone, scene.geometry.boundCenter, scene.geometry.boundRadius);

  const int largest = *std::max_element(options.photons.begin(), options.photons.end());
  double referenceMs = 0.0;
  const CausticMap reference = mapOf(scene, 64 * largest, referenceMs);
  // The error: over a grid of 0.25 mm across the ball's shadow (a disk of radius R about the focus)
  // outside the focus's 2 mm (where the irradiance grows without bound as the cells narrow), the
  // mean absolute difference from the reference relative to the reference's mean: Σ|m − r| / Σ r;
  // and the share of the power the map puts within 2 mm of the focus, against the reference's.
  // The focus's disk on a grid of 0.01 mm, finer than any map's cells here (the reference's are
  // 0.025 mm): its sum is the light there, not a sample of a spike a cell wide.
  std::vector<glm::vec2> points, focus;
  for (double y = -radius; y <= radius; y += 2.5e-4)
    for (double x = -radius; x <= radius; x += 2.5e-4) {
      const double r2 = x * x + y * y;
      if (r2 <= radius * radius && r2 >= 4e-6) points.emplace_back(static_cast<float>(x), static_cast<float>(y));
    }
  for (double y = -2e-3; y <= 2e-3; y += 1e-5)
    for (double x = -2e-3; x <= 2e-3; x += 1e-5)
      if (x * x + y * y < 4e-6) focus.emplace_back(static_cast<float>(x), static_cast<float>(y));
  const auto sumOver = [](const CausticMap& map, const std::vector<glm::vec2>& where) {
    double sum = 0.0;
    for (const glm::vec2& p : where) sum += map.irradiance(p.x, p.y).x;
    return sum;
  };
  const double referenceSum = sumOver(reference, points), referenceFocus = sumOver(reference, focus);

  nlohmann::json rows = nlohmann::json::array();
  std::ofstream csv;
  if (!options.csvFile.empty()) {
    csv.open(options.csvFile);
    csv << "photons,ms,error,focus_error,cell_mm\n";
  }
  std::printf("caustics on the ball lens (R %.3f m, n %.2f, focus %.4f m below the centre), reference %d photons (%.0f ms)\n",
              radius, n, focal, 64 * largest, referenceMs);
  std::printf("%10s %10s %12s %12s %9s\n", "photons", "ms", "error", "focus error", "cell mm");
  for (const int photons : options.photons) {
    std::vector<double> times;
    CausticMap map;
    for (int k = 0; k < std::max(1, options.frames); ++k) {
      double ms = 0.0;
      map = mapOf(scene, photons, ms);
      times.push_back(ms);
    }
    std::sort(times.begin(), times.end());
    const double ms = times[times.size() / 2];
    double sum = 0.0;
    for (const glm::vec2& p : points) sum += std::abs(map.irradiance(p.x, p.y).x - reference.irradiance(p.x, p.y).x);
    const double rms = sum / referenceSum;
    const double peak = std::abs(sumOver(map, focus) - referenceFocus) / referenceFocus;
    std::printf("%10d %10.2f %12.4f %12.4f %9.3f\n", photons, ms, rms, peak, 1e3 * map.cellSize());
    rows.push_back({{"photons", photons}, {"ms", ms}, {"error", rms}, {"focusError", peak}, {"cellMm", 1e3 * map.cellSize()}});
    if (csv) csv << photons << ',' << ms << ',' << rms << ',' << peak << ',' << 1e3 * map.cellSize() << '\n';
  }
  return rows;
}

}  // namespace slime

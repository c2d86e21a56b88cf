#include "app/bench/render/bench_accuracy.h"

#include "app/bench/report/bench_progress.h"
#include "app/bench/render/bench_render.h"
#include "app/bench/report/bench_report.h"
#include "app/bench/report/bench_timing.h"
#include "core/geometry/camera.h"
#include "core/geometry/level_of_detail.h"
#include "render/image/image_io.h"
#include "render/trace/renderer.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace slime {
namespace {

using nlohmann::json;

constexpr double kMaxPsnr = 99.0;

struct Frame {
  Image image;
  double ms = 0.0;
};

Frame renderTimed(const Settings& settings, const TriangleMesh& mesh, int frames) {
  Renderer renderer(settings);
  renderer.updateSlime({mesh});
  Frame frame;
  frame.image.resize(settings.camera.width, settings.camera.height);
  renderer.render(settings, frame.image);  // untimed: first touches of memory and threads
  std::vector<double> samples;
  for (int i = 0; i < frames; ++i) {
    const Stopwatch watch;
    renderer.render(settings, frame.image);
    samples.push_back(watch.milliseconds());
  }
  frame.ms = summarize(samples).median;
  return frame;
}

// |a − b| per channel, magnified kDifferenceGain times, so that a one-step error shows.
constexpr float kDifferenceGain = 8.0f;
Image differenceImage(const Image& a, const Image& b) {
  Image difference;
  difference.resize(a.width, a.height);
  for (std::size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i)
    difference.pixels[i] = kDifferenceGain * glm::abs(a.pixels[i] - b.pixels[i]);
  return difference;
}

}  // namespace

ImageError compareImages(const Image& image, const Image& reference) {
  if (image.width != reference.width || image.height != reference.height)
    throw std::invalid_argument("compareImages: the images differ in size");
  const std::vector<std::uint8_t> a = toSrgb8(image), b = toSrgb8(reference);
  ImageError error;
  double sumSquares = 0.0;
  std::size_t visible = 0;
  for (std::size_t pixel = 0; pixel + 2 < a.size(); pixel += 3) {
    int largest = 0;
    for (std::size_t c = pixel; c < pixel + 3; ++c) {
      const int difference = std::abs(static_cast<int>(a[c]) - static_cast<int>(b[c]));
      sumSquares += static_cast<double>(difference) * difference;
      largest = std::max(largest, difference);
    }
    error.maxError = std::max(error.maxError, static_cast<double>(largest));
    visible += largest > kVisibleStep;
  }
  const std::size_t pixels = a.size() / 3;
  error.rmse = pixels ? std::sqrt(sumSquares / static_cast<double>(a.size())) : 0.0;
  error.psnr = error.rmse > 0.0 ? std::min(kMaxPsnr, 20.0 * std::log10(255.0 / error.rmse)) : kMaxPsnr;
  error.visibleFraction = pixels ? static_cast<double>(visible) / static_cast<double>(pixels) : 0.0;
  return error;
}

json runAccuracyBench(const Settings& baseSettings, const AccuracyBenchOptions& options) {
  Settings settings = baseSettings;
  settings.camera.width = options.width;
  settings.camera.height = options.height;
  settings.render.threads = options.threads;
  settings.render.backend = "embree";
  const int largestDepth = *std::max_element(options.depths.begin(), options.depths.end());
  const double units = options.depths.size() + options.levels.size() * options.normals.size() * options.depths.size();
  BenchProgress progress("bench accuracy", units);

  // The slime resting on the floor; the analytic sphere takes the centre of its vertices.
  const TriangleMesh sphereMesh = restingSlime(settings.slime, 3);
  const glm::dvec3 centre{settings.slime.position.x, settings.slime.position.y, settings.slime.radius};
  const double distance = glm::length(settings.camera.position - centre);

  // References and the sphere's own cost at every depth.
  std::vector<Frame> spheres;
  Settings sphereSettings = settings;
  sphereSettings.slime.shape = "sphere";
  for (int depth : options.depths) {
    sphereSettings.render.depth = depth;
    spheres.push_back(renderTimed(sphereSettings, sphereMesh, options.frames));
    progress.advance(1.0, "analytic sphere, depth " + std::to_string(depth));
  }
  const Image& reference = spheres[std::find(options.depths.begin(), options.depths.end(), largestDepth) - options.depths.begin()].image;
  if (!options.imageDirectory.empty()) writePng(reference, options.imageDirectory + "/accuracy_reference.png");

  CsvTable table{{"level", "faces", "normals", "depth", "ms_per_frame", "rmse", "psnr", "max_error", "visible_fraction",
                  "invisible", "sagitta_px"}, {}};
  json runs = json::array();
  json cheapest;
  settings.slime.shape = "mesh";
  for (int level : options.levels) {
    const TriangleMesh mesh = restingSlime(settings.slime, level);
    const double sagittaPixels = projectedSagittaPixels(level, settings.slime.radius, distance, settings.camera.fov, options.height);
    for (const std::string& normals : options.normals) {
      for (std::size_t d = 0; d < options.depths.size(); ++d) {
        settings.slime.level = level;
        settings.render.normals = normals;
        settings.render.depth = options.depths[d];
        const Frame frame = renderTimed(settings, mesh, options.frames);
        const ImageError error = compareImages(frame.image, reference);
        const ImageError geometric = compareImages(frame.image, spheres[d].image);
        const bool invisible = error.visibleFraction <= kVisibleFraction;
        json entry = {{"level", level}, {"faces", mesh.triangles.size()}, {"normals", normals}, {"depth", options.depths[d]},
                      {"ms_per_frame", frame.ms}, {"rmse", error.rmse}, {"psnr", error.psnr}, {"max_error", error.maxError},
                      {"visible_fraction", error.visibleFraction}, {"invisible", invisible}, {"sagitta_px", sagittaPixels},
                      {"geometric_only", {{"rmse", geometric.rmse}, {"psnr", geometric.psnr}, {"max_error", geometric.maxError},
                                          {"visible_fraction", geometric.visibleFraction},
                                          {"invisible", geometric.visibleFraction <= kVisibleFraction}}}};
        table.add({level, mesh.triangles.size(), normals, options.depths[d], frame.ms, error.rmse, error.psnr, error.maxError,
                   error.visibleFraction, invisible, sagittaPixels});
        if (invisible && (cheapest.is_null() || frame.ms < cheapest["ms_per_frame"].get<double>())) cheapest = entry;
        if (!options.imageDirectory.empty() && normals == "smooth" && options.depths[d] == 3) {
          const std::string stem = options.imageDirectory + "/accuracy_level" + std::to_string(level);
          writePng(frame.image, stem + ".png");
          writePng(differenceImage(frame.image, spheres[d].image), stem + "_difference.png");
        }
        runs.push_back(std::move(entry));
        progress.advance(1.0, "level " + std::to_string(level) + ", " + normals + ", depth " + std::to_string(options.depths[d]));
      }
    }
  }
  progress.finish();

  // The on-screen sagitta of the smallest level whose mesh is invisible against the sphere at the same
  // depth (smooth normals, the scene's own depth: at depth 1 no refraction shows the facets): the
  // threshold that slime.level=auto (core/geometry/level_of_detail.h) should use.
  json smallestInvisible;
  for (const json& run : runs)
    if (run["geometric_only"]["invisible"].get<bool>() && run["normals"] == "smooth" &&
        run["depth"].get<int>() == baseSettings.render.depth &&
        (smallestInvisible.is_null() || run["level"].get<int>() < smallestInvisible["level"].get<int>()))
      smallestInvisible = run;

  json report = {{"bench", "accuracy"}, {"machine", machineJson()}, {"width", options.width}, {"height", options.height},
                 {"reference", {{"shape", "sphere"}, {"depth", largestDepth}}}, {"distance", distance},
                 {"threshold", {{"step", kVisibleStep}, {"fraction", kVisibleFraction},
                                {"rule", "invisible when at most 1% of the pixels differ by more than 2 steps of 8-bit sRGB"}}},
                 {"runs", runs}, {"cheapest_invisible", cheapest}, {"smallest_invisible_smooth", smallestInvisible},
                 {"auto_level", {{"threshold_px", kInvisibleSagittaPixels},
                                 {"chosen_here", chooseLevel(settings.slime.radius, distance, settings.camera.fov, options.height)}}}};
  json sphereCost = json::array();
  for (std::size_t d = 0; d < options.depths.size(); ++d) sphereCost.push_back({{"depth", options.depths[d]}, {"ms_per_frame", spheres[d].ms}});
  report["sphere_cost"] = sphereCost;

  std::printf("level normals depth  ms/frame   RMSE   PSNR dB  max  >2 steps  sagitta px\n");
  for (const json& run : runs)
    std::printf("%5d %-7s %5d %9.2f %6.2f %8.2f %4.0f %8.4f%% %9.4f%s\n", run["level"].get<int>(),
                run["normals"].get<std::string>().c_str(), run["depth"].get<int>(), run["ms_per_frame"].get<double>(),
                run["rmse"].get<double>(), run["psnr"].get<double>(), run["max_error"].get<double>(),
                100.0 * run["visible_fraction"].get<double>(), run["sagitta_px"].get<double>(),
                run["invisible"].get<bool>() ? "  invisible" : "");
  if (cheapest.is_null()) {
    std::printf("no configuration is below visibility\n");
  } else {
    std::printf("cheapest invisible: level %d, %s normals, depth %d: %.2f ms/frame, PSNR %.2f dB\n", cheapest["level"].get<int>(),
                cheapest["normals"].get<std::string>().c_str(), cheapest["depth"].get<int>(),
                cheapest["ms_per_frame"].get<double>(), cheapest["psnr"].get<double>());
  }
  if (!smallestInvisible.is_null())
    std::printf("smallest invisible level (smooth): %d, on-screen sagitta %.3f px (slime.level=auto threshold %.3f px)\n",
                smallestInvisible["level"].get<int>(), smallestInvisible["sagitta_px"].get<double>(), kInvisibleSagittaPixels);

  if (!options.jsonFile.empty()) writeJsonFile(report, options.jsonFile);
  if (!options.csvFile.empty()) writeCsvFile(table, options.csvFile);
  return report;
}

}  // namespace slime

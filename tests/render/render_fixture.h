// Helpers shared by the render tests: a small default scene, one-call rendering and image comparison.
#pragma once

#include "core/geometry/icosphere.h"
#include "core/simulation/simulation.h"
#include "core/settings/settings.h"
#include "core/settings/settings_io.h"
#include "render/image/image_io.h"
#include "render/trace/renderer.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

namespace slime::testing {

// The small scene without caustics (on by default since issue 30): for the tests about the camera's
// rays, the brute-force oracle or the redraw logic, not the light through the slime. The brute force
// traces its photons on one thread with its O(triangles) queries (some 30 times Embree's time), and
// the map's photons follow every sub-pixel move of the mesh, which those invariants do not concern.
inline Settings withoutCaustics(Settings settings) {
  settings.render.caustics = false;
  return settings;
}

// The default scene at a small size with the slime resting on the floor, all threads.
inline Settings smallScene(int width = 96, int height = 72) {
  Settings settings = defaultSettings();
  settings.camera.width = width;
  settings.camera.height = height;
  settings.slime.position = {0.0, 0.0, settings.slime.radius};
  return settings;
}

// The small scene with a slime that bends, reflects and absorbs nothing (ior 1, transmission 1, no
// absorption, no Phong terms) and a floor without its mirror term: a path through the slime spends two
// of the depth-3 segments in it, so the floor seen through it could not trace its reflection.
inline Settings invisibleSlimeScene() {
  Settings settings = smallScene(96, 72);
  settings.slime.ior = 1.0;
  settings.slime.transmission = 1.0;
  settings.slime.absorption = 0.0;
  settings.slime.specular = settings.slime.diffuse = settings.slime.ambient = 0.0;
  settings.floor.specular = 0.0;
  return settings;
}

inline TriangleMesh restingMesh(const Settings& settings) {
  return makeIcosphere(settings.slime.level, settings.slime.radius, settings.slime.position);
}

// The slime settled as `slime snapshot` settles it: dropped from its start position, until no vertex
// moves faster than 5 mm/s (after 0.3 s), at most 3 s.
inline TriangleMesh settledMesh(const Settings& settings) {
  Simulation simulation(settings);
  while (simulation.time() < 3.0) {
    simulation.step();
    if (simulation.time() > 0.3 && simulation.stepCount() % 10 == 0 && simulation.metrics().maxSpeed < 0.005) break;
  }
  return {simulation.positions(), simulation.triangles()};
}

// Renders `mesh` (or nothing when it is empty) with the given settings.
inline Image renderMesh(const Settings& settings, const TriangleMesh& mesh, RenderStats* stats = nullptr) {
  Renderer renderer(settings);
  renderer.updateSlime({mesh});
  Image image;
  image.resize(settings.camera.width, settings.camera.height);
  const RenderStats result = renderer.render(settings, image);
  if (stats) *stats = result;
  return image;
}

inline Image renderScene(const Settings& settings, RenderStats* stats = nullptr) {
  return renderMesh(settings, restingMesh(settings), stats);
}

// Per-pixel comparison in 8-bit sRGB, the units a person sees.
struct ImageDifference {
  double largest = 0.0;         // largest channel difference, in 1/255 steps
  double fractionAbove = 0.0;   // fraction of pixels with any channel differing by more than the tolerance
  double mean = 0.0;            // mean channel difference, in 1/255 steps
};

inline ImageDifference compareImages(const Image& a, const Image& b, double tolerance) {
  ImageDifference difference;
  const auto bytesA = toSrgb8(a), bytesB = toSrgb8(b);
  if (bytesA.size() != bytesB.size() || bytesA.empty()) return {255.0, 1.0, 255.0};
  std::size_t above = 0;
  double sum = 0.0;
  for (std::size_t pixel = 0; pixel < bytesA.size() / 3; ++pixel) {
    double worst = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double d = std::abs(static_cast<double>(bytesA[3 * pixel + c]) - bytesB[3 * pixel + c]);
      worst = std::max(worst, d);
      sum += d;
    }
    difference.largest = std::max(difference.largest, worst);
    if (worst > tolerance) ++above;
  }
  difference.fractionAbove = static_cast<double>(above) / static_cast<double>(bytesA.size() / 3);
  difference.mean = sum / static_cast<double>(bytesA.size());
  return difference;
}

// |a − b| × 8 per channel, so that small differences are visible in the written PNG.
inline Image differenceImage(const Image& a, const Image& b) {
  Image d;
  d.resize(a.width, a.height);
  for (std::size_t i = 0; i < d.pixels.size() && i < b.pixels.size(); ++i)
    d.pixels[i] = glm::min(glm::abs(a.pixels[i] - b.pixels[i]) * 8.0f, glm::vec3(1.0f));
  return d;
}

inline std::string outputPath(const std::string& name) {
  std::filesystem::create_directories(SLIME_TEST_OUTPUT_DIR);
  return std::string(SLIME_TEST_OUTPUT_DIR) + "/" + name;
}

// Slimes that are not convex, from the level-4 icosphere of `settings`: a dent, a waist, facets.
struct Shape {
  const char* what;
  TriangleMesh mesh;
};

inline std::vector<Shape> nonConvexShapes(const Settings& settings) {
  const TriangleMesh ball = makeIcosphere(4, settings.slime.radius, settings.slime.position);
  const glm::dvec3 c = settings.slime.position;
  const double r = settings.slime.radius;
  std::vector<Shape> shapes;
  TriangleMesh dented = ball;  // a press: the top pushed in by a quarter of the radius
  for (auto& p : dented.positions) {
    const double fromAxis = std::hypot(p.x - c.x, p.y - c.y);
    if (p.z > c.z + 0.5 * r && fromAxis < 0.5 * r) p.z -= 0.25 * r * std::cos(fromAxis / (0.5 * r) * 1.5707963);
  }
  shapes.push_back({"dented", dented});
  TriangleMesh necked = ball;  // pulled up by a pinch: stretched, with a waist below the top
  for (auto& p : necked.positions) {
    const double height = (p.z - c.z) / r, waist = 1.0 - 0.55 * std::exp(-std::pow((height - 0.4) / 0.2, 2.0));
    p = glm::dvec3(c.x + (p.x - c.x) * waist, c.y + (p.y - c.y) * waist, c.z + (p.z - c.z) * (height > 0.0 ? 1.6 : 1.0));
  }
  shapes.push_back({"necked", necked});
  TriangleMesh rough = ball;  // facets: every vertex moved by up to 0.2 % of the radius
  std::mt19937 random(11);
  std::uniform_real_distribution<double> jitter(-0.002 * r, 0.002 * r);
  for (auto& p : rough.positions) p += glm::dvec3(jitter(random), jitter(random), jitter(random));
  shapes.push_back({"rough", rough});
  return shapes;
}

}  // namespace slime::testing

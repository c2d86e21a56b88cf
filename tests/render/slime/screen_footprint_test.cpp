// The footprint (render/slime/screen_footprint.h) against a per-pixel oracle: a pixel may change with the
// slime when its primary ray, its floor point's shadow ray or its floor point's mirror ray can reach
// the bounding sphere (SlimeGeometry::mayHit, the renderer's own test). Every such pixel must be in
// the footprint, and the footprint must not be much larger than the set of such pixels.
#include "core/geometry/camera.h"
#include "core/geometry/icosphere.h"
#include "core/settings/settings_io.h"
#include "render/trace/optics.h"
#include "render/slime/screen_footprint.h"

#include <gtest/gtest.h>

#include <random>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <cstdio>
#include <functional>
#include <string>

namespace slime {
namespace {

struct View {
  std::string what;
  glm::dvec3 eye;
  glm::dvec3 target;
  glm::dvec3 slimeCenter;
  glm::dvec3 light;
  double floorSpecular = 0.0;
  glm::dvec3 stretch{1.0};  // the ball scaled about its centre: the bulk slime hanging or pressed flat
};

struct Coverage {
  long long reachable = 0;  // pixels the oracle says the slime can change
  long long missed = 0;     // of those, outside the footprint
};

// The renderer's primary ray through pixel (x, y) (Renderer::Impl::traceTile, one sample per pixel).
Ray primaryRay(const Camera& camera, int x, int y, int width, int height) {
  const glm::vec3 right(camera.right * (camera.tanHalfFov * camera.aspect));
  const glm::vec3 up(camera.up * camera.tanHalfFov);
  const float u = (x + 0.5f) / width, v = (y + 0.5f) / height;
  const glm::vec3 direction = glm::vec3(camera.forward) + (2.0f * u - 1.0f) * right + (1.0f - 2.0f * v) * up;
  return Ray{glm::vec3(camera.position), glm::normalize(direction), 0.0f, kInfinity};
}

// Whether a ray meets the slime: the renderer's own bound (mayHit), or, for the stretched shapes, every
// triangle tested (Möller & Trumbore 1997), which does not trust the bound.
using HitTest = std::function<bool(const Ray&)>;

bool hitsTriangles(const Ray& ray, const TriangleMesh& mesh) {
  for (const Triangle& t : mesh.triangles) {
    const glm::vec3 a(mesh.positions[t.x]), b(mesh.positions[t.y]), c(mesh.positions[t.z]);
    const glm::vec3 e1 = b - a, e2 = c - a, p = glm::cross(ray.direction, e2);
    const float det = glm::dot(e1, p);
    if (std::abs(det) < 1e-12f) continue;
    const glm::vec3 s = ray.origin - a;
    const float u = glm::dot(s, p) / det;
    if (u < 0.0f || u > 1.0f) continue;
    const glm::vec3 q = glm::cross(s, e1);
    const float v = glm::dot(ray.direction, q) / det;
    if (v < 0.0f || u + v > 1.0f) continue;
    const float distance = glm::dot(e2, q) / det;
    if (distance > ray.tNear && distance < ray.tFar) return true;
  }
  return false;
}

bool slimeCanChange(const Ray& ray, const HitTest& mayHit, const ShadingParameters& parameters) {
  if (mayHit(ray)) return true;
  if (ray.direction.z >= 0.0f) return false;  // the sky
  const float t = std::max(0.0f, ray.origin.z) / -ray.direction.z;
  glm::vec3 point = ray.origin + t * ray.direction;
  point.z = 0.0f;
  const glm::vec3 origin = point + glm::vec3(0.0f, 0.0f, kRayOffset);
  if (parameters.shadows && parameters.lightPosition.z > 0.0f) {
    const glm::vec3 toLight = parameters.lightPosition - origin;
    const float distance = glm::length(toLight);
    if (mayHit(Ray{origin, toLight / distance, 0.0f, distance})) return true;
  }
  if (parameters.floorSpecular > 0.0f) {
    const Ray mirror{origin, {ray.direction.x, ray.direction.y, -ray.direction.z}, 0.0f, kInfinity};
    if (mayHit(mirror)) return true;
  }
  return false;
}

Settings settingsFor(const View& view) {
  Settings settings = defaultSettings();
  lookAt(settings.camera, view.eye, view.target);
  settings.light.position = view.light;
  settings.floor.specular = view.floorSpecular;
  return settings;
}

Coverage check(const View& view, int width, int height, ScreenFootprint& footprint, bool bruteForce = false) {
  const Settings settings = settingsFor(view);
  TriangleMesh mesh = makeIcosphere(3, settings.slime.radius, view.slimeCenter);
  for (glm::dvec3& p : mesh.positions) p = view.slimeCenter + view.stretch * (p - view.slimeCenter);
  SlimeGeometry geometry;
  geometry.update(mesh.positions, mesh.triangles);
  const Camera camera = makeCamera(settings.camera, width, height);
  const ShadingParameters parameters = makeShadingParameters(settings, height);
  slimeFootprint(camera, geometry, parameters, width, height, footprint);
  const HitTest mayHit = bruteForce ? HitTest([&](const Ray& ray) { return hitsTriangles(ray, mesh); })
                                    : HitTest([&](const Ray& ray) { return geometry.mayHit(ray); });
  Coverage coverage;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      if (!slimeCanChange(primaryRay(camera, x, y, width, height), mayHit, parameters)) continue;
      ++coverage.reachable;
      coverage.missed += !footprint.contains(x, y);
    }
  }
  return coverage;
}

TEST(ScreenFootprint, HoldsEveryPixelTheSlimeCanReachAndLittleElse) {
  const double r = 0.04;
  const View views[] = {
      {"default view, resting", {0.0, -0.22, 0.1}, {0.0, 0.0, r}, {0.0, 0.0, r}, {0.3, -0.05, 0.35}},
      {"in the air, from the side", {0.25, 0.1, 0.12}, {0, 0, 0.05}, {0.01, -0.02, 0.09}, {0.3, -0.05, 0.35}},
      {"off centre, low light", {0.0, -0.3, 0.15}, {0.05, 0.0, 0.0}, {-0.06, 0.03, r}, {-0.2, 0.1, 0.13}},
      {"looking down", {0.02, -0.01, 0.4}, {0.0, 0.0, 0.0}, {0.0, 0.0, r}, {0.3, -0.05, 0.35}},
      {"varnished floor", {0.0, -0.22, 0.1}, {0.0, 0.0, r}, {0.0, 0.02, 0.07}, {0.3, -0.05, 0.35}, 0.2},
      {"at the image's edge", {0.0, -0.22, 0.1}, {0.09, 0.0, r}, {0.0, 0.0, r}, {0.3, -0.05, 0.35}},
  };
  ScreenFootprint footprint;
  for (const View& view : views) {
    for (const glm::ivec2 size : {glm::ivec2(160, 120), glm::ivec2(97, 131)}) {
      const Coverage coverage = check(view, size.x, size.y, footprint);
      const std::string what = view.what + " at " + std::to_string(size.x) + "x" + std::to_string(size.y);
      EXPECT_GT(coverage.reachable, 0) << what;
      EXPECT_EQ(coverage.missed, 0) << what << ": " << coverage.missed << " of " << coverage.reachable
                                    << " pixels missed";
      // Two pixels of margin around shapes a few dozen pixels across: at most about half as many again.
      EXPECT_LE(footprint.area(), 1.6 * coverage.reachable + 4 * (size.x + size.y)) << what;
    }
  }
}

// The bulk slime held up by a pinch hangs several times taller than it is wide, and pressed it spreads
// flat: the footprint must still hold every pixel whose primary, shadow or mirror ray meets one of its
// triangles (tested one by one, not through the renderer's bound).
TEST(ScreenFootprint, HoldsAStretchedOrFlattenedSlime) {
  const double r = 0.04;
  const View views[] = {
      {"hanging, 3.5 times its height", {0.0, -0.35, 0.15}, {0.0, 0.0, 0.12}, {0.0, 0.0, 0.16}, {0.3, -0.05, 0.35},
       0.0, {0.55, 0.55, 3.5}},
      {"pressed flat", {0.0, -0.22, 0.1}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.3 * r}, {0.3, -0.05, 0.35}, 0.0,
       {1.8, 1.8, 0.3}},
      {"pulled sideways, varnished floor", {0.05, -0.3, 0.12}, {0.05, 0.0, r}, {0.06, 0.0, r}, {-0.2, 0.1, 0.2}, 0.3,
       {3.0, 0.6, 0.6}},
  };
  ScreenFootprint footprint;
  for (const View& view : views) {
    const Coverage coverage = check(view, 160, 120, footprint, true);
    EXPECT_GT(coverage.reachable, 0) << view.what;
    EXPECT_EQ(coverage.missed, 0) << view.what << ": " << coverage.missed << " of " << coverage.reachable
                                  << " pixels missed";
    std::printf("%s: footprint %lld pixels for %lld reachable\n", view.what.c_str(),
                static_cast<long long>(footprint.area()), coverage.reachable);
    // The vertices' outlines hug the shape (the bounding sphere's ellipses took 2.5–6.9 times the
    // reachable pixels here): two pixels of margin around it, little else.
    EXPECT_LE(footprint.area(), 1.6 * coverage.reachable + 4 * (160 + 120)) << view.what;
  }
}

// The outline itself: the hull of a cloud, each row's crossing with it, and no outline for points on
// a line.
TEST(ScreenFootprint, ConvexOutlineIsTheHullOfItsPoints) {
  std::vector<glm::dvec2> points{{0, 0}, {4, 0}, {4, 3}, {0, 3}, {1, 0.5}, {2, 0}, {0.5, 2.9}, {4, 0}};
  ConvexOutline outline;
  outline.build(points);
  ASSERT_TRUE(outline.bounded());
  EXPECT_EQ(outline.corners().size(), 4u);  // the rectangle's corners; inner and edge points dropped
  std::vector<ConvexOutline::Crossing> rows;
  outline.crossRows(5, rows);
  ASSERT_EQ(rows.size(), 5u);
  for (int row = 0; row < 3; ++row) {  // the lines y = 0.5, 1.5, 2.5
    EXPECT_TRUE(rows[row].any) << row;
    EXPECT_DOUBLE_EQ(rows[row].low, 0.0) << row;
    EXPECT_DOUBLE_EQ(rows[row].high, 4.0) << row;
  }
  EXPECT_FALSE(rows[3].any);  // y = 3.5 and 4.5 pass above it
  EXPECT_FALSE(rows[4].any);

  std::vector<glm::dvec2> triangle{{0, 0}, {4, 0}, {0, 4}, {1, 1}};
  outline.build(triangle);
  outline.crossRows(6, rows);
  EXPECT_DOUBLE_EQ(rows[0].low, 0.0);
  EXPECT_DOUBLE_EQ(rows[0].high, 3.5);  // the slanted side at y = 0.5
  EXPECT_DOUBLE_EQ(rows[3].high, 0.5);
  EXPECT_FALSE(rows[4].any);

  // A dense cloud (the points inside the extremes' octagon are set aside before the sort): a
  // hexagon's corners and 2,000 points inside it.
  std::vector<glm::dvec2> cloud, corners;
  for (int k = 0; k < 6; ++k) corners.emplace_back(3.0 * std::cos(k * 1.0471976), 3.0 * std::sin(k * 1.0471976));
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  while (cloud.size() < 2000) {
    const glm::dvec2 p(2.5 * unit(random), 2.5 * unit(random));
    if (glm::length(p) < 2.55) cloud.push_back(p);  // inside the hexagon's inscribed circle (2.598)
  }
  cloud.insert(cloud.begin() + 700, corners.begin(), corners.end());
  outline.build(cloud);
  ASSERT_EQ(outline.corners().size(), 6u);
  for (const glm::dvec2& corner : corners) {
    bool found = false;
    for (const glm::dvec2& c : outline.corners()) found = found || glm::length(c - corner) < 1e-12;
    EXPECT_TRUE(found) << corner.x << ", " << corner.y;
  }

  std::vector<glm::dvec2> line{{0, 0}, {1, 1}, {2, 2}, {3, 3}};
  outline.build(line);
  EXPECT_FALSE(outline.bounded());
}

TEST(ScreenFootprint, WholeRowsWhereNoBoundCanBeGiven) {
  const double r = 0.04;
  ScreenFootprint footprint;
  const int width = 80, height = 60;
  // The eye inside the bounding sphere, and the sphere behind the eye: every pixel.
  const glm::dvec3 light{0.3, -0.05, 0.35};
  const View unbounded[] = {{"eye inside", {0.0, 0.0, r}, {0.0, 1.0, r}, {0.0, 0.0, r}, light},
                            {"behind the eye", {0.0, 0.2, 0.05}, {0.0, 1.0, 0.05}, {0.0, 0.0, r}, light}};
  for (const View& view : unbounded) {
    const Coverage coverage = check(view, width, height, footprint);
    EXPECT_EQ(coverage.missed, 0) << view.what;
    EXPECT_EQ(footprint.area(), static_cast<long long>(width) * height) << view.what;
  }
  // The light below the sphere's top: its shadow has no bound, so every row that sees the floor.
  const View low{"light below the top", {0.0, -0.22, 0.1}, {0.0, 0.0, r}, {0.0, 0.0, r}, {0.3, -0.05, 0.05}};
  const Coverage coverage = check(low, width, height, footprint);
  EXPECT_EQ(coverage.missed, 0);
  const Camera camera = makeCamera(settingsFor(low).camera, width, height);
  for (int y = 0; y < height; ++y) {
    if (primaryRay(camera, width / 2, y, width, height).direction.z < -1e-3f) {
      EXPECT_EQ(footprint.rows[y].x0, 0) << "row " << y;
      EXPECT_EQ(footprint.rows[y].x1, width) << "row " << y;
    }
  }
}

TEST(ScreenFootprint, EmptyWithoutASlimeAndForAnEmptyImage) {
  const Settings settings = defaultSettings();
  const Camera camera = makeCamera(settings.camera, 40, 30);
  const ShadingParameters parameters = makeShadingParameters(settings, 30);
  const SlimeGeometry none;
  EXPECT_EQ(slimeFootprint(camera, none, parameters, 40, 30).area(), 0);
  const TriangleMesh mesh = makeIcosphere(2, 0.04, {0.0, 0.0, 0.04});
  SlimeGeometry geometry;
  geometry.update(mesh.positions, mesh.triangles);
  EXPECT_TRUE(slimeFootprint(camera, geometry, parameters, 0, 0).rows.empty());
}

}  // namespace
}  // namespace slime

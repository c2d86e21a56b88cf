// The light's grid (render/slime/pencil_grid.h) against the brute force: every crossing of a segment with
// the slime's surface, found by testing every triangle with the brute force's Möller–Trumbore, must
// be what the grid finds, the same triangles at the same distances (the grid runs the same
// operations on the triangles it chooses), on convex and non-convex slimes, for shadow segments
// ending at the apex and for segments anywhere; and from the eye, each primary ray's closest hit.
#include "render/trace/brute_tracer.h"
#include "render/trace/embree_scene.h"
#include "render/slime/pencil_grid.h"
#include "render/slime/slime_geometry.h"
#include "render_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <tuple>
#include <vector>

namespace slime::testing {
namespace {

std::vector<SlimeHit> bruteCrossings(const SlimeGeometry& geometry, const Ray& ray) {
  std::vector<SlimeHit> hits;
  for (std::size_t f = 0; f < geometry.triangles.size(); ++f) {
    const Triangle& t = geometry.triangles[f];
    float u = 0.0f, v = 0.0f;
    const float along = intersectTriangle(ray, geometry.positions[t.x], geometry.positions[t.y], geometry.positions[t.z], u, v);
    if (along < kInfinity) hits.push_back(SlimeHit{along, static_cast<std::uint32_t>(f), u, v});
  }
  return hits;
}

void sortHits(std::vector<SlimeHit>& hits) {
  std::sort(hits.begin(), hits.end(), [](const SlimeHit& a, const SlimeHit& b) { return std::tie(a.t, a.primitive) < std::tie(b.t, b.primitive); });
}

// Compares the grid with the brute force on `count` segments from `makeRay`; counts the crossings seen.
template <typename MakeRay>
void expectSameCrossings(const PencilGrid& grid, const SlimeGeometry& geometry, int count, MakeRay makeRay, const char* what,
                         int& crossings) {
  crossings = 0;
  for (int n = 0; n < count; ++n) {
    const Ray ray = makeRay();
    SegmentCrossings found;
    grid.crossings(ray, found);
    std::vector<SlimeHit> expected = bruteCrossings(geometry, ray);
    ASSERT_LE(expected.size(), static_cast<std::size_t>(SegmentCrossings::kCapacity)) << what;
    ASSERT_EQ(found.count, static_cast<int>(expected.size())) << what << ", segment " << n;
    for (int k = 1; k < found.count; ++k) EXPECT_LE(found.hits[k - 1].t, found.hits[k].t) << what << ": nearest first";
    std::vector<SlimeHit> got(found.hits, found.hits + found.count);
    sortHits(got);
    sortHits(expected);
    for (std::size_t k = 0; k < got.size(); ++k) {
      EXPECT_EQ(got[k].primitive, expected[k].primitive) << what << ", segment " << n;
      EXPECT_EQ(got[k].t, expected[k].t) << what << ", segment " << n;
      EXPECT_EQ(got[k].u, expected[k].u) << what;
      EXPECT_EQ(got[k].v, expected[k].v) << what;
    }
    crossings += found.count;
  }
}

TEST(PencilGrid, ShadowSegmentsCrossWhatTheBruteForceCrosses) {
  const Settings settings = smallScene();
  std::vector<Shape> shapes = nonConvexShapes(settings);
  shapes.push_back({"ball", restingMesh(settings)});
  const glm::vec3 light(settings.light.position);
  for (const glm::vec3 apex : {light, glm::vec3(-0.12f, 0.03f, 0.05f)}) {  // the default light, and one low beside the slime
    for (const Shape& shape : shapes) {
      SlimeGeometry geometry;
      geometry.update(shape.mesh.positions, shape.mesh.triangles);
      PencilGrid grid;
      ASSERT_TRUE(grid.build(geometry, apex)) << shape.what;
      EXPECT_LT(grid.entryCount(), 8 * geometry.triangles.size()) << shape.what << ": a triangle in a few cells";
      std::mt19937 random(7);
      std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
      // Shadow rays as the tracer makes them: from the floor around the slime, from inside its
      // bounds and from its surface (offset a little), to the apex.
      const auto towardsApex = [&] {
        glm::vec3 origin = geometry.boundCenter + 1.5f * geometry.boundRadius * glm::vec3(unit(random), unit(random), unit(random));
        if (unit(random) < -0.4f) origin.z = 1e-5f;
        if (unit(random) > 0.5f) origin = geometry.positions[static_cast<std::size_t>(random() % geometry.vertexCount())] + 1e-5f * glm::vec3(unit(random), unit(random), unit(random));
        const glm::vec3 toApex = apex - origin;
        const float distance = glm::length(toApex);
        return Ray{origin, toApex / distance, 0.0f, distance};
      };
      int crossed = 0;
      expectSameCrossings(grid, geometry, 2000, towardsApex, shape.what, crossed);
      EXPECT_GT(crossed, 700) << shape.what << ": too few crossings to compare";
      // Any segment, not through the apex: longer in the projection, still exact.
      const auto anywhere = [&] {
        const glm::vec3 origin = geometry.boundCenter + 2.0f * geometry.boundRadius * glm::vec3(unit(random), unit(random), unit(random));
        const glm::vec3 direction = glm::normalize(glm::vec3(unit(random), unit(random), unit(random)));
        return Ray{origin, direction, 0.0f, unit(random) < 0.0f ? kInfinity : 2.0f * geometry.boundRadius};
      };
      expectSameCrossings(grid, geometry, 1000, anywhere, shape.what, crossed);
      EXPECT_GT(crossed, 100) << shape.what;
    }
  }
}

// From the eye, the grid of the triangles facing it gives each primary ray the brute force's closest hit.
TEST(PencilGrid, PrimaryRaysFindTheBruteForcesClosestHit) {
  const Settings settings = smallScene();
  std::vector<Shape> shapes = nonConvexShapes(settings);
  shapes.push_back({"ball", restingMesh(settings)});
  for (const glm::vec3 eye : {glm::vec3(settings.camera.position), glm::vec3(0.05f, 0.1f, 0.2f), glm::vec3(0.0f, 0.0f, -0.1f)}) {
    for (const Shape& shape : shapes) {
      SlimeGeometry geometry;
      geometry.update(shape.mesh.positions, shape.mesh.triangles);
      PencilGrid grid;
      ASSERT_TRUE(grid.build(geometry, eye, true)) << shape.what;
      PencilGrid all;
      ASSERT_TRUE(all.build(geometry, eye)) << shape.what;
      EXPECT_LT(grid.entryCount(), 0.7 * all.entryCount()) << shape.what << ": about half the triangles face the eye";
      const BruteTracer brute(geometry);
      std::mt19937 random(3);
      std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
      int hits = 0;
      for (int n = 0; n < 3000; ++n) {
        const glm::vec3 target = geometry.boundCenter + 1.1f * geometry.boundRadius * glm::vec3(unit(random), unit(random), unit(random));
        const Ray ray{eye, glm::normalize(target - eye), 0.0f, kInfinity};
        const SlimeHit found = grid.nearest(ray), expected = brute.intersect(ray);
        ASSERT_EQ(found.valid(), expected.valid()) << shape.what << ", ray " << n;
        if (!found.valid()) continue;
        ++hits;
        EXPECT_EQ(found.t, expected.t) << shape.what << ", ray " << n;
        if (found.primitive != expected.primitive) continue;  // a tie on a shared edge: either triangle
        EXPECT_EQ(found.u, expected.u) << shape.what;
        EXPECT_EQ(found.v, expected.v) << shape.what;
      }
      EXPECT_GT(hits, 1000) << shape.what << ": too few hits to compare";
    }
  }
}

TEST(PencilGrid, RefusesAnApexAtTheSlimeAndTheTracerWalksInstead) {
  const Settings settings = smallScene();
  const TriangleMesh mesh = restingMesh(settings);
  SlimeGeometry geometry;
  geometry.update(mesh.positions, mesh.triangles);
  PencilGrid grid;
  EXPECT_FALSE(grid.build(geometry, geometry.boundCenter));
  EXPECT_FALSE(grid.build(geometry, geometry.boundCenter + glm::vec3(0.0f, 0.0f, 1.1f * geometry.boundRadius)));
  EXPECT_FALSE(grid.ready());
  const TriangleMesh fine = makeIcosphere(6, settings.slime.radius, settings.slime.position);  // 81,920 triangles
  SlimeGeometry fineGeometry;
  fineGeometry.update(fine.positions, fine.triangles);
  EXPECT_FALSE(grid.build(fineGeometry, glm::vec3(settings.light.position))) << "level 6: Embree and the walk";
  const TriangleMesh level5 = makeIcosphere(5, settings.slime.radius, settings.slime.position);
  fineGeometry.update(level5.positions, level5.triangles);
  EXPECT_TRUE(grid.build(fineGeometry, glm::vec3(settings.light.position))) << "level 5: a grid";
  grid.clear();
  SegmentCrossings none;
  grid.crossings(Ray{geometry.boundCenter + glm::vec3(0.0f, 0.0f, -1.0f), {0.0f, 0.0f, 1.0f}, 0.0f, 2.0f}, none);
  EXPECT_EQ(none.count, 0);

  EmbreeScene scene(0);
  scene.update(geometry, true);
  Ray rays[8];
  const bool active[8] = {true};
  SegmentCrossings crossings[8];
  EXPECT_FALSE(scene.lightCrossings8(rays, active, crossings)) << "no light prepared";
  scene.prepareLight(geometry, geometry.boundCenter, true);
  EXPECT_FALSE(scene.lightCrossings8(rays, active, crossings)) << "a light inside the slime: the walk";
  scene.prepareLight(geometry, glm::vec3(settings.light.position), true);
  EXPECT_TRUE(scene.lightCrossings8(rays, active, crossings));
  scene.update(geometry, false);
  EXPECT_FALSE(scene.lightCrossings8(rays, active, crossings)) << "a grid of the last shape";
  scene.prepareLight(geometry, glm::vec3(settings.light.position), false);
  EXPECT_FALSE(scene.lightCrossings8(rays, active, crossings)) << "shadows off";
  SlimeHit hits[8];
  EXPECT_FALSE(scene.primaryHits8(rays, active, hits)) << "no eye prepared";
  scene.prepareEye(geometry, glm::vec3(settings.camera.position), true);
  EXPECT_TRUE(scene.primaryHits8(rays, active, hits));
  scene.update(geometry, false);
  EXPECT_FALSE(scene.primaryHits8(rays, active, hits)) << "a grid of the last shape";
}

}  // namespace
}  // namespace slime::testing

// The tracer's shortcuts on a slime that is not convex (a dent, a waist, facets): a ray inside the
// slime is asked backwards from beyond its bounds beside a query of the non-supporting triangles
// alone, and a shadow ray from both its ends (WhittedTracer::findHits, crossFromBothEnds8). The
// oracle: the same frame traced with no triangle taken as supporting, when every such shortcut
// falls back to the plain forward query and the walk along the shadow ray.
#include "core/geometry/camera.h"
#include "core/geometry/icosphere.h"
#include "render/trace/brute_tracer.h"
#include "render/trace/embree_scene.h"
#include "render/floor/floor_texture.h"
#include "render/trace/shading_parameters.h"
#include "render/trace/whitted_tracer.h"
#include "render_fixture.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

namespace slime::testing {
namespace {

// Every pixel of the settings' view, one sample each, traced by the tracer itself (as the ray log does).
Image traceImage(const Settings& settings, const SlimeGeometry& geometry, const SlimeIntersector& intersector) {
  const int width = settings.camera.width, height = settings.camera.height;
  const FloorTexture floor(settings.floor);
  const ShadingParameters parameters = makeShadingParameters(settings, height);
  const WhittedTracer tracer(geometry, intersector, floor, parameters);
  const Camera camera = makeCamera(settings.camera, width, height);
  Image image;
  image.resize(width, height);
  TraceCounters counters;
  for (int y = 0; y < height; ++y) {
    for (int x0 = 0; x0 < width; x0 += 8) {
      Ray rays[8];
      bool active[8] = {};
      SlimeHit hits[8];
      const int count = std::min(8, width - x0);
      for (int i = 0; i < count; ++i) {
        rays[i] = Ray{glm::vec3(camera.position), glm::vec3(camera.rayDirection((x0 + i + 0.5) / width, (y + 0.5) / height)),
                      0.0f, kInfinity};
        active[i] = geometry.mayHit(rays[i]);
      }
      intersector.intersect8(rays, active, hits);
      glm::vec3 colors[8];
      tracer.tracePrimaries(rays, hits, count, counters, nullptr, colors);
      for (int i = 0; i < count; ++i) image.at(x0 + i, y) = colors[i];
    }
  }
  return image;
}

// No triangle taken as supporting: every triangle is one a ray may come back in through.
void supportNothing(SlimeGeometry& geometry) {
  geometry.supporting.assign(geometry.triangles.size(), 0);
  geometry.convex = false;
  geometry.nonSupportingTriangles = geometry.triangles;
  geometry.nonSupportingPrimitives.clear();
  for (std::size_t f = 0; f < geometry.triangles.size(); ++f)
    geometry.nonSupportingPrimitives.push_back(static_cast<std::uint32_t>(f));
}

TEST(NonSupporting, ShortcutsOnANonConvexSlimeMatchThePlainWalk) {
  Settings settings = smallScene(200, 150);
  settings.camera.fov = 25.0;  // closer in: the slime fills much of the frame
  for (Shape& shape : nonConvexShapes(settings)) {
    SlimeGeometry geometry;
    geometry.update(shape.mesh.positions, shape.mesh.triangles);
    ASSERT_FALSE(geometry.isConvex()) << shape.what;
    ASSERT_LT(geometry.nonSupportingTriangles.size(), geometry.triangles.size()) << shape.what;
    EmbreeScene scene(0);
    scene.update(geometry, true);
    const Image shortcut = traceImage(settings, geometry, scene);
    const std::size_t nonSupporting = geometry.nonSupportingTriangles.size();
    supportNothing(geometry);
    scene.update(geometry, false);
    const Image plain = traceImage(settings, geometry, scene);
    // The two differ only by rounding (a stretch's length as one difference or as the walk's steps)
    // and by the supporting test's tolerance (80 µm on the default slime).
    const ImageDifference d = compareImages(shortcut, plain, 1.0);
    std::printf("%s: %zu of %zu triangles non-supporting; %.4f %% of pixels over 1 step, largest %.0f\n", shape.what,
                nonSupporting, geometry.triangles.size(), 100 * d.fractionAbove, d.largest);
    EXPECT_LE(d.fractionAbove, 1e-3) << shape.what << ": largest " << d.largest << "/255";
    if (d.fractionAbove > 1e-3)
      writePng(differenceImage(shortcut, plain), outputPath(std::string("non_supporting_") + shape.what + "_diff.png"));
  }
}

// Embree's BVH of the non-supporting triangles against the brute force over the same set.
TEST(NonSupporting, EmbreeAgreesWithBruteForce) {
  const Settings settings = smallScene();
  for (Shape& shape : nonConvexShapes(settings)) {
    SlimeGeometry geometry;
    geometry.update(shape.mesh.positions, shape.mesh.triangles);
    EmbreeScene scene(0);
    scene.update(geometry, true);
    const BruteTracer brute(geometry);
    std::mt19937 random(5);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    int hits = 0;
    for (int packet = 0; packet < 400; ++packet) {
      Ray rays[8];
      bool active[8];
      for (int i = 0; i < 8; ++i) {
        // From inside the bounds to anywhere, and some from outside towards the slime.
        const glm::vec3 origin = geometry.boundCenter + geometry.boundRadius * glm::vec3(unit(random), unit(random), unit(random));
        const glm::vec3 direction = glm::normalize(glm::vec3(unit(random), unit(random), unit(random)));
        rays[i] = Ray{origin, direction, 1e-5f, i % 3 == 0 ? kInfinity : geometry.boundRadius};
        active[i] = i != 5;
      }
      SlimeHit fromEmbree[8], fromBrute[8];
      scene.intersectNonSupporting8(rays, active, fromEmbree);
      brute.intersectNonSupporting8(rays, active, fromBrute);
      for (int i = 0; i < 8; ++i) {
        ASSERT_EQ(fromEmbree[i].valid(), fromBrute[i].valid()) << shape.what << " packet " << packet << " ray " << i;
        if (!fromEmbree[i].valid()) continue;
        ++hits;
        EXPECT_EQ(fromEmbree[i].primitive, fromBrute[i].primitive) << shape.what;
        EXPECT_FALSE(geometry.supports(fromEmbree[i].primitive)) << shape.what;
        EXPECT_NEAR(fromEmbree[i].t, fromBrute[i].t, 1e-6f) << shape.what;
      }
    }
    EXPECT_GT(hits, 50) << shape.what << ": too few hits to compare";
  }
}

}  // namespace
}  // namespace slime::testing

// The walk over the surface that finds where a ray inside the slime leaves it through a supporting
// triangle (render/slime/exit_walk.h), against the brute force: whatever it finds must be the crossing the
// reversed query finds (the ray's last), it must find most of them, and its lanes must equal its
// one-ray-at-a-time form bit for bit.
#include "render/slime/exit_walk.h"

#include "core/geometry/icosphere.h"
#include "render/trace/brute_tracer.h"
#include "render/trace/optics.h"
#include "render/slime/slime_geometry.h"
#include "render_fixture.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

namespace slime::testing {
namespace {

// Chords as the tracer makes them: from just inside a random point of the surface, into the jelly
// (refracted: the inward normal turned by up to ~60°), up to where they leave the bounding sphere.
struct Chord {
  Ray ray;        // the walk's segment: [kRayOffset, where the bounding sphere is left]
  glm::vec3 exit;  // where the ray leaves the bounding sphere (the walk's first guess)
};

std::vector<Chord> chordsInside(const SlimeGeometry& geometry, int count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<std::size_t> triangle(0, geometry.triangles.size() - 1);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), spread(-0.8f, 0.8f);
  std::vector<Chord> chords;
  while (static_cast<int>(chords.size()) < count) {
    const Triangle& t = geometry.triangles[triangle(random)];
    float u = unit(random), v = unit(random);
    if (u + v > 1.0f) u = 1.0f - u, v = 1.0f - v;
    const glm::vec3 a = geometry.positions[t.x], b = geometry.positions[t.y], c = geometry.positions[t.z];
    const glm::vec3 point = a + u * (b - a) + v * (c - a);
    const glm::vec3 outward = glm::normalize(glm::cross(b - a, c - a));
    const glm::vec3 direction = glm::normalize(-outward + glm::vec3(spread(random), spread(random), spread(random)));
    if (glm::dot(direction, outward) > -0.2f) continue;  // grazing: not a chord through the jelly
    Ray ray{offsetRayOrigin(point, -outward, direction), direction, 0.0f, kInfinity};
    const float beyond = geometry.boundExitDistance(ray) + 1e-4f;
    ray.tNear = kRayOffset;
    ray.tFar = beyond;
    chords.push_back({ray, ray.origin + beyond * ray.direction});
  }
  return chords;
}

constexpr int kBatch = ExitWalk::kBatch;

std::vector<Shape> shapes() {
  Settings settings = smallScene();
  std::vector<Shape> all{{"ball", makeIcosphere(4, settings.slime.radius, settings.slime.position)},
                         {"coarse ball", makeIcosphere(2, settings.slime.radius, settings.slime.position)}};
  for (Shape& shape : nonConvexShapes(settings)) all.push_back(shape);
  return all;
}

// A shape's geometry and its walk, connected and mapped.
struct Mapped {
  explicit Mapped(const TriangleMesh& mesh) {
    geometry.update(mesh.positions, mesh.triangles);
    walk.connect(geometry.triangles);
    walk.map(geometry);
  }
  SlimeGeometry geometry;
  ExitWalk walk;
};

// kBatch chords from `first` as the walk is asked them; lane i asked when active(i).
struct Batch {
  Ray rays[kBatch];
  glm::vec3 exits[kBatch];
  bool active[kBatch];
};
template <typename Active>
Batch batchOf(const std::vector<Chord>& chords, std::size_t first, Active active) {
  Batch batch;
  for (int i = 0; i < kBatch; ++i) {
    batch.rays[i] = chords[first + i].ray;
    batch.exits[i] = chords[first + i].exit;
    batch.active[i] = active(i);
  }
  return batch;
}

TEST(ExitWalk, FindsOnlyTheLastCrossingAndMostOfThem) {
  for (const Shape& shape : shapes()) {
    const Mapped mapped(shape.mesh);
    const SlimeGeometry& geometry = mapped.geometry;
    const BruteTracer brute(geometry);
    const std::vector<Chord> chords = chordsInside(geometry, 4000, 7);
    int asked = 0, found = 0, wrong = 0, findable = 0;
    for (std::size_t first = 0; first + kBatch <= chords.size(); first += kBatch) {
      const Batch batch = batchOf(chords, first, [](int i) { return i % 8 != 3; });  // an idle lane finds nothing
      const Ray* rays = batch.rays;
      const bool* active = batch.active;
      SlimeHit hits[kBatch];
      mapped.walk.supportingExits(geometry, rays, batch.exits, active, hits);
      EXPECT_FALSE(hits[3].valid()) << shape.what;
      EXPECT_FALSE(hits[11].valid()) << shape.what;
      for (int i = 0; i < kBatch; ++i) {
        // The reversed query's answer: the first crossing met coming back from beyond the sphere.
        const Ray& ray = rays[i];
        const Ray back{ray.origin + ray.tFar * ray.direction, -ray.direction, 0.0f, ray.tFar - ray.tNear};
        const SlimeHit last = brute.intersect(back);
        asked += active[i];
        findable += active[i] && last.valid() && geometry.supports(last.primitive);
        if (!hits[i].valid()) continue;
        ++found;
        // The same triangle, and the same point within rounding (0.1 µm; the two come from opposite ends).
        const bool same = last.valid() && last.primitive == hits[i].primitive &&
                          std::abs(ray.tFar - last.t - hits[i].t) <= 1e-7f;
        if (!same && ++wrong <= 5)
          ADD_FAILURE() << shape.what << ": chord " << first + i << " walked to triangle " << hits[i].primitive << " at t "
                        << hits[i].t << ", the brute force's last crossing is " << last.primitive << " at t "
                        << ray.tFar - last.t;
        EXPECT_TRUE(geometry.supports(hits[i].primitive)) << shape.what;
        EXPECT_GE(hits[i].u, 0.0f);
        EXPECT_GE(hits[i].v, 0.0f);
        EXPECT_LE(hits[i].u + hits[i].v, 1.0f + 1e-6f);
      }
    }
    EXPECT_EQ(wrong, 0) << shape.what;
    // The walk pays only where it mostly succeeds: of the chords that leave through a supporting
    // triangle, it finds at least 80 % on every shape here.
    std::printf("%s: the walk found %d of %d chords leaving through a supporting triangle (%d chords)\n", shape.what,
                found, findable, asked);
    EXPECT_GE(found, 0.8 * findable) << shape.what;
  }
}

TEST(ExitWalk, LanesEqualOneRayAtATimeBitForBit) {
  for (const Shape& shape : shapes()) {
    const Mapped mapped(shape.mesh);
    const std::vector<Chord> chords = chordsInside(mapped.geometry, 2000, 3);
    int differing = 0;
    for (std::size_t first = 0; first + kBatch <= chords.size(); first += kBatch) {
      const Batch b = batchOf(chords, first, [first](int i) { return (first / 8 + i) % 5 != 0; });
      SlimeHit lanes[kBatch], single[kBatch];
      mapped.walk.supportingExits(mapped.geometry, b.rays, b.exits, b.active, lanes);
      mapped.walk.supportingExits8OneByOne(mapped.geometry, b.rays, b.exits, b.active, single);
      mapped.walk.supportingExits8OneByOne(mapped.geometry, b.rays + 8, b.exits + 8, b.active + 8, single + 8);
      for (int i = 0; i < kBatch; ++i) differing += std::memcmp(&lanes[i], &single[i], sizeof(SlimeHit)) != 0;
    }
    EXPECT_EQ(differing, 0) << shape.what;
  }
}

TEST(ExitWalk, FindsNothingUntilItsShapeIsMapped) {
  Settings settings = smallScene();
  const TriangleMesh ball = makeIcosphere(3, settings.slime.radius, settings.slime.position);
  SlimeGeometry geometry;
  geometry.update(ball.positions, ball.triangles);
  const std::vector<Chord> chords = chordsInside(geometry, kBatch, 5);
  Ray rays[kBatch];
  glm::vec3 exits[kBatch];
  bool active[kBatch];
  for (int i = 0; i < kBatch; ++i) rays[i] = chords[i].ray, exits[i] = chords[i].exit, active[i] = true;
  const auto found = [&](const ExitWalk& walk) {
    SlimeHit hits[kBatch];
    walk.supportingExits(geometry, rays, exits, active, hits);
    int count = 0;
    for (const SlimeHit& hit : hits) count += hit.valid();
    return count;
  };
  ExitWalk walk;
  EXPECT_EQ(found(walk), 0) << "nothing connected or mapped";
  walk.connect(geometry.triangles);
  EXPECT_EQ(found(walk), 0) << "connected, not mapped";
  walk.map(geometry);
  EXPECT_GT(found(walk), kBatch / 2) << "connected and mapped";
  const TriangleMesh finer = makeIcosphere(4, settings.slime.radius, settings.slime.position);
  geometry.update(finer.positions, finer.triangles);
  walk.map(geometry);
  EXPECT_EQ(found(walk), 0) << "mapped, but connected for another topology";
}

}  // namespace
}  // namespace slime::testing

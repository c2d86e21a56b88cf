// Self-intersection ("acne"): secondary rays leaving the slime's surface must not hit the triangle
// they leave. On the convex undeformed icosphere a ray leaving outwards can hit nothing, and a ray
// leaving inwards first meets the far side. Count the rays that violate this for a range of offsets.
#include "render/trace/embree_scene.h"
#include "render/trace/optics.h"
#include "render/slime/slime_geometry.h"

#include "core/geometry/icosphere.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

namespace slime {
namespace {

struct AcneCount {
  int outward = 0;  // outward rays that hit the slime
  int inward = 0;   // inward rays whose first hit is within 1 % of the radius
};

AcneCount countAcne(const SlimeGeometry& geometry, const EmbreeScene& scene, float offset, int samples) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  AcneCount count;
  const float radius = geometry.boundRadius;
  for (int i = 0; i < samples; ++i) {
    const std::size_t index = static_cast<std::size_t>(uniform(random) * geometry.triangles.size()) % geometry.triangles.size();
    const Triangle& t = geometry.triangles[index];
    float u = uniform(random), v = uniform(random);
    if (u + v > 1.0f) { u = 1.0f - u; v = 1.0f - v; }
    const glm::vec3 p = (1.0f - u - v) * geometry.positions[t.x] + u * geometry.positions[t.y] + v * geometry.positions[t.z];
    const glm::vec3 n = geometry.geometricNormal(SlimeHit{0.0f, static_cast<std::uint32_t>(index), u, v}, p);
    // Directions from grazing (1° above the surface) to normal, the hardest being the grazing ones.
    glm::vec3 tangent = glm::normalize(glm::cross(n, std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0)));
    const float elevation = 0.0175f + uniform(random) * 1.5f;
    const glm::vec3 out = glm::normalize(std::cos(elevation) * tangent + std::sin(elevation) * n);
    const glm::vec3 in = glm::normalize(std::cos(elevation) * tangent - std::sin(elevation) * n);
    const SlimeHit outwardHit = scene.intersect(Ray{offsetRayOrigin(p, n, out, offset), out, 0.0f, kInfinity});
    if (outwardHit.valid()) ++count.outward;
    const SlimeHit inwardHit = scene.intersect(Ray{offsetRayOrigin(p, n, in, offset), in, 0.0f, kInfinity});
    if (!inwardHit.valid() || inwardHit.t < 0.01f * radius * std::sin(elevation)) ++count.inward;
  }
  return count;
}

TEST(SecondaryOffset, NoSelfIntersectionAtTheChosenOffset) {
  SlimeGeometry geometry;
  const TriangleMesh mesh = makeIcosphere(5, 0.04, {0.05, -0.02, 0.04});
  geometry.update(mesh.positions, mesh.triangles);
  EmbreeScene scene(0);
  scene.update(geometry, true);

  constexpr int kSamples = 20000;
  const AcneCount chosen = countAcne(geometry, scene, kRayOffset, kSamples);
  EXPECT_EQ(chosen.outward, 0);
  EXPECT_EQ(chosen.inward, 0);

  // The threshold: the smallest offset of the sweep with no acne; the chosen one keeps a 10× margin.
  float cleanFrom = -1.0f;
  for (const float offset : {1e-4f, 3e-5f, 1e-5f, 3e-6f, 1e-6f, 3e-7f, 1e-7f, 3e-8f, 1e-8f, 0.0f}) {
    const AcneCount c = countAcne(geometry, scene, offset, kSamples);
    std::printf("offset %.0e m: %d outward, %d inward self-hits of %d\n", offset, c.outward, c.inward, kSamples);
    if (c.outward + c.inward > 0) break;
    cleanFrom = offset;
  }
  EXPECT_GE(cleanFrom, 0.0f);
  EXPECT_LE(cleanFrom * 10.0f, kRayOffset) << "the offset keeps less than a 10x margin over acne";
}

}  // namespace
}  // namespace slime

// The pixels outside the slime's reach are shaded as floor or sky in lanes (WhittedTracer::
// traceFloorOrSky: 16 at a time with AVX-512, 8 with AVX2, render/simd/wide_lanes.h), with the very
// operations of the general path (tracePrimaries, one ray's Whitted tree at a time). The renderer
// mixes the two in one frame, the footprint deciding which pixel takes which, so the two must agree
// bit for bit, whatever the number of rays shaded together.
#include "core/geometry/camera.h"
#include "render/trace/brute_tracer.h"
#include "render/floor/floor_texture.h"
#include "render/trace/shading_parameters.h"
#include "render/trace/whitted_tracer.h"
#include "render_fixture.h"

#include <gtest/gtest.h>

#include <string>

namespace slime::testing {
namespace {

struct View {
  std::string what;
  glm::dvec3 eye;
  double yaw, pitch;
  std::string pattern = "planks";
};

TEST(FloorLanes, FloorOrSkyInLanesEqualsTheGeneralPathBitForBit) {
  const View views[] = {
      {"default view", {0.0, -0.22, 0.1}, 90.0, -20.0},
      {"the horizon and the sky", {0.0, -0.22, 0.1}, 90.0, 10.0},
      {"looking down from high up", {0.3, 0.2, 3.0}, 30.0, -85.0},
      {"grazing, far planks", {0.0, 0.0, 0.01}, 45.0, -1.0},
      {"tiles", {0.0, -0.22, 0.1}, 90.0, -20.0, "tiles"},
  };
  SlimeGeometry nothing;  // no slime: every ray sees the floor or the sky
  const BruteTracer intersector(nothing);
  for (const View& view : views) {
    Settings settings = smallScene(67, 23);  // a width of no multiple of 8 or 16
    settings.camera.position = view.eye;
    settings.camera.yaw = view.yaw;
    settings.camera.pitch = view.pitch;
    settings.floor.pattern = view.pattern;
    const FloorTexture floor(settings.floor);
    const ShadingParameters parameters = makeShadingParameters(settings, settings.camera.height);
    const WhittedTracer tracer(nothing, intersector, floor, parameters);
    const Camera camera = makeCamera(settings.camera, settings.camera.width, settings.camera.height);
    const glm::vec3 eye(camera.position);
    int compared = 0, differing = 0, floorPixels = 0;
    // Every run length from 1 to the widest lanes, along each row.
    for (int count = 1; count <= WhittedTracer::kFloorOrSkyRays; ++count) {
      for (int y = 0; y < settings.camera.height; ++y) {
        for (int x0 = 0; x0 + count <= settings.camera.width; x0 += count) {
          float directionX[WhittedTracer::kFloorOrSkyRays], directionY[WhittedTracer::kFloorOrSkyRays],
              directionZ[WhittedTracer::kFloorOrSkyRays];
          Ray rays[WhittedTracer::kFloorOrSkyRays];
          for (int i = 0; i < count; ++i) {
            const glm::vec3 d(camera.rayDirection((x0 + i + 0.5) / settings.camera.width, (y + 0.5) / settings.camera.height));
            directionX[i] = d.x;
            directionY[i] = d.y;
            directionZ[i] = d.z;
            rays[i] = Ray{eye, d, 0.0f, kInfinity};
            floorPixels += d.z < 0.0f;
          }
          TraceCounters lanesCounters, generalCounters;
          glm::vec3 lanes[WhittedTracer::kFloorOrSkyRays], general[WhittedTracer::kFloorOrSkyRays];
          tracer.traceFloorOrSky(eye, directionX, directionY, directionZ, count, lanesCounters, lanes);
          for (int first = 0; first < count; first += 8) {
            const SlimeHit misses[8];
            tracer.tracePrimaries(rays + first, misses, std::min(8, count - first), generalCounters, nullptr, general + first);
          }
          for (int i = 0; i < count; ++i) {
            ++compared;
            differing += lanes[i] != general[i];
          }
          EXPECT_EQ(lanesCounters.rays.primary, generalCounters.rays.primary) << view.what;
          EXPECT_EQ(lanesCounters.rays.shadow, generalCounters.rays.shadow) << view.what;
        }
      }
    }
    EXPECT_GT(floorPixels, 0) << view.what;
    EXPECT_EQ(differing, 0) << view.what << ": " << differing << " of " << compared
                            << " pixels differ between the lanes and the general path";
  }
}

}  // namespace
}  // namespace slime::testing

// The primary rays' first hits found in object order (render/trace/primary_visibility.h) against the eye's
// grid, which it replaces, and the brute force: for every pixel of several views of convex and
// non-convex slimes, at the pixel's centre and at jittered points (progressive anti-aliasing), the
// same triangle at the same distance and barycentrics, bit for bit; and no answer where it cannot
// serve.
#include "render/trace/primary_visibility.h"

#include "core/geometry/camera.h"
#include "core/geometry/icosphere.h"
#include "render/trace/brute_tracer.h"
#include "render/slime/pencil_grid.h"
#include "render/trace/primary_view.h"
#include "render/slime/slime_geometry.h"
#include "render_fixture.h"

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

namespace slime::testing {
namespace {

struct View {
  const char* what;
  double yaw, pitch, distanceScale;  // the camera's angles and its distance from the slime, relative
};

// Every pixel's first hit through the visibility, the eye's grid and the brute force; the
// mismatches with each, and the pixels that hit.
void compareEveryPixel(const Settings& settings, const SlimeGeometry& geometry, glm::vec2 offset, const std::string& what) {
  const int width = settings.camera.width, height = settings.camera.height;
  const Camera camera = makeCamera(settings.camera, width, height);
  PrimaryVisibility visibility;
  ASSERT_TRUE(visibility.build(geometry, camera, width, height, offset)) << what;
  PencilGrid grid;
  ASSERT_TRUE(grid.build(geometry, glm::vec3(camera.position), true)) << what;
  const BruteTracer brute(geometry);
  const PrimaryView view(camera, width, height);
  int hitting = 0, unlikeGrid = 0, unlikeBrute = 0;
  for (int y = 0; y < height; ++y) {
    for (int x0 = 0; x0 < width; x0 += 8) {
      float dx[8], dy[8], dz[8];
      primaryDirections8(view, x0, offset.x, static_cast<float>(y) + offset.y, dx, dy, dz);
      const int count = std::min(8, width - x0);
      bool active[8] = {};
      for (int i = 0; i < count; ++i) active[i] = (x0 + i + y) % 7 != 3;  // some lanes not asked
      SlimeHit hits[8];
      visibility.hits8(x0, y, count, active, hits);
      for (int i = 0; i < 8; ++i) {
        if (!active[i]) {
          EXPECT_FALSE(hits[i].valid()) << what << ": a lane not asked";
          continue;
        }
        const Ray ray{glm::vec3(camera.position), {dx[i], dy[i], dz[i]}, 0.0f, kInfinity};
        const SlimeHit fromGrid = grid.nearest(ray);
        hitting += hits[i].valid();
        if (std::memcmp(&hits[i], &fromGrid, sizeof(SlimeHit)) != 0 && ++unlikeGrid <= 3)
          ADD_FAILURE() << what << ": pixel (" << x0 + i << ", " << y << ") visibility " << hits[i].primitive << " at "
                        << hits[i].t << ", grid " << fromGrid.primitive << " at " << fromGrid.t;
        if ((x0 + i + 3 * y) % 5 != 0) continue;  // the brute force (every triangle) on a fifth of the pixels
        const SlimeHit fromBrute = brute.intersect(ray);
        if ((hits[i].primitive != fromBrute.primitive || hits[i].t != fromBrute.t) && ++unlikeBrute <= 3)
          ADD_FAILURE() << what << ": pixel (" << x0 + i << ", " << y << ") visibility " << hits[i].primitive << " at "
                        << hits[i].t << ", brute force " << fromBrute.primitive << " at " << fromBrute.t;
      }
    }
  }
  EXPECT_EQ(unlikeGrid, 0) << what;
  EXPECT_EQ(unlikeBrute, 0) << what;
  EXPECT_GT(hitting, width * height / 20) << what << ": the slime is in view";
}

TEST(PrimaryVisibility, EqualsTheEyesGridAndTheBruteForcePixelForPixel) {
  Settings settings = withoutCaustics(smallScene(128, 96));
  settings.camera.fov = 30.0;
  std::vector<Shape> shapes{{"ball", makeIcosphere(4, settings.slime.radius, settings.slime.position)},
                            {"coarse ball", makeIcosphere(2, settings.slime.radius, settings.slime.position)}};
  for (Shape& shape : nonConvexShapes(settings)) shapes.push_back(shape);
  const View views[] = {{"default view", settings.camera.yaw, settings.camera.pitch, 1.0},
                        {"from above", settings.camera.yaw + 40.0, -60.0, 1.0},
                        {"close", settings.camera.yaw - 25.0, -15.0, 0.45}};
  const glm::vec2 offsets[] = {{0.5f, 0.5f}, {0.1372f, 0.8613f}, {0.9999f, 0.0f}};
  for (const Shape& shape : shapes) {
    SlimeGeometry geometry;
    geometry.update(shape.mesh.positions, shape.mesh.triangles);
    for (const View& view : views) {
      Settings s = settings;
      const glm::dvec3 target = settings.slime.position;
      const glm::dvec3 eye = target - viewDirection(view.yaw, view.pitch) * (glm::length(settings.camera.position - target) * view.distanceScale);
      lookAt(s.camera, eye, target);
      for (const glm::vec2& offset : offsets)
        compareEveryPixel(s, geometry, offset,
                          std::string(shape.what) + ", " + view.what + ", offset " + std::to_string(offset.x) + "," +
                              std::to_string(offset.y));
    }
  }
}

TEST(PrimaryVisibility, DoesNotServeAnEyeAtTheSlimeOrASlimeBehindTheCamera) {
  Settings settings = smallScene(96, 72);
  const TriangleMesh ball = makeIcosphere(3, settings.slime.radius, settings.slime.position);
  SlimeGeometry geometry;
  geometry.update(ball.positions, ball.triangles);
  PrimaryVisibility visibility;
  const auto serves = [&](const Settings& s) {
    return visibility.build(geometry, makeCamera(s.camera, s.camera.width, s.camera.height), s.camera.width,
                            s.camera.height, {0.5f, 0.5f});
  };
  EXPECT_TRUE(serves(settings));
  EXPECT_TRUE(visibility.ready());
  Settings inside = settings;  // the eye within 1.2 bounding radii of the slime's centre, looking at it
  inside.camera.fov = 120.0;
  lookAt(inside.camera, settings.slime.position + glm::dvec3(0.0, 0.0, 1.1 * settings.slime.radius), settings.slime.position);
  EXPECT_FALSE(serves(inside));
  EXPECT_FALSE(visibility.ready());
  Settings away = settings;  // looking away: the slime behind the camera
  lookAt(away.camera, settings.camera.position, 2.0 * settings.camera.position - settings.slime.position);
  EXPECT_FALSE(serves(away));
  SlimeGeometry sphere = geometry;
  sphere.setAnalyticSphere(true, static_cast<float>(settings.slime.radius));
  EXPECT_FALSE(visibility.build(sphere, makeCamera(settings.camera, 96, 72), 96, 72, {0.5f, 0.5f}));
}

}  // namespace
}  // namespace slime::testing

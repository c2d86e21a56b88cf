#include "render/slime/screen_footprint.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/geometric.hpp>

namespace slime {
namespace {

constexpr int kMarginPixels = 2;

// Where along the line a + x s the direction lies in the cone k |d|² − (d·c)² ≤ 0 (both nappes; the
// callers make sure the line meets only the one they mean): no x, an interval, or, when the line
// runs along the cone (the quadratic's leading coefficient ≤ 0) or the numbers overflow, every x.
struct LineInterval {
  bool any = false;
  double low = 0.0, high = 0.0;
};

LineInterval coneInterval(const glm::dvec3& a, const glm::dvec3& s, const glm::dvec3& c, double k) {
  constexpr double kEverything = 1e300;
  const double sc = glm::dot(s, c), ac = glm::dot(a, c);
  const double quadratic = k * glm::dot(s, s) - sc * sc;
  const double linear = k * glm::dot(a, s) - ac * sc;  // half the coefficient of x
  const double constant = k * glm::dot(a, a) - ac * ac;
  if (!(quadratic > 0.0) || !std::isfinite(linear) || !std::isfinite(constant))
    return {true, -kEverything, kEverything};
  const double discriminant = linear * linear - quadratic * constant;
  if (discriminant < 0.0) return {};
  const double root = std::sqrt(discriminant);
  const LineInterval interval{true, (-linear - root) / quadratic, (-linear + root) / quadratic};
  if (!std::isfinite(interval.low) || !std::isfinite(interval.high)) return {true, -kEverything, kEverything};
  return interval;
}

// The pixels whose sample x + 0.5 lies in [low, high], clamped to the image.
ScreenFootprint::Span pixelsOf(const LineInterval& interval, int width) {
  if (!interval.any) return {};
  const auto column = [width](double x) {
    return static_cast<int>(std::clamp(x, 0.0, static_cast<double>(width)));
  };
  return {column(std::floor(interval.low - 0.5)), column(std::floor(interval.high - 0.5) + 1.0)};
}

// Where a point in front of the eye appears, in the footprint's coordinates: x along a row as in
// a + x s, and the row's coordinate y + 0.5. False behind the eye (or beside it).
bool onImage(const Camera& camera, const glm::dvec3& point, int width, int height, glm::dvec2& at) {
  const glm::dvec3 d = point - camera.position;
  const double depth = glm::dot(d, camera.forward);
  if (!(depth > 1e-9)) return false;
  at = {0.5 * width * (1.0 + glm::dot(d, camera.right) / (depth * camera.tanHalfFov * camera.aspect)),
        0.5 * height * (1.0 - glm::dot(d, camera.up) / (depth * camera.tanHalfFov))};
  return std::isfinite(at.x) && std::isfinite(at.y);
}

// The outline on the image of the slime's vertices (or of their mirror images below the floor), each
// row's crossing with it into `rows`; false (no outline) unless every vertex lies in front of the eye.
bool imageOutline(const Camera& camera, const SlimeGeometry& geometry, bool mirrored, int width, int height,
                  ScreenFootprint::Outline& outline) {
  outline.points.clear();
  for (std::size_t i = 0; i < geometry.vertexCount(); ++i) {
    const glm::vec3& p = geometry.positions[i];
    glm::dvec2 at;
    if (!onImage(camera, glm::dvec3(p.x, p.y, mirrored ? -p.z : p.z), width, height, at)) return false;
    outline.points.push_back(at);
  }
  outline.hull.build(outline.points);
  if (!outline.hull.bounded()) return false;
  outline.hull.crossRows(height, outline.rows);
  return true;
}

// The outline on the image of the vertices' shadow on the floor (the vertices cast from the light
// onto z = 0, their hull seen from the eye: seen in perspective a convex patch of the floor stays
// convex), each row's crossing into `rows`; false unless the light is above every vertex and the
// shadow's corners lie in front of the eye.
bool shadowOutline(const Camera& camera, const glm::dvec3& light, const SlimeGeometry& geometry, int width, int height,
                   ScreenFootprint::Outline& outline) {
  outline.points.clear();
  for (std::size_t i = 0; i < geometry.vertexCount(); ++i) {
    const glm::dvec3 p(geometry.positions[i]);
    if (!(light.z - p.z > 1e-9 * std::max(1.0, light.z))) return false;
    const double s = light.z / (light.z - p.z);
    outline.points.emplace_back(light.x + (p.x - light.x) * s, light.y + (p.y - light.y) * s);
  }
  outline.hull.build(outline.points);  // on the floor
  if (!outline.hull.bounded()) return false;
  outline.points.clear();
  for (const glm::dvec2& corner : outline.hull.corners()) {
    glm::dvec2 at;
    if (!onImage(camera, glm::dvec3(corner, 0.0), width, height, at)) return false;
    outline.points.push_back(at);
  }
  outline.hull.build(outline.points);  // on the image
  if (!outline.hull.bounded()) return false;
  outline.hull.crossRows(height, outline.rows);
  return true;
}

LineInterval crossing(const ScreenFootprint::Outline& outline, int row) {
  const ConvexOutline::Crossing& c = outline.rows[static_cast<std::size_t>(row)];
  return {c.any, c.low, c.high};
}

ScreenFootprint::Span hull(const ScreenFootprint::Span& a, const ScreenFootprint::Span& b) {
  if (a.x0 >= a.x1) return b;
  if (b.x0 >= b.x1) return a;
  return {std::min(a.x0, b.x0), std::max(a.x1, b.x1)};
}

}  // namespace

long long ScreenFootprint::area() const {
  long long sum = 0;
  for (const Span& span : rows) sum += std::max(0, span.x1 - span.x0);
  return sum;
}

void slimeFootprint(const Camera& camera, const SlimeGeometry& geometry, const ShadingParameters& parameters,
                    int width, int height, ScreenFootprint& footprint) {
  footprint.rows.assign(static_cast<std::size_t>(std::max(0, height)), ScreenFootprint::Span{});
  if (width <= 0 || height <= 0) return;
  if (geometry.boundRadius <= 0.0f && !geometry.analyticSphere) return;  // no slime
  const ScreenFootprint::Span whole{0, width};

  // The bounding sphere, with the same slack as SlimeGeometry::mayHit.
  const glm::dvec3 center(geometry.boundCenter);
  const double radius = geometry.boundRadius * 1.0001 + 1e-6;
  const glm::dvec3 eye = camera.position, light(parameters.lightPosition);
  const glm::dvec3 toCenter = center - eye, toMirror = glm::dvec3(center.x, center.y, -center.z) - eye;
  const bool mirror = parameters.floorSpecular > 0.0f;
  // Only a sphere wholly in front of the eye has a bounded image.
  const double margin = 1e-6 * radius;
  if (glm::dot(toCenter, camera.forward) <= radius + margin ||
      (mirror && glm::dot(toMirror, camera.forward) <= radius + margin)) {
    footprint.rows.assign(footprint.rows.size(), whole);
    return;
  }
  const bool shadows = parameters.shadows && light.z > 0.0;
  const glm::dvec3 fromLight = center - light;
  // The shadow needs the eye above the floor (a row's floor points on a line), a camera without roll
  // and the light above the sphere (its shadow then an ellipse); otherwise every floor pixel may be in it.
  const glm::dvec3 right = camera.right * (camera.tanHalfFov * camera.aspect),
                   up = camera.up * camera.tanHalfFov;
  const bool boundedShadow = eye.z > 0.0 && right.z == 0.0 && light.z > center.z + radius + margin;

  // A mesh slime lies inside the convex hull of its vertices: where they allow, the outlines of that
  // hull (on the image, in the mirror, its shadow) replace the sphere's ellipses.
  const bool mesh = !geometry.analyticSphere && geometry.vertexCount() > 0;
  ScreenFootprint::Outline& seen = footprint.outlines[0];
  ScreenFootprint::Outline& mirrored = footprint.outlines[1];
  ScreenFootprint::Outline& shade = footprint.outlines[2];
  const bool seenOutline = mesh && imageOutline(camera, geometry, false, width, height, seen);
  const bool mirrorOutline = mesh && mirror && imageOutline(camera, geometry, true, width, height, mirrored);
  const bool shadowOutlined = mesh && shadows && boundedShadow && shadowOutline(camera, light, geometry, width, height, shade);

  // Camera::rayDirection for the sample at (x, v): a + x s with x in pixels.
  const glm::dvec3 step = right * (2.0 / width);
  for (int y = 0; y < height; ++y) {
    const double v = (y + 0.5) / height;
    const glm::dvec3 base = camera.forward - right + (1.0 - 2.0 * v) * up;
    ScreenFootprint::Span span = pixelsOf(
        seenOutline ? crossing(seen, y) : coneInterval(base, step, toCenter, glm::dot(toCenter, toCenter) - radius * radius),
        width);
    if (mirror)
      span = hull(span, pixelsOf(mirrorOutline ? crossing(mirrored, y)
                                               : coneInterval(base, step, toMirror,
                                                              glm::dot(toMirror, toMirror) - radius * radius),
                                 width));
    if (shadows && base.z < 0.0) {  // this row sees the floor
      if (!boundedShadow) {
        span = whole;
      } else {
        // The row's floor points eye + t (a + x s), t = −eye_z / a_z, seen from the light.
        const double t = -eye.z / base.z;
        const LineInterval shadow = shadowOutlined ? crossing(shade, y)
                                                   : coneInterval(eye + t * base - light, t * step, fromLight,
                                                                  glm::dot(fromLight, fromLight) - radius * radius);
        span = hull(span, pixelsOf(shadow, width));
      }
    }
    footprint.rows[y] = span;
  }

  // Widen each span by kMarginPixels columns each way and to the kMarginPixels rows either side.
  std::array<ScreenFootprint::Span, kMarginPixels> above{};  // the unwidened spans of the rows just above
  for (int y = 0; y < height; ++y) {
    const ScreenFootprint::Span own = footprint.rows[y];
    ScreenFootprint::Span widened = own;
    for (const ScreenFootprint::Span& span : above) widened = hull(widened, span);
    for (int below = y + 1; below <= std::min(height - 1, y + kMarginPixels); ++below)
      widened = hull(widened, footprint.rows[below]);
    if (widened.x0 < widened.x1)
      widened = {std::max(0, widened.x0 - kMarginPixels), std::min(width, widened.x1 + kMarginPixels)};
    std::rotate(above.begin(), above.begin() + 1, above.end());
    above.back() = own;
    footprint.rows[y] = widened;
  }
}

ScreenFootprint slimeFootprint(const Camera& camera, const SlimeGeometry& geometry,
                               const ShadingParameters& parameters, int width, int height) {
  ScreenFootprint footprint;
  slimeFootprint(camera, geometry, parameters, width, height, footprint);
  return footprint;
}

}  // namespace slime

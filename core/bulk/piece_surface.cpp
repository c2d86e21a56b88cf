#include "core/bulk/piece_surface.h"

#include "core/geometry/enclosed_solid.h"
#include "core/geometry/surface_extraction.h"
#include "core/bulk/surface_embedding.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace slime {
namespace {

constexpr int kTaubinPasses = 8;
// The merged bodies' indicator's blur (blurGrid's passes; about 2 spacings' standard deviation): 7 left
// normal jumps of 10.3° across a merged seam 2 s later, 9 left 8.7° (the drawn slime a little rounder,
// aspect 0.710 against 0.704), 11 left 7.9° (0.716).
constexpr int kMergeBlurPasses = 9;
constexpr double kBlend = 2.0;  // the blend radius of the cut's rim, in spacings
// The extraction grid's cells per spacing along each axis: surface nets put one vertex per cell the
// surface crosses, so the grid is as fine as the drawn surface's edges (spacing is twice their length).
constexpr double kCellsPerSpacing = 1.5;

void bounds(const SurfaceView& surface, glm::dvec3& low, glm::dvec3& high) {
  for (const glm::dvec3& p : surface.positions) {
    low = glm::min(low, p);
    high = glm::max(high, p);
  }
}

// f(grid point, tetrahedron) for every grid point inside a tetrahedron of `body` at its positions now.
template <typename F>
void forGridPointsInTetrahedra(const ScalarGrid& grid, const BulkBody& body, F f) {
  const glm::ivec3 n = grid.size;
  const double h = grid.spacing;
  const std::vector<glm::dvec3>& x = body.state.positions;
  for (std::size_t e = 0; e < body.mesh.tetrahedra.size(); ++e) {
    const Tetrahedron& t = body.mesh.tetrahedra[e];
    const glm::dvec3 a = x[t.x], b = x[t.y], c = x[t.z], d = x[t.w];
    const glm::dvec3 lo = (glm::min(glm::min(a, b), glm::min(c, d)) - grid.origin) / h;
    const glm::dvec3 hi = (glm::max(glm::max(a, b), glm::max(c, d)) - grid.origin) / h;
    for (int k = std::max(0, static_cast<int>(std::ceil(lo.z))); k <= std::min(n.z - 1, static_cast<int>(std::floor(hi.z))); ++k)
      for (int j = std::max(0, static_cast<int>(std::ceil(lo.y))); j <= std::min(n.y - 1, static_cast<int>(std::floor(hi.y))); ++j)
        for (int i = std::max(0, static_cast<int>(std::ceil(lo.x))); i <= std::min(n.x - 1, static_cast<int>(std::floor(hi.x))); ++i) {
          const glm::dvec4 w = barycentric(grid.point(i, j, k), a, b, c, d);
          if (w.x >= 0.0 && w.y >= 0.0 && w.z >= 0.0 && w.w >= 0.0) f(grid.index(i, j, k), e);
        }
  }
}

}  // namespace

void offsetToVolume(TriangleMesh& mesh, double volume) {
  std::vector<glm::dvec3> normals(mesh.positions.size());
  for (int round = 0; round < 2; ++round) {
    std::fill(normals.begin(), normals.end(), glm::dvec3(0.0));
    double area = 0.0;
    for (const Triangle& t : mesh.triangles) {
      const glm::dvec3 n = glm::cross(mesh.positions[t.y] - mesh.positions[t.x], mesh.positions[t.z] - mesh.positions[t.x]);
      area += 0.5 * glm::length(n);
      for (int corner = 0; corner < 3; ++corner) normals[t[corner]] += n;
    }
    if (area <= 0.0) return;
    const double delta = (volume - enclosedSolid(mesh).volume) / area;
    for (std::size_t i = 0; i < normals.size(); ++i) {
      const double length = glm::length(normals[i]);
      if (length > 0.0) mesh.positions[i] += (delta / length) * normals[i];
    }
  }
}

double meanEdgeLength(const SurfaceView& surface) {
  double sum = 0.0;
  for (const Triangle& t : surface.triangles)
    sum += glm::length(surface.positions[t.y] - surface.positions[t.x]) + glm::length(surface.positions[t.z] - surface.positions[t.y]) +
           glm::length(surface.positions[t.x] - surface.positions[t.z]);
  return surface.triangles.empty() ? 0.0 : sum / (3.0 * static_cast<double>(surface.triangles.size()));
}

std::vector<TriangleMesh> splitDrawnSurface(const SurfaceView& drawn, const BulkBody& body,
                                            const std::vector<std::uint32_t>& partOf, std::uint32_t parts,
                                            double spacing) {
  glm::dvec3 low(std::numeric_limits<double>::infinity()), high(-std::numeric_limits<double>::infinity());
  bounds(drawn, low, high);
  ScalarGrid distance = gridAround(low, high, spacing / kCellsPerSpacing, 3.0 * spacing);
  signedDistanceOnGrid(drawn, distance);
  const glm::ivec3 n = distance.size;
  // Each grid point's part: the tetrahedron it lies in.
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> label(distance.count(), kNone);
  forGridPointsInTetrahedra(distance, body, [&](std::size_t g, std::size_t e) { label[g] = partOf[e]; });
  // Points in no tetrahedron (the drawn surface stands proud of the body's faces) take a labelled
  // neighbour's part, pass after pass.
  std::vector<std::uint32_t> next;
  for (int pass = 0; pass < 8; ++pass) {
    next = label;
    bool changed = false;
    for (int k = 0; k < n.z; ++k)
      for (int j = 0; j < n.y; ++j)
        for (int i = 0; i < n.x; ++i) {
          const std::size_t g = distance.index(i, j, k);
          if (label[g] != kNone) continue;
          const int offsets[6][3] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
          for (const auto& o : offsets) {
            const int a = i + o[0], b = j + o[1], c = k + o[2];
            if (a < 0 || b < 0 || c < 0 || a >= n.x || b >= n.y || c >= n.z) continue;
            const std::uint32_t other = label[distance.index(a, b, c)];
            if (other != kNone) {
              next[g] = other;
              changed = true;
              break;
            }
          }
        }
    label.swap(next);
    if (!changed) break;
  }
  std::vector<TriangleMesh> surfaces(parts);
  ScalarGrid own = distance;
  for (std::uint32_t part = 0; part < parts; ++part) {
    // The part's indicator (unlabelled points, all outside, count as its own: they do not cut),
    // blurred, as a distance-like field about the cut; the part's field is its smooth min with the
    // distance, which rounds the cut's rim (a sharp rim's normals jump by 90°).
    for (std::size_t g = 0; g < own.values.size(); ++g) own.values[g] = label[g] == kNone || label[g] == part ? 1.0 : 0.0;
    blurGrid(own, static_cast<int>(std::lround(2.0 * kCellsPerSpacing * kCellsPerSpacing)));  // a blur two spacings wide whatever the cells
    for (std::size_t g = 0; g < own.values.size(); ++g)
      own.values[g] = -smoothMax(-distance.values[g], -4.0 * spacing * (own.values[g] - 0.5), kBlend * spacing);
    surfaces[part] = extractSurface(own);
    keepLargestPart(surfaces[part]);
    taubinSmooth(surfaces[part], kTaubinPasses);
  }
  return surfaces;
}

TriangleMesh mergedDrawnSurface(std::span<const BulkBody* const> bodies, std::span<const SurfaceView> surfaces, double spacing,
                                int level) {
  glm::dvec3 low(std::numeric_limits<double>::infinity()), high(-std::numeric_limits<double>::infinity());
  for (const SurfaceView& surface : surfaces) bounds(surface, low, high);
  ScalarGrid merged = gridAround(low, high, spacing / kCellsPerSpacing, 3.0 * spacing);
  // The bodies' indicator, blurred: the union of their tetrahedra, rounded over a few spacings, which
  // fills the seam's crease. (Not the drawn surfaces' signed distance: a small torn piece's drawn surface
  // is crumpled, its normals jumping by 70–170°, and their smooth union kept that as the seam: 52°.)
  for (const BulkBody* body : bodies) forGridPointsInTetrahedra(merged, *body, [&](std::size_t g, std::size_t) { merged.values[g] = 1.0; });
  blurGrid(merged, kMergeBlurPasses);
  glm::dvec3 centre(0.0);
  double inside = 0.0;
  for (int k = 0; k < merged.size.z; ++k)
    for (int j = 0; j < merged.size.y; ++j)
      for (int i = 0; i < merged.size.x; ++i) {
        double& value = merged.values[merged.index(i, j, k)];
        value -= 0.5;
        if (value > 0.0) {
          centre += merged.point(i, j, k);
          inside += 1.0;
        }
      }
  if (inside == 0.0) return {};
  centre /= inside;
  // Drawn as a slime never torn: the drawn icosphere about the union's centroid, each vertex where its
  // ray from the centre last leaves the union (the field's outermost fall through zero, bisected). A
  // union that is not star-shaped about its centroid (rays that leave it more than once) is drawn by
  // the grid's surface nets instead.
  TriangleMesh mesh = makeIcosphere(level, 1.0, glm::dvec3(0.0));
  double reach = 0.0;  // the farthest inside point, and a spacing: every ray has left the union by then
  for (int k = 0; k < merged.size.z; ++k)
    for (int j = 0; j < merged.size.y; ++j)
      for (int i = 0; i < merged.size.x; ++i)
        if (merged.values[merged.index(i, j, k)] > 0.0) reach = std::max(reach, glm::length(merged.point(i, j, k) - centre));
  reach += merged.spacing;
  const double step = 0.5 * merged.spacing;
  std::size_t reentering = 0;
  bool star = sampleGrid(merged, centre) > 0.0;
  for (glm::dvec3& p : mesh.positions) {
    if (!star) break;
    const glm::dvec3 d = p;
    double exit = -1.0, previous = sampleGrid(merged, centre);
    int exits = 0;
    for (double r = step; r <= reach; r += step) {
      const double value = sampleGrid(merged, centre + r * d);
      if (previous > 0.0 && value <= 0.0) {
        exit = r;
        ++exits;
      }
      previous = value;
    }
    if (exit < 0.0) {
      star = false;
      break;
    }
    reentering += exits > 1;
    double in = exit - step, out = exit;
    for (int iteration = 0; iteration < 30; ++iteration) {
      const double middle = 0.5 * (in + out);
      (sampleGrid(merged, centre + middle * d) > 0.0 ? in : out) = middle;
    }
    p = centre + 0.5 * (in + out) * d;
  }
  if (star && reentering * 50 <= mesh.positions.size()) {  // at most 2 % of the rays re-enter
    taubinSmooth(mesh, kTaubinPasses);  // the body's facets, which the blur leaves as faint creases
    return mesh;
  }
  mesh = extractSurface(merged);
  if (keepLargestPart(mesh) > 0) return {};  // the bodies do not meet
  taubinSmooth(mesh, kTaubinPasses);
  return mesh;
}

}  // namespace slime

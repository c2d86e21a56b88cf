// The slime as the renderer sees it: float vertex positions (padded for Embree), per-frame vertex
// normals, triangles, a bounding sphere for culling, and the analytic sphere of slime.shape=sphere.
// Shared by both intersection back-ends and by shading, so only the intersection differs.
// The slime may be several pieces (closed surfaces, core/geometry/surface_view.h): they are held as one
// mesh, piece after piece, each piece's triangles offset by the vertices of the pieces before it. Every
// structure built on the mesh holds for disjoint closed parts as for one: "supporting" is judged against
// every vertex of every piece, the exit walk steps only across shared edges (within a piece), and the
// bounds, outlines and grids bound all the pieces together.
#pragma once

#include "core/geometry/icosphere.h"
#include "core/geometry/surface_view.h"
#include "render/trace/ray.h"

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace slime {

struct SlimeGeometry {
  std::vector<glm::vec3> positions;  // one extra zero vertex at the end: Embree reads 16 bytes past the last
  std::vector<glm::vec3> normals;    // area-weighted vertex normals of the current (deformed) mesh
  std::vector<glm::vec3> faceNormals;  // unit outward normal of each triangle (geometricNormal)
  std::vector<Triangle> triangles;
  std::vector<std::uint32_t> pieceTriangleStarts;  // piece k's triangles begin here (one entry a piece)
  glm::vec3 boundCenter{0.0f};       // a sphere that contains every vertex
  float boundRadius = 0.0f;
  glm::vec3 meshBoundCenter{0.0f};   // the mesh's own bounds (the sphere's replace them in sphere mode)
  float meshBoundRadius = 0.0f;
  bool sphereRequested = false;      // slime.shape == sphere
  bool analyticSphere = false;       // ... and there is a slime: the exact sphere below replaces the mesh
  // Per triangle: its plane supports the slime, i.e. no vertex stands above it (within
  // kConvexTolerance). A ray that leaves the surface through such a triangle heads into the half
  // space above its plane, where there is no slime: it cannot meet the slime again and needs no
  // query (see whitted_tracer.h). A resting slime has a few dozen triangles that do not support it
  // (the facets of its tetrahedra), a pulled or pressed one whole regions; every other one still does.
  std::vector<std::uint8_t> supporting;
  // Every triangle supports the slime: the slime is convex (a straight line crosses it once at most).
  bool convex = false;
  // The triangles that do not support it, and their indices in `triangles`: the only ones a straight
  // line can enter the slime through once it has been inside (SlimeIntersector::intersectNonSupporting8).
  std::vector<Triangle> nonSupportingTriangles;
  std::vector<std::uint32_t> nonSupportingPrimitives;
  glm::vec3 nonSupportingCenter{0.0f};  // a sphere that contains them (a pulled slime's neck, a press's dent)
  float nonSupportingRadius = 0.0f;
  // The vertices in small spatial clusters (median splits of the first frame of a topology), and each
  // cluster's bounding sphere this frame: a triangle's plane is tested against a cluster's sphere
  // before its vertices.
  std::vector<std::uint32_t> clusterOrder;   // vertex indices, cluster after cluster
  std::vector<std::uint32_t> clusterBegin;   // cluster k holds clusterOrder[clusterBegin[k], clusterBegin[k + 1])
  // A tree eight wide over the clusters, bounded this frame: level 0 the clusters, each level above
  // one node for each 8 consecutive nodes of the level below (neighbours in the median splits), up to
  // a top of at most 8. Each node is bounded from its own vertices twice: a sphere (centroid,
  // farthest vertex) and a disk (the vertex normals' mean direction, the radius within the disk's
  // plane, the half thickness along its normal). A plane is tested against the top, then only below
  // the nodes it cuts, so a triangle costs about the log of the vertex count; and a plane nearly
  // parallel to the surface (a supporting triangle's) passes over the disks of the patches around
  // it, which their spheres would reach through.
  struct NodeBounds {
    enum Field { kCentre = 0, kRadius = 3, kNormal = 4, kAcross = 7, kThickness = 8, kFields = 9 };
    std::array<std::vector<float>, kFields> values;  // by field, node after node; padded to a multiple of 8
    // Bounds node k by the vertices order[begin, end).
    void set(std::size_t k, const std::vector<std::uint32_t>& order, const std::vector<glm::vec3>& positions,
             const std::vector<glm::vec3>& normals, std::size_t begin, std::size_t end);
    // Bit i: node k + i may reach above the plane n·x = level (n a unit vector).
    unsigned above(std::size_t k, const glm::vec3& n, float level) const;
  };
  std::vector<NodeBounds> nodeLevels;
  struct NodeRun {
    std::uint32_t depth, index;  // node `index` of nodeLevels[depth]
    std::uint32_t begin, end;    // its vertices: clusterOrder[begin, end)
  };
  std::vector<NodeRun> nodeRuns;  // every node of every level, set with the clusters
  std::vector<float> clusterVertices[3];     // x, y, z of the vertices, 16 slots a cluster (NaN where empty)
  glm::vec3 sphereCenter{0.0f};
  float sphereRadius = 0.0f;

  // A vertex may stand this far (relative to the bounding radius) above the plane of a triangle and
  // still count as below it: 2e-3·R is 80 µm on the default slime, a quarter of a pixel
  // of the default view; dents shallower than that are not seen in reflections anyway.
  static constexpr float kConvexTolerance = 2e-3f;

  bool isConvex() const { return analyticSphere || convex; }
  // Whether a query of the non-supporting triangles alone costs a fraction of one of the whole mesh
  // (they are at most half of it), so that the tracer's shortcuts through them pay (whitted_tracer.cpp, shadow_rays.cpp).
  bool fewNonSupporting() const { return isConvex() || 2 * nonSupportingTriangles.size() <= triangles.size(); }
  // Whether triangle `primitive`'s plane supports the slime (always, for the analytic sphere).
  bool supports(std::uint32_t primitive) const {
    return analyticSphere || convex || (primitive < supporting.size() && supporting[primitive] != 0);
  }

  std::size_t vertexCount() const { return positions.empty() ? 0 : positions.size() - 1; }

  // Copies the pieces, one after another, into one mesh; recomputes normals and bounds. Returns true
  // when the topology changed (the number of pieces, their vertex counts or their triangles). Throws
  // std::invalid_argument for a triangle whose index lies outside its own piece's vertices.
  bool update(std::span<const SurfaceView> surfaces);
  // One piece.
  bool update(const std::vector<glm::dvec3>& newPositions, const std::vector<Triangle>& newTriangles) {
    const SurfaceView surface{newPositions, newTriangles};
    return update(std::span<const SurfaceView>(&surface, 1));
  }

  // The clusters of a new topology and the tree over them (buildClusters), and this frame's
  // supporting triangles and convexity.
  void buildClusters();
  void findSupportingTriangles();
  // nonSupportingTriangles, nonSupportingPrimitives, their sphere and `convex`, from `supporting`.
  void listNonSupporting();

  // Makes the analytic sphere (centre of the vertices, of all pieces together, `radius`) the slime,
  // or the mesh again.
  void setAnalyticSphere(bool enabled, float radius);

  // Whether the segment [tNear, tFar] of the ray can touch the bounding sphere (slack included).
  // Inline: every primary and every shadow ray asks it.
  bool mayHit(const Ray& ray) const {
    if (boundRadius <= 0.0f && !analyticSphere) return false;
    // Closest approach of the ray to the centre, clamped to the segment; slack covers float rounding.
    const float radius = boundRadius * 1.0001f + 1e-6f;
    const glm::vec3 toCenter = boundCenter - ray.origin;
    const float along = toCenter.x * ray.direction.x + toCenter.y * ray.direction.y + toCenter.z * ray.direction.z;
    const float tClosest = std::clamp(along, ray.tNear, ray.tFar);
    const glm::vec3 offset = ray.origin + tClosest * ray.direction - boundCenter;
    return offset.x * offset.x + offset.y * offset.y + offset.z * offset.z <= radius * radius;
  }
  // The same for the non-supporting triangles' bounding sphere: false when the segment cannot cross one.
  bool mayCrossNonSupporting(const Ray& ray) const {
    return !nonSupportingTriangles.empty() && touchesSphere(ray, nonSupportingCenter, nonSupportingRadius);
  }
  // mayHit's test for any sphere. mayHit keeps its own copy: written through this helper (even forced
  // inline, the centre by value) GCC 12 made addLight, which calls mayHit for every lit floor point,
  // take 6.9 % of a one-thread frame's samples instead of 3.3 % (perf, 2026-11-24).
  static bool touchesSphere(const Ray& ray, const glm::vec3& center, float sphereRadius) {
    // Closest approach of the ray to the centre, clamped to the segment; slack covers float rounding.
    const float radius = sphereRadius * 1.0001f + 1e-6f;
    const glm::vec3 toCenter = center - ray.origin;
    const float along = toCenter.x * ray.direction.x + toCenter.y * ray.direction.y + toCenter.z * ray.direction.z;
    const float tClosest = std::clamp(along, ray.tNear, ray.tFar);
    const glm::vec3 offset = ray.origin + tClosest * ray.direction - center;
    return offset.x * offset.x + offset.y * offset.y + offset.z * offset.z <= radius * radius;
  }

  // How far along `ray` (from an origin inside the bounding sphere) it leaves that sphere, with the
  // slack of mayHit; 0 when the origin lies outside.
  float boundExitDistance(const Ray& ray) const {
    const float radius = boundRadius * 1.0001f + 1e-6f;
    const glm::vec3 fromCenter = ray.origin - boundCenter;
    const float along = fromCenter.x * ray.direction.x + fromCenter.y * ray.direction.y + fromCenter.z * ray.direction.z;
    const float excess = fromCenter.x * fromCenter.x + fromCenter.y * fromCenter.y + fromCenter.z * fromCenter.z - radius * radius;
    return std::max(0.0f, -along + std::sqrt(std::max(0.0f, along * along - excess)));
  }

  // Unit geometric normal (outward) at a hit point: the triangle's, computed once per frame by update.
  glm::vec3 geometricNormal(const SlimeHit& hit, const glm::vec3& point) const {
    return analyticSphere ? glm::normalize(point - sphereCenter) : faceNormals[hit.primitive];
  }
};

}  // namespace slime

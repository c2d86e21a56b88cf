// The slime in Embree 3: one device, one dynamic scene holding the slime as a triangle mesh that
// shares SlimeGeometry's vertex and index arrays (written in place every frame, then refitted), and
// the analytic sphere of slime.shape=sphere as a one-point sphere primitive; and a second scene of the
// frame's non-supporting triangles alone, built anew each frame. Beside Embree, two grids of the
// triangles as the light and the eye see them (render/slime/pencil_grid.h) answer the shadow rays and the
// primary rays, and a walk over the surface (render/slime/exit_walk.h) where rays inside leave it, where
// they can. The floor and sky are not in Embree: they are analytic (see
// whitted_tracer.h).
#pragma once

#include "render/slime/exit_walk.h"
#include "render/slime/pencil_grid.h"
#include "render/trace/ray.h"
#include "render/slime/slime_geometry.h"

#include <embree3/rtcore.h>

#include <cstdint>
#include <string>
#include <vector>

namespace slime {

class EmbreeScene final : public SlimeIntersector {
 public:
  explicit EmbreeScene(int threads);  // threads = 0: all cores
  ~EmbreeScene() override;
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  // Re-reads `geometry` (which must outlive this scene's use of it). Refits the BVH when only the
  // positions moved; attaches new buffers and rebuilds when the topology changed or the shape
  // drifted far from the one the BVH was built for. Throws std::runtime_error on an Embree error.
  void update(const SlimeGeometry& geometry, bool topologyChanged);

  SlimeHit intersect(const Ray& ray) const override;
  void intersect8(const Ray* rays, const bool* active, SlimeHit* hits) const override;
  void intersectNonSupporting8(const Ray* rays, const bool* active, SlimeHit* hits) const override;
  // Makes lightCrossings8 answer for a light at `light` (bins the triangles by their direction from
  // it, render/slime/pencil_grid.h) when `wanted`, once per shape and light; call before tracing, after
  // update. Without it, or where the grid cannot serve, lightCrossings8 returns false.
  void prepareLight(const SlimeGeometry& geometry, const glm::vec3& light, bool wanted);
  // Each segment's crossings from the light's grid (no Embree query): exact, as the brute force's test.
  bool lightCrossings8(const Ray* rays, const bool* active, SegmentCrossings* crossings) const override;
  // The same for the primary rays from `eye` (binning only the triangles that face it) and primaryHits8.
  void prepareEye(const SlimeGeometry& geometry, const glm::vec3& eye, bool wanted);
  bool primaryHits8(const Ray* rays, const bool* active, SlimeHit* hits) const override;
  // Where rays inside leave through a supporting triangle, from the walk over the surface mapped by
  // update (not for the analytic sphere).
  bool supportingExits(const Ray* rays, const glm::vec3* exitPoints, const bool* active, SlimeHit* hits) const override;

  int rebuildCount() const { return rebuilds_; }

 private:
  void attachMesh(const SlimeGeometry& geometry);
  // The non-supporting triangles of this frame, as a BVH of their own (built anew: the set changes).
  void buildNonSupporting(const SlimeGeometry& geometry);
  // intersect8 in `scene`; a triangle hit's primID is mapped through `primitives` when given.
  void intersect8In(RTCScene scene, const std::vector<std::uint32_t>* primitives, const Ray* rays, const bool* active,
                    SlimeHit* hits) const;
  void throwOnError(const char* during);

  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  RTCGeometry mesh_ = nullptr;
  RTCGeometry sphere_ = nullptr;
  unsigned meshId_ = RTC_INVALID_GEOMETRY_ID;
  unsigned sphereId_ = RTC_INVALID_GEOMETRY_ID;
  RTCScene nonSupportingScene_ = nullptr;
  RTCGeometry nonSupporting_ = nullptr;
  const std::vector<std::uint32_t>* nonSupportingPrimitives_ = nullptr;  // the geometry's, see update()
  // A grid of the triangles seen from one point, rebuilt when the shape or the point changes.
  struct ApexGrid {
    PencilGrid grid;
    bool stale = true;  // the shape changed since the grid was built
    bool facingApexOnly = false;
    void prepare(const SlimeGeometry& geometry, const glm::vec3& apex, bool wanted);
    bool serves() const { return !stale && grid.ready(); }
  };
  const SlimeGeometry* geometry_ = nullptr;  // the one update() last read
  ExitWalk exitWalk_;
  ApexGrid lightGrid_;
  ApexGrid eyeGrid_{PencilGrid{}, true, true};
  bool sphereEnabled_ = false;
  float builtRadius_ = 0.0f;      // bounding radius when the BVH was last built from scratch
  int refitsSinceBuild_ = 0;
  int rebuilds_ = 0;
  std::string error_;             // the last message from the device error callback
};

}  // namespace slime

// Whitted ray tracing (SPEC §4) shared by both back-ends: only SlimeIntersector differs. The floor
// z = 0 and the sky are analytic, so a ray is tested against the slime only when it can reach the
// slime's bounding sphere; every other ray costs a plane test or nothing. A ray leaving the slime
// through a triangle whose plane has the whole slime below it (SlimeGeometry::supports) cannot meet
// it again and is not tested either.
//
// At a slime surface: I = local Phong + w_r I_reflected + w_t I_refracted, with
//   fresnel mode: w_r = F (dielectric Fresnel), w_t = (1 − F)·k_t entering, (1 − F) leaving;
//   seed mode:    w_r = k_s, w_t = k_t (constants, as the seed);
// and the light inside attenuated by Beer–Lambert exp(−σ l) over the path length l in the jelly.
// Physical shading (ShadingModel) has no local Phong and k_t = 1 (folded into σ). A path branches
// until it has render.depth segments or carries too little to change an 8-bit pixel
// (visibleThroughput: the product of its w's and Beer–Lambert factors times the scene's brightest
// radiance): a path totally reflected inside the jelly keeps all its light and goes on, one that
// loses it at each partial reflection stops after a few. At the cap a ray still totally reflected
// takes the analytic floor or sky along its reflection, as one leaving the jelly there does.
// The floor's and the sky's own shading (footprint, pattern, light, haze) is in floor_shading.cpp; the
// shadow rays' walk through the slime in shadow_rays.cpp.
#pragma once

#include "render/caustics/caustic_map.h"
#include "render/floor/floor_texture.h"
#include "render/floor/sky_occlusion.h"
#include "render/trace/ray.h"
#include "render/trace/renderer.h"
#include "render/trace/shading_parameters.h"
#include "render/slime/slime_geometry.h"
#include "render/simd/wide_lanes.h"

#include <vector>

namespace slime {

// What a tracing thread counts (no shared writes): rays by kind plus slime queries actually made.
struct TraceCounters {
  RayCounts rays;
  std::uint64_t slimeQueries = 0;  // rays asked of the slime (Embree, the brute force, a grid, the walk, the visibility: one each)
  std::uint64_t nonFinitePixels = 0;
  std::uint64_t cachedFloorPixels = 0;  // primary floor hits whose FloorShading came from the cache
  std::uint64_t reusedPixels = 0;       // pixels copied from the last frame (RenderStats::reusedPixels)
  std::uint64_t filledPixels = 0;       // checkerboard: pixels filled in from their neighbours (RenderStats)
  std::uint64_t tracedFillPixels = 0;   // checkerboard: pixels of the skipped colour traced after all (RenderStats)
  double busyMs = 0.0;                  // wall time spent in tiles by this thread
  PixelRect bytesWritten;               // the pixels whose sRGB bytes this thread wrote (RenderStats::bytesWritten)
};

// The floor seen along one ray, everything that does not depend on the slime: colour =
//   mix(ambient + T_light · lit (+ k_s I_mirror), horizon, haze)
// with T_light the light's transmittance past the slime (a shadow ray) traced per frame. For a still
// camera the primary rays' FloorShading is the same every frame and the renderer keeps it per pixel.
struct FloorShading {
  glm::vec3 ambient{0.0f};  // albedo × ambient light
  glm::vec3 lit{0.0f};      // light colour × (k_d (N·L) albedo + k_s (R·V)^n); zero when the light is below
  float haze = 0.0f;        // the horizon haze's share, 1 − exp(−distance / hazeDistance)
  bool filled = false;      // computed (a cache entry not yet computed is not)
};

class WhittedTracer {
 public:
  WhittedTracer(const SlimeGeometry& geometry, const SlimeIntersector& intersector, const FloorTexture& floor,
                const ShadingParameters& parameters)
      : geometry_(geometry), intersector_(intersector), floor_(floor), parameters_(parameters),
        skyOcclusion_(geometry, parameters) {}

  // Radiance along `count` ≤ kMaxPrimaries neighbouring primary rays whose slime hits are known,
  // into colors[]. The rays' Whitted trees are traced breadth first, one generation at a time, as
  // one wavefront: every slime query of a generation and every shadow ray of the wavefront goes to
  // the intersector as packets of up to 8 (neighbouring pixels refract and reflect alike, so these
  // packets stay coherent), the chords from inside to the walk 16 at a time. Sixteen pixels a
  // wavefront: its fixed costs shared, its batches fuller (8 pixels: 3 % slower, 2026-11-24).
  // `floorCache`, if given, holds the FloorShading of these count pixels. `outOfReach` promises that
  // the slime can neither be seen nor cast a shadow in these pixels (outside its ScreenFootprint):
  // on a matte floor they are then shaded as floor or sky at once, with no query and no wavefront.
  static constexpr int kMaxPrimaries = 16;
  void tracePrimaries(const Ray* rays, const SlimeHit* hits, int count, TraceCounters& counters,
                      FloorShading* floorCache, glm::vec3* colors, bool outOfReach = false) const;

  // Up to `count` ≤ kFloorOrSkyRays primary rays from `eye` (unit directions by lane) that can
  // neither meet the slime nor see its shadow (outside its ScreenFootprint): the floor or the sky,
  // into colors[]. On a matte floor in lanes (8 with AVX2, 16 with AVX-512), with the very operations
  // of tracePrimaries, so a pixel shaded here equals one shaded there bit for bit (the footprint's
  // invariant test demands it).
#if defined(SLIME_WIDE_LANES)
  static constexpr int kFloorOrSkyRays = kWidestLanes;
#else
  static constexpr int kFloorOrSkyRays = 8;
#endif
  void traceFloorOrSky(const glm::vec3& eye, const float* directionX, const float* directionY, const float* directionZ,
                       int count, TraceCounters& counters, glm::vec3* colors) const;

  // One primary ray whose slime hit is known (tracePrimaries with one ray).
  glm::vec3 tracePrimary(const Ray& ray, const SlimeHit& hit, TraceCounters& counters,
                         FloorShading* floorCache = nullptr) const;

  struct Wavefront;  // per-thread work lists (whitted_tracer.cpp)

  // Caustics (render/caustics/): the floor in the slime's shadow gets the light the map says came
  // through the slime, in place of the straight shadow ray's transmittance. Null: no caustics.
  void setCaustics(const CausticMap* map) { caustics_ = map; }

 private:
  // Environment: a ray out of segments leaving the jelly: it sees only the floor, unshadowed, or the sky.
  enum class Kind { Primary, Reflection, Refraction, Environment };
  struct Path {
    int segment = 1;            // 1 for primary rays
    glm::vec3 weight{1.0f};     // product of the optical factors so far, its throughput (visibleThroughput)
    float travelled = 0.0f;     // distance from the eye to the ray origin (footprint cone)
    bool inside = false;        // the ray runs inside the slime
    bool leavesSlime = false;   // the ray leaves the slime's surface outwards through a supporting triangle
  };
  // A ray of the wavefront: its radiance times `factor` adds to pixel `pixel` of the packet.
  struct PendingRay {
    Ray ray;
    Path path;
    glm::vec3 factor{1.0f};
    SlimeHit hit;
    int pixel = 0;
    Kind kind = Kind::Primary;
    bool hitKnown = false;
  };
  // A shadow ray towards the light that may meet the slime: light transmittance × `multiplier` adds
  // to pixel `pixel`.
  struct PendingShadow {
    Ray ray;
    glm::vec3 multiplier{0.0f};
    int pixel = 0;
    bool fromFloor = false;  // from a floor point: with caustics, blocked or not, and then the caustic map's gain
  };

  // The slime hits of the rays that do not know theirs, queried 8 at a time.
  void findHits(std::vector<PendingRay>& rays, TraceCounters& counters) const;
  // The floor's shading of every ray of a generation that sees the floor (primaries excepted), looked
  // up kFloorBatch at a time; floors[r] is left unfilled for the others.
  void lookUpFloors(const std::vector<PendingRay>& rays, std::vector<FloorShading>& floors) const;
  // `floor`: the ray's floor shading if lookUpFloors found it (else computed here as needed).
  void shade(const PendingRay& ray, const FloorShading& floor, Wavefront& wavefront, TraceCounters& counters,
             FloorShading* floorCache, glm::vec3* colors) const;
  // Up to 8 rays of a generation that hit the slime (their hit before the floor), shaded together.
  void shadeSlimes8(const PendingRay* const* rays, int count, Wavefront& wavefront, TraceCounters& counters,
                    glm::vec3* colors) const;
  // The floor at distance t along `ray`, its radiance times `factor` into pixel `pixel`.
  void shadeFloor(const Ray& ray, float t, const Path& path, const glm::vec3& factor, int pixel, Wavefront& wavefront,
                  TraceCounters& counters, FloorShading* floorCache, glm::vec3* colors) const;
  // The light reaching `origin` times `multiplier`, for pixel `pixel`: added at once when nothing can
  // shadow it (`unshadowed`: it leaves a convex slime's outside, or lies outside the slime's
  // footprint; or its ray misses the slime's bounds), else queued.
  void addLight(const glm::vec3& origin, const glm::vec3& multiplier, int pixel, bool unshadowed, bool fromFloor,
                Wavefront& wavefront, TraceCounters& counters, glm::vec3* colors) const;
  // Traces the packet's queued shadow rays 8 at a time and adds what reaches each pixel.
  void traceShadows(const std::vector<PendingShadow>& shadows, TraceCounters& counters, glm::vec3* colors) const;
  // The same floor shading, its FloorShading already known (from the cache or floorShadings).
  // `unshadowed`: nothing can shadow this floor point (outside the slime's footprint).
  void shadeFloorWith(const Ray& ray, float t, const FloorShading& shading, const Path& path, const glm::vec3& factor,
                      int pixel, Wavefront& wavefront, TraceCounters& counters, glm::vec3* colors,
                      bool unshadowed = false) const;
  FloorShading floorShading(const glm::vec3& point, const glm::vec3& direction, float distance) const;
  // floorShading for up to kFloorBatch rays that reach the floor at t[i] along them, distances[i]
  // from the eye (needed[i]), the pattern looked up in lanes (16 with AVX-512, 8 with AVX2 or
  // without); writes shadings[i] of those only.
  static constexpr int kFloorBatch = kFloorOrSkyRays;
  void floorShadings(const Ray* rays, const float* t, const float* distances, const bool* needed,
                     FloorShading* shadings) const;
  // Up to N rays reaching the floor, by lane (unneeded lanes stay zero), and what floorLanes finds there.
  template <int N>
  struct FloorRays {
    float originX[N] = {}, originY[N] = {}, directionX[N] = {}, directionY[N] = {}, directionZ[N] = {};
    float t[N] = {}, distance[N] = {};  // along the ray to the floor; from the eye (the footprint's cone)
    bool needed[N] = {};
  };
  template <int N>
  struct FloorPoints {
    float x[N] = {}, y[N] = {};         // the floor point
    float haze[N] = {}, lightZ[N] = {};  // the horizon haze's share; the light direction's z there
    float albedo[3][N] = {};             // the pattern over the pixel's footprint, by channel
  };
  // floorFootprint, the pattern and litFloor's haze and light direction, N lanes at a time (N = 8
  // with AVX2, 16 with AVX-512: render/simd/wide_lanes.h; a lane's result is the same for either N).
  template <int N>
  void floorLanes(const FloorRays<N>& rays, FloorPoints<N>& points) const;
  // traceFloorOrSky for N ≥ count rays at once.
  template <int N>
  void traceFloorOrSkyLanes(const glm::vec3& eye, const float* directionX, const float* directionY,
                            const float* directionZ, int count, TraceCounters& counters, glm::vec3* colors) const;
  // Half extents on the floor of the pixel cone's footprint, `distance` from the eye along `direction`.
  glm::vec2 floorFootprint(const glm::vec3& direction, float distance) const;
  // The floor's FloorShading at `point` once its albedo is known.
  FloorShading litFloor(const glm::vec3& point, const glm::vec3& direction, float distance, const glm::vec3& albedo) const;
  // One crossing of a shadow ray with the slime's surface at `hit`: `transmittance` takes what passes
  // it and the ray moves past it. False when the walk is over (blocked, or out of a convex slime).
  bool crossShadowSurface(Ray& ray, const SlimeHit& hit, glm::vec3& transmittance) const;
  // The fraction of the light a shadow ray keeps crossing the slime's surface into the jelly or out
  // of it, `cosine` the angle's with the surface's normal: 1 − Fresnel (× k_t going in), or k_t (seed optics).
  float surfaceTransmission(float cosine, bool entering) const;
  // Fraction of the point light passing the slime along each of up to 8 shadow rays (active[i]; the
  // rays are consumed), per channel: partial and coloured behind the translucent slime (surface
  // transmission and Beer–Lambert along the chord), 0 if opaque. Crossings are traced as packets.
  void lightTransmittance8(Ray* rays, const bool* active, glm::vec3* visible, TraceCounters& counters) const;
  // With caustics, for shadow rays from the floor: whether each meets the slime at all (one query, or
  // the light's grid); the light that passes the slime is then the caustic map's, not the straight ray's.
  void lightBlocked8(const Ray* rays, const bool* active, bool* blocked, TraceCounters& counters) const;
  // lightTransmittance8's first step: each walking shadow ray's crossing found from both its ends at
  // once, where it crosses no non-supporting triangle; the rays it settles stop walking (the others,
  // e.g. from inside the jelly or through a dent, walk on from past their first crossing).
  void crossFromBothEnds8(Ray* rays, bool* walking, glm::vec3* visible, TraceCounters& counters) const;
  // The light passing along `ray` through all its crossings with the slime's surface, known at once
  // (SlimeIntersector::lightCrossings8): crossShadowSurface's factors at each.
  glm::vec3 transmittanceAlong(const Ray& ray, const SegmentCrossings& crossings) const;
  glm::vec3 sky(const glm::vec3& direction) const;

  const SlimeGeometry& geometry_;
  const SlimeIntersector& intersector_;
  const FloorTexture& floor_;
  const ShadingParameters& parameters_;
  // The sky the slime hides from the floor in its shadow: the floor's ambient term is scaled by its
  // visibility there (render/floor/sky_occlusion.h).
  SkyOcclusion skyOcclusion_;
  const CausticMap* caustics_ = nullptr;
};

}  // namespace slime

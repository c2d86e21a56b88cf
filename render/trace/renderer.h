// The ray tracer: one Embree device and scene holding the slime (a dynamic triangle mesh refitted
// every frame) over the analytic floor z = 0, traced Whitted-style in parallel TBB tiles. The slime is
// a list of closed surfaces, one per piece (core/geometry/surface_view.h), drawn as one mesh.
// Rendering is one call: render(settings, image). The window shows the image, the snapshot writes it,
// the benchmark times it: the same code path.
//
// CONTRACT used by app/ (keep these signatures; add whatever else rendering needs):
//   Image, RayCounts, RenderStats, SurfaceView, Renderer(settings), updateSlime(one SurfaceView per piece),
//   render, pick.
#pragma once

#include "core/geometry/surface_view.h"
#include "core/settings/settings.h"
#include "render/image/image.h"  // Image: a linear-RGB float image, row-major, top row first

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace slime {

struct RayCounts {
  std::uint64_t primary = 0;
  std::uint64_t shadow = 0;
  std::uint64_t reflection = 0;
  std::uint64_t refraction = 0;
  std::uint64_t total() const { return primary + shadow + reflection + refraction; }
};

struct RenderStats {
  double refitMs = 0.0;  // BVH refit/rebuild in the last updateSlime
  double setupMs = 0.0;  // before tracing: settings sync (a new floor texture), shading constants, floor cache
  double traceMs = 0.0;  // tracing and shading the image (wall time, setupMs and causticsMs included)
  double causticsMs = 0.0;  // photons traced and gathered into the caustic map this frame (wall time)
  std::uint64_t causticPhotons = 0;  // photons behind this frame's caustic map (0: no caustics)
  double busyMs = 0.0;   // time the threads spent in tiles, summed: busyMs / (traceMs · threads) = parallel use
  int threads = 0;       // threads tracing (the arena's concurrency)
  std::uint64_t cachedFloorPixels = 0;  // primary floor hits served from the still-view floor cache
  // Pixels copied from the last frame, not traced: the camera is still and the slime cannot reach them
  // (outside its footprint, render/slime/screen_footprint.h). Their rays are not in `rays`.
  std::uint64_t reusedPixels = 0;
  // Checkerboard tracing (settings.render.checkerboard, with buffersKept and one sample a pixel:
  // render/trace/checkerboard.h): pixels of the footprint filled in from their traced neighbours, not
  // traced; and pixels of the skipped colour traced after all, their neighbours disagreeing.
  std::uint64_t filledPixels = 0;
  std::uint64_t tracedFillPixels = 0;
  RayCounts rays;        // every ray by kind, whether it met Embree or only the analytic floor/sky
  std::uint64_t slimeQueries = 0;  // rays that could reach the slime's bounds and were tested against it
  std::uint64_t nonFinitePixels = 0;  // pixels whose colour came out NaN/inf (written black); must stay 0
  // With `srgba`: the smallest rectangle holding every pixel whose bytes this call wrote (all of them
  // unless `buffersKept` let it leave some as they were); empty when it wrote none. A window need
  // upload and draw only these pixels again.
  PixelRect bytesWritten;
};

class Renderer {
 public:
  explicit Renderer(const Settings& settings);  // device, floor texture; throws on a bad texture
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // The slime's pieces, each a closed surface, disjoint from the others (none: no slime). Their vertices
  // go into the one Embree buffer, piece after piece, and the BVH is refitted; it is rebuilt when the
  // topology changes (the number of pieces, a piece's vertex count or its triangles). Throws
  // std::invalid_argument for a triangle that indexes outside its piece.
  void updateSlime(const std::vector<SurfaceView>& surfaces);

  // Traces the scene seen by settings.camera into `image` at the image's current size. With `srgba`,
  // each tile also writes its pixels there as 8-bit sRGB, 4 bytes a pixel (image_io.h's toSrgb8
  // with 4 channels, the same bytes), while they are in cache: what a window shows.
  // `buffersKept` promises that `image` and `srgba` are the buffers of the last call, unwritten
  // since (a window's): pixels that cannot have changed, outside the slime's footprint now and in the
  // last frame, are then left as they are. Without it every pixel is written.
  // With settings.render.checkerboard, buffersKept and one sample a pixel, while the camera stays and
  // the last frame's pixels stand, the pixels of the slime's footprint are traced in a checkerboard and
  // the others filled in (RenderStats::filledPixels): a window's frame while the slime moves. Without buffersKept (a snapshot, a still image's refinement, the
  // check's reference) every pixel is traced.
  // `pixelOffset`, with one sample per pixel (render.spp = 1), is the point of each pixel its ray goes
  // through, in pixels from the pixel's top-left corner: (0.5, 0.5), the centre, unless a caller
  // accumulates frames (AccumulationBuffer). With more samples it is ignored.
  RenderStats render(const Settings& settings, Image& image, std::vector<std::uint8_t>* srgba = nullptr,
                     bool buffersKept = false, glm::vec2 pixelOffset = {0.5f, 0.5f});

  // The rows [rowBegin, rowEnd) of a render(settings, image, nullptr, false, pixelOffset), the other
  // rows of `image` left as they are: a still image's refinement sample traced a band per frame, so
  // that no frame holds a whole-image trace. Bands of the same view and pixelOffset in a row, with no
  // render() or updateSlime between them, share the first one's setup (its caustic map, the slime's
  // footprint, the light's and the eye's grids): the caller changes nothing else between the bands
  // of one sample. The floor caches and the record of the last render() are neither used nor
  // disturbed: the next buffersKept render() still leaves the pixels that cannot have changed as
  // they are, if its caller has not written over its buffers since (an average of samples has).
  RenderStats renderRows(const Settings& settings, Image& image, glm::vec2 pixelOffset, int rowBegin, int rowEnd);

  // Caustics (render.caustics) gathered progressively: each render() while the slime, the light and the
  // optics stay adds one budget of photons (render.photons) to the map, up to its finished count, and
  // any change starts again from one budget: the interactive viewer's frames. Off (the default: a
  // snapshot, a benchmark, a test), every render() uses the finished map, so its image depends on the
  // scene alone and not on the frames rendered before (render/caustics/caustics.h).
  void setProgressiveCaustics(bool progressive);
  // With progressive caustics, the photons a frame traces stop at about this much time (Caustics::setFrameBudget).
  void setCausticsFrameBudget(double milliseconds);

  // The point where the ray through image point (u, v) in [0,1]² first hits the slime, if it does.
  std::optional<glm::dvec3> pick(const Settings& settings, double u, double v) const;

 private:
  RenderStats trace(const Settings& settings, Image& image, std::vector<std::uint8_t>* srgba, bool buffersKept,
                    glm::vec2 pixelOffset, int rowBegin, int rowEnd);

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace slime

#include "render/trace/renderer.h"

#include "core/geometry/camera.h"
#include "render/caustics/caustics.h"
#include "render/trace/brute_tracer.h"
#include "render/trace/checkerboard.h"
#include "render/trace/embree_scene.h"
#include "render/trace/embree_util.h"
#include "render/floor/floor_texture.h"
#include "render/image/image_io.h"
#include "render/trace/primary_view.h"
#include "render/trace/primary_visibility.h"
#include "render/slime/screen_footprint.h"
#include "render/slime/slime_geometry.h"
#include "render/trace/tsan_handoff.h"
#include "render/trace/whitted_tracer.h"

#include <tbb/blocked_range.h>
#include <tbb/blocked_range2d.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

#include <glm/geometric.hpp>

#if defined(__AVX2__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

namespace slime {
namespace {

constexpr int kTileRows = 8;
constexpr int kTileColumns = 32;  // a multiple of the 8-ray packet width
constexpr int kPacket = 8;
// Pixels seen to lie outside the slime's footprint are shaded this many at a time (8 with AVX2, 16 with AVX-512).
constexpr int kFloorLanes = WhittedTracer::kFloorOrSkyRays;
constexpr int kWavefrontPixels = WhittedTracer::kMaxPrimaries;  // pixels whose Whitted trees are traced together
// A checkerboarded run traces every other pixel of twice a wavefront's span: still a full wavefront.
constexpr int kRunPixels = std::max(kFloorLanes, 2 * kWavefrontPixels);

double millisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

bool sameFloor(const FloorSettings& a, const FloorSettings& b) {
  return a.pattern == b.pattern && a.scale == b.scale && a.colorA == b.colorA && a.colorB == b.colorB && a.image == b.image;
}

// Everything a primary ray's FloorShading, and the colour of a pixel outside the slime's footprint,
// depend on: the view, the image size, the floor's lighting, the sky, and whether the floor sends
// shadow and mirror rays (the floor texture itself is checked by Impl::sync).
using FloorCacheKey = std::array<double, 40>;

FloorCacheKey floorCacheKey(const Camera& camera, const ShadingParameters& p, int width, int height, glm::vec2 pixelOffset) {
  const glm::vec3 light = p.lightPosition, color = p.lightColor, ambient = p.ambientLight, horizon = p.skyHorizon,
                  zenith = p.skyZenith;
  return {camera.position.x, camera.position.y, camera.position.z, camera.forward.x, camera.forward.y,
          camera.forward.z,  camera.right.x,    camera.right.y,    camera.right.z,    camera.up.x,
          camera.up.y,       camera.up.z,       camera.tanHalfFov, camera.aspect,     static_cast<double>(width),
          static_cast<double>(height), p.floorDiffuse, p.floorSpecular, p.floorShininess, p.hazeDistance,
          p.pixelSpread,     light.x,           light.y,           light.z,           color.x,
          color.y,           color.z,           ambient.x,         ambient.y,         ambient.z,
          horizon.x,         horizon.y,         horizon.z,         zenith.x,          zenith.y,
          zenith.z,          static_cast<double>(p.depth), p.shadows ? 1.0 : 0.0, pixelOffset.x, pixelOffset.y};
}

}  // namespace

struct Renderer::Impl {
  SlimeGeometry geometry;
  EmbreeScene embree;
  BruteTracer brute{geometry};
  // The primary rays' first hits, found in object order for the frame (one sample per pixel).
  PrimaryVisibility visibility;
  FloorSettings floorSettings;
  FloorTexture floor;
  int threads = 0;
  std::unique_ptr<tbb::task_arena> arena;
  tbb::enumerable_thread_specific<TraceCounters> counters;
  double refitMs = 0.0;
  Caustics caustics;  // the photons and the floor's caustic map, kept while nothing moves
  bool progressiveCaustics = false;  // setProgressiveCaustics
  // Per pixel, the FloorShading its primary ray saw (one sample per pixel only). The floor does not
  // move: while the camera, the image size and the floor's lighting stay, only the shadow ray and the
  // slime are traced again there; the entries are recomputed whenever floorCacheKey changes.
  std::vector<FloorShading> floorCache;
  FloorCacheKey floorCacheView{};
  bool floorCacheValid = false;
  // Under the same key, the final colour of each pixel outside the slime's footprint, once traced:
  // such a pixel sees the floor or the sky and no shadow of the slime, so it is copied, not traced.
  std::vector<glm::vec3> reusableColors;
  std::vector<std::uint8_t> reusable;  // 1: reusableColors holds the pixel
  // The key changed this frame: every entry is stale. The tiles clear their own entries as they go,
  // in parallel, rather than the frame clearing 19 MB up front (a moving camera does so every frame).
  bool cachesStale = false;
  // The key of the last frame and whether it had changed from the frame before: while the view keeps
  // changing (the camera moves, or the image refines), filling the caches would only cost the frame
  // their writes, so they are filled on the first frame after a single change or a stop.
  FloorCacheKey lastView{};
  bool lastViewValid = false, lastViewChanged = false;
  // The buffers the last frame wrote, its footprint, and whether it kept the caches (one sample per
  // pixel, finished): a pixel outside that footprint and this one already holds its copied colour
  // and bytes when the caller kept the same buffers (imageInPlace, bytesInPlace).
  const glm::vec3* lastPixels = nullptr;
  const std::uint8_t* lastBytes = nullptr;
  ScreenFootprint footprint, lastFootprint;  // this frame's and the last (swapped: no allocation per frame)
  bool lastKeptCaches = false;
  bool imageInPlace = false, bytesInPlace = false;
  // Checkerboard tracing this frame (render/trace/checkerboard.h): the parity of the pixels traced,
  // and per pixel, 1 where a tile left it to be filled in (cleared as it is filled).
  // With the quarter (render.checkerboardQuarter) also the phase of the rows traced; the two flip
  // in turn, so four frames in a row trace each pixel once.
  // With the sixteenth (render.checkerboardSixteenth), the traced pixel of each 4 × 4 block instead,
  // (blockX, blockY), which visits all 16 in 16 frames (blockFrame counts them).
  bool halved = false, quartered = false, sixteenth = false;
  // renderRows: the view and pixel offset of the last band's setup, its caustic map, and whether the
  // next band of the same key may reuse them (nothing rendered whole or moved since).
  FloorCacheKey bandView{};
  const CausticMap* bandCausticMap = nullptr;
  bool bandSetupValid = false;
  int parity = 0, phase = 0, blockX = 0, blockY = 0, blockFrame = 0;
  std::vector<std::uint8_t> skipped;

  explicit Impl(const Settings& settings)
      : embree(settings.render.threads), floorSettings(settings.floor), floor(settings.floor) {
    makeArena(settings.render.threads);
  }

  void makeArena(int count) {
    threads = count;
    arena = count > 0 ? std::make_unique<tbb::task_arena>(count) : std::make_unique<tbb::task_arena>();
  }

  // Keeps the floor texture, thread count and slime shape in step with the settings of this frame.
  void sync(const Settings& settings) {
    if (!sameFloor(settings.floor, floorSettings)) {
      bandSetupValid = false;
      floor = FloorTexture(settings.floor);
      floorSettings = settings.floor;
      floorCacheValid = false;
    }
    if (settings.render.threads != threads) makeArena(settings.render.threads);
    const bool sphere = settings.slime.shape == "sphere";
    const float radius = static_cast<float>(settings.slime.radius);
    if (sphere != geometry.sphereRequested || (sphere && radius != geometry.sphereRadius)) {
      bandSetupValid = false;
      geometry.setAnalyticSphere(sphere, radius);
      embree.update(geometry, false);
    }
  }

  // Traces the pixels [rows) × [columns): primary rays 8 at a time as one coherent packet (only
  // those that can reach the slime's bounding sphere), then their Whitted trees as packets. With a
  // floor cache, packets outside `footprint` are copied from the last frame once they have been traced.
  void traceTile(const WhittedTracer& tracer, const SlimeIntersector& intersector, const Camera& camera,
                 int samplesPerAxis, glm::vec2 pixelOffset, int rowBegin, int rowEnd, int columnBegin, int columnEnd, Image& image,
                 std::uint8_t* srgba, FloorShading* floorShadings, const ScreenFootprint* footprint, TraceCounters& counts) {
    FlushDenormals flush;
    const auto start = std::chrono::steady_clock::now();
    const float inverseSamples = 1.0f / static_cast<float>(samplesPerAxis * samplesPerAxis);
    const glm::vec3 eye(camera.position);
    const PrimaryView view(camera, image.width, image.height);
    const auto resetCaches = [&](std::size_t first, int count) {  // the view changed: nothing kept holds
      for (int i = 0; i < count; ++i) {
        floorShadings[first + i].filled = false;
        reusable[first + i] = 0;
      }
    };
    const auto copied = [&](std::size_t first, int count) {  // pixels whose colours the last frame kept
      return floorShadings && std::all_of(&reusable[first], &reusable[first] + count, [](std::uint8_t r) { return r != 0; });
    };
    for (int y = rowBegin; y < rowEnd; ++y) {
      int count = 0;
      for (int x0 = columnBegin; x0 < columnEnd; x0 += count) {
        count = std::min(kPacket, columnEnd - x0);
        const std::size_t first = static_cast<std::size_t>(y) * image.width + x0;
        if (floorShadings && cachesStale) resetCaches(first, count);
        const bool outside = footprint && footprint->outside(x0, count, y);
        if (outside && copied(first, count)) {
          // Outside the last frame's footprint too, the last frame copied or stored exactly these colours.
          const bool inPlace = imageInPlace && lastFootprint.outside(x0, count, y);
          if (!inPlace)
            for (int i = 0; i < count; ++i) image.at(x0 + i, y) = reusableColors[first + i];
          if (srgba && !(inPlace && bytesInPlace)) {
            encodeSrgb8(&image.pixels[first], static_cast<std::size_t>(count), 4, srgba + 4 * first);
            counts.bytesWritten = counts.bytesWritten.unitedWith({x0, y, x0 + count, y + 1});
          }
          counts.reusedPixels += static_cast<std::uint64_t>(count);
          continue;
        }
        if (outside && count == kPacket && kFloorLanes > kPacket && x0 + kPacket < columnEnd) {
          // Where the processor has wider lanes, the next packet joins this one if it too lies
          // outside the footprint and is to be traced: floor or sky, kFloorLanes pixels at a time.
          const int next = std::min(kFloorLanes - kPacket, columnEnd - x0 - kPacket);
          if (floorShadings && cachesStale) resetCaches(first + kPacket, next);
          if (footprint->outside(x0 + kPacket, next, y) && !copied(first + kPacket, next)) count += next;
        }
        if (!outside && count == kPacket && x0 + kPacket < columnEnd) {
          // Two packets of the slime's reach traced together: their Whitted trees as one wavefront.
          const int next = std::min(kPacket, columnEnd - x0 - kPacket);
          if (floorShadings && cachesStale) resetCaches(first + kPacket, next);
          if (!footprint || !footprint->outside(x0 + kPacket, next, y)) count += next;
        }
        while (halved && !outside && count % kPacket == 0 && count < 2 * kWavefrontPixels && x0 + count < columnEnd) {
          // Checkerboarded, a run takes up to four packets: half their pixels make a full wavefront.
          const int next = std::min(kPacket, columnEnd - x0 - count);
          if (floorShadings && cachesStale) resetCaches(first + count, next);
          if (footprint->outside(x0 + count, next, y)) break;
          count += next;
        }
        glm::vec3 sums[kRunPixels] = {};
        for (int sampleY = 0; sampleY < samplesPerAxis; ++sampleY) {
          for (int sampleX = 0; sampleX < samplesPerAxis; ++sampleX) {
            // One sample: the caller's point of the pixel; more: the centre of each cell of an n × n
            // grid in the pixel (stratified supersampling).
            const float offsetX = samplesPerAxis == 1 ? pixelOffset.x : (sampleX + 0.5f) / samplesPerAxis;
            const float offsetY = samplesPerAxis == 1 ? pixelOffset.y : (sampleY + 0.5f) / samplesPerAxis;
            float directionX[kRunPixels], directionY[kRunPixels], directionZ[kRunPixels];
            for (int from = 0; from < count; from += kPacket)
              primaryDirections8(view, x0 + from, offsetX, y + offsetY, directionX + from, directionY + from, directionZ + from);
            glm::vec3 colors[kRunPixels];
            if (outside) {
              // Nothing here can meet the slime or its shadow: the floor or the sky, in lanes.
              tracer.traceFloorOrSky(eye, directionX, directionY, directionZ, count, counts, colors);
            } else if (halved) {
              // Checkerboard: the pixels of this frame's colour inside the footprint's span are traced,
              // the others left to fillSkipped; those outside the span are traced (they may be kept).
              int columns[kRunPixels], picked[kRunPixels], traced = 0;
              float pickedX[kRunPixels], pickedY[kRunPixels], pickedZ[kRunPixels];
              glm::vec3 pickedColors[kRunPixels];
              for (int i = 0; i < count; ++i) {
                const int x = x0 + i;
                const CheckerboardPass pass = sixteenth ? checkerboardSixteenthPass(x, y, blockX, blockY)
                                                        : checkerboardPass(x, y, parity, quartered, phase);
                if (pass != CheckerboardPass::Traced && footprint->contains(x, y)) {
                  skipped[first + i] = static_cast<std::uint8_t>(pass);
                  colors[i] = glm::vec3(0.0f);
                  continue;
                }
                columns[traced] = x;
                picked[traced] = i;
                pickedX[traced] = directionX[i];
                pickedY[traced] = directionY[i];
                pickedZ[traced] = directionZ[i];
                ++traced;
              }
              for (int from = 0; from < traced; from += kWavefrontPixels)
                traceColumns(tracer, intersector, eye, y, columns + from, std::min(kWavefrontPixels, traced - from),
                             pickedX + from, pickedY + from, pickedZ + from, image.width, floorShadings, counts,
                             pickedColors + from);
              for (int j = 0; j < traced; ++j) colors[picked[j]] = pickedColors[j];
            } else {
              Ray rays[kWavefrontPixels];
              bool active[kWavefrontPixels] = {};
              SlimeHit hits[kWavefrontPixels];
              for (int from = 0; from < count; from += kPacket) {  // the primaries' hits, 8 at a time
                const int size = std::min(kPacket, count - from);
                int activeCount = 0;
                for (int i = from; i < from + size; ++i) {
                  rays[i] = Ray{eye, {directionX[i], directionY[i], directionZ[i]}, 0.0f, kInfinity};
                  active[i] = geometry.mayHit(rays[i]);
                  activeCount += active[i];
                }
                if (activeCount == 0) continue;
                counts.slimeQueries += static_cast<std::uint64_t>(activeCount);
                if (visibility.ready()) visibility.hits8(x0 + from, y, size, active + from, hits + from);
                else if (!intersector.primaryHits8(rays + from, active + from, hits + from))
                  intersector.intersect8(rays + from, active + from, hits + from);
              }
              tracer.tracePrimaries(rays, hits, count, counts, floorShadings ? floorShadings + first : nullptr, colors);
            }
            for (int i = 0; i < count; ++i) sums[i] += colors[i];
          }
        }
        glm::vec3* pixels = &image.pixels[first];
        int nonFinite = 0;
        for (int i = 0; i < count; ++i) {
          const glm::vec3 color = samplesPerAxis == 1 ? sums[i] : sums[i] * inverseSamples;
          // A non-finite colour would be a bug upstream: count it (tests demand 0), never show it.
          const bool finite = std::isfinite(color.x + color.y + color.z);
          nonFinite += !finite;
          pixels[i] = finite ? color : glm::vec3(0.0f);
        }
        counts.nonFinitePixels += static_cast<std::uint64_t>(nonFinite);
        if (outside && floorShadings) {
          std::copy(pixels, pixels + count, &reusableColors[first]);
          std::fill(&reusable[first], &reusable[first] + count, std::uint8_t{1});
        }
        if (srgba) {
          encodeSrgb8(&image.pixels[first], static_cast<std::size_t>(count), 4, srgba + 4 * first);
          counts.bytesWritten = counts.bytesWritten.unitedWith({x0, y, x0 + count, y + 1});
        }
      }
    }
    counts.busyMs += millisecondsSince(start);
  }

  // Traces up to kWavefrontPixels primary rays of row y, at `columns` (any order) along the given unit
  // directions, as tracePrimaries does for a run: colours into colors[j], each pixel's floor cache kept.
  void traceColumns(const WhittedTracer& tracer, const SlimeIntersector& intersector, const glm::vec3& eye, int y,
                    const int* columns, int count, const float* directionX, const float* directionY,
                    const float* directionZ, int width, FloorShading* floorShadings, TraceCounters& counts,
                    glm::vec3* colors) {
    if (count <= 0) return;
    Ray rays[kWavefrontPixels];
    bool active[kWavefrontPixels] = {};
    SlimeHit hits[kWavefrontPixels];
    FloorShading shadings[kWavefrontPixels];
    for (int from = 0; from < count; from += kPacket) {
      const int size = std::min(kPacket, count - from);
      int activeCount = 0;
      for (int j = from; j < from + size; ++j) {
        rays[j] = Ray{eye, {directionX[j], directionY[j], directionZ[j]}, 0.0f, kInfinity};
        active[j] = geometry.mayHit(rays[j]);
        activeCount += active[j];
      }
      if (activeCount == 0) continue;
      counts.slimeQueries += static_cast<std::uint64_t>(activeCount);
      if (visibility.ready()) {
        for (int j = from; j < from + size; ++j) {
          if (!active[j]) continue;
          SlimeHit found[kPacket];  // hits8 writes a whole packet
          visibility.hits8(columns[j], y, 1, active + j, found);
          hits[j] = found[0];
        }
      } else if (!intersector.primaryHits8(rays + from, active + from, hits + from)) {
        intersector.intersect8(rays + from, active + from, hits + from);
      }
    }
    const std::size_t row = static_cast<std::size_t>(y) * width;
    if (floorShadings)
      for (int j = 0; j < count; ++j) shadings[j] = floorShadings[row + columns[j]];
    tracer.tracePrimaries(rays, hits, count, counts, floorShadings ? shadings : nullptr, colors);
    if (floorShadings)
      for (int j = 0; j < count; ++j) floorShadings[row + columns[j]] = shadings[j];
  }

  // After the tiles: each pixel a tile skipped (checkerboard) for `pass` in rows [rowBegin, rowEnd)
  // is filled in from its four neighbours (beside it, or diagonal for the quarter's first fill), or
  // traced where they disagree (render/trace/checkerboard.h). Those neighbours are all final before
  // this pass starts and none is written by it: rows may be filled in parallel.
  void fillSkipped(const WhittedTracer& tracer, const SlimeIntersector& intersector, const Camera& camera,
                   glm::vec2 pixelOffset, CheckerboardPass pass, int rowBegin, int rowEnd, Image& image,
                   FloorShading* floorShadings, TraceCounters& counts) {
    FlushDenormals flush;
    const auto start = std::chrono::steady_clock::now();
    const glm::vec3 eye(camera.position);
    const PrimaryView view(camera, image.width, image.height);
    const int width = image.width, height = image.height;
    const int step = checkerboardStep(pass);
    const bool diagonal = pass == CheckerboardPass::FromDiagonals || pass == CheckerboardPass::FromDiagonalsWide;
    for (int y = rowBegin; y < rowEnd; ++y) {
      const ScreenFootprint::Span span = footprint.rows[y];
      const std::size_t row = static_cast<std::size_t>(y) * width;
      int columns[kWavefrontPixels], pending = 0;
      float directionX[kWavefrontPixels], directionY[kWavefrontPixels], directionZ[kWavefrontPixels];
      const auto tracePending = [&] {
        glm::vec3 colors[kWavefrontPixels];
        traceColumns(tracer, intersector, eye, y, columns, pending, directionX, directionY, directionZ, width,
                     floorShadings, counts, colors);
        for (int j = 0; j < pending; ++j) {  // encoded with the row's span after the last pass (encodeFootprint)
          const bool finite = std::isfinite(colors[j].x + colors[j].y + colors[j].z);
          counts.nonFinitePixels += !finite;
          image.pixels[row + columns[j]] = finite ? colors[j] : glm::vec3(0.0f);
        }
        counts.tracedFillPixels += static_cast<std::uint64_t>(pending);
        pending = 0;
      };
      for (int x = std::max(0, span.x0); x < std::min(width, span.x1); ++x) {
        if (skipped[row + x] != static_cast<std::uint8_t>(pass)) continue;
        skipped[row + x] = 0;
        const bool left = x >= step, right = x + step < width, up = y >= step, down = y + step < height;
        const glm::vec3* p = &image.pixels[row + x];
        const std::ptrdiff_t across = step, along = static_cast<std::ptrdiff_t>(step) * width;
        const glm::vec3* neighbours[4] = {left ? p - across : nullptr, right ? p + across : nullptr,
                                          up ? p - along : nullptr, down ? p + along : nullptr};
        if (diagonal) {  // two opposite pairs: up-left/down-right, up-right/down-left
          neighbours[0] = left && up ? p - along - across : nullptr;
          neighbours[1] = right && down ? p + along + across : nullptr;
          neighbours[2] = right && up ? p - along + across : nullptr;
          neighbours[3] = left && down ? p + along - across : nullptr;
        }
        glm::vec3 color;
        if (fillFromNeighbours(neighbours, color)) {
          image.pixels[row + x] = color;
          ++counts.filledPixels;
          continue;
        }
        float x8[kPacket], y8[kPacket], z8[kPacket];  // the pixel's ray, as every pass makes it
        primaryDirections8(view, x, pixelOffset.x, y + pixelOffset.y, x8, y8, z8);
        columns[pending] = x;
        directionX[pending] = x8[0];
        directionY[pending] = y8[0];
        directionZ[pending] = z8[0];
        if (++pending == kWavefrontPixels) tracePending();
      }
      tracePending();
    }
    counts.busyMs += millisecondsSince(start);
  }

  // After the last fill pass: the footprint's pixels of rows [rowBegin, rowEnd) as sRGB bytes, a row's
  // span in one call (8 pixels a step), not one pixel at a time as each pass fills or traces it
  // (issue 28: the fills' single-pixel encoding was 2-4 % of a held frame's samples).
  void encodeFootprint(const Image& image, std::uint8_t* srgba, int rowBegin, int rowEnd) const {
    for (int y = rowBegin; y < rowEnd; ++y) {
      const ScreenFootprint::Span span = footprint.rows[y];
      const int x0 = std::max(0, span.x0), x1 = std::min(image.width, span.x1);
      if (x1 <= x0) continue;
      const std::size_t first = static_cast<std::size_t>(y) * image.width + x0;
      encodeSrgb8(&image.pixels[first], static_cast<std::size_t>(x1 - x0), 4, srgba + 4 * first);
    }
  }
};

Renderer::Renderer(const Settings& settings) : impl_(std::make_unique<Impl>(settings)) {}

Renderer::~Renderer() = default;

void Renderer::setProgressiveCaustics(bool progressive) { impl_->progressiveCaustics = progressive; }
void Renderer::setCausticsFrameBudget(double milliseconds) { impl_->caustics.setFrameBudget(milliseconds); }

void Renderer::updateSlime(const std::vector<SurfaceView>& surfaces) {
  const auto start = std::chrono::steady_clock::now();
  impl_->bandSetupValid = false;
  const bool topologyChanged = impl_->geometry.update(surfaces);
  impl_->embree.update(impl_->geometry, topologyChanged);
  impl_->refitMs = millisecondsSince(start);
}

RenderStats Renderer::render(const Settings& settings, Image& image, std::vector<std::uint8_t>* srgba,
                             bool buffersKept, glm::vec2 pixelOffset) {
  return trace(settings, image, srgba, buffersKept, pixelOffset, 0, image.height);
}

RenderStats Renderer::renderRows(const Settings& settings, Image& image, glm::vec2 pixelOffset, int rowBegin, int rowEnd) {
  return trace(settings, image, nullptr, false, pixelOffset, std::clamp(rowBegin, 0, image.height),
               std::clamp(rowEnd, 0, image.height));
}

RenderStats Renderer::trace(const Settings& settings, Image& image, std::vector<std::uint8_t>* srgba, bool buffersKept,
                            glm::vec2 pixelOffset, int rowBegin, int rowEnd) {
  Impl& impl = *impl_;
  // A band of the rows leaves the view's caches and the last frame's record alone: they hold the
  // whole image of the view a window's next render() reuses.
  const bool wholeImage = rowBegin == 0 && rowEnd == image.height;
  const auto start = std::chrono::steady_clock::now();
  impl.sync(settings);
  RenderStats stats;
  stats.refitMs = impl.refitMs;
  if (image.width <= 0 || image.height <= 0 || rowEnd <= rowBegin) return stats;
  std::uint8_t* bytes = nullptr;
  if (srgba) {
    srgba->resize(4 * image.pixels.size());
    bytes = srgba->data();
  }

  ShadingParameters parameters = makeShadingParameters(settings, image.height);  // its depth settled below
  const Camera camera = makeCamera(settings.camera, image.width, image.height);
  const int samplesPerAxis = std::max(1, static_cast<int>(std::lround(std::sqrt(std::max(1, settings.render.spp)))));
  const bool brute = settings.render.backend == "brute";
  const SlimeIntersector& intersector = brute ? static_cast<const SlimeIntersector&>(impl.brute) : impl.embree;
  WhittedTracer tracer(impl.geometry, intersector, impl.floor, parameters);
  // The caustic map's photons meet the slime through Embree's own queries (PhotonTracer: intersect),
  // not the light's or the eye's grids, and the tiles alone read the map: so the photons are traced
  // beside the frame's setup below, on the same cores, rather than before it (issue 28: the setup's
  // three tasks leave a core idle while the longest finishes).
  const CausticMap* causticMap = nullptr;
  const auto causticsOfTheFrame = [&] {
    const auto causticsStart = std::chrono::steady_clock::now();
    causticMap = impl.caustics.update(settings, parameters, impl.geometry, intersector, brute ? nullptr : impl.arena.get(),
                                      impl.progressiveCaustics);
    stats.causticsMs = millisecondsSince(causticsStart);
  };

  FloorShading* floorShadings = nullptr;  // the caches, with one sample per pixel while the view holds
  const bool lastKeptCaches = impl.lastKeptCaches;
  if (wholeImage) impl.lastKeptCaches = false;  // until this frame is finished
  impl.imageInPlace = impl.bytesInPlace = false;
  // Outside the footprint a pixel sees only the floor or the sky, whatever its samples. Beside it,
  // the grids of the triangles as the light and the eye see them, which answer the shadow rays' and
  // the primary rays' queries (the brute force, the oracle, asks its own).
  const auto footprintOfTheSlime = [&] {
    slimeFootprint(camera, impl.geometry, parameters, image.width, image.height, impl.footprint);
  };
  // The primary rays' first hits in object order where one sample a pixel is traced; else the eye's grid.
  const auto primaryHits = [&] {
    const bool found = samplesPerAxis == 1 && impl.visibility.build(impl.geometry, camera, image.width, image.height, pixelOffset);
    if (!found) impl.visibility.clear();
    impl.embree.prepareEye(impl.geometry, glm::vec3(camera.position), !found);
  };
  const FloorCacheKey view = floorCacheKey(camera, parameters, image.width, image.height, pixelOffset);
  const bool setupKept = !wholeImage && impl.bandSetupValid && view == impl.bandView;
  impl.bandSetupValid = false;
  if (setupKept) {
    causticMap = impl.bandCausticMap;  // the band before's setup holds
  } else if (brute) {
    causticsOfTheFrame();
    footprintOfTheSlime();
    impl.visibility.clear();
    impl.embree.prepareLight(impl.geometry, parameters.lightPosition, false);
    impl.embree.prepareEye(impl.geometry, glm::vec3(camera.position), false);
  } else {
    const auto task = [&impl](auto&& work) {
      return [&impl, work] {
        takeOver(&impl);
        work();
        handOff(&impl);
      };
    };
    handOff(&impl);
    impl.arena->execute([&] {
      tbb::parallel_invoke(task(causticsOfTheFrame), task(footprintOfTheSlime),
                           task([&] { impl.embree.prepareLight(impl.geometry, parameters.lightPosition, parameters.shadows); }),
                           task(primaryHits));
    });
    takeOver(&impl);
  }
  if (!wholeImage) {
    impl.bandView = view;
    impl.bandCausticMap = causticMap;
    impl.bandSetupValid = true;
  }
  tracer.setCaustics(causticMap);
  stats.causticPhotons = impl.caustics.photons();
  const ScreenFootprint* footprint = &impl.footprint;
  if (samplesPerAxis == 1 && wholeImage) {
    const bool viewChanged = !impl.lastViewValid || view != impl.lastView;
    const bool keepsMoving = viewChanged && impl.lastViewChanged;
    impl.lastView = view;
    impl.lastViewValid = true;
    impl.lastViewChanged = viewChanged;
    impl.cachesStale = !impl.floorCacheValid || view != impl.floorCacheView;
    if (impl.cachesStale && keepsMoving) {
      impl.floorCacheValid = false;  // no caches this frame
    } else {
      if (impl.cachesStale) {
        impl.floorCache.resize(image.pixels.size());
        impl.reusableColors.resize(image.pixels.size());
        impl.reusable.resize(image.pixels.size());
        impl.floorCacheView = view;
        impl.floorCacheValid = true;
      }
      floorShadings = impl.floorCache.data();
      impl.imageInPlace = buffersKept && lastKeptCaches && !impl.cachesStale && impl.lastPixels == image.pixels.data();
      impl.bytesInPlace = impl.imageInPlace && bytes && impl.lastBytes == bytes;
    }
  }

  // Only where the last frame's pixels stand (the camera still, a window's buffers): a first frame or
  // a turning camera is traced whole.
  impl.halved = settings.render.checkerboard && impl.imageInPlace && !brute;
  impl.quartered = impl.halved && settings.render.checkerboardQuarter;
  impl.sixteenth = impl.quartered && settings.render.checkerboardSixteenth;
  // A checkerboarded frame is a moving one: its paths stop at render.movingDepth segments (a totally
  // reflected one looks up the floor or sky there), the still frames after it go the whole way.
  if (impl.halved) parameters.depth = std::min(parameters.depth, settings.render.movingDepth);
  if (impl.halved) {
    impl.parity ^= 1;  // the other colour from the last halved frame
    if (impl.parity == 0) impl.phase ^= 1;  // and every other time, the other rows of the quarter
    // The sixteenth's block offset: frame k (mod 16) traces (2·b0 + b2, 2·b1 + b3) of k's bits b0..b3,
    // so consecutive frames trace pixels two apart and 16 frames trace each pixel once.
    const int k = impl.blockFrame++ & 15;
    impl.blockX = 2 * (k & 1) + ((k >> 2) & 1);
    impl.blockY = 2 * ((k >> 1) & 1) + ((k >> 3) & 1);
    if (impl.skipped.size() != image.pixels.size()) impl.skipped.assign(image.pixels.size(), 0);
  }
  for (TraceCounters& counts : impl.counters) counts = TraceCounters{};
  stats.setupMs = millisecondsSince(start);
  stats.threads = brute ? 1 : impl.arena->max_concurrency();
  if (brute) {
    // The seed's algorithm is the oracle: one thread, no packets that matter, every triangle.
    impl.traceTile(tracer, intersector, camera, samplesPerAxis, pixelOffset, rowBegin, rowEnd, 0, image.width, image, bytes,
                   floorShadings, footprint, impl.counters.local());
  } else {
    handOff(&impl);  // the frame's inputs, to the workers
    impl.arena->execute([&] {
      tbb::parallel_for(tbb::blocked_range2d<int>(rowBegin, rowEnd, kTileRows, 0, image.width, kTileColumns),
                        [&](const tbb::blocked_range2d<int>& tile) {
                          takeOver(&impl);
                          impl.traceTile(tracer, intersector, camera, samplesPerAxis, pixelOffset, tile.rows().begin(),
                                         tile.rows().end(), tile.cols().begin(), tile.cols().end(), image, bytes,
                                         floorShadings, footprint, impl.counters.local());
                          handOff(&impl);  // the tile's pixels and counters, back to the caller
                        });
      if (!impl.halved) return;
      const auto fill = [&](CheckerboardPass pass) {
        tbb::parallel_for(tbb::blocked_range<int>(0, image.height, kTileRows), [&](const tbb::blocked_range<int>& rows) {
          takeOver(&impl);
          impl.fillSkipped(tracer, intersector, camera, pixelOffset, pass, rows.begin(), rows.end(), image,
                           floorShadings, impl.counters.local());
          handOff(&impl);
        });
      };
      if (impl.sixteenth) {  // the quarter's lattice first, from neighbours two pixels away
        fill(CheckerboardPass::FromDiagonalsWide);
        fill(CheckerboardPass::FromBesideWide);
      }
      if (impl.quartered) fill(CheckerboardPass::FromDiagonals);  // the traced colour's other rows first
      fill(CheckerboardPass::FromBeside);
      if (bytes)
        tbb::parallel_for(tbb::blocked_range<int>(0, image.height, 4 * kTileRows), [&](const tbb::blocked_range<int>& rows) {
          takeOver(&impl);
          impl.encodeFootprint(image, bytes, rows.begin(), rows.end());
          handOff(&impl);
        });
    });
    takeOver(&impl);
  }
  for (const TraceCounters& counts : impl.counters) {
    stats.rays.primary += counts.rays.primary;
    stats.rays.shadow += counts.rays.shadow;
    stats.rays.reflection += counts.rays.reflection;
    stats.rays.refraction += counts.rays.refraction;
    stats.slimeQueries += counts.slimeQueries;
    stats.nonFinitePixels += counts.nonFinitePixels;
    stats.cachedFloorPixels += counts.cachedFloorPixels;
    stats.reusedPixels += counts.reusedPixels;
    stats.filledPixels += counts.filledPixels;
    stats.tracedFillPixels += counts.tracedFillPixels;
    stats.busyMs += counts.busyMs;
    stats.bytesWritten = stats.bytesWritten.unitedWith(counts.bytesWritten);
  }
  if (!wholeImage) {
    stats.traceMs = millisecondsSince(start);
    return stats;
  }
  impl.lastPixels = image.pixels.data();
  impl.lastBytes = bytes;
  std::swap(impl.footprint, impl.lastFootprint);
  impl.lastKeptCaches = floorShadings != nullptr;
  stats.traceMs = millisecondsSince(start);
  return stats;
}

std::optional<glm::dvec3> Renderer::pick(const Settings& settings, double u, double v) const {
  const Camera camera = makeCamera(settings.camera, std::max(1, settings.camera.width), std::max(1, settings.camera.height));
  const Ray ray{glm::vec3(camera.position), glm::vec3(camera.rayDirection(u, v)), 0.0f, kInfinity};
  if (!impl_->geometry.mayHit(ray)) return std::nullopt;
  const SlimeHit hit = impl_->embree.intersect(ray);
  if (!hit.valid()) return std::nullopt;
  return glm::dvec3(ray.origin + hit.t * ray.direction);
}

}  // namespace slime

// `slime view --check-every K` (issue 28, "faithful images"): every K-th frame the viewer also traces,
// in full and with a renderer of its own (no caches, no pixel reuse, nothing kept from earlier
// frames), the image the same physics state and camera give at the view's full size — what
// `slime snapshot` would write for them — and measures what it showed against it as a PSNR over the
// 8-bit sRGB channels the window shows. Every shortcut of the interactive path (pixels copied from
// the last frame outside the slime's footprint, creep too small to see left undrawn, a reduced
// resolution) is judged by these figures.
#pragma once

#include "core/geometry/icosphere.h"
#include "core/geometry/surface_view.h"
#include "core/settings/settings.h"
#include "render/image/image.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <limits>
#include <vector>

namespace slime {

// PSNR of two images with a peak of 255: 10·log10(255² / MSE), the MSE over the R, G and B bytes of
// every pixel. Identical images (MSE 0) give kIdenticalPsnrDb, so that a mean stays finite.
// `shown` is RGBA bytes of shownWidth × shownHeight; when that is smaller than the reference (a
// reduced resolution) it is enlarged bilinearly to the reference's size, as the window's blit does.
constexpr double kIdenticalPsnrDb = 100.0;
double psnrDb(const std::vector<std::uint8_t>& shown, int shownWidth, int shownHeight,
              const std::vector<std::uint8_t>& reference, int width, int height);

// The running figures of the checked frames: all of them, and those where the slime was held.
struct PsnrFigures {
  std::int64_t frames = 0;
  double sumDb = 0.0;
  double minDb = std::numeric_limits<double>::infinity();
  void add(double db);
  double meanDb() const { return frames > 0 ? sumDb / static_cast<double>(frames) : 0.0; }
  double minimumDb() const { return frames > 0 ? minDb : 0.0; }
};

class ImageCheck {
 public:
  explicit ImageCheck(int every) : every_(every) {}
  int every() const { return every_; }
  // Whether frame `frame` (0-based) is checked: every K-th, the first included.
  bool due(std::int64_t frame) const { return every_ > 0 && frame % every_ == 0; }

  // Traces the reference for `settings` (camera.width × camera.height: the full view) and the slime
  // as `pieces` (one closed surface each), compares `shown` with it and adds the result; returns the PSNR in dB.
  double check(const Settings& settings, const std::vector<SurfaceView>& pieces,
               const std::vector<std::uint8_t>& shown, int shownWidth, int shownHeight, bool handled);
  // A frame that showed a still image refined over several samples: not comparable with the
  // one-sample reference, counted apart.
  void skipRefined() { ++skippedRefined_; }

  const PsnrFigures& all() const { return all_; }
  const PsnrFigures& handled() const { return handled_; }
  std::int64_t skippedRefined() const { return skippedRefined_; }
  double milliseconds() const { return milliseconds_; }  // spent checking, left out of the frames' times

 private:
  int every_ = 0;
  PsnrFigures all_, handled_;
  std::int64_t skippedRefined_ = 0;
  double milliseconds_ = 0.0;
  Image reference_;
  std::vector<std::uint8_t> referenceBytes_;
};

}  // namespace slime

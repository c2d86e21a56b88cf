#include "app/viewer/image_check.h"

#include "render/image/image_io.h"
#include "render/trace/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace slime {
namespace {

// The shown byte of channel c at reference pixel (x, y): the shown image sampled at that pixel's
// centre, bilinearly (texel centres at +0.5), clamped at the edges — GL_LINEAR's enlargement.
double shownChannel(const std::vector<std::uint8_t>& shown, int w, int h, double u, double v, int c) {
  const double x = std::clamp(u * w - 0.5, 0.0, w - 1.0), y = std::clamp(v * h - 0.5, 0.0, h - 1.0);
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const int x1 = std::min(x0 + 1, w - 1), y1 = std::min(y0 + 1, h - 1);
  const double fx = x - x0, fy = y - y0;
  const auto at = [&](int px, int py) { return static_cast<double>(shown[4 * (static_cast<std::size_t>(py) * w + px) + c]); };
  return (at(x0, y0) * (1 - fx) + at(x1, y0) * fx) * (1 - fy) + (at(x0, y1) * (1 - fx) + at(x1, y1) * fx) * fy;
}

}  // namespace

double psnrDb(const std::vector<std::uint8_t>& shown, int shownWidth, int shownHeight,
              const std::vector<std::uint8_t>& reference, int width, int height) {
  if (width <= 0 || height <= 0 || shownWidth <= 0 || shownHeight <= 0) return 0.0;
  const bool same = shownWidth == width && shownHeight == height;
  double squares = 0.0;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const std::size_t i = 4 * (static_cast<std::size_t>(y) * width + x);
      for (int c = 0; c < 3; ++c) {
        const double value = same ? shown[i + c]
                                  : shownChannel(shown, shownWidth, shownHeight, (x + 0.5) / width, (y + 0.5) / height, c);
        const double difference = value - reference[i + c];
        squares += difference * difference;
      }
    }
  }
  const double mse = squares / (3.0 * width * height);
  if (mse <= 0.0) return kIdenticalPsnrDb;
  return std::min(kIdenticalPsnrDb, 10.0 * std::log10(255.0 * 255.0 / mse));
}

void PsnrFigures::add(double db) {
  ++frames;
  sumDb += db;
  minDb = std::min(minDb, db);
}

double ImageCheck::check(const Settings& settings, const std::vector<SurfaceView>& pieces,
                         const std::vector<std::uint8_t>& shown, int shownWidth, int shownHeight, bool handled) {
  const auto start = std::chrono::steady_clock::now();
  // A renderer of its own each time: what `slime snapshot` does for one image, nothing carried over.
  Renderer renderer(settings);
  renderer.updateSlime(pieces);
  reference_.resize(settings.camera.width, settings.camera.height);
  renderer.render(settings, reference_);
  toSrgb8(reference_, 4, referenceBytes_);
  const double db = psnrDb(shown, shownWidth, shownHeight, referenceBytes_, reference_.width, reference_.height);
  all_.add(db);
  if (handled) handled_.add(db);
  milliseconds_ += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return db;
}

}  // namespace slime

#include "app/bench/render/bench_reference.h"

#include "render/image/image_io.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace slime {
namespace {

Image readSized(const std::string& path, const std::string& what, const Image* like) {
  if (path.empty()) throw std::runtime_error("slime bench reference: " + what + " is needed (a PFM file)");
  Image image = readPfm(path);
  if (like && (image.width != like->width || image.height != like->height))
    throw std::runtime_error("slime bench reference: " + what + " '" + path + "' is " + std::to_string(image.width) +
                             "x" + std::to_string(image.height) + ", the other images " + std::to_string(like->width) +
                             "x" + std::to_string(like->height));
  return image;
}

double psnrOver(const Image& a, const Image& b, const Image& masks, int channel, std::size_t& pixels) {
  double squared = 0.0;
  pixels = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    if (!(masks.pixels[i][channel] > 0.5f)) continue;
    ++pixels;
    for (int c = 0; c < 3; ++c) {
      const double d = static_cast<double>(encodeSrgb8(a.pixels[i][c])) - encodeSrgb8(b.pixels[i][c]);
      squared += d * d;
    }
  }
  if (pixels == 0) return std::numeric_limits<double>::quiet_NaN();
  const double rmse = std::sqrt(squared / (3.0 * static_cast<double>(pixels)));
  return rmse == 0.0 ? std::numeric_limits<double>::infinity() : 20.0 * std::log10(255.0 / rmse);
}

glm::dvec3 meanGain(const Image& lit, const Image& bare, const Image& masks, const Image* haze) {
  glm::dvec3 sum{0.0};
  std::size_t pixels = 0;
  for (std::size_t i = 0; i < lit.pixels.size(); ++i) {
    if (!(masks.pixels[i][1] > 0.5f)) continue;
    ++pixels;
    for (int c = 0; c < 3; ++c) {
      const double added = haze ? haze->pixels[i][c] : 0.0;
      const double light = lit.pixels[i][c] - added, none = bare.pixels[i][c] - added;
      sum[c] += none > 0.0 ? light / none : 0.0;
    }
  }
  return pixels == 0 ? glm::dvec3(0.0) : sum / static_cast<double>(pixels);
}

}  // namespace

ReferenceRegionFigures compareWithReference(const ReferenceBenchOptions& options) {
  const Image ours = readSized(options.ours, "--ours", nullptr);
  const Image reference = readSized(options.reference, "--reference", &ours);
  const Image masks = readSized(options.masks, "--masks", &ours);
  ReferenceRegionFigures f;
  f.slimePsnr = psnrOver(ours, reference, masks, 0, f.slimePixels);
  f.shadowPsnr = psnrOver(ours, reference, masks, 1, f.shadowPixels);
  f.floorPsnr = psnrOver(ours, reference, masks, 2, f.floorPixels);
  if (!options.oursBare.empty() || !options.referenceBare.empty()) {
    const Image haze = options.haze.empty() ? Image{} : readSized(options.haze, "--haze", &ours);
    const Image* added = options.haze.empty() ? nullptr : &haze;
    f.oursShadowGain = meanGain(ours, readSized(options.oursBare, "--ours-bare", &ours), masks, added);
    f.referenceShadowGain = meanGain(reference, readSized(options.referenceBare, "--reference-bare", &ours), masks, added);
  }
  return f;
}

void runReferenceBench(const ReferenceBenchOptions& options) {
  const ReferenceRegionFigures f = compareWithReference(options);
  std::printf("%s: PSNR slime %.2f dB (%zu px), shadow %.2f dB (%zu px), floor %.2f dB (%zu px)", options.label.c_str(),
              f.slimePsnr, f.slimePixels, f.shadowPsnr, f.shadowPixels, f.floorPsnr, f.floorPixels);
  if (!options.oursBare.empty())
    std::printf("; shadow gain ours (%.4f, %.4f, %.4f), reference (%.4f, %.4f, %.4f), ratio (%.3f, %.3f, %.3f)",
                f.oursShadowGain.x, f.oursShadowGain.y, f.oursShadowGain.z, f.referenceShadowGain.x,
                f.referenceShadowGain.y, f.referenceShadowGain.z, f.oursShadowGain.x / f.referenceShadowGain.x,
                f.oursShadowGain.y / f.referenceShadowGain.y, f.oursShadowGain.z / f.referenceShadowGain.z);
  std::printf("\n");
  if (options.picture.empty()) return;
  // Ours | the reference | |difference| × 4 in 8-bit sRGB, and under them the masks' outlines.
  const Image ours = readPfm(options.ours), reference = readPfm(options.reference);
  const int w = ours.width, h = ours.height;
  Image picture;
  picture.resize(3 * w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      picture.at(x, y) = ours.at(x, y);
      picture.at(w + x, y) = reference.at(x, y);
      glm::vec3 difference;
      for (int c = 0; c < 3; ++c) {
        const float d = std::abs(static_cast<float>(encodeSrgb8(ours.at(x, y)[c])) - encodeSrgb8(reference.at(x, y)[c]));
        difference[c] = srgbToLinear(std::min(1.0f, 4.0f * d / 255.0f));
      }
      picture.at(2 * w + x, y) = difference;
    }
  writePng(picture, options.picture);
  std::printf("wrote %s (ours | reference | difference x4 in 8-bit sRGB)\n", options.picture.c_str());
}

}  // namespace slime

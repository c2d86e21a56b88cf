// `slime bench accuracy`: the image error of the undeformed mesh slime against the analytic sphere
// (slime.shape=sphere) at the same view, against the frame time, for levels × {flat, smooth} × depth.
//
// The reference is the analytic sphere traced at the largest depth, so both the geometric error
// (level, normals) and the truncation of the ray tree (depth) count. Errors are measured on the
// 8-bit sRGB images a person would see, in 8-bit steps: RMSE, PSNR = 20 log10(255 / RMSE), the
// largest per-pixel error (max over channels) and the fraction of pixels off by more than 2 steps.
//
// Visibility threshold: a configuration is "invisible" when at most 1 % of its pixels differ from
// the reference by more than 2 steps of 8-bit sRGB. Two steps (0.8 % of full scale) is below the
// just-noticeable difference of a flat patch (about 1 % in luminance, Weber's law). The 1 % of the
// pixels (about 4,000 at 734×564, under 4 % of the slime's own pixels at the default view) are
// isolated pixels where a facet moves the silhouette or a refracted plank edge by a fraction of a
// pixel; measured at the default view, the level-4 mesh at depth 3 has 0.8 % of them (PSNR 50 dB),
// level 3 has 1.9 % (PSNR 44 dB), where the refracted plank edges visibly kink.
#pragma once

#include "core/settings/settings.h"
#include "render/image/image.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace slime {

constexpr double kVisibleStep = 2.0;          // 8-bit sRGB steps
constexpr double kVisibleFraction = 0.01;     // of the pixels

struct AccuracyBenchOptions {
  std::vector<int> levels{0, 1, 2, 3, 4, 5, 6};
  std::vector<int> depths{1, 2, 3, 4, 5, 6};
  std::vector<std::string> normals{"flat", "smooth"};
  int frames = 3;   // timed frames per configuration (after one untimed)
  int width = 734, height = 564;
  int threads = 0;  // 0: all cores
  std::string jsonFile;
  std::string csvFile;
  std::string imageDirectory;  // when set: the reference and each level's smooth image at depth 3 as PNG
};

nlohmann::json runAccuracyBench(const Settings& settings, const AccuracyBenchOptions& options);

struct ImageError {
  double rmse = 0.0;            // 8-bit steps
  double psnr = 0.0;            // dB (capped at 99 for identical images)
  double maxError = 0.0;        // 8-bit steps, largest over pixels and channels
  double visibleFraction = 0.0; // pixels with an error over kVisibleStep
};

// Both images must have the same size; compared as 8-bit sRGB.
ImageError compareImages(const Image& image, const Image& reference);

}  // namespace slime

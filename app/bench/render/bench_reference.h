// `slime bench reference`: our frame against a path tracer's of the same scene (scripts/reference/,
// Blender's Cycles), both linear float images (PFM). Per region of the masks (the reference script's:
// the pixels that see the slime, the floor in its shadow eroded by 2 mm, the lit floor eroded by 2 mm) it
// gives PSNR on the 8-bit sRGB pixels a person sees, 20 log10(255 / RMSE over the region's channels),
// and, with both images' renders without the slime's shadow ("bare"), the shadow's gain per channel:
// the mean over the shadow's pixels of light arriving ÷ light with no slime, on floats, with what the
// horizon's haze adds to the pixel taken away from both first (it does not come through the slime).
#pragma once

#include <glm/vec3.hpp>

#include <string>

namespace slime {

struct ReferenceBenchOptions {
  std::string ours, reference, masks;         // PFM files (required)
  std::string oursBare, referenceBare;        // PFM files: the same frames with no slime in the light's way
  std::string haze;                           // PFM: what the haze adds to each floor pixel, taken from both
  std::string picture;                        // PNG: ours | reference | difference ×4 (optional)
  std::string label;                          // a name for the row printed
};

struct ReferenceRegionFigures {
  double slimePsnr = 0.0, shadowPsnr = 0.0, floorPsnr = 0.0;
  std::size_t slimePixels = 0, shadowPixels = 0, floorPixels = 0;
  glm::dvec3 oursShadowGain{0.0}, referenceShadowGain{0.0};  // zero without the bare images
};

// PSNR (dB) of two images' 8-bit sRGB values over the pixels where `mask` holds (all channels).
// Infinity when they agree there exactly; NaN when the mask is empty.
ReferenceRegionFigures compareWithReference(const ReferenceBenchOptions& options);

// Runs the comparison, prints one row and writes the picture. Throws std::runtime_error naming a file
// that is missing, unreadable or of another size than the others.
void runReferenceBench(const ReferenceBenchOptions& options);

}  // namespace slime

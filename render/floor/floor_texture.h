// The floor's albedo: procedural planks (the default), tiles or checker, or a PNG image. Every lookup
// takes the pixel's footprint on the floor (half extents along x and y, from the ray's cone) and
// returns the pattern averaged over it, so the floor neither aliases nor shimmers towards the horizon:
// the procedural patterns are box-filtered analytically, the image through a mipmap pyramid.
#pragma once

#include "core/settings/settings.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <vector>

namespace slime {

class FloorTexture {
 public:
  // Throws SettingsError naming floor.pattern or floor.image when the pattern or image is unusable.
  explicit FloorTexture(const FloorSettings& settings);

  // Linear-RGB albedo averaged over the box [x ± footprint.x] × [y ± footprint.y] (metres).
  glm::vec3 albedo(glm::vec2 point, glm::vec2 footprint) const;

  // albedo() for N lookups at once (structure of arrays in, channels[c][i] out for the lanes with
  // active[i]; the others may be written too): the planks N lanes at a time when the build has AVX2 (N = 8) or
  // AVX-512 (N = 16; render/simd/wide_lanes.h), else one lookup at a time. Within rounding of albedo()
  // (the golden tests bound the difference), and a lane's result is the same for either N.
  template <int N>
  void albedoLanes(const float* x, const float* y, const float* footprintX, const float* footprintY, const bool* active,
                   float (*channels)[N]) const;

  // The albedo seen from very far away (the average of the pattern).
  glm::vec3 meanAlbedo() const { return mean_; }

 private:
  enum class Pattern { Planks, Tiles, Checker, Image };
  struct MipLevel {
    int width = 0, height = 0;
    std::vector<glm::vec3> texels;
    glm::vec3 bilinear(float x, float y) const;  // texel coordinates, wrapping
  };

  glm::vec3 planks(glm::vec2 p, glm::vec2 footprint) const;
  glm::vec3 tiles(glm::vec2 p, glm::vec2 footprint) const;
  glm::vec3 checker(glm::vec2 p, glm::vec2 footprint) const;
  glm::vec3 image(glm::vec2 p, glm::vec2 footprint) const;
  template <int N>
  void planksLanes(const float* x, const float* y, const float* footprintX, const float* footprintY,
                   float (*channels)[N]) const;
  void loadImage(const std::string& path);

  Pattern pattern_ = Pattern::Planks;
  float scale_ = 0.1f;
  float inverseScale_ = 10.0f;
  glm::vec3 colorA_{0.6f}, colorB_{0.4f}, mean_{0.5f};
  std::vector<MipLevel> mips_;  // level 0 = the image, each next one half the size
};

}  // namespace slime

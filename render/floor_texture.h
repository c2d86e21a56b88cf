// The floor's albedo: procedural planks (the default), tiles or checker, or a PNG image. Every lookup
// takes the pixel's footprint on the floor (half extents along x and y, from the ray's cone) and
// returns the pattern averaged over it, so the floor neither aliases nor shimmers towards the horizon:
// the procedural patterns are box-filtered analytically, the image through a mipmap pyramid.
#pragma once

#include "core/settings.h"

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

  // albedo() for up to 8 lookups at once (structure of arrays in, channels[c][i] out; lanes with
  // active[i] false are left alone): the planks in 8-wide AVX2 when the build has it, else one
  // lookup at a time. Within rounding of albedo() (the golden tests bound the difference).
  void albedo8(const float* x, const float* y, const float* footprintX, const float* footprintY, const bool* active,
               float (*channels)[8]) const;

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
  void planks8(const float* x, const float* y, const float* footprintX, const float* footprintY, float (*channels)[8]) const;
  void loadImage(const std::string& path);

  Pattern pattern_ = Pattern::Planks;
  float scale_ = 0.1f;
  float inverseScale_ = 10.0f;
  glm::vec3 colorA_{0.6f}, colorB_{0.4f}, mean_{0.5f};
  std::vector<MipLevel> mips_;  // level 0 = the image, each next one half the size
};

}  // namespace slime

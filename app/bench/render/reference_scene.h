// The scene as a physically based path tracer needs it (scripts/reference/, Blender's Cycles): what
// `slime snapshot --reference-scene DIR` writes beside its frame, so that the same camera, light,
// floor, sky and jelly can be rendered by a program that knows nothing of Slime.
//
// DIR/scene.json holds the camera's frame (eye, forward, right, up, tan of half the vertical fov, the
// image size), the light (position, colour, the floor's k_d, the ambient), the sky's horizon and zenith,
// the haze distance, the jelly's index and absorption per metre (physical shading's σ, the one
// σ a dielectric that absorbs has), and the floor's albedo as three square tiles of texels around the
// slime (DIR/floor_near.pfm, floor_mid.pfm, floor_far.pfm: each texel the pattern averaged over it,
// FloorTexture::albedo with the texel's half width as footprint) and the mean albedo beyond them.
#pragma once

#include "core/settings/settings.h"

#include <string>

namespace slime {

// Writes DIR/scene.json and the floor's tiles for `settings` (its camera at its image size). Throws
// std::runtime_error naming the file when one cannot be written.
void writeReferenceScene(const std::string& directory, const Settings& settings);

}  // namespace slime

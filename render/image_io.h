// Image files: linear float ↔ sRGB 8-bit PNG through stb_image / stb_image_write (implementations from
// Debian's libstb). Writing goes to a temporary file renamed into place, so an error never leaves a
// partial PNG behind.
#pragma once

#include "render/image.h"

#include <cstdint>
#include <string>
#include <vector>

namespace slime {

using LinearImage = Image;

// The sRGB transfer curve (IEC 61966-2-1), linear [0,1] → encoded [0,1], and its inverse.
float linearToSrgb(float linear);
float srgbToLinear(float encoded);

// Clamped to [0,1], sRGB-encoded, rounded to 8 bits: 3 bytes per pixel, row-major, top row first.
std::vector<std::uint8_t> toSrgb8(const Image& image);

// Writes the image as an 8-bit sRGB PNG. Throws std::runtime_error naming the path on failure.
void writePng(const Image& image, const std::string& path);

// Reads a PNG (any channel count; grey is widened, alpha dropped) into linear RGB.
// Throws std::runtime_error naming the path when it is unreadable or not a PNG.
Image readPng(const std::string& path);

}  // namespace slime

// Image files: linear float ↔ sRGB 8-bit PNG through stb_image / stb_image_write (implementations from
// Debian's libstb). Writing goes to a temporary file renamed into place, so an error never leaves a
// partial PNG behind.
#pragma once

#include "render/image/image.h"

#include <cstdint>
#include <string>
#include <vector>

namespace slime {

using LinearImage = Image;

// The sRGB transfer curve (IEC 61966-2-1), linear [0,1] → encoded [0,1], and its inverse.
float linearToSrgb(float linear);
float srgbToLinear(float encoded);

// One linear value clamped to [0,1] (NaN as 0), sRGB-encoded and rounded to 8 bits: exactly
// lround(linearToSrgb(x) · 255), by one table lookup and one comparison instead of a pow (the
// points where that result steps are worked out once, by bisection on the curve itself).
std::uint8_t encodeSrgb8(float linear);

// `count` pixels so encoded into `channels` (3, or 4 with alpha 255) bytes each.
void encodeSrgb8(const glm::vec3* pixels, std::size_t count, int channels, std::uint8_t* out);

// The whole image so encoded: `channels` bytes per pixel (3, or 4 with alpha 255), row-major, top row
// first, into `bytes` (resized; reused without allocating when its size is right). Rows run on TBB
// threads.
void toSrgb8(const Image& image, int channels, std::vector<std::uint8_t>& bytes);
std::vector<std::uint8_t> toSrgb8(const Image& image);  // 3 bytes per pixel

// Writes the image as an 8-bit sRGB PNG. Throws std::runtime_error naming the path on failure.
void writePng(const Image& image, const std::string& path);

// Writes the image's linear floats as a PFM (Portable Float Map: "PF", width height, -1 for little
// endian, then rows bottom to top, three 32-bit floats a pixel), unclamped and unencoded: what a
// path tracer's float image is compared with (scripts/reference/). Throws naming the path on failure.
void writePfm(const Image& image, const std::string& path);

// Reads a colour PFM ("PF", either byte order) into linear RGB, top row first. Throws
// std::runtime_error naming the path when it is unreadable, not a colour PFM or cut short.
Image readPfm(const std::string& path);

// Reads a PNG (any channel count; grey is widened, alpha dropped) into linear RGB.
// Throws std::runtime_error naming the path when it is unreadable or not a PNG.
Image readPng(const std::string& path);

}  // namespace slime

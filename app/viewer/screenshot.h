// Writes what the current GL framebuffer shows to a PNG (F12 in the window, `snapshot --ui` headless).
#pragma once

#include <glm/vec2.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace slime {

// Reads size.x × size.y pixels of the bound read framebuffer and writes them, top row first, as an
// 8-bit RGB PNG. Throws std::runtime_error when the file cannot be written.
void writeFramebufferPng(glm::ivec2 size, const std::string& path);

// The same pixels as 8-bit RGB, top row first (a frame of `slime record --ui`).
std::vector<std::uint8_t> readFramebufferRgb(glm::ivec2 size);

}  // namespace slime

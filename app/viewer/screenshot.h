// Writes what the current GL framebuffer shows to a PNG (F12 in the window, `snapshot --ui` headless).
#pragma once

#include <glm/vec2.hpp>

#include <string>

namespace slime {

// Reads size.x × size.y pixels of the bound read framebuffer and writes them, top row first, as an
// 8-bit RGB PNG. Throws std::runtime_error when the file cannot be written.
void writeFramebufferPng(glm::ivec2 size, const std::string& path);

}  // namespace slime

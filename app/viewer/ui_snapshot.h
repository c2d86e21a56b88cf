// `slime snapshot --ui`: the whole viewer — traced image and panels — drawn headless (EGL, no display)
// by the same frame code as the window, and written to a PNG.
#pragma once

#include "core/settings.h"
#include "core/simulation.h"

#include <functional>
#include <string>

namespace slime {

// Draws the viewer at settings.camera.width × height and writes it to `path`. `settle`, if given,
// advances the viewer's fresh simulation first. Throws std::runtime_error when there is no EGL/GL or
// the file cannot be written.
void writeUiSnapshot(const Settings& settings, const std::string& path,
                     const std::function<void(Simulation&)>& settle = nullptr);

}  // namespace slime

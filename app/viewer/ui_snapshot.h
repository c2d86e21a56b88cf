// `slime snapshot --ui`: the whole viewer — traced image and panels — drawn headless (EGL or OSMesa, no display)
// by the same frame code as the window, and written to a PNG.
#pragma once

#include "app/viewer/headless_gl.h"
#include "core/settings/settings.h"
#include "core/simulation/simulation.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace slime {

// Draws the viewer at settings.camera.width × height and writes it to `path`. `settle`, if given,
// advances the viewer's fresh simulation first. Throws std::runtime_error when there is no headless GL or
// the file cannot be written.
void writeUiSnapshot(const Settings& settings, const std::string& path,
                     const std::function<void(Simulation&)>& settle = nullptr,
                     HeadlessApi api = HeadlessApi::Auto);

// The whole viewer drawn headless frame after frame (`slime record --ui`): the caller advances the
// simulation, then draw() returns the picture as 8-bit RGB, top row first.
class UiFrames {
 public:
  // Throws std::runtime_error when there is no headless GL context.
  explicit UiFrames(const Settings& settings, HeadlessApi api = HeadlessApi::Auto);
  ~UiFrames();
  UiFrames(const UiFrames&) = delete;
  UiFrames& operator=(const UiFrames&) = delete;

  Simulation& simulation();
  std::vector<std::uint8_t> draw();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace slime

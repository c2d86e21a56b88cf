// The seam between the viewer's frame code and the platform it runs on (as Polyscope's engine
// back-ends): a GLFW window (window.h) or an EGL surfaceless context rendering into an FBO
// (headless_gl.h). Both give a current GL 3.3 core context; the frame code is shared.
#pragma once

#include "app/viewer/frame_input.h"
#include "render/image/image.h"  // PixelRect

#include <glm/vec2.hpp>

#include <vector>

namespace slime {

class ViewerBackend {
 public:
  virtual ~ViewerBackend() = default;

  // Collects the input since the last frame (and the wall time that passed). In a headless run time
  // stands still, so a snapshot is the same every time.
  virtual FrameInput pollInput() = 0;

  // Pixels of the framebuffer to draw into, and of the window the cursor lives in (they differ on
  // HiDPI screens). Either may be 0×0 while the window is minimised.
  virtual glm::ivec2 framebufferSize() const = 0;
  virtual glm::ivec2 windowSize() const = 0;

  // The platform half of Dear ImGui: installs it, starts its frame, removes it.
  virtual void initImGuiPlatform() = 0;
  virtual void newImGuiPlatformFrame() = 0;
  virtual void shutdownImGuiPlatform() = 0;

  // Waits up to `seconds` for input (a window's events), returning as soon as some arrives. The
  // viewer calls it after a frame that had nothing new to trace, so that a still window does not
  // draw the same frame again hundreds of times a second on a whole core. Headless: returns at once.
  virtual void waitForInput(double seconds) { (void)seconds; }

  // Whether the framebuffer keeps what was drawn into it from one frame to the next (nothing is
  // swapped away), so that a frame need draw again only what changed (app/viewer/frame_compositor.h).
  virtual bool keepsFramebuffer() const = 0;

  // Shows the finished frame: with a kept framebuffer only the rectangles `changed` (framebuffer
  // pixels, top row 0) are new; without one, the whole (swap buffers).
  virtual void present(const std::vector<PixelRect>& changed) = 0;
};

}  // namespace slime

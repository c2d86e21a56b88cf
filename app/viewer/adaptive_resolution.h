// The fallback for a frame that does not fit its budget (issue 15). Full resolution is the default
// path, and with no target (0 fps, the default) the only one. With a target frame rate, only when
// kFramesOverBudget frames in a row take longer than the target frame time while the view moves (each
// traces a new image: the slime or the camera moved) does the traced image shrink, to the scale
// predicted to fit; it returns to full resolution as soon as a full-resolution frame is predicted to
// fit, or at the first frame that needs no new image (the view stopped changing: a still image refines
// at full resolution, and a slime that only creeps, traced every few frames, never engages it).
//
// The prediction: the trace grows with the pixel count, scale²; the rest of the frame (panels and
// present, the physics beside them, the upload) does not. Both are smoothed over the moving frames.
// The trace also has costs that do not shrink with the image, so the prediction is optimistic going
// down (a frame still over budget steps down again) and pessimistic going up (one step at a time, when
// the larger image is predicted to fit with headroom); between the two the scale stays, so noise does
// not resize the image every frame.
#pragma once

namespace slime {

class AdaptiveResolution {
 public:
  static constexpr int kFramesOverBudget = 3;
  static constexpr int kFullSteps = 20;    // scales are multiples of 1 / kFullSteps
  static constexpr int kMinimumSteps = 6;  // the smallest: 0.3 of the full width and height
  static constexpr double kMinimumScale = static_cast<double>(kMinimumSteps) / kFullSteps;
  static constexpr double kHeadroom = 0.9;  // a step up must be predicted within this share of the budget
  static constexpr double kMaximumTargetFps = 240.0;

  // Frames per second to hold; 0 turns the fallback off. Throws std::invalid_argument outside
  // 0..kMaximumTargetFps.
  void setTargetFps(double fps);
  double targetFps() const { return targetFps_; }

  // After each frame: its wall time, the time it spent tracing (0 if none) and whether it traced a
  // new image (not a refinement sample of a still one).
  void update(double frameMs, double traceMs, bool tracedNewImage);

  // The factor on the traced image's width and height: 1, or kMinimumScale..1 - 1 / kFullSteps.
  double scale() const { return static_cast<double>(steps_) / kFullSteps; }

 private:
  void returnToFull();
  double predictedFrameMs(int steps) const;

  double targetFps_ = 0.0;
  int steps_ = kFullSteps;
  int framesOverBudget_ = 0;
  double fullTraceMs_ = 0.0;  // smoothed trace time, scaled to full resolution; 0: no moving frame yet
  double otherMs_ = 0.0;      // smoothed rest of the frame
};

}  // namespace slime

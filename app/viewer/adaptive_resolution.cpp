#include "app/viewer/adaptive_resolution.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace slime {
namespace {

constexpr double kSmoothing = 0.5;  // weight of the newest frame in the smoothed times

double smooth(double average, double sample) {
  return average > 0.0 ? (1.0 - kSmoothing) * average + kSmoothing * sample : sample;
}

}  // namespace

void AdaptiveResolution::setTargetFps(double fps) {
  if (!(fps >= 0.0 && fps <= kMaximumTargetFps)) {
    char message[128];
    std::snprintf(message, sizeof message, "target fps %g is not allowed; expected 0 (off) to %g", fps,
                  kMaximumTargetFps);
    throw std::invalid_argument(message);
  }
  targetFps_ = fps;
  returnToFull();
}

void AdaptiveResolution::returnToFull() {
  steps_ = kFullSteps;
  framesOverBudget_ = 0;
}

double AdaptiveResolution::predictedFrameMs(int steps) const {
  const double scale = static_cast<double>(steps) / kFullSteps;
  return otherMs_ + fullTraceMs_ * scale * scale;
}

void AdaptiveResolution::update(double frameMs, double traceMs, bool tracedNewImage) {
  if (targetFps_ <= 0.0) return;
  if (!tracedNewImage) {
    returnToFull();
    return;
  }
  const double current = scale();
  fullTraceMs_ = smooth(fullTraceMs_, traceMs / (current * current));
  otherMs_ = smooth(otherMs_, std::max(0.0, frameMs - traceMs));
  const double budgetMs = 1000.0 / targetFps_;
  if (steps_ == kFullSteps) {
    framesOverBudget_ = frameMs > budgetMs ? framesOverBudget_ + 1 : 0;
    if (framesOverBudget_ < kFramesOverBudget) return;
  } else if (predictedFrameMs(kFullSteps) <= kHeadroom * budgetMs) {
    returnToFull();
    return;
  }
  if (steps_ == kFullSteps || predictedFrameMs(steps_) > budgetMs) {
    // Down: to the largest step predicted to fit with headroom, at least one step.
    const double traceBudgetMs = std::max(0.0, kHeadroom * budgetMs - otherMs_);
    const double fittingScale = std::sqrt(traceBudgetMs / fullTraceMs_);
    const int fitting = static_cast<int>(std::floor(fittingScale * kFullSteps + 1e-9));
    steps_ = std::clamp(std::min(fitting, steps_ - 1), kMinimumSteps, kFullSteps - 1);
  } else if (steps_ + 1 < kFullSteps && predictedFrameMs(steps_ + 1) <= kHeadroom * budgetMs) {
    ++steps_;
  }
}

}  // namespace slime

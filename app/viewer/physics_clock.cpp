#include "app/viewer/physics_clock.h"

#include <algorithm>
#include <cmath>

namespace slime {

int PhysicsClock::stepsFor(double wallSeconds, double timeScale, double dt) {
  if (!(dt > 0.0) || !(wallSeconds > 0.0) || !(timeScale > 0.0)) return 0;
  backlogSeconds_ += wallSeconds * timeScale;
  const double maxSteps = std::floor(kMaxCatchUpSeconds / dt);
  const double wanted = std::floor(backlogSeconds_ / dt);
  const double steps = std::min(wanted, std::max(maxSteps, 1.0));
  backlogSeconds_ -= steps * dt;
  if (wanted > steps) {  // a frame too slow to keep up: give up the backlog rather than spiral
    droppedSeconds_ += backlogSeconds_;
    backlogSeconds_ = 0.0;
  }
  return static_cast<int>(steps);
}

void PhysicsClock::giveBack(int steps, double dt) {
  if (steps <= 0 || !(dt > 0.0)) return;
  backlogSeconds_ += steps * dt;
  if (backlogSeconds_ > kMaxCatchUpSeconds) {
    droppedSeconds_ += backlogSeconds_ - kMaxCatchUpSeconds;
    backlogSeconds_ = kMaxCatchUpSeconds;
  }
}

}  // namespace slime

// The viewer's physics clock: the window never owns it. Each frame the wall time that passed (times
// sim.timeScale) becomes a whole number of fixed steps of sim.dt; the remainder carries over. A slow
// frame cannot make the next one slower still: at most kMaxCatchUpSeconds of simulated time is stepped
// per frame and the rest of the backlog is dropped (the slime then runs slower than real time).
#pragma once

namespace slime {

class PhysicsClock {
 public:
  static constexpr double kMaxCatchUpSeconds = 0.25;

  // Steps of `dt` to run for `wallSeconds` of wall time at `timeScale`.
  int stepsFor(double wallSeconds, double timeScale, double dt);

  // Forgets the backlog (pause, reload).
  void reset() { backlogSeconds_ = 0.0; }

  double droppedSeconds() const { return droppedSeconds_; }  // simulated time given up so far

 private:
  double backlogSeconds_ = 0.0;
  double droppedSeconds_ = 0.0;
};

}  // namespace slime

// The viewer's physics clock: the window never owns it. Each frame the wall time that passed (times
// sim.timeScale) becomes a whole number of fixed steps of sim.dt; the remainder carries over. A slow
// frame cannot make the next one slower still: at most kMaxCatchUpSeconds of simulated time is stepped
// per frame and the rest of the backlog is dropped (the slime then runs slower than real time).
// The caller may also stop a frame's steps early, at its wall-time budget, and give the rest back:
// they are stepped in the next frames' slices, never in one long frame.
#pragma once

namespace slime {

class PhysicsClock {
 public:
  static constexpr double kMaxCatchUpSeconds = 0.25;

  // Steps of `dt` to run for `wallSeconds` of wall time at `timeScale`.
  int stepsFor(double wallSeconds, double timeScale, double dt);

  // Steps of `dt` that stepsFor gave but the frame did not run (its time budget ran out) go back to the
  // backlog, which holds at most kMaxCatchUpSeconds; the rest is dropped.
  void giveBack(int steps, double dt);

  // Forgets the backlog (pause, reload).
  void reset() { backlogSeconds_ = 0.0; }

  double droppedSeconds() const { return droppedSeconds_; }  // simulated time given up so far

 private:
  double backlogSeconds_ = 0.0;
  double droppedSeconds_ = 0.0;
};

}  // namespace slime

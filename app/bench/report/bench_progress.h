// A progress bar for long benchmark runs: drawn in place on stderr when stderr is a terminal
// (isatty), silent otherwise, so logs and CI output stay clean.
#pragma once

#include <chrono>
#include <string>

namespace slime {

class BenchProgress {
 public:
  // `total` units of work (any unit: frames, runs); `label` names the bench.
  BenchProgress(std::string label, double total);
  ~BenchProgress();
  BenchProgress(const BenchProgress&) = delete;
  BenchProgress& operator=(const BenchProgress&) = delete;

  // Adds `amount` done units and redraws with `what` (the configuration being measured).
  void advance(double amount, const std::string& what);
  void finish();

 private:
  void draw(const std::string& what);

  std::string label_;
  double total_ = 1.0;
  double done_ = 0.0;
  bool enabled_ = false;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point lastDraw_;
};

}  // namespace slime

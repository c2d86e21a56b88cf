// Timing helpers shared by the benches: a wall-clock stopwatch and the median/min/max summary of
// repeated measurements (the median resists the noise of a shared machine better than the mean).
#pragma once

#include <nlohmann/json.hpp>

#include <chrono>
#include <vector>

namespace slime {

struct TimingSummary {
  double median = 0.0;
  double min = 0.0;
  double max = 0.0;
  int samples = 0;
};

// Median (mean of the middle two for an even count), min and max; zeros for no samples.
TimingSummary summarize(std::vector<double> samples);

nlohmann::json toJson(const TimingSummary& summary);

class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double milliseconds() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace slime

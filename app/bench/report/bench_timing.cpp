#include "app/bench/report/bench_timing.h"

#include <algorithm>

namespace slime {

TimingSummary summarize(std::vector<double> samples) {
  TimingSummary summary;
  if (samples.empty()) return summary;
  std::sort(samples.begin(), samples.end());
  const std::size_t n = samples.size();
  summary.median = n % 2 == 1 ? samples[n / 2] : 0.5 * (samples[n / 2 - 1] + samples[n / 2]);
  summary.min = samples.front();
  summary.max = samples.back();
  summary.samples = static_cast<int>(n);
  return summary;
}

nlohmann::json toJson(const TimingSummary& summary) {
  return {{"median", summary.median}, {"min", summary.min}, {"max", summary.max}, {"samples", summary.samples}};
}

}  // namespace slime

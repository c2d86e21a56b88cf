// `slime bench caustics`: the caustic map's error against its photon count and time, on the ball
// lens (the analytic sphere, lit from far above, its paraxial focus on the floor), against a map of
// 64 times the largest count.
#pragma once

#include "core/settings/settings.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace slime {

struct CausticsBenchOptions {
  std::vector<int> photons{2500, 5000, 10000, 20000, 40000, 80000, 160000};
  int frames = 3;  // timed runs per count (the median is reported)
  std::string csvFile;
};

nlohmann::json runCausticsBench(const Settings& settings, const CausticsBenchOptions& options);

}  // namespace slime

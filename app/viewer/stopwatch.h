// Wall-clock milliseconds since construction: how the viewer times a frame's stages.
#pragma once

#include <chrono>

namespace slime {

class Stopwatch {
 public:
  double milliseconds() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace slime

#include "render/trace/accumulation_buffer.h"

#include "render/image/image_io.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace slime {

AccumulationBuffer::AccumulationBuffer(int target) { setTarget(target); }

void AccumulationBuffer::setTarget(int target) {
  perAxis_ = std::max(1, static_cast<int>(std::lround(std::sqrt(static_cast<double>(std::max(1, target))))));
  target_ = perAxis_ * perAxis_;
  samples_ = std::min(samples_, target_);
}

glm::vec2 AccumulationBuffer::offset(int k) const {
  // Cells of the n × n grid in a spread-out order: pair p = k / 2 takes the p-th cell of the grid's
  // upper half (by a stride coprime with its size, so consecutive pairs land far apart), and its
  // partner is the cell mirrored through the centre. An odd n has a centre cell of its own: it goes last.
  const int n = perAxis_, cells = n * n, half = cells / 2;
  if (cells == 1 || k >= 2 * half) return {0.5f, 0.5f};
  int stride = std::max(1, half / 2 + 1);
  while (std::gcd(stride, half) != 1) ++stride;
  const int cell = ((k / 2) * stride) % half;
  const int x = cell % n, y = cell / n;
  const int mirroredX = k % 2 ? n - 1 - x : x, mirroredY = k % 2 ? n - 1 - y : y;
  return {(mirroredX + 0.5f) / n, (mirroredY + 0.5f) / n};
}

bool AccumulationBuffer::add(const Image& frame, Image& average, std::vector<std::uint8_t>* srgba) {
  const std::size_t count = frame.pixels.size();
  if (samples_ == 0 || frame.width != width_ || frame.height != height_) {
    width_ = frame.width;
    height_ = frame.height;
    sum_.assign(frame.pixels.begin(), frame.pixels.end());
    samples_ = 1;
  } else if (samples_ < target_) {
    for (std::size_t i = 0; i < count; ++i) sum_[i] += frame.pixels[i];
    ++samples_;
  }
  if (samples_ % 2 != 0 && samples_ != target_) return false;  // half a pair: not centred
  average.resize(width_, height_);
  const float scale = 1.0f / static_cast<float>(samples_);
  for (std::size_t i = 0; i < count; ++i) average.pixels[i] = sum_[i] * scale;
  if (srgba) {
    srgba->resize(4 * count);
    encodeSrgb8(average.pixels.data(), count, 4, srgba->data());
  }
  return true;
}

}  // namespace slime

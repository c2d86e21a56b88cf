#include "render/trace/checkerboard.h"

#include <glm/common.hpp>
#include <glm/exponential.hpp>

#include <algorithm>
#include <cmath>

namespace slime {

bool fillFromNeighbours(const glm::vec3* const neighbours[4], glm::vec3& color, float contrast) {
  // The range of √max(c, 0) over the neighbours, per channel: √ is monotone (and IEEE's correctly
  // rounded √ too), so it is √ of the largest value less √ of the smallest: 6 roots, not 12, the
  // same bits as taking the root of each (the fill pass was 4 % of a held frame's samples in perf).
  glm::vec3 low(INFINITY), high(-INFINITY);
  int count = 0;
  for (int i = 0; i < 4; ++i) {
    if (!neighbours[i]) continue;
    if (!std::isfinite(neighbours[i]->x + neighbours[i]->y + neighbours[i]->z)) return false;
    low = glm::min(low, *neighbours[i]);
    high = glm::max(high, *neighbours[i]);
    ++count;
  }
  if (count == 0) return false;
  const glm::vec3 range = glm::sqrt(glm::max(high, glm::vec3(0.0f))) - glm::sqrt(glm::max(low, glm::vec3(0.0f)));
  // NaN (a non-finite neighbour) fails this test too: the pixel is traced.
  if (!(std::max({range.x, range.y, range.z}) <= contrast)) return false;
  const auto spread = [](const glm::vec3& a, const glm::vec3& b) {
    const glm::vec3 d = glm::abs(a - b);
    return d.x + d.y + d.z;
  };
  const glm::vec3 *left = neighbours[0], *right = neighbours[1], *up = neighbours[2], *down = neighbours[3];
  if (left && right && up && down) {
    const float across = spread(*left, *right), along = spread(*up, *down);
    if (across < along) color = 0.5f * (*left + *right);
    else if (along < across) color = 0.5f * (*up + *down);
    else color = 0.25f * (*left + *right + *up + *down);
    return true;
  }
  glm::vec3 sum(0.0f);
  for (int i = 0; i < 4; ++i)
    if (neighbours[i]) sum += *neighbours[i];
  color = sum / static_cast<float>(count);
  return true;
}

}  // namespace slime

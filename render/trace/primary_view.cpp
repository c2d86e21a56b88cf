#include "render/trace/primary_view.h"

#include <glm/geometric.hpp>

#if defined(__AVX2__)
#include <immintrin.h>
#endif

namespace slime {

void primaryDirections8(const PrimaryView& view, int column, float offsetX, float y, float* directionX,
                        float* directionY, float* directionZ) {
#if defined(__AVX2__)
  const __m256 pixel = _mm256_cvtepi32_ps(_mm256_add_epi32(_mm256_set1_epi32(column), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7)));
  const __m256 x = _mm256_add_ps(pixel, _mm256_set1_ps(offsetX));
  const __m256 across = _mm256_sub_ps(_mm256_mul_ps(_mm256_set1_ps(2.0f), _mm256_div_ps(x, _mm256_set1_ps(view.width))),
                                      _mm256_set1_ps(1.0f));
  const float down = 1.0f - 2.0f * (y / view.height);
  __m256 d[3];
  for (int c = 0; c < 3; ++c)
    d[c] = _mm256_add_ps(_mm256_add_ps(_mm256_set1_ps(view.forward[c]), _mm256_mul_ps(across, _mm256_set1_ps(view.right[c]))),
                         _mm256_set1_ps(down * view.up[c]));
  const __m256 length2 = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(d[0], d[0]), _mm256_mul_ps(d[1], d[1])), _mm256_mul_ps(d[2], d[2]));
  const __m256 inverse = _mm256_div_ps(_mm256_set1_ps(1.0f), _mm256_sqrt_ps(length2));
  _mm256_storeu_ps(directionX, _mm256_mul_ps(d[0], inverse));
  _mm256_storeu_ps(directionY, _mm256_mul_ps(d[1], inverse));
  _mm256_storeu_ps(directionZ, _mm256_mul_ps(d[2], inverse));
#else
  const float down = 1.0f - 2.0f * (y / view.height);
  for (int i = 0; i < 8; ++i) {
    const float across = 2.0f * ((static_cast<float>(column + i) + offsetX) / view.width) - 1.0f;
    const glm::vec3 d = glm::normalize(view.forward + across * view.right + down * view.up);
    directionX[i] = d.x;
    directionY[i] = d.y;
    directionZ[i] = d.z;
  }
#endif
}


}  // namespace slime

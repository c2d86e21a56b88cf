#include "render/floor_texture.h"

#include "core/settings_io.h"
#include "render/image_io.h"

#include <glm/common.hpp>
#include <glm/exponential.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

#if defined(__AVX2__)
#include <immintrin.h>
#endif

namespace slime {
namespace {

constexpr float kPi = 3.14159265358979f;

// ⌊x⌋ without a libm call (baseline x86-64 has no roundss); exact for |x| < 2^23, libm beyond.
inline float floorOf(float x) {
  if (!(std::abs(x) < 8388608.0f)) return std::floor(x);
  const float truncated = static_cast<float>(static_cast<std::int32_t>(x));
  return truncated > x ? truncated - 1.0f : truncated;
}

// sin x to ≈ 1e-3 (Bhaskara-style parabola with one refinement): plenty for a wood grain.
inline float grainSine(float x) {
  constexpr float kInverseTwoPi = 1.0f / (2.0f * kPi);
  float turns = x * kInverseTwoPi;
  turns -= floorOf(turns + 0.5f);           // in [−0.5, 0.5) turns
  const float y = 8.0f * turns * (1.0f - 2.0f * std::abs(turns));  // parabola through the sine's zeros and peaks
  return y * (0.775f + 0.225f * std::abs(y));
}

// A well-mixed integer hash (lowbias32) of a pair: 32 independent-looking bits.
std::uint32_t hashBits(std::int32_t i, std::int32_t j) {
  std::uint32_t x = static_cast<std::uint32_t>(i) * 0x9E3779B9u ^ (static_cast<std::uint32_t>(j) + 0x7F4A7C15u);
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

// The hash → [0, 1).
float hash01(std::int32_t i, std::int32_t j) { return static_cast<float>(hashBits(i, j) >> 8) * (1.0f / 16777216.0f); }

// Byte k of a hash → [0, 1) (the centre of one of 256 steps): four draws from one hash.
float hashByte(std::uint32_t bits, int k) {
  return (static_cast<float>((bits >> (8 * k)) & 0xFFu) + 0.5f) * (1.0f / 256.0f);
}

// The integral from 0 to x of a pulse train that is 1 on [k, k + width) for every integer k:
//   P(x) = ⌊x⌋·width + min(x − ⌊x⌋, width).
float pulseIntegral(float x, float width) {
  const float whole = floorOf(x);
  return whole * width + std::min(x - whole, width);
}

// The pulse train box-filtered over [x − halfWidth, x + halfWidth]: (P(x+h) − P(x−h)) / 2h.
float filteredPulse(float x, float halfWidth, float width) {
  if (halfWidth < 1e-6f) return x - floorOf(x) < width ? 1.0f : 0.0f;
  return (pulseIntegral(x + halfWidth, width) - pulseIntegral(x - halfWidth, width)) / (2.0f * halfWidth);
}

// The integral of the ±1 square wave (+1 on [0,1), −1 on [1,2)): the triangle wave 1 − |x mod 2 − 1|.
float squareIntegral(float x) { return 1.0f - std::abs(x - 2.0f * floorOf(0.5f * x) - 1.0f); }

float filteredSquare(float x, float halfWidth) {
  if (halfWidth < 1e-6f) return x - 2.0f * floorOf(0.5f * x) < 1.0f ? 1.0f : -1.0f;
  return (squareIntegral(x + halfWidth) - squareIntegral(x - halfWidth)) / (2.0f * halfWidth);
}

// How much of a detail of `period` survives a box of half width h: 1 well below, 0 at and above.
float detailVisibility(float halfWidth, float period) { return glm::clamp(1.0f - 2.0f * halfWidth / period, 0.0f, 1.0f); }

glm::vec3 toVec3(const glm::dvec3& v) { return glm::vec3(v); }

}  // namespace

FloorTexture::FloorTexture(const FloorSettings& settings)
    : scale_(static_cast<float>(settings.scale)), inverseScale_(1.0f / scale_), colorA_(toVec3(settings.colorA)), colorB_(toVec3(settings.colorB)) {
  if (!(scale_ > 0.0f)) throw SettingsError("floor.scale must be > 0 m, got " + std::to_string(settings.scale));
  if (settings.pattern == "planks") pattern_ = Pattern::Planks;
  else if (settings.pattern == "tiles") pattern_ = Pattern::Tiles;
  else if (settings.pattern == "checker") pattern_ = Pattern::Checker;
  else if (settings.pattern == "image") pattern_ = Pattern::Image;
  else throw SettingsError("floor.pattern must be one of planks, tiles, checker, image; got '" + settings.pattern + "'");

  if (pattern_ == Pattern::Image) {
    loadImage(settings.image);
    mean_ = mips_.back().texels.front();
  } else {
    // Far away every procedural pattern tends to its area average; sample it with a huge footprint.
    mean_ = albedo({0.37f * scale_, 0.61f * scale_}, glm::vec2(1000.0f * scale_));
  }
}

glm::vec3 FloorTexture::albedo(glm::vec2 point, glm::vec2 footprint) const {
  // Kilometres away (a grazing ray) the footprint covers everything: the mean, and no integer overflow.
  if (!(std::abs(point.x) < 1e5f && std::abs(point.y) < 1e5f)) return mean_;
  switch (pattern_) {
    case Pattern::Planks: return planks(point, footprint);
    case Pattern::Tiles: return tiles(point, footprint);
    case Pattern::Checker: return checker(point, footprint);
    case Pattern::Image: return image(point, footprint);
  }
  return mean_;
}

// Boards `scale` wide running along x, six widths long, each row's joints staggered; each board has
// its own shade between colorA and colorB, wavy grain along its length and dark seams between boards.
// One hash per board draws its shade, brightness, grain phase and grain density (a byte each).
glm::vec3 FloorTexture::planks(glm::vec2 p, glm::vec2 footprint) const {
  constexpr float kLength = 6.0f;      // board length in board widths
  constexpr float kSeam = 0.03f;       // seam width as a fraction of the board width
  constexpr float kGrainPerBoard = 11.0f;
  constexpr float kDarkestGrainDensity = 0.7f, kGrainDensityRange = 0.6f;
  const glm::vec2 q = p * inverseScale_;        // in board widths
  const glm::vec2 h = footprint * inverseScale_;
  const float row = floorOf(q.y);
  const auto rowIndex = static_cast<std::int32_t>(row);
  const float stagger = hash01(rowIndex, 17) * kLength;
  const float along = (q.x + stagger) * (1.0f / kLength);  // in board lengths
  const float board = floorOf(along);
  const std::uint32_t draws = hashBits(static_cast<std::int32_t>(board), rowIndex);

  // Per-board shade and brightness, faded to their mean once a board is smaller than the footprint.
  const float boardVisibility = detailVisibility(std::max(h.x, h.y), 1.0f);
  const float shade = glm::mix(0.5f, hashByte(draws, 0), boardVisibility);
  const float brightness = 1.0f + 0.18f * boardVisibility * (hashByte(draws, 1) - 0.5f);
  glm::vec3 color = glm::mix(colorA_, colorB_, shade) * brightness;

  // Grain: stripes across y that wander slowly along x, fading as the footprint reaches their period
  // (skipped once it has faded for every density).
  constexpr float kGrainPeriod = 1.0f / kGrainPerBoard;
  if (h.y < 0.5f * kGrainPeriod / kDarkestGrainDensity) {
    const float phase = hashByte(draws, 2) * 2.0f * kPi;
    const float density = kDarkestGrainDensity + kGrainDensityRange * hashByte(draws, 3);
    const float wander = (1.0f + 1.5f * density) * grainSine(q.x * (0.9f + density) + phase);
    const float grain = grainSine(2.0f * kPi * kGrainPerBoard * density * q.y + wander + phase);
    color *= 1.0f + 0.05f * grain * detailVisibility(h.y, kGrainPeriod / density);
  }

  // Seams: the long ones between rows (exactly filtered), the joints between boards of one row.
  const float longSeam = filteredPulse(q.y + 0.5f * kSeam, h.y, kSeam);
  const float joint = filteredPulse(along + 0.5f * kSeam / kLength, h.x * (1.0f / kLength), kSeam / kLength);
  const float seam = 1.0f - (1.0f - longSeam) * (1.0f - joint);
  return glm::mix(color, colorB_ * 0.35f, seam);
}

void FloorTexture::albedo8(const float* x, const float* y, const float* footprintX, const float* footprintY,
                           const bool* active, float (*channels)[8]) const {
#if defined(__AVX2__)
  if (pattern_ == Pattern::Planks) {
    float lanes[3][8];
    planks8(x, y, footprintX, footprintY, lanes);
    for (int i = 0; i < 8; ++i) {
      if (!active[i]) continue;
      const bool near = std::abs(x[i]) < 1e5f && std::abs(y[i]) < 1e5f;
      for (int c = 0; c < 3; ++c) channels[c][i] = near ? lanes[c][i] : mean_[c];
    }
    return;
  }
#endif
  for (int i = 0; i < 8; ++i) {
    if (!active[i]) continue;
    const glm::vec3 albedo = this->albedo({x[i], y[i]}, {footprintX[i], footprintY[i]});
    for (int c = 0; c < 3; ++c) channels[c][i] = albedo[c];
  }
}

#if defined(__AVX2__)
namespace {

// The scalar helpers above, 8 lanes at a time (same formulas, same order of operations).
struct Lanes {
  static __m256 all(float v) { return _mm256_set1_ps(v); }
  static __m256 abs(__m256 v) { return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), v); }
  static __m256 floor(__m256 v) { return _mm256_round_ps(v, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC); }
  static __m256 mix(__m256 a, __m256 b, __m256 t) {  // glm::mix: a (1 − t) + b t
    return _mm256_add_ps(_mm256_mul_ps(a, _mm256_sub_ps(all(1.0f), t)), _mm256_mul_ps(b, t));
  }
  static __m256 clamp01(__m256 v) { return _mm256_min_ps(_mm256_max_ps(v, all(0.0f)), all(1.0f)); }
  static __m256i hashBits(__m256i i, __m256i j) {
    __m256i x = _mm256_xor_si256(_mm256_mullo_epi32(i, _mm256_set1_epi32(static_cast<int>(0x9E3779B9u))),
                                 _mm256_add_epi32(j, _mm256_set1_epi32(0x7F4A7C15)));
    x = _mm256_xor_si256(x, _mm256_srli_epi32(x, 16));
    x = _mm256_mullo_epi32(x, _mm256_set1_epi32(0x7feb352d));
    x = _mm256_xor_si256(x, _mm256_srli_epi32(x, 15));
    x = _mm256_mullo_epi32(x, _mm256_set1_epi32(static_cast<int>(0x846ca68bu)));
    return _mm256_xor_si256(x, _mm256_srli_epi32(x, 16));
  }
  static __m256 hash01(__m256i bits) {
    return _mm256_mul_ps(_mm256_cvtepi32_ps(_mm256_srli_epi32(bits, 8)), all(1.0f / 16777216.0f));
  }
  static __m256 hashByte(__m256i bits, int k) {
    const __m256i byte = _mm256_and_si256(_mm256_srlv_epi32(bits, _mm256_set1_epi32(8 * k)), _mm256_set1_epi32(0xFF));
    return _mm256_mul_ps(_mm256_add_ps(_mm256_cvtepi32_ps(byte), all(0.5f)), all(1.0f / 256.0f));
  }
  static __m256 grainSine(__m256 x) {
    __m256 turns = _mm256_mul_ps(x, all(1.0f / (2.0f * kPi)));
    turns = _mm256_sub_ps(turns, floor(_mm256_add_ps(turns, all(0.5f))));
    const __m256 y = _mm256_mul_ps(_mm256_mul_ps(all(8.0f), turns),
                                   _mm256_sub_ps(all(1.0f), _mm256_mul_ps(all(2.0f), abs(turns))));
    return _mm256_mul_ps(y, _mm256_add_ps(all(0.775f), _mm256_mul_ps(all(0.225f), abs(y))));
  }
  static __m256 pulseIntegral(__m256 x, __m256 width) {
    const __m256 whole = floor(x);
    return _mm256_add_ps(_mm256_mul_ps(whole, width), _mm256_min_ps(_mm256_sub_ps(x, whole), width));
  }
  static __m256 filteredPulse(__m256 x, __m256 halfWidth, __m256 width) {
    const __m256 point = _mm256_and_ps(_mm256_cmp_ps(_mm256_sub_ps(x, floor(x)), width, _CMP_LT_OQ), all(1.0f));
    const __m256 box = _mm256_div_ps(_mm256_sub_ps(pulseIntegral(_mm256_add_ps(x, halfWidth), width),
                                                   pulseIntegral(_mm256_sub_ps(x, halfWidth), width)),
                                     _mm256_mul_ps(all(2.0f), halfWidth));
    return _mm256_blendv_ps(box, point, _mm256_cmp_ps(halfWidth, all(1e-6f), _CMP_LT_OQ));
  }
};

}  // namespace

// planks() for 8 lookups: the same pattern, lane by lane (see there for what each step draws).
void FloorTexture::planks8(const float* x, const float* y, const float* footprintX, const float* footprintY,
                           float (*channels)[8]) const {
  using L = Lanes;
  constexpr float kLength = 6.0f, kSeam = 0.03f, kGrainPerBoard = 11.0f;
  constexpr float kDarkestGrainDensity = 0.7f, kGrainDensityRange = 0.6f, kGrainPeriod = 1.0f / kGrainPerBoard;
  const __m256 inverseScale = L::all(inverseScale_);
  const __m256 qx = _mm256_mul_ps(_mm256_loadu_ps(x), inverseScale), qy = _mm256_mul_ps(_mm256_loadu_ps(y), inverseScale);
  const __m256 hx = _mm256_mul_ps(_mm256_loadu_ps(footprintX), inverseScale);
  const __m256 hy = _mm256_mul_ps(_mm256_loadu_ps(footprintY), inverseScale);
  // Lanes far away (kilometres) are replaced by the mean in albedo8; clamp them so the integers stay sane.
  const __m256 row = L::floor(_mm256_min_ps(_mm256_max_ps(qy, L::all(-1e7f)), L::all(1e7f)));
  const __m256i rowIndex = _mm256_cvttps_epi32(row);
  const __m256 stagger = _mm256_mul_ps(L::hash01(L::hashBits(rowIndex, _mm256_set1_epi32(17))), L::all(kLength));
  const __m256 along = _mm256_mul_ps(_mm256_add_ps(_mm256_min_ps(_mm256_max_ps(qx, L::all(-1e7f)), L::all(1e7f)), stagger),
                                     L::all(1.0f / kLength));
  const __m256 board = L::floor(along);
  const __m256i draws = L::hashBits(_mm256_cvttps_epi32(board), rowIndex);

  const __m256 boardVisibility = L::clamp01(_mm256_sub_ps(L::all(1.0f), _mm256_mul_ps(L::all(2.0f), _mm256_max_ps(hx, hy))));
  const __m256 shade = L::mix(L::all(0.5f), L::hashByte(draws, 0), boardVisibility);
  const __m256 brightness = _mm256_add_ps(
      L::all(1.0f), _mm256_mul_ps(_mm256_mul_ps(L::all(0.18f), boardVisibility), _mm256_sub_ps(L::hashByte(draws, 1), L::all(0.5f))));

  // Grain, where the footprint leaves any of it: a factor of 1 elsewhere.
  __m256 grainFactor = L::all(1.0f);
  const __m256 grainShows = _mm256_cmp_ps(hy, L::all(0.5f * kGrainPeriod / kDarkestGrainDensity), _CMP_LT_OQ);
  if (_mm256_movemask_ps(grainShows) != 0) {
    const __m256 phase = _mm256_mul_ps(_mm256_mul_ps(L::hashByte(draws, 2), L::all(2.0f)), L::all(kPi));
    const __m256 density = _mm256_add_ps(L::all(kDarkestGrainDensity), _mm256_mul_ps(L::all(kGrainDensityRange), L::hashByte(draws, 3)));
    const __m256 wander = _mm256_mul_ps(
        _mm256_add_ps(L::all(1.0f), _mm256_mul_ps(L::all(1.5f), density)),
        L::grainSine(_mm256_add_ps(_mm256_mul_ps(qx, _mm256_add_ps(L::all(0.9f), density)), phase)));
    const __m256 grain = L::grainSine(_mm256_add_ps(
        _mm256_add_ps(_mm256_mul_ps(_mm256_mul_ps(L::all(2.0f * kPi * kGrainPerBoard), density), qy), wander), phase));
    // detailVisibility(h_y, period / density) = clamp(1 − 2 h_y / (period / density)).
    const __m256 visibility = L::clamp01(
        _mm256_sub_ps(L::all(1.0f), _mm256_div_ps(_mm256_mul_ps(L::all(2.0f), hy), _mm256_div_ps(L::all(kGrainPeriod), density))));
    const __m256 factor = _mm256_add_ps(L::all(1.0f), _mm256_mul_ps(_mm256_mul_ps(L::all(0.05f), grain), visibility));
    grainFactor = _mm256_blendv_ps(grainFactor, factor, grainShows);
  }

  const __m256 longSeam = L::filteredPulse(_mm256_add_ps(qy, L::all(0.5f * kSeam)), hy, L::all(kSeam));
  const __m256 joint = L::filteredPulse(_mm256_add_ps(along, L::all(0.5f * kSeam / kLength)),
                                        _mm256_mul_ps(hx, L::all(1.0f / kLength)), L::all(kSeam / kLength));
  const __m256 seam = _mm256_sub_ps(L::all(1.0f), _mm256_mul_ps(_mm256_sub_ps(L::all(1.0f), longSeam), _mm256_sub_ps(L::all(1.0f), joint)));

  for (int c = 0; c < 3; ++c) {
    const __m256 color = _mm256_mul_ps(_mm256_mul_ps(L::mix(L::all(colorA_[c]), L::all(colorB_[c]), shade), brightness), grainFactor);
    _mm256_storeu_ps(channels[c], L::mix(color, L::all(colorB_[c] * 0.35f), seam));
  }
}
#endif

// Square tiles of side `scale` in colorA, with grout lines in colorB and a slight shade per tile.
glm::vec3 FloorTexture::tiles(glm::vec2 p, glm::vec2 footprint) const {
  constexpr float kGrout = 0.06f;
  const glm::vec2 q = p / scale_, h = footprint / scale_;
  const float visibility = detailVisibility(std::max(h.x, h.y), 1.0f);
  const float shade = 1.0f + 0.12f * visibility *
      (hash01(static_cast<std::int32_t>(floorOf(q.x)), static_cast<std::int32_t>(floorOf(q.y))) - 0.5f);
  const float groutX = filteredPulse(q.x + 0.5f * kGrout, h.x, kGrout);
  const float groutY = filteredPulse(q.y + 0.5f * kGrout, h.y, kGrout);
  const float grout = 1.0f - (1.0f - groutX) * (1.0f - groutY);
  return glm::mix(colorA_ * shade, colorB_, grout);
}

// Alternating cells of side `scale`: the box filter of s(x)·s(y) is the product of the filtered waves.
glm::vec3 FloorTexture::checker(glm::vec2 p, glm::vec2 footprint) const {
  const glm::vec2 q = p / scale_, h = footprint / scale_;
  const float sign = filteredSquare(q.x, h.x) * filteredSquare(q.y, h.y);
  return glm::mix(colorB_, colorA_, 0.5f + 0.5f * sign);
}

// One copy of the image covers scale × scale·(height/width) metres, repeated; trilinear mipmapping.
glm::vec3 FloorTexture::image(glm::vec2 p, glm::vec2 footprint) const {
  const MipLevel& base = mips_.front();
  const float texelsPerMetre = static_cast<float>(base.width) / scale_;
  const float footprintTexels = 2.0f * std::max(footprint.x, footprint.y) * texelsPerMetre;
  const float lod = glm::clamp(std::log2(std::max(footprintTexels, 1.0f)), 0.0f, static_cast<float>(mips_.size() - 1));
  const int lower = static_cast<int>(lod);
  const int upper = std::min(lower + 1, static_cast<int>(mips_.size()) - 1);
  const float blend = lod - static_cast<float>(lower);
  auto sample = [&](const MipLevel& level) {
    const float perMetre = static_cast<float>(level.width) / scale_;
    return level.bilinear(p.x * perMetre - 0.5f, -p.y * perMetre - 0.5f);
  };
  return glm::mix(sample(mips_[lower]), sample(mips_[upper]), blend);
}

glm::vec3 FloorTexture::MipLevel::bilinear(float x, float y) const {
  const float fx = floorOf(x), fy = floorOf(y);
  const float tx = x - fx, ty = y - fy;
  auto wrap = [](float value, int size) {
    const int i = static_cast<int>(std::fmod(value, static_cast<float>(size)));
    return i < 0 ? i + size : i;
  };
  const int x0 = wrap(fx, width), x1 = (x0 + 1) % width;
  const int y0 = wrap(fy, height), y1 = (y0 + 1) % height;
  auto texel = [&](int i, int j) { return texels[static_cast<std::size_t>(j) * width + i]; };
  return glm::mix(glm::mix(texel(x0, y0), texel(x1, y0), tx), glm::mix(texel(x0, y1), texel(x1, y1), tx), ty);
}

void FloorTexture::loadImage(const std::string& path) {
  if (path.empty()) throw SettingsError("floor.image: floor.pattern is 'image' but no PNG file is given");
  LinearImage loaded;
  try {
    loaded = readPng(path);
  } catch (const std::exception& e) {
    throw SettingsError(std::string("floor.image: ") + e.what());
  }
  MipLevel level{loaded.width, loaded.height, std::move(loaded.pixels)};
  mips_.push_back(std::move(level));
  // Each coarser level averages 2×2 texels of the one above (odd sizes wrap the last column/row).
  while (mips_.back().width > 1 || mips_.back().height > 1) {
    const MipLevel& fine = mips_.back();
    MipLevel coarse{std::max(1, fine.width / 2), std::max(1, fine.height / 2), {}};
    coarse.texels.resize(static_cast<std::size_t>(coarse.width) * coarse.height);
    for (int j = 0; j < coarse.height; ++j) {
      for (int i = 0; i < coarse.width; ++i) {
        glm::vec3 sum(0.0f);
        for (int dj = 0; dj < 2; ++dj)
          for (int di = 0; di < 2; ++di)
            sum += fine.texels[static_cast<std::size_t>(std::min(2 * j + dj, fine.height - 1)) * fine.width +
                               std::min(2 * i + di, fine.width - 1)];
        coarse.texels[static_cast<std::size_t>(j) * coarse.width + i] = 0.25f * sum;
      }
    }
    mips_.push_back(std::move(coarse));
  }
}

}  // namespace slime

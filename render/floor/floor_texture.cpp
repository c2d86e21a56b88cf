#include "render/floor/floor_texture.h"

#include "core/settings/settings_io.h"
#include "render/image/image_io.h"
#include "render/simd/wide_lanes.h"

#include <glm/common.hpp>
#include <glm/exponential.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

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

template <int N>
void FloorTexture::albedoLanes(const float* x, const float* y, const float* footprintX, const float* footprintY,
                               const bool* active, float (*channels)[N]) const {
#if defined(SLIME_WIDE_LANES)
  if (pattern_ == Pattern::Planks) {
    // Every lane is written (an inactive one with whatever its coordinates give); kilometres away, the mean.
    using F = typename Wide<N>::F;
    planksLanes<N>(x, y, footprintX, footprintY, channels);
    const auto near = (absLanes(loadLanes<F>(x)) < 1e5f) & (absLanes(loadLanes<F>(y)) < 1e5f);
    for (int c = 0; c < 3; ++c) storeLanes(channels[c], near ? loadLanes<F>(channels[c]) : splat<F>(mean_[c]));
    return;
  }
#endif
  for (int i = 0; i < N; ++i) {
    if (!active[i]) continue;
    const glm::vec3 albedo = this->albedo({x[i], y[i]}, {footprintX[i], footprintY[i]});
    for (int c = 0; c < 3; ++c) channels[c][i] = albedo[c];
  }
}

#if defined(SLIME_WIDE_LANES)
namespace {

// The scalar helpers above, N lanes at a time (same formulas, same order of operations).
template <int N>
struct PlankLanes {
  using F = typename Wide<N>::F;
  using I = typename Wide<N>::I;
  using U = typename Wide<N>::U;
  static U hashBits(I i, I j) {
    U x = ((U)i * 0x9E3779B9u) ^ ((U)j + 0x7F4A7C15u);
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    return x ^ (x >> 16);
  }
  static F hash01(U bits) { return __builtin_convertvector((I)(bits >> 8), F) * (1.0f / 16777216.0f); }
  static F hashByte(U bits, int k) {
    return (__builtin_convertvector((I)((bits >> (8 * k)) & 0xFFu), F) + 0.5f) * (1.0f / 256.0f);
  }
  static F mix(F a, F b, F t) { return a * (1.0f - t) + b * t; }  // glm::mix
  static F clamp01(F v) { return minLanes(maxLanes(v, splat<F>(0.0f)), splat<F>(1.0f)); }
  static F grainSine(F x) {
    F turns = x * (1.0f / (2.0f * kPi));
    turns = turns - floorLanes(turns + 0.5f);
    const F y = (8.0f * turns) * (1.0f - 2.0f * absLanes(turns));
    return y * (0.775f + 0.225f * absLanes(y));
  }
  static F pulseIntegral(F x, F width) {
    const F whole = floorLanes(x);
    return whole * width + minLanes(x - whole, width);
  }
  static F filteredPulse(F x, F halfWidth, F width) {
    const F point = x - floorLanes(x) < width ? splat<F>(1.0f) : splat<F>(0.0f);
    const F box = (pulseIntegral(x + halfWidth, width) - pulseIntegral(x - halfWidth, width)) / (2.0f * halfWidth);
    return halfWidth < 1e-6f ? point : box;
  }
};

}  // namespace

// planks() for N lookups: the same pattern, lane by lane (see there for what each step draws).
template <int N>
void FloorTexture::planksLanes(const float* x, const float* y, const float* footprintX, const float* footprintY,
                               float (*channels)[N]) const {
  using L = PlankLanes<N>;
  using F = typename L::F;
  using I = typename L::I;
  constexpr float kLength = 6.0f, kSeam = 0.03f, kGrainPerBoard = 11.0f;
  constexpr float kDarkestGrainDensity = 0.7f, kGrainDensityRange = 0.6f, kGrainPeriod = 1.0f / kGrainPerBoard;
  const F qx = loadLanes<F>(x) * inverseScale_, qy = loadLanes<F>(y) * inverseScale_;
  const F hx = loadLanes<F>(footprintX) * inverseScale_, hy = loadLanes<F>(footprintY) * inverseScale_;
  // Lanes far away (kilometres) are replaced by the mean in albedoLanes; clamp them so the integers stay sane.
  const F row = floorLanes(minLanes(maxLanes(qy, splat<F>(-1e7f)), splat<F>(1e7f)));
  const I rowIndex = __builtin_convertvector(row, I);
  const F stagger = L::hash01(L::hashBits(rowIndex, I{} + 17)) * kLength;
  const F along = (minLanes(maxLanes(qx, splat<F>(-1e7f)), splat<F>(1e7f)) + stagger) * (1.0f / kLength);
  const F board = floorLanes(along);
  const auto draws = L::hashBits(__builtin_convertvector(board, I), rowIndex);

  const F boardVisibility = L::clamp01(1.0f - 2.0f * maxLanes(hx, hy));
  const F shade = L::mix(splat<F>(0.5f), L::hashByte(draws, 0), boardVisibility);
  const F brightness = 1.0f + (0.18f * boardVisibility) * (L::hashByte(draws, 1) - 0.5f);

  // Grain, where the footprint leaves any of it: a factor of 1 elsewhere.
  F grainFactor = splat<F>(1.0f);
  const I grainShows = hy < 0.5f * kGrainPeriod / kDarkestGrainDensity;
  if (maskBits(grainShows) != 0) {
    const F phase = (L::hashByte(draws, 2) * 2.0f) * kPi;
    const F density = kDarkestGrainDensity + kGrainDensityRange * L::hashByte(draws, 3);
    const F wander = (1.0f + 1.5f * density) * L::grainSine(qx * (0.9f + density) + phase);
    const F grain = L::grainSine(((2.0f * kPi * kGrainPerBoard) * density) * qy + wander + phase);
    // detailVisibility(h_y, period / density) = clamp(1 − 2 h_y / (period / density)).
    const F visibility = L::clamp01(1.0f - (2.0f * hy) / (kGrainPeriod / density));
    grainFactor = grainShows ? 1.0f + (0.05f * grain) * visibility : grainFactor;
  }

  const F longSeam = L::filteredPulse(qy + 0.5f * kSeam, hy, splat<F>(kSeam));
  const F joint = L::filteredPulse(along + 0.5f * kSeam / kLength, hx * (1.0f / kLength), splat<F>(kSeam / kLength));
  const F seam = 1.0f - (1.0f - longSeam) * (1.0f - joint);

  for (int c = 0; c < 3; ++c) {
    const F color = (L::mix(splat<F>(colorA_[c]), splat<F>(colorB_[c]), shade) * brightness) * grainFactor;
    storeLanes(channels[c], L::mix(color, splat<F>(colorB_[c] * 0.35f), seam));
  }
}
#endif

template void FloorTexture::albedoLanes<8>(const float*, const float*, const float*, const float*, const bool*,
                                           float (*)[8]) const;
#if defined(SLIME_WIDE_LANES_16)
template void FloorTexture::albedoLanes<16>(const float*, const float*, const float*, const float*, const bool*,
                                            float (*)[16]) const;
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

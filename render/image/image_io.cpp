#include "render/image/image_io.h"

#include "core/settings/file_output.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#if defined(__AVX2__)
#include <immintrin.h>
#endif

namespace slime {
namespace {

void appendBytes(void* context, void* data, int size) {
  auto* bytes = static_cast<std::vector<std::uint8_t>*>(context);
  const auto* begin = static_cast<const std::uint8_t*>(data);
  bytes->insert(bytes->end(), begin, begin + size);
}

}  // namespace

float linearToSrgb(float linear) {
  linear = std::clamp(linear, 0.0f, 1.0f);
  return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

float srgbToLinear(float encoded) {
  return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

namespace {

int encodeByCurve(float linear) { return static_cast<int>(std::lround(linearToSrgb(linear) * 255.0f)); }

// For floats ≥ 0 the order of the bit patterns is the order of the values. Cut [0, 1] into buckets
// of 2^16 consecutive floats: no bucket holds two of the points where encodeByCurve steps (in
// [0.5, 1) a bucket is 0.0039 wide and a step of the 8-bit code at least 0.0059 of linear; each
// octave lower halves the bucket and shrinks the step less), so a value's code is its bucket's
// first code, plus one if it has reached the bucket's next step. (2^17 failed just above 0.5.)
constexpr int kBucketShift = 16;

// One 32-bit entry per bucket, so that 8 values need one gather (and the table, 64 KB, stays near
// the core): the bucket's first code above bit 17, and below it where in the bucket the next step
// lies, as the low 16 bits of its float (0x10000, out of reach, when it lies beyond the bucket).
constexpr int kStepBits = 17;
constexpr std::uint32_t kStepMask = (1u << kStepBits) - 1, kLowMask = (1u << kBucketShift) - 1;

struct EncodingTable {
  std::vector<std::uint32_t> entries;

  EncodingTable() {
    const auto bitsOf = [](float value) { return std::bit_cast<std::uint32_t>(value); };
    // steps[c]: the smallest float in [0, 1] that encodeByCurve takes to c or more, by bisection.
    std::array<std::uint32_t, 257> steps{};
    for (int code = 1; code <= 255; ++code) {
      std::uint32_t low = bitsOf(0.0f), high = bitsOf(1.0f);  // encodeByCurve(1) = 255 ≥ code
      while (low < high) {
        const std::uint32_t middle = low + (high - low) / 2;
        if (encodeByCurve(std::bit_cast<float>(middle)) >= code) high = middle;
        else low = middle + 1;
      }
      steps[code] = low;
    }
    steps[256] = bitsOf(2.0f);  // beyond every value that reaches the table
    const std::size_t buckets = (bitsOf(1.0f) >> kBucketShift) + 1;
    entries.resize(buckets);
    for (std::size_t k = 0; k < buckets; ++k) {
      const std::uint32_t first = static_cast<std::uint32_t>(k << kBucketShift);
      const int code = encodeByCurve(std::bit_cast<float>(first));
      const std::uint32_t next = steps[code + 1];
      const std::uint32_t offset = next >> kBucketShift == k ? next & kLowMask : kLowMask + 1;  // in this bucket, or never
      entries[k] = static_cast<std::uint32_t>(code) << kStepBits | offset;
    }
  }
};

const EncodingTable& encodingTable() {
  static const EncodingTable table;
  return table;
}

}  // namespace

std::uint8_t encodeSrgb8(float linear) {
  const EncodingTable& table = encodingTable();
  if (!(linear > 0.0f)) return 0;  // also NaN, which would be a bug upstream: never write garbage
  if (linear >= 1.0f) return 255;
  const std::uint32_t bits = std::bit_cast<std::uint32_t>(linear);
  const std::uint32_t entry = table.entries[bits >> kBucketShift];
  return static_cast<std::uint8_t>((entry >> kStepBits) + ((bits & kLowMask) >= (entry & kStepMask) ? 1 : 0));
}

void encodeSrgb8(const glm::vec3* pixels, std::size_t count, int channels, std::uint8_t* out) {
#if defined(__AVX2__)
  // 8 pixels at a time: their 24 floats, whatever the channel, through the same table (a value
  // clamped to [0, 1], NaN to 0, lands in bucket 0 or the last, whose codes are 0 and 255).
  const EncodingTable& table = encodingTable();
  for (; count >= 8; count -= 8, pixels += 8, out += 8 * channels) {
    const float* values = &pixels[0].x;
    __m256i codes[3];  // the 24 values' codes in order (r0 g0 b0 r1 ...), one per 32-bit lane
    for (int k = 0; k < 3; ++k) {
      const __m256 clamped = _mm256_min_ps(_mm256_max_ps(_mm256_loadu_ps(values + 8 * k), _mm256_setzero_ps()), _mm256_set1_ps(1.0f));
      const __m256i bits = _mm256_castps_si256(clamped);
      const __m256i entry = _mm256_i32gather_epi32(reinterpret_cast<const int*>(table.entries.data()),
                                                   _mm256_srli_epi32(bits, kBucketShift), 4);
      const __m256i low = _mm256_and_si256(bits, _mm256_set1_epi32(static_cast<int>(kLowMask)));
      const __m256i step = _mm256_and_si256(entry, _mm256_set1_epi32(static_cast<int>(kStepMask)));
      const __m256i reached = _mm256_cmpgt_epi32(step, low);  // all ones (−1) while the step is not reached
      codes[k] = _mm256_add_epi32(_mm256_srli_epi32(entry, kStepBits), _mm256_add_epi32(reached, _mm256_set1_epi32(1)));
    }
    // Narrowed to bytes: the packs work within 128-bit halves, leaving the 4-byte groups
    // [c0 0-3, c1 0-3, c2 0-3, c2 0-3 | c0 4-7, c1 4-7, c2 4-7, c2 4-7]; put them back in order.
    const __m256i words = _mm256_packus_epi32(codes[0], codes[1]), lastWords = _mm256_packus_epi32(codes[2], codes[2]);
    const __m256i grouped = _mm256_packus_epi16(words, lastWords);
    if (channels == 3) {
      const __m256i bytes = _mm256_permutevar8x32_epi32(grouped, _mm256_setr_epi32(0, 4, 1, 5, 2, 6, 3, 7));
      _mm_storeu_si128(reinterpret_cast<__m128i*>(out), _mm256_castsi256_si128(bytes));
      _mm_storel_epi64(reinterpret_cast<__m128i*>(out + 16), _mm256_extracti128_si256(bytes, 1));
    } else {
      // Pixels 0-3 from bytes 0-11 in the low half, pixels 4-7 from bytes 12-23 in the high half; an
      // opaque alpha byte after each three.
      const __m256i halves = _mm256_permutevar8x32_epi32(grouped, _mm256_setr_epi32(0, 4, 1, 5, 5, 2, 6, 3));
      const __m256i spread = _mm256_shuffle_epi8(
          halves, _mm256_setr_epi8(0, 1, 2, -1, 3, 4, 5, -1, 6, 7, 8, -1, 9, 10, 11, -1, 0, 1, 2, -1, 3, 4, 5, -1, 6, 7, 8,
                                   -1, 9, 10, 11, -1));
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(out),
                          _mm256_or_si256(spread, _mm256_set1_epi32(static_cast<int>(0xFF000000u))));
    }
  }
#endif
  for (std::size_t i = 0; i < count; ++i, out += channels) {
    out[0] = encodeSrgb8(pixels[i].x);
    out[1] = encodeSrgb8(pixels[i].y);
    out[2] = encodeSrgb8(pixels[i].z);
    if (channels == 4) out[3] = 255;
  }
}

void toSrgb8(const Image& image, int channels, std::vector<std::uint8_t>& bytes) {
  const std::size_t width = static_cast<std::size_t>(std::max(image.width, 0));
  bytes.resize(image.pixels.size() * static_cast<std::size_t>(channels));
  const auto encodeRows = [&](const tbb::blocked_range<int>& rows) {
    for (int row = rows.begin(); row < rows.end(); ++row) {
      const std::size_t first = static_cast<std::size_t>(row) * width;
      encodeSrgb8(image.pixels.data() + first, width, channels, bytes.data() + first * static_cast<std::size_t>(channels));
    }
  };
  tbb::parallel_for(tbb::blocked_range<int>(0, std::max(image.height, 0), 16), encodeRows);
}

std::vector<std::uint8_t> toSrgb8(const Image& image) {
  std::vector<std::uint8_t> bytes;
  toSrgb8(image, 3, bytes);
  return bytes;
}

void writePng(const Image& image, const std::string& path) {
  if (image.width <= 0 || image.height <= 0) throw std::runtime_error("cannot write an empty image to " + path);
  const std::vector<std::uint8_t> rgb = toSrgb8(image);
  std::vector<std::uint8_t> png;
  if (!stbi_write_png_to_func(appendBytes, &png, image.width, image.height, 3, rgb.data(), image.width * 3))
    throw std::runtime_error("cannot encode a PNG for " + path);

  writeFileAtomically(path, png.data(), png.size());  // readers see the old file or the whole new one
}

Image readPng(const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) throw std::runtime_error("cannot read '" + path + "': " + std::strerror(errno));
  unsigned char signature[8] = {};
  const std::size_t read = std::fread(signature, 1, sizeof signature, file);
  static const unsigned char kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (read != sizeof signature || std::memcmp(signature, kPngSignature, sizeof signature) != 0) {
    std::fclose(file);
    throw std::runtime_error("'" + path + "' is not a PNG file");
  }
  std::rewind(file);
  int width = 0, height = 0, channels = 0;
  unsigned char* data = stbi_load_from_file(file, &width, &height, &channels, 3);
  std::fclose(file);
  if (!data) throw std::runtime_error("cannot decode '" + path + "': " + stbi_failure_reason());
  Image image;
  image.resize(width, height);
  float table[256];
  for (int i = 0; i < 256; ++i) table[i] = srgbToLinear(static_cast<float>(i) / 255.0f);
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    image.pixels[i] = {table[data[3 * i]], table[data[3 * i + 1]], table[data[3 * i + 2]]};
  stbi_image_free(data);
  return image;
}

}  // namespace slime

namespace slime {

void writePfm(const Image& image, const std::string& path) {
  if (image.width <= 0 || image.height <= 0) throw std::runtime_error("cannot write an empty image to " + path);
  static_assert(std::endian::native == std::endian::little, "the PFM header below says little endian");
  static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "a row of pixels is copied as floats");
  const std::string header = "PF\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n-1.0\n";
  std::vector<std::uint8_t> bytes(header.begin(), header.end());
  const std::size_t row = static_cast<std::size_t>(image.width) * 3 * sizeof(float);
  bytes.resize(header.size() + row * static_cast<std::size_t>(image.height));
  for (int y = 0; y < image.height; ++y)  // PFM's rows run bottom to top
    std::memcpy(bytes.data() + header.size() + row * static_cast<std::size_t>(image.height - 1 - y),
                &image.at(0, y).x, row);
  writeFileAtomically(path, bytes.data(), bytes.size());
}

Image readPfm(const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) throw std::runtime_error("cannot read '" + path + "': " + std::strerror(errno));
  char magic[3] = {};
  int width = 0, height = 0;
  double scale = 0.0;
  const bool headerRead = std::fscanf(file, "%2s %d %d %lf", magic, &width, &height, &scale) == 4;
  if (!headerRead || std::strcmp(magic, "PF") != 0 || width <= 0 || height <= 0 || width > 65536 || height > 65536 ||
      scale == 0.0 || std::fgetc(file) == EOF) {
    std::fclose(file);
    throw std::runtime_error("'" + path + "' is not a colour PFM (\"PF\", width, height, scale, then floats)");
  }
  Image image;
  image.resize(width, height);
  const std::size_t count = static_cast<std::size_t>(width) * 3;
  std::vector<std::uint32_t> words(count);
  for (int y = height - 1; y >= 0; --y) {
    if (std::fread(words.data(), sizeof(std::uint32_t), count, file) != count) {
      std::fclose(file);
      throw std::runtime_error("'" + path + "' ends before its " + std::to_string(width) + "x" + std::to_string(height) +
                               " pixels");
    }
    if ((scale < 0.0) != (std::endian::native == std::endian::little))
      for (std::uint32_t& word : words) word = __builtin_bswap32(word);
    std::memcpy(&image.at(0, y).x, words.data(), count * sizeof(float));
  }
  std::fclose(file);
  return image;
}

}  // namespace slime

#include "render/image_io.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <unistd.h>

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

std::vector<std::uint8_t> toSrgb8(const Image& image) {
  std::vector<std::uint8_t> bytes(image.pixels.size() * 3);
  auto encode = [](float linear) {
    if (!(linear == linear)) linear = 0.0f;  // NaN would be a bug upstream; never write garbage
    return static_cast<std::uint8_t>(std::lround(linearToSrgb(linear) * 255.0f));
  };
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    bytes[3 * i + 0] = encode(image.pixels[i].x);
    bytes[3 * i + 1] = encode(image.pixels[i].y);
    bytes[3 * i + 2] = encode(image.pixels[i].z);
  }
  return bytes;
}

void writePng(const Image& image, const std::string& path) {
  if (image.width <= 0 || image.height <= 0) throw std::runtime_error("cannot write an empty image to " + path);
  const std::vector<std::uint8_t> rgb = toSrgb8(image);
  std::vector<std::uint8_t> png;
  if (!stbi_write_png_to_func(appendBytes, &png, image.width, image.height, 3, rgb.data(), image.width * 3))
    throw std::runtime_error("cannot encode a PNG for " + path);

  // Write beside the target, then rename: readers see the old file or the whole new one.
  const std::string temporary = path + ".tmp" + std::to_string(::getpid());
  std::FILE* file = std::fopen(temporary.c_str(), "wb");
  if (!file) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
  const bool written = std::fwrite(png.data(), 1, png.size(), file) == png.size();
  const bool closed = std::fclose(file) == 0;
  if (!written || !closed) {
    const int error = errno;
    std::remove(temporary.c_str());
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(error));
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    const int error = errno;
    std::remove(temporary.c_str());
    throw std::runtime_error("cannot write " + path + ": " + std::strerror(error));
  }
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

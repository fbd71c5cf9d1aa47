#include "irradiance/io/rgba16f_cube.h"

#include <algorithm>
#include <cmath>

#include <Imath/half.h>

namespace vs11::irradiance {

namespace {

constexpr int kChannels = 4;
constexpr float kOpaque = 1.0f;

float ClampToHalfRange(float value) {
  return std::isnan(value) ? value : std::clamp(value, -kHalfMax, kHalfMax);
}

}  // namespace

std::vector<std::uint8_t> Rgba16fFaceBytes(const CubeMap& cube) {
  const std::size_t texels_per_face = static_cast<std::size_t>(cube.face_size) * cube.face_size;
  std::vector<float> floats;
  floats.reserve(kCubeFaceCount * texels_per_face * kChannels);
  for (const Image& face : cube.faces) {
    for (const glm::vec3& texel : face.pixels) {
      floats.insert(floats.end(), {ClampToHalfRange(texel.r), ClampToHalfRange(texel.g),
                                   ClampToHalfRange(texel.b), kOpaque});
    }
  }
  std::vector<std::uint16_t> halfs(floats.size());
  for (std::size_t i = 0; i < floats.size(); ++i) halfs[i] = imath_float_to_half(floats[i]);
  std::vector<std::uint8_t> bytes;
  bytes.reserve(halfs.size() * 2);
  for (std::uint16_t half : halfs) {  // little-endian whatever the host
    bytes.push_back(static_cast<std::uint8_t>(half & 0xFF));
    bytes.push_back(static_cast<std::uint8_t>(half >> 8));
  }
  return bytes;
}

std::size_t CountBeyondHalfRange(const CubeMap& cube) {
  std::size_t count = 0;
  for (const Image& face : cube.faces) {
    for (const glm::vec3& texel : face.pixels) {
      for (int c = 0; c < 3; ++c) count += std::abs(texel[c]) > kHalfMax ? 1 : 0;
    }
  }
  return count;
}

void LittleEndianBytes::U32(std::uint32_t value) {
  for (int shift = 0; shift < 32; shift += 8) out_.push_back(static_cast<std::uint8_t>(value >> shift));
}

void LittleEndianBytes::U64(std::uint64_t value) {
  for (int shift = 0; shift < 64; shift += 8) out_.push_back(static_cast<std::uint8_t>(value >> shift));
}

void LittleEndianBytes::Bytes(std::span<const std::uint8_t> bytes) {
  out_.insert(out_.end(), bytes.begin(), bytes.end());
}

void LittleEndianBytes::ZerosUntilMultipleOf(std::size_t alignment) {
  while (out_.size() % alignment != 0) out_.push_back(0);
}

}  // namespace vs11::irradiance

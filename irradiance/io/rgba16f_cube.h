// A cube map as the texel bytes GPU texture containers hold for an RGBA16F cube (DXGI
// R16G16B16A16_FLOAT, Vulkan R16G16B16A16_SFLOAT): the six faces in D3DCUBEMAP_FACES order
// (+x -x +y -y +z -z, the order of DDS and of KTX2 alike), each face top row first and each row
// left to right as cube_map.h orients it, four little-endian IEEE 754 half floats per texel with
// alpha 1. DDS and KTX2 share this face table (KTX2: "+Y up, +Z forward, +X on the right, rd").
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "irradiance/io/cube_map.h"

namespace vs11::irradiance {

inline constexpr int kRgba16fTexelBytes = 8;  // 4 channels x 2 bytes
// The largest finite half (2^15 x (2 - 2^-10)); a larger value would round to infinity.
inline constexpr float kHalfMax = 65504.0f;

// The texel bytes of every face (6 x face_size^2 x 8 bytes). Values beyond +-kHalfMax are clamped to
// it (CountBeyondHalfRange says how many, for a warning); NaN stays NaN. Rounding to half is
// OpenImageIO's (Imath's, to nearest even).
std::vector<std::uint8_t> Rgba16fFaceBytes(const CubeMap& cube);

// How many colour values (texels x channels) of `cube` lie beyond +-kHalfMax.
std::size_t CountBeyondHalfRange(const CubeMap& cube);

// Appends little-endian words to a byte vector: the one byte order both containers use.
class LittleEndianBytes {
 public:
  explicit LittleEndianBytes(std::vector<std::uint8_t>& out) : out_(out) {}
  void U32(std::uint32_t value);
  void U64(std::uint64_t value);
  void Bytes(std::span<const std::uint8_t> bytes);
  void ZerosUntilMultipleOf(std::size_t alignment);  // pads the whole vector's size
  std::size_t size() const { return out_.size(); }

 private:
  std::vector<std::uint8_t>& out_;
};

}  // namespace vs11::irradiance

// DDS files built byte by byte from the DirectDraw Surface reference (DDS_HEADER, DDS_PIXELFORMAT,
// DDS_HEADER_DXT10) and the BC6H format reference, independently of the code under test: headers of
// any format, BC6H mode-11 blocks, and cube maps of random blocks (every bit pattern of a BC1-BC7
// block decodes to something, so random blocks are valid files of those formats).
#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "tests/irradiance/io/environment_test_support.h"

namespace vs11::irradiance::envtest {

constexpr std::uint32_t kDdsdMipMapCount = 0x20000;

constexpr std::uint32_t kDx10MiscTextureCube = 0x4;
constexpr std::uint32_t kDx10Texture2D = 3;
constexpr std::uint32_t kDx10Texture3D = 4;
constexpr std::uint32_t kAllFaceBits = 0xfc00;
constexpr std::uint32_t kD3dFmtA16B16G16R16F = 113;
// DXGI_FORMAT codes.
constexpr std::uint32_t kDxgiRgba32Float = 2;
constexpr std::uint32_t kDxgiRgb32Float = 6;
constexpr std::uint32_t kDxgiRgba16Float = 10;
constexpr std::uint32_t kDxgiR11G11B10Float = 26;
constexpr std::uint32_t kDxgiRgb9e5 = 67;
constexpr std::uint32_t kDxgiBc6hUf16 = 95;
constexpr std::uint32_t kDxgiBc6hSf16 = 96;
constexpr std::uint32_t kFourCcDx10 = 0x30315844;  // "DX10"
constexpr std::uint32_t kFourCcDxt1 = 0x31545844;  // "DXT1"

// Every field of a DDS header that these tests vary.
struct DdsFields {
  std::uint32_t width = 2;
  std::uint32_t height = 2;
  std::uint32_t header_size = kDdsHeaderSize;
  std::uint32_t mip_count = 1;
  std::uint32_t caps2 = 0;
  std::uint32_t four_cc = 0;  // with DDPF_FOURCC; "DX10" adds the DX10 header below
  std::uint32_t dxgi_format = 0;
  std::uint32_t dx10_misc = 0;
  std::uint32_t dx10_dimension = kDx10Texture2D;
  std::uint32_t dx10_array_size = 1;
};

inline std::string DdsBytes(const DdsFields& f) {
  std::string bytes;
  Append(bytes, kDdsMagic);
  Append(bytes, f.header_size);
  Append(bytes, kDdsdCapsHeightWidthPixelFormat | kDdsdMipMapCount);
  Append(bytes, f.height);
  Append(bytes, f.width);
  Append(bytes, std::uint32_t{0});  // pitch or linear size: readers compute it
  Append(bytes, std::uint32_t{0});  // depth
  Append(bytes, f.mip_count);
  for (int i = 0; i < 11; ++i) Append(bytes, std::uint32_t{0});
  Append(bytes, kDdsPixelFormatSize);
  Append(bytes, kDdpfFourCc);
  Append(bytes, f.four_cc);
  for (int i = 0; i < 5; ++i) Append(bytes, std::uint32_t{0});  // bit count, masks
  Append(bytes, kDdsCapsComplexTexture);
  Append(bytes, f.caps2);
  for (int i = 0; i < 3; ++i) Append(bytes, std::uint32_t{0});
  if (f.four_cc == kFourCcDx10) {
    for (std::uint32_t word :
         {f.dxgi_format, f.dx10_dimension, f.dx10_misc, f.dx10_array_size, std::uint32_t{0}}) {
      Append(bytes, word);
    }
  }
  return bytes;
}

inline DdsFields Dx10Cube(std::uint32_t size, std::uint32_t dxgi_format) {
  DdsFields f;
  f.width = f.height = size;
  f.four_cc = kFourCcDx10;
  f.dxgi_format = dxgi_format;
  f.dx10_misc = kDx10MiscTextureCube;
  f.caps2 = kDdsCaps2Cubemap | kAllFaceBits;  // as DirectXTex writes them too
  return f;
}

inline DdsFields LegacyCube(std::uint32_t size, std::uint32_t four_cc) {
  DdsFields f;
  f.width = f.height = size;
  f.four_cc = four_cc;
  f.caps2 = kDdsCaps2Cubemap | kAllFaceBits;
  return f;
}

// FourCC codes of the legacy header, as the little-endian word of their four letters.
constexpr std::uint32_t FourCcCode(const char (&code)[5]) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(code[0])) |
         static_cast<std::uint32_t>(static_cast<unsigned char>(code[1])) << 8 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(code[2])) << 16 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(code[3])) << 24;
}

// A DDS file of `fields`' format holding `faces` images of `block_bytes`-byte blocks of random bits.
inline std::string RandomBlockDds(const DdsFields& fields, int block_bytes, unsigned seed, int faces = 6) {
  std::string bytes = DdsBytes(fields);
  const std::size_t blocks_per_face = ((fields.width + 3) / 4) * ((fields.height + 3) / 4);
  std::mt19937 random(seed);
  for (std::size_t i = 0; i < faces * blocks_per_face * block_bytes; ++i) {
    bytes.push_back(static_cast<char>(random() & 0xff));
  }
  return bytes;
}

// BC6H mode 11 (mode bits 00011): one region, endpoints stored directly with 10 bits per channel,
// then sixteen 4-bit indices, the first (anchor) with its top bit implied 0 (so indices[0] < 8).
inline std::array<std::uint8_t, 16> PackBc6hMode11(const std::array<int, 3>& e0, const std::array<int, 3>& e1,
                                                   const std::array<int, 16>& indices) {
  std::array<std::uint8_t, 16> block{};
  int position = 0;
  const auto put_bits = [&](std::uint32_t value, int count) {
    for (int i = 0; i < count; ++i, ++position) {
      if ((value >> i) & 1) block[position / 8] |= static_cast<std::uint8_t>(1 << (position % 8));
    }
  };
  put_bits(0b00011, 5);
  for (const std::array<int, 3>& endpoint : {e0, e1}) {
    for (int c = 0; c < 3; ++c) put_bits(endpoint[c] & 0x3ff, 10);
  }
  for (int i = 0; i < 16; ++i) put_bits(indices[i], i == 0 ? 3 : 4);
  EXPECT_EQ(position, 128);
  return block;
}

// An unsigned BC6H (DXGI BC6H_UF16) cube map of a sky-like radiance: a bright lobe toward `sun`
// over a dim base, one mode-11 block per 4 x 4 texels with the block's endpoints taken from the
// radiance at its centre and the indices a ramp, so that files of different suns and sizes differ.
inline std::string SkyBc6hCube(int face_size, glm::dvec3 sun) {
  constexpr int kMaxUnsignedEndpoint = 1022;  // 1023 unquantises to the largest half, 65504
  std::string bytes = DdsBytes(Dx10Cube(static_cast<std::uint32_t>(face_size), kDxgiBc6hUf16));
  sun = glm::normalize(sun);
  for (CubeFace face : kAllCubeFaces) {
    for (int by = 0; by < face_size; by += 4) {
      for (int bx = 0; bx < face_size; bx += 4) {
        const double facing = glm::dot(TexelDirection(face, bx + 2, by + 2, face_size), sun);
        const double level = 0.2 + 0.8 * std::pow(0.5 * (1.0 + facing), 8.0);
        std::array<int, 3> e0;
        std::array<int, 3> e1;
        const glm::dvec3 tint(1.0, 0.8, 0.6);
        for (int c = 0; c < 3; ++c) {
          e1[c] = static_cast<int>(kMaxUnsignedEndpoint * level * tint[c]);
          e0[c] = e1[c] * 7 / 8;
        }
        std::array<int, 16> indices;
        for (int i = 0; i < 16; ++i) indices[i] = (i % 4 + i / 4) * 2 + (i == 0 ? 0 : 1);
        const std::array<std::uint8_t, 16> block = PackBc6hMode11(e0, e1, indices);
        bytes.append(reinterpret_cast<const char*>(block.data()), block.size());
      }
    }
  }
  return bytes;
}

}  // namespace vs11::irradiance::envtest

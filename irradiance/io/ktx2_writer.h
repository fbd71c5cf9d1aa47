// A cube map as a KTX 2.0 file (Khronos KTX File Format Specification 2.0): one level of
// VK_FORMAT_R16G16B16A16_SFLOAT, six faces, no supercompression. The layout, all little-endian:
//
//   offset  0  identifier  AB 4B 54 58 20 32 30 BB 0D 0A 1A 0A ("«KTX 20»\r\n\x1A\n")
//          12  vkFormat 97, typeSize 2, pixelWidth = pixelHeight = face size, pixelDepth 0,
//              layerCount 0, faceCount 6, levelCount 1, supercompressionScheme 0
//          48  index: dfdByteOffset 104, dfdByteLength 92, kvdByteOffset 196, kvdByteLength,
//              sgdByteOffset 0 and sgdByteLength 0 (UInt64: no supercompression global data)
//          80  level index: byteOffset, byteLength = uncompressedByteLength = 6 x size^2 x 8
//         104  Data Format Descriptor: dfdTotalSize 92, then one basic descriptor block (Khronos Data
//              Format Specification) of 88 bytes: vendorId 0 (Khronos) / descriptorType 0 (basic);
//              versionNumber 2 / descriptorBlockSize 88; colorModel RGBSDA (1), colorPrimaries
//              BT709 (1), transferFunction LINEAR (1), flags ALPHA_STRAIGHT (0);
//              texelBlockDimension0..3 all 0 (1x1x1x1); bytesPlane0 8, bytesPlane1..7 0; four
//              samples R, G, B, A (channel ids 0, 1, 2, 15) with qualifiers FLOAT | SIGNED (0xC0),
//              bitOffset 0, 16, 32, 48, bitLength 15 (16 bits), samplePosition 0, sampleLower -1.0f
//              (0xBF800000) and sampleUpper 1.0f (0x3F800000), as for every SFLOAT format
//         196  key/value data: one pair, KTXwriter = "vs11 irrmap" (NUL-terminated key and value),
//              padded to 4 bytes
//              mipPadding to lcm(texel block size 8, 4) = 8
//              level 0: faces +X -X +Y -Y +Z -Z, each top row first (orientation "rd", which a
//              cube map must have), texels as rgba16f_cube.h packs them
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "irradiance/io/cube_map.h"
#include "vm/core/result.h"

namespace vs11::irradiance {

inline constexpr std::string_view kKtx2WriterName = "vs11 irrmap";

// The whole file. Precondition (asserted): cube.face_size > 0.
std::vector<std::uint8_t> EncodeKtx2CubeRgba16f(const CubeMap& cube);

// Writes it atomically (vm/core/atomic_file.h): success, or the error saying what failed.
Status WriteKtx2Cube(const CubeMap& cube, const std::filesystem::path& path);

}  // namespace vs11::irradiance

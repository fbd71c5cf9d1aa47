// A cube map as a KTX 1.1 file (Khronos KTX File Format Specification 1.1), the container Filament's
// ktxreader (Ktx1Bundle, Ktx1Reader::createTexture) loads cube maps from and cmgen writes: one level of
// RGBA16F, six faces, no key/value data. All little-endian:
//
//   offset  0  identifier AB 4B 54 58 20 31 31 BB 0D 0A 1A 0A ("«KTX 11»\r\n\x1A\n")
//          12  endianness 0x04030201; glType HALF_FLOAT (0x140B); glTypeSize 2; glFormat RGBA
//              (0x1908); glInternalFormat RGBA16F (0x881A); glBaseInternalFormat RGBA (0x1908);
//              pixelWidth = pixelHeight = face size; pixelDepth 0; numberOfArrayElements 0;
//              numberOfFaces 6; numberOfMipmapLevels 1; bytesOfKeyValueData 0
//          64  imageSize: the bytes of one face (size^2 x 8; a non-array cube map counts per face)
//          68  faces +X -X +Y -Y +Z -Z, each top row first, texels as rgba16f_cube.h packs them; a
//              face is a multiple of 4 bytes, so no cubePadding
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "irradiance/io/cube_map.h"
#include "vm/core/result.h"

namespace vs11::irradiance {

// The whole file, `cube` as it is. Precondition (asserted): cube.face_size > 0.
std::vector<std::uint8_t> EncodeKtx1CubeRgba16f(const CubeMap& cube);

// Writes it atomically (vm/core/atomic_file.h): success, or the error saying what failed.
Status WriteKtx1Cube(const CubeMap& cube, const std::filesystem::path& path);

// `cube` mirrored in x, L'(x, y, z) = L(-x, y, z): faces +x and -x swapped and every face flipped left
// to right, what cmgen does to every cube it writes unless given --no-mirror.
CubeMap MirroredInX(const CubeMap& cube);

}  // namespace vs11::irradiance

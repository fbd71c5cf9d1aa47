// A cube map as a DirectDraw Surface file the way Direct3D 10+ and DirectXTex load one: the magic
// "DDS ", DDS_HEADER (124 bytes) with a "DX10" FourCC, DDS_HEADER_DXT10 (20 bytes), then level 0 of
// the six faces (rgba16f_cube.h). Every field as Microsoft's DDS reference defines it:
//
//   DDS_HEADER  dwSize 124; dwFlags CAPS | HEIGHT | WIDTH | PITCH | PIXELFORMAT | MIPMAPCOUNT
//               (0x1 | 0x2 | 0x4 | 0x8 | 0x1000 | 0x20000); dwHeight = dwWidth = face size;
//               dwPitchOrLinearSize = face size x 8 (bytes per row); dwDepth 0; dwMipMapCount 1;
//               dwReserved1[11] 0; ddspf {dwSize 32, dwFlags DDPF_FOURCC (0x4), dwFourCC "DX10",
//               bit counts and masks 0}; dwCaps TEXTURE | COMPLEX (0x1000 | 0x8); dwCaps2 CUBEMAP and
//               all six faces (0x200 | 0xFC00); dwCaps3, dwCaps4, dwReserved2 0
//   DXT10       dxgiFormat DXGI_FORMAT_R16G16B16A16_FLOAT (10); resourceDimension TEXTURE2D (3);
//               miscFlag DDS_RESOURCE_MISC_TEXTURECUBE (0x4); arraySize 1 (one cube);
//               miscFlags2 DDS_ALPHA_MODE_OPAQUE (3: alpha is 1 everywhere)
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "irradiance/io/cube_map.h"
#include "vm/core/result.h"

namespace vs11::irradiance {

// The whole file. Precondition (asserted): cube.face_size > 0.
std::vector<std::uint8_t> EncodeDdsCubeRgba16f(const CubeMap& cube);

// Writes it atomically (vm/core/atomic_file.h): success, or the error saying what failed.
Status WriteDdsCube(const CubeMap& cube, const std::filesystem::path& path);

}  // namespace vs11::irradiance

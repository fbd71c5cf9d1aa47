// The DirectDraw Surface (DDS) container as far as environment maps need it, beside OpenImageIO:
//
// - Every DDS file's size is checked against what its header implies before any pixel is read,
//   so that a truncated file is reported as such (OpenImageIO 2.4's read_image succeeds on a short
//   file, only recording an error) and a header claiming a huge image allocates nothing. Volumes
//   and texture arrays are refused.
// - The uncompressed float formats OpenImageIO 2.4 refuses ("Unsupported compression type") are
//   read here: DXGI R32G32B32A32_FLOAT, R32G32B32_FLOAT, R16G16B16A16_FLOAT, R11G11B10_FLOAT and
//   R9G9B9E5_SHAREDEXP in a DX10 header, and the legacy D3DFMT codes A32B32G32R32F (116) and
//   A16B16G16R16F (113) as FourCC. Only mip level 0 is read; alpha is dropped.
// - Premultiplied-alpha DXT2 and DXT4 are refused (OpenImageIO 2.4.7 divides by their alpha and
//   crashes on a texel whose alpha is 0).
// - Everything else (8-bit RGB(A), BC1-BC5, BC6H unsigned and signed, BC7, ...) is left to
//   OpenImageIO, which decodes it (its BC6H output is checked bit for bit in dds_reader_test.cc).
//   OpenImageIO finds a cube map by the legacy caps2 flags only, so a DX10 cube map of such a
//   format without them is refused rather than read as its first face.
//
// Reading is in two steps, so that the caller can apply its own rules (environment_io.cc: cube
// maps have six square faces) between them: ReadDdsHeader parses and validates, ReadDdsPixels
// decodes.
//
// A cube map comes out as OpenImageIO presents one: its six faces stacked top to bottom in the
// order +x -x +y -y +z -z (a vertical strip), each face top row first as stored.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "irradiance/io/cube_map.h"
#include "vm/core/result.h"

namespace vs11::irradiance {

// How texels are stored: uncompressed with `bytes` per pixel, or in 4 x 4 blocks of `bytes`, and
// who decodes them.
enum class DdsDecoder { kOpenImageIo, kFloat32, kHalf, kR11G11B10, kRgb9e5 };
struct DdsFormat {
  std::string_view name;
  int bytes;
  bool block_compressed;
  DdsDecoder decoder;
  int channels;  // stored channels, for kFloat32 and kHalf
};

// The magic (4 bytes), DDS_HEADER (124) and DDS_HEADER_DXT10 (20).
inline constexpr std::size_t kDdsMaxHeaderBytes = 4 + 124 + 20;

// What a DDS header says, once it has been read and checked against the container's own rules
// (ReadDdsHeader). Whether the image makes an environment map (a cube map with six square faces)
// is the caller's question: `is_cube_map` and `faces` say what the file holds.
struct DdsFileHeader {
  std::uint64_t width = 0;  // of level 0 (of each face)
  std::uint64_t height = 0;
  bool is_cube_map = false;  // flagged as a cube map, in the DX10 or the legacy header
  std::uint64_t faces = 1;   // images stored: 1, or the cube faces flagged (0 to 6)
  std::uint32_t cube_face_flags = 0;  // the legacy caps2 face bits (DDSCAPS2_CUBEMAP_POSITIVEX ..)
  bool volume_or_array = false;  // accepted only in a format OpenImageIO decodes (it reports on it)
  std::optional<DdsFormat> format;  // nullopt: a format whose size is not known here
  std::uint64_t mip_count = 1;
  std::uint64_t data_offset = 0;   // where the first face's level 0 starts
  std::uint64_t chain_bytes = 0;   // one face's whole mip chain: the distance between faces
  std::uint64_t level0_bytes = 0;  // one face's level 0
  // The magic, DDS_HEADER and, if present, DDS_HEADER_DXT10, as stored (data_offset bytes).
  std::array<unsigned char, kDdsMaxHeaderBytes> raw{};
};

// What ReadDdsPixels leaves to OpenImageIO, or the pixels it read.
struct DdsPixels {
  std::optional<Image> image;  // read here: linear RGB, the faces stacked top to bottom
  // Else, for a cube map of six faces that stack into one plain image (a multiple of 4 texels for
  // block-compressed formats): a DDS file in memory holding level 0 of the six faces as one image
  // six faces high, for OpenImageIO to read in place of the file. OpenImageIO 2.4 reads a cube map
  // by faces with process-wide state, so that two read at once swap faces (issue 18); a plain image
  // it reads in one piece, safely beside other reads. Empty: OpenImageIO reads the file.
  std::vector<unsigned char> stacked_faces;
};

// Reads and checks the header of `path`: its size fields, the mip chain, the pixel format (the
// unsupported and the crashing ones refused), volumes and arrays, and that the file is long enough
// for level 0 of every face. `max_pixels` bounds width x height x faces; larger headers are errors,
// nothing is allocated. nullopt when the file does not start with the DDS magic "DDS "; errors
// (kCannotReadFile) say what is wrong without the file name.
Result<std::optional<DdsFileHeader>> ReadDdsHeader(const std::filesystem::path& path, std::size_t max_pixels);

// Reads level 0 of every face `header` (from ReadDdsHeader on the same file) describes, or says
// that OpenImageIO should (with the faces stacked in memory when it is a cube map of six faces); an
// error (kCannotReadFile, without the file name) when the pixels cannot be read.
Result<DdsPixels> ReadDdsPixels(const std::filesystem::path& path, const DdsFileHeader& header);

}  // namespace vs11::irradiance

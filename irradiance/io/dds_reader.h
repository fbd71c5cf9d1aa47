// The DirectDraw Surface (DDS) container as far as environment maps need it, beside OpenImageIO:
//
// - Every DDS file's size is checked against what its header implies before any pixel is read,
//   so that a truncated file is reported as such (OpenImageIO 2.4's read_image succeeds on a short
//   file, only recording an error) and a header claiming a huge image allocates nothing. Cube maps
//   must have all six faces.
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
// A cube map comes out as OpenImageIO presents one: its six faces stacked top to bottom in the
// order +x -x +y -y +z -z (a vertical strip), each face top row first as stored.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "irradiance/io/cube_map.h"

namespace vs11::irradiance {

struct DdsReadResult {
  enum class Outcome {
    kNotDds,              // the file does not start with the DDS magic "DDS "
    kLeaveToOpenImageIo,  // a DDS file in a format OpenImageIO reads, long enough if its size
                          // is known here
    kRead,                // `image` holds the pixels
    kError,               // `error` says what is wrong
  };
  Outcome outcome = Outcome::kNotDds;
  Image image;               // kRead: linear RGB
  bool is_cube_map = false;  // kRead, or kLeaveToOpenImageIo with stacked_faces: a cube map (all six faces)
  std::string error;         // kError: the problem, without the file name
  // kLeaveToOpenImageIo, for a cube map whose faces stack into one plain image (square faces, a
  // multiple of 4 texels for block-compressed formats): a DDS file in memory holding level 0 of the
  // six faces as one image six faces high, for OpenImageIO to read in place of the file. OpenImageIO
  // 2.4 reads a cube map by faces with process-wide state, so that two read at once swap faces
  // (issue 18); a plain image it reads in one piece, safely beside other reads.
  std::vector<unsigned char> stacked_faces;
};

// `max_pixels` bounds width x height x faces; larger headers are errors, nothing is allocated.
DdsReadResult ReadDds(const std::filesystem::path& path, std::size_t max_pixels);

}  // namespace vs11::irradiance

#include "irradiance/io/dds_writer.h"

#include <cassert>

#include <fmt/format.h>

#include "irradiance/io/rgba16f_cube.h"
#include "vm/core/atomic_file.h"

namespace vs11::irradiance {
namespace {

// Values from Microsoft's DDS_HEADER, DDS_PIXELFORMAT and DDS_HEADER_DXT10 reference pages.
constexpr std::uint32_t kDdsMagic = 0x20534444;  // "DDS "
constexpr std::uint32_t kHeaderSize = 124;
constexpr std::uint32_t kPixelFormatSize = 32;
constexpr std::uint32_t kDdsdCaps = 0x1;
constexpr std::uint32_t kDdsdHeight = 0x2;
constexpr std::uint32_t kDdsdWidth = 0x4;
constexpr std::uint32_t kDdsdPitch = 0x8;
constexpr std::uint32_t kDdsdPixelFormat = 0x1000;
constexpr std::uint32_t kDdsdMipMapCount = 0x20000;
constexpr std::uint32_t kDdpfFourCc = 0x4;
constexpr std::uint32_t kFourCcDx10 = 0x30315844;  // "DX10"
constexpr std::uint32_t kDdsCapsComplex = 0x8;
constexpr std::uint32_t kDdsCapsTexture = 0x1000;
constexpr std::uint32_t kDdsCaps2Cubemap = 0x200;
constexpr std::uint32_t kDdsCaps2AllFaces = 0x400 | 0x800 | 0x1000 | 0x2000 | 0x4000 | 0x8000;
constexpr int kReserved1Words = 11;
constexpr int kPixelFormatMaskWords = 5;  // dwRGBBitCount and the four masks
constexpr std::uint32_t kDxgiFormatR16G16B16A16Float = 10;
constexpr std::uint32_t kResourceDimensionTexture2d = 3;
constexpr std::uint32_t kResourceMiscTextureCube = 0x4;
constexpr std::uint32_t kAlphaModeOpaque = 3;

void AppendHeader(LittleEndianBytes& out, std::uint32_t face_size) {
  out.U32(kDdsMagic);
  out.U32(kHeaderSize);
  out.U32(kDdsdCaps | kDdsdHeight | kDdsdWidth | kDdsdPitch | kDdsdPixelFormat | kDdsdMipMapCount);
  out.U32(face_size);  // dwHeight
  out.U32(face_size);  // dwWidth
  out.U32(face_size * kRgba16fTexelBytes);  // dwPitchOrLinearSize: bytes per row
  out.U32(0);          // dwDepth
  out.U32(1);          // dwMipMapCount
  for (int i = 0; i < kReserved1Words; ++i) out.U32(0);
  out.U32(kPixelFormatSize);
  out.U32(kDdpfFourCc);
  out.U32(kFourCcDx10);
  for (int i = 0; i < kPixelFormatMaskWords; ++i) out.U32(0);
  out.U32(kDdsCapsTexture | kDdsCapsComplex);
  out.U32(kDdsCaps2Cubemap | kDdsCaps2AllFaces);
  out.U32(0);  // dwCaps3
  out.U32(0);  // dwCaps4
  out.U32(0);  // dwReserved2
  out.U32(kDxgiFormatR16G16B16A16Float);
  out.U32(kResourceDimensionTexture2d);
  out.U32(kResourceMiscTextureCube);
  out.U32(1);  // arraySize: one cube
  out.U32(kAlphaModeOpaque);
}

}  // namespace

std::vector<std::uint8_t> EncodeDdsCubeRgba16f(const CubeMap& cube) {
  assert(cube.face_size > 0);
  std::vector<std::uint8_t> file;
  LittleEndianBytes out(file);
  AppendHeader(out, static_cast<std::uint32_t>(cube.face_size));
  out.Bytes(Rgba16fFaceBytes(cube));
  return file;
}

Status WriteDdsCube(const CubeMap& cube, const std::filesystem::path& path) {
  if (cube.face_size <= 0) {
    return Failure(DiagnosticCode::kCannotWriteFile, fmt::format("{}: cannot write an empty cube map", path.string()));
  }
  return WriteFileAtomically(path, EncodeDdsCubeRgba16f(cube));
}

}  // namespace vs11::irradiance

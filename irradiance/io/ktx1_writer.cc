#include "irradiance/io/ktx1_writer.h"

#include <array>
#include <cassert>
#include <utility>

#include <fmt/format.h>

#include "irradiance/io/rgba16f_cube.h"
#include "vm/core/atomic_file.h"

namespace vs11::irradiance {
namespace {

// Values from the KTX 1.1 specification and OpenGL's enumerants (glcorearb.h).
constexpr std::array<std::uint8_t, 12> kIdentifier = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x31,
                                                      0x31, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
constexpr std::uint32_t kEndianness = 0x04030201;
constexpr std::uint32_t kGlHalfFloat = 0x140B;
constexpr std::uint32_t kGlTypeSize = 2;  // bytes of one component
constexpr std::uint32_t kGlRgba = 0x1908;
constexpr std::uint32_t kGlRgba16f = 0x881A;
constexpr std::uint32_t kCubeFaces = 6;

}  // namespace

std::vector<std::uint8_t> EncodeKtx1CubeRgba16f(const CubeMap& cube) {
  assert(cube.face_size > 0);
  const std::uint32_t size = static_cast<std::uint32_t>(cube.face_size);
  const std::vector<std::uint8_t> texels = Rgba16fFaceBytes(cube);
  std::vector<std::uint8_t> file;
  LittleEndianBytes out(file);
  out.Bytes(kIdentifier);
  for (std::uint32_t word : {kEndianness, kGlHalfFloat, kGlTypeSize, kGlRgba, kGlRgba16f, kGlRgba, size, size, 0u,
                             0u, kCubeFaces, 1u, 0u}) {
    out.U32(word);  // endianness .. bytesOfKeyValueData
  }
  out.U32(static_cast<std::uint32_t>(texels.size() / kCubeFaces));  // imageSize: one face
  out.Bytes(texels);
  return file;
}

Status WriteKtx1Cube(const CubeMap& cube, const std::filesystem::path& path) {
  if (cube.face_size <= 0) {
    return Failure(DiagnosticCode::kCannotWriteFile, fmt::format("{}: cannot write an empty cube map", path.string()));
  }
  return WriteFileAtomically(path, EncodeKtx1CubeRgba16f(cube));
}

CubeMap MirroredInX(const CubeMap& cube) {
  CubeMap mirrored = cube;
  std::swap(mirrored.face(CubeFace::kPositiveX), mirrored.face(CubeFace::kNegativeX));
  for (Image& face : mirrored.faces) {
    for (int y = 0; y < face.height; ++y) {
      for (int x = 0; x < face.width / 2; ++x) std::swap(face.at(x, y), face.at(face.width - 1 - x, y));
    }
  }
  return mirrored;
}

}  // namespace vs11::irradiance

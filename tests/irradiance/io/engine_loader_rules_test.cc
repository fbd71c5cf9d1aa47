// The irradiance map files, read the way the engines that cannot run here read them, each reader
// written in this test from the engine's own loader source (facts, not code):
//   Babylon.js, irradiance.dds: DDSTools.GetDDSInfo and UploadDDSLevels (packages/dev/core/src/Misc/
//     dds.ts): the header as 32-bit words; DDPF_FOURCC (0x4) in word 20 makes it a FourCC format;
//     word 21 "DX10" sends it to word 32 for the DXGI format, where 10 (R16G16B16A16_FLOAT) is a
//     64-bit half-float texel; word 28 & DDSCAPS2_CUBEMAP (0x200) makes a cube of six faces; levels
//     from word 7 when DDSD_MIPMAPCOUNT (0x20000) is in word 2; width word 4, height word 3; the
//     texels start at word 1 + 4 + 20 bytes, faces one after the other (+x -x +y -y +z -z, Babylon's
//     right left up down front back), each width x height x 8 bytes per level.
//   Filament, irradiance.ktx: image::Ktx1Bundle (libs/image/src/Ktx1Bundle.cpp) and
//     ktxreader::Ktx1Reader::createTexture (libs/ktxreader/src/Ktx1Reader.cpp): a 64-byte header read
//     as it lies (little-endian words after the 12-byte identifier); numberOfFaces 6 makes a cube map
//     (SAMPLER_CUBEMAP); 0 array elements and 0 levels count as 1; the key/value block is skipped by
//     bytesOfKeyValueData; each level is an imageSize word, per face for a non-array cube, then the
//     faces back to back (no cubePadding); glFormat 0 would mean compressed; glType HALF_FLOAT
//     (0x140B) -> PixelDataType::HALF, glFormat RGBA (0x1908) -> PixelDataFormat::RGBA, glInternalFormat
//     RGBA16F (0x881A) -> TextureFormat::RGBA16F.
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include <Imath/half.h>

#include "irradiance/io/cube_map.h"
#include "irradiance/io/dds_writer.h"
#include "irradiance/io/ktx1_writer.h"
#include "irradiance/io/map_file_formats.h"
#include "tests/irradiance/io/environment_test_support.h"

namespace vs11::irradiance {
namespace {

using namespace envtest;
using EngineLoaderRules = TempFolderTest;

constexpr int kFaceSize = 4;  // MakeTestCube(4)'s values are exact in half floats

std::uint32_t Word(std::span<const std::uint8_t> bytes, std::size_t at) {
  std::uint32_t value = 0;
  std::memcpy(&value, bytes.data() + at, 4);  // as the engines read it: in place, on a little-endian host
  return value;
}

float Half(std::span<const std::uint8_t> bytes, std::size_t at) {
  Imath::half half;
  half.setBits(static_cast<std::uint16_t>(bytes[at] | (bytes[at + 1] << 8)));
  return half;
}

// Every texel of six RGBA16F faces from `offset` on, face after face, rows from the top, against `cube`.
void ExpectFaces(std::span<const std::uint8_t> bytes, std::size_t offset, const CubeMap& cube) {
  for (CubeFace face : kAllCubeFaces) {
    for (int y = 0; y < kFaceSize; ++y) {
      for (int x = 0; x < kFaceSize; ++x) {
        const std::size_t at = offset + 8 * ((static_cast<std::size_t>(face) * kFaceSize + y) * kFaceSize + x);
        const glm::vec3 want = cube.face(face).at(x, y);
        for (int c = 0; c < 3; ++c) {
          EXPECT_EQ(Half(bytes, at + 2 * c), want[c]) << CubeFaceName(face) << " (" << x << ", " << y << ")";
        }
        EXPECT_EQ(Half(bytes, at + 6), 1.0f);
      }
    }
  }
}

TEST_F(EngineLoaderRules, BabylonDdsToolsReadsTheDdsAsAHalfFloatCube) {
  const CubeMap cube = MakeTestCube(kFaceSize);
  const std::vector<std::uint8_t> file = EncodeDdsCubeRgba16f(cube);
  ASSERT_GE(file.size(), 148u);
  auto word = [&](int index) { return Word(file, 4 * static_cast<std::size_t>(index)); };
  EXPECT_EQ(word(0), 0x20534444u);                     // DDS_MAGIC
  EXPECT_NE(word(20) & 0x4, 0u);                       // isFourCC
  EXPECT_EQ(word(21), 0x30315844u);                    // FOURCC_DX10
  EXPECT_EQ(word(32), 10u);                            // DXGI_FORMAT_R16G16B16A16_FLOAT: half float, bpp 64
  EXPECT_EQ(word(28) & 0x200, 0x200u);                 // isCube
  ASSERT_NE(word(2) & 0x20000, 0u);                    // DDSD_MIPMAPCOUNT, so word 7 counts the levels
  EXPECT_EQ(word(7), 1u);
  EXPECT_EQ(word(4), static_cast<std::uint32_t>(kFaceSize));
  EXPECT_EQ(word(3), static_cast<std::uint32_t>(kFaceSize));
  const std::size_t data_offset = word(1) + 4 + 20;   // dwSize + magic + the DX10 header's 5 words
  EXPECT_EQ(data_offset, 148u);
  EXPECT_EQ(file.size(), data_offset + 6 * kFaceSize * kFaceSize * 8);
  ExpectFaces(file, data_offset, cube);
}

TEST_F(EngineLoaderRules, FilamentKtx1ReaderReadsTheKtxAsAnRgba16fCube) {
  const CubeMap cube = MakeTestCube(kFaceSize);
  ASSERT_EQ(WriteMapFile(cube, MapFileFormat::kKtx, 0, Path("irradiance.ktx")).message(), "");
  const std::string text = ReadBytes(Path("irradiance.ktx"));
  const std::vector<std::uint8_t> file(text.begin(), text.end());
  ASSERT_GE(file.size(), 68u);
  const std::uint8_t identifier[12] = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x31, 0x31, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
  EXPECT_EQ(std::memcmp(file.data(), identifier, 12), 0);
  auto field = [&](int index) { return Word(file, 12 + 4 * static_cast<std::size_t>(index)); };
  EXPECT_EQ(field(0), 0x04030201u);   // endianness: the words are read as they lie
  EXPECT_EQ(field(1), 0x140Bu);       // glType HALF_FLOAT -> PixelDataType::HALF
  EXPECT_EQ(field(2), 2u);            // glTypeSize
  EXPECT_EQ(field(3), 0x1908u);       // glFormat RGBA -> PixelDataFormat::RGBA, and not compressed (0)
  EXPECT_EQ(field(4), 0x881Au);       // glInternalFormat RGBA16F -> TextureFormat::RGBA16F
  EXPECT_EQ(field(5), 0x1908u);       // glBaseInternalFormat
  EXPECT_EQ(field(6), static_cast<std::uint32_t>(kFaceSize));
  EXPECT_EQ(field(7), static_cast<std::uint32_t>(kFaceSize));
  EXPECT_EQ(field(8), 0u);            // pixelDepth
  EXPECT_EQ(field(9), 0u);            // numberOfArrayElements: one, a non-array cube
  EXPECT_EQ(field(10), 6u);           // numberOfFaces: isCubemap, SAMPLER_CUBEMAP
  EXPECT_EQ(field(11), 1u);           // numberOfMipmapLevels
  const std::uint32_t key_value_bytes = field(12);
  const std::size_t level = 64 + key_value_bytes;
  const std::uint32_t image_size = Word(file, level);  // one face's bytes
  EXPECT_EQ(image_size, static_cast<std::uint32_t>(kFaceSize * kFaceSize * 8));
  EXPECT_EQ(file.size(), level + 4 + 6 * image_size);
  // Filament gets the cube mirrored in x, as cmgen writes every cube it makes.
  ExpectFaces(file, level + 4, MirroredInX(cube));
}

// Mirrored in x: texel (x, y) of a face holds what the input shows at direction (-dx, dy, dz).
TEST_F(EngineLoaderRules, MirroredInXShowsEachDirectionsMirrorImage) {
  const CubeMap cube = MakeTestCube(kFaceSize);
  const CubeMap mirrored = MirroredInX(cube);
  for (CubeFace face : kAllCubeFaces) {
    for (int y = 0; y < kFaceSize; ++y) {
      for (int x = 0; x < kFaceSize; ++x) {
        glm::dvec3 d = TexelDirection(face, x, y, kFaceSize);
        d.x = -d.x;
        const FacePoint source = DirectionToFace(d);  // s, t in [-1, 1] across the face, at a texel's centre
        const int sx = static_cast<int>((source.s + 1.0) / 2.0 * kFaceSize);
        const int sy = static_cast<int>((source.t + 1.0) / 2.0 * kFaceSize);
        EXPECT_EQ(mirrored.face(face).at(x, y), cube.face(source.face).at(sx, sy))
            << CubeFaceName(face) << " (" << x << ", " << y << ")";
      }
    }
  }
}

}  // namespace
}  // namespace vs11::irradiance

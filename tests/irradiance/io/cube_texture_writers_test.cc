// The irradiance cube as DDS and KTX2 files (dds_writer.h, ktx2_writer.h) and six Radiance faces
// (map_file_formats.h), read back: the DDS through vs11's own DDS reader and the environment loader,
// the KTX2 through a parser written here from the KTX 2.0 and Khronos Data Format specifications,
// every field checked against them, the faces through the six-face loader.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "irradiance/io/dds_reader.h"
#include "irradiance/io/dds_writer.h"
#include "irradiance/io/environment_io.h"
#include "irradiance/io/ktx2_writer.h"
#include "irradiance/io/map_file_formats.h"
#include "irradiance/io/rgba16f_cube.h"
#include "tests/irradiance/io/environment_test_support.h"

namespace vs11::irradiance {
namespace {

using namespace envtest;
using CubeTextureWriters = TempFolderTest;
using testing::HasSubstr;

// MakeTestCube(4)'s values have at most 11 significant bits, so half floats hold them exactly.
constexpr int kFaceSize = 4;

std::uint32_t U32(const std::vector<std::uint8_t>& bytes, std::size_t at) {
  std::uint32_t value = 0;
  for (int i = 3; i >= 0; --i) value = (value << 8) | bytes.at(at + i);
  return value;
}

std::uint64_t U64(const std::vector<std::uint8_t>& bytes, std::size_t at) {
  return U32(bytes, at) | (static_cast<std::uint64_t>(U32(bytes, at + 4)) << 32);
}

// IEEE 754 binary16 decoded by hand: sign, 5-bit exponent (bias 15), 10-bit mantissa.
float DecodeHalf(std::uint16_t bits) {
  const int sign = bits >> 15;
  const int exponent = (bits >> 10) & 0x1F;
  const int mantissa = bits & 0x3FF;
  float magnitude = 0.0f;
  if (exponent == 0) {
    magnitude = std::ldexp(static_cast<float>(mantissa), -24);
  } else if (exponent == 31) {
    magnitude = mantissa == 0 ? INFINITY : NAN;
  } else {
    magnitude = std::ldexp(static_cast<float>(1024 + mantissa), exponent - 25);
  }
  return sign ? -magnitude : magnitude;
}

// The RGBA texels stored from `offset` on, face by face, compared with `cube`; alpha must be 1.
void ExpectTexels(const std::vector<std::uint8_t>& bytes, std::size_t offset, const CubeMap& cube) {
  int failures = 0;
  std::size_t at = offset;
  for (CubeFace face : kAllCubeFaces) {
    for (int y = 0; y < cube.face_size; ++y) {
      for (int x = 0; x < cube.face_size; ++x, at += 8) {
        const glm::vec3 expected = cube.face(face).at(x, y);
        for (int c = 0; c < 4; ++c) {
          const float value = DecodeHalf(static_cast<std::uint16_t>(bytes.at(at + 2 * c) | (bytes.at(at + 2 * c + 1) << 8)));
          const float want = c < 3 ? expected[c] : 1.0f;
          if (value != want && failures++ < 10) {
            ADD_FAILURE() << CubeFaceName(face) << " (" << x << ", " << y << ") channel " << c << ": " << value
                          << " vs " << want;
          }
        }
      }
    }
  }
  EXPECT_EQ(failures, 0);
  EXPECT_EQ(at, bytes.size()) << "bytes after the last face";
}

std::vector<std::uint8_t> FileBytes(const fs::path& path) {
  const std::string text = ReadBytes(path);
  return std::vector<std::uint8_t>(text.begin(), text.end());
}

// ---- DDS --------------------------------------------------------------------------------------

// Every DDS_HEADER and DDS_HEADER_DXT10 field, at its offset in Microsoft's DDS reference.
TEST_F(CubeTextureWriters, DdsHeaderHoldsMicrosoftsValuesForAnRgba16fCube) {
  const std::vector<std::uint8_t> bytes = EncodeDdsCubeRgba16f(MakeTestCube(kFaceSize));
  ASSERT_EQ(bytes.size(), 4u + 124 + 20 + 6 * kFaceSize * kFaceSize * 8);
  EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + 4), "DDS ");
  EXPECT_EQ(U32(bytes, 4), 124u);                                  // dwSize
  EXPECT_EQ(U32(bytes, 8), 0x1u | 0x2 | 0x4 | 0x8 | 0x1000 | 0x20000);  // CAPS HEIGHT WIDTH PITCH PIXELFORMAT MIPMAPCOUNT
  EXPECT_EQ(U32(bytes, 12), static_cast<std::uint32_t>(kFaceSize));  // dwHeight
  EXPECT_EQ(U32(bytes, 16), static_cast<std::uint32_t>(kFaceSize));  // dwWidth
  EXPECT_EQ(U32(bytes, 20), static_cast<std::uint32_t>(kFaceSize * 8));  // dwPitchOrLinearSize
  EXPECT_EQ(U32(bytes, 24), 0u);  // dwDepth
  EXPECT_EQ(U32(bytes, 28), 1u);  // dwMipMapCount
  for (int i = 0; i < 11; ++i) EXPECT_EQ(U32(bytes, 32 + 4 * i), 0u) << "dwReserved1[" << i << "]";
  EXPECT_EQ(U32(bytes, 76), 32u);    // ddspf.dwSize
  EXPECT_EQ(U32(bytes, 80), 0x4u);   // ddspf.dwFlags = DDPF_FOURCC
  EXPECT_EQ(std::string(bytes.begin() + 84, bytes.begin() + 88), "DX10");
  for (int i = 0; i < 5; ++i) EXPECT_EQ(U32(bytes, 88 + 4 * i), 0u) << "bit count / mask " << i;
  EXPECT_EQ(U32(bytes, 108), 0x1000u | 0x8);  // dwCaps: TEXTURE | COMPLEX
  EXPECT_EQ(U32(bytes, 112), 0x200u | 0x400 | 0x800 | 0x1000 | 0x2000 | 0x4000 | 0x8000);  // CUBEMAP, all faces
  EXPECT_EQ(U32(bytes, 116), 0u);  // dwCaps3
  EXPECT_EQ(U32(bytes, 120), 0u);  // dwCaps4
  EXPECT_EQ(U32(bytes, 124), 0u);  // dwReserved2
  EXPECT_EQ(U32(bytes, 128), 10u);   // DXGI_FORMAT_R16G16B16A16_FLOAT
  EXPECT_EQ(U32(bytes, 132), 3u);    // D3D10_RESOURCE_DIMENSION_TEXTURE2D
  EXPECT_EQ(U32(bytes, 136), 0x4u);  // DDS_RESOURCE_MISC_TEXTURECUBE
  EXPECT_EQ(U32(bytes, 140), 1u);    // arraySize: one cube
  EXPECT_EQ(U32(bytes, 144), 3u);    // DDS_ALPHA_MODE_OPAQUE
  ExpectTexels(bytes, 148, MakeTestCube(kFaceSize));
}

TEST_F(CubeTextureWriters, DdsReadsBackThroughVs11sDdsReader) {
  const CubeMap cube = MakeTestCube(kFaceSize);
  ASSERT_EQ(WriteDdsCube(cube, Path("map.dds")).message(), "");
  const Result<std::optional<DdsFileHeader>> read_header = ReadDdsHeader(Path("map.dds"), 1 << 20);
  ASSERT_TRUE(read_header.ok() && read_header->has_value()) << read_header.message();
  const DdsFileHeader& header = **read_header;
  EXPECT_TRUE(header.is_cube_map);
  EXPECT_EQ(header.faces, 6u);
  EXPECT_EQ(header.width, static_cast<std::uint64_t>(kFaceSize));
  EXPECT_EQ(header.height, static_cast<std::uint64_t>(kFaceSize));
  EXPECT_EQ(header.mip_count, 1u);
  ASSERT_TRUE(header.format.has_value());
  EXPECT_EQ(header.format->name, "R16G16B16A16_FLOAT");
  const Result<DdsPixels> pixels = ReadDdsPixels(Path("map.dds"), header);
  ASSERT_TRUE(pixels.ok() && pixels->image.has_value()) << pixels.message();
  const Image& image = *pixels->image;
  ASSERT_EQ(image.width, kFaceSize);
  ASSERT_EQ(image.height, 6 * kFaceSize);  // the faces stacked, +x first
  for (CubeFace face : kAllCubeFaces) {
    for (int y = 0; y < kFaceSize; ++y) {
      for (int x = 0; x < kFaceSize; ++x) {
        EXPECT_EQ(image.at(x, static_cast<int>(face) * kFaceSize + y), cube.face(face).at(x, y))
            << CubeFaceName(face) << " (" << x << ", " << y << ")";
      }
    }
  }
}

TEST_F(CubeTextureWriters, DdsLoadsAsTheSameCubeThroughTheEnvironmentLoader) {
  const CubeMap cube = MakeTestCube(kFaceSize);
  ASSERT_EQ(WriteMapFile(cube, MapFileFormat::kDds, 0, Path("irradiance.dds")).message(), "");
  const Result<LoadedEnvironment> loaded = LoadEnvironment(Path("irradiance.dds"));
  ASSERT_TRUE(loaded.ok()) << loaded.message();
  EXPECT_TRUE(loaded->warnings.empty());
  ExpectCubesEqual(loaded->cube, cube);
  EXPECT_EQ(FolderContents(), std::vector<std::string>{"irradiance.dds"});  // no temporary left
}

// Values beyond the largest half become it, not infinity, and are counted for the warning.
TEST_F(CubeTextureWriters, ValuesBeyondHalfRangeAreClampedAndCounted) {
  CubeMap cube = MakeTestCube(2);
  cube.face(CubeFace::kPositiveY).at(0, 0) = glm::vec3(1e6f, -1e6f, 65504.0f);
  EXPECT_EQ(CountBeyondHalfRange(cube), 2u);
  ASSERT_EQ(WriteDdsCube(cube, Path("bright.dds")).message(), "");
  const Result<LoadedEnvironment> loaded = LoadEnvironment(Path("bright.dds"));
  ASSERT_TRUE(loaded.ok()) << loaded.message();
  // The loader clamps negatives to 0 (radiance); the stored half is checked in the bytes instead.
  EXPECT_EQ(loaded->cube.face(CubeFace::kPositiveY).at(0, 0).r, kHalfMax);
  const std::vector<std::uint8_t> bytes = FileBytes(Path("bright.dds"));
  const std::size_t texel = 148 + 2 * 4 * 8;  // +y is the third face of 2 x 2 texels
  EXPECT_EQ(DecodeHalf(static_cast<std::uint16_t>(bytes[texel + 2] | (bytes[texel + 3] << 8))), -kHalfMax);
  const std::optional<std::string> warning = MapRangeWarning(cube, MapFileFormat::kDds, "irradiance.dds");
  ASSERT_TRUE(warning.has_value());
  EXPECT_THAT(*warning, HasSubstr("irradiance.dds: 2 colour values"));
  EXPECT_EQ(MapRangeWarning(cube, MapFileFormat::kExr, "irradiance.exr"), std::nullopt);
  EXPECT_EQ(MapRangeWarning(MakeTestCube(2), MapFileFormat::kKtx2, "irradiance.ktx2"), std::nullopt);
}

// ---- KTX2 -------------------------------------------------------------------------------------

// A KTX 2.0 file as its specification lays it out, read field by field.
struct Ktx2File {
  std::vector<std::uint8_t> bytes;
  std::uint32_t Header(int field) const { return U32(bytes, 12 + 4 * field); }  // vkFormat = 0 .. scheme = 8
  std::uint32_t dfd_offset() const { return U32(bytes, 48); }
  std::uint32_t dfd_length() const { return U32(bytes, 52); }
  std::uint32_t kvd_offset() const { return U32(bytes, 56); }
  std::uint32_t kvd_length() const { return U32(bytes, 60); }
  std::uint64_t sgd_offset() const { return U64(bytes, 64); }
  std::uint64_t sgd_length() const { return U64(bytes, 72); }
  std::uint64_t LevelField(int field) const { return U64(bytes, 80 + 8 * field); }  // level 0
  std::uint32_t DfdWord(int word) const { return U32(bytes, dfd_offset() + 4 * word); }
};

void ExpectKtx2HeaderAndIndex(const Ktx2File& file, std::uint32_t size) {
  const std::vector<std::uint8_t> identifier = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
  EXPECT_EQ(std::vector<std::uint8_t>(file.bytes.begin(), file.bytes.begin() + 12), identifier);
  EXPECT_EQ(file.Header(0), 97u);  // vkFormat VK_FORMAT_R16G16B16A16_SFLOAT
  EXPECT_EQ(file.Header(1), 2u);   // typeSize: 16-bit components
  EXPECT_EQ(file.Header(2), size);  // pixelWidth
  EXPECT_EQ(file.Header(3), size);  // pixelHeight (= pixelWidth for a cube map)
  EXPECT_EQ(file.Header(4), 0u);   // pixelDepth (0 for a cube map)
  EXPECT_EQ(file.Header(5), 0u);   // layerCount: not an array
  EXPECT_EQ(file.Header(6), 6u);   // faceCount
  EXPECT_EQ(file.Header(7), 1u);   // levelCount
  EXPECT_EQ(file.Header(8), 0u);   // supercompressionScheme: none
  EXPECT_EQ(file.dfd_offset(), 80u + 24 * 1);  // right after the level index of one level
  EXPECT_EQ(file.dfd_length(), file.DfdWord(0));  // dfdByteLength = dfdTotalSize
  EXPECT_EQ(file.kvd_offset(), file.dfd_offset() + file.dfd_length());  // else the file is invalid
  EXPECT_EQ(file.sgd_offset(), 0u);
  EXPECT_EQ(file.sgd_length(), 0u);
  const std::uint64_t level_bytes = 6ull * size * size * 8;
  const std::uint64_t kvd_end = file.kvd_offset() + file.kvd_length();
  EXPECT_EQ(file.LevelField(0) % 8, 0u) << "byteOffset aligned to lcm(texel block size 8, 4)";
  EXPECT_LT(file.LevelField(0) - kvd_end, 8u) << "mipPadding is the least that aligns";
  for (std::uint64_t at = kvd_end; at < file.LevelField(0); ++at) EXPECT_EQ(file.bytes[at], 0) << "mipPadding";
  EXPECT_EQ(file.LevelField(1), level_bytes);  // byteLength
  EXPECT_EQ(file.LevelField(2), level_bytes);  // uncompressedByteLength = byteLength without supercompression
  EXPECT_EQ(file.LevelField(2) % 6, 0u);       // % (faceCount * max(1, layerCount))
  EXPECT_EQ(file.LevelField(0) + level_bytes, file.bytes.size());
}

// The basic descriptor block of the Khronos Data Format Specification for R16G16B16A16_SFLOAT.
void ExpectKtx2DataFormatDescriptor(const Ktx2File& file) {
  constexpr std::uint32_t kSamples = 4;
  EXPECT_EQ(file.DfdWord(0), 4 + 24 + 16 * kSamples);  // dfdTotalSize
  EXPECT_EQ(file.DfdWord(1) & 0x1FFFF, 0u);            // vendorId: Khronos
  EXPECT_EQ(file.DfdWord(1) >> 17, 0u);                // descriptorType: basic
  EXPECT_EQ(file.DfdWord(2) & 0xFFFF, 2u);             // versionNumber: 1.3
  EXPECT_EQ(file.DfdWord(2) >> 16, 24 + 16 * kSamples);  // descriptorBlockSize
  EXPECT_EQ(file.DfdWord(3) & 0xFF, 1u);               // colorModel RGBSDA
  EXPECT_EQ((file.DfdWord(3) >> 8) & 0xFF, 1u);        // colorPrimaries BT709
  EXPECT_EQ((file.DfdWord(3) >> 16) & 0xFF, 1u);       // transferFunction LINEAR
  EXPECT_EQ(file.DfdWord(3) >> 24, 0u);                // flags ALPHA_STRAIGHT
  EXPECT_EQ(file.DfdWord(4), 0u);                      // texelBlockDimension0..3: 1 x 1 x 1 x 1
  EXPECT_EQ(file.DfdWord(5), 8u);                      // bytesPlane0 = 8, bytesPlane1..3 = 0
  EXPECT_EQ(file.DfdWord(6), 0u);                      // bytesPlane4..7
  const std::uint32_t channels[kSamples] = {0, 1, 2, 15};  // R, G, B, A
  for (std::uint32_t s = 0; s < kSamples; ++s) {
    const std::uint32_t word = file.DfdWord(7 + 4 * static_cast<int>(s));
    EXPECT_EQ(word & 0xFFFF, 16 * s) << "sample " << s << " bitOffset";
    EXPECT_EQ((word >> 16) & 0xFF, 15u) << "sample " << s << " bitLength (16 bits)";
    EXPECT_EQ((word >> 24) & 0xF, channels[s]) << "sample " << s << " channelType";
    EXPECT_EQ(word >> 28, 0x8u | 0x4) << "sample " << s << " qualifiers: FLOAT | SIGNED, not EXPONENT, LINEAR";
    EXPECT_EQ(file.DfdWord(8 + 4 * static_cast<int>(s)), 0u) << "sample " << s << " samplePosition0..3";
    float lower, upper;
    const std::uint32_t lower_bits = file.DfdWord(9 + 4 * static_cast<int>(s));
    const std::uint32_t upper_bits = file.DfdWord(10 + 4 * static_cast<int>(s));
    std::memcpy(&lower, &lower_bits, 4);
    std::memcpy(&upper, &upper_bits, 4);
    EXPECT_EQ(lower, -1.0f) << "sample " << s << " sampleLower of a signed float";
    EXPECT_EQ(upper, 1.0f) << "sample " << s << " sampleUpper";
  }
}

// keyAndValueByteLength, the NUL-terminated key, the value, and 0-filled valuePadding to 4 bytes.
void ExpectKtx2KeyValueData(const Ktx2File& file) {
  std::size_t at = file.kvd_offset();
  const std::size_t end = at + file.kvd_length();
  std::vector<std::string> keys;
  while (at < end) {
    const std::uint32_t length = U32(file.bytes, at);
    ASSERT_GE(length, 2u);
    const std::string pair(file.bytes.begin() + at + 4, file.bytes.begin() + at + 4 + length);
    const std::size_t nul = pair.find('\0');
    ASSERT_NE(nul, std::string::npos) << "the key's NUL";
    keys.push_back(pair.substr(0, nul));
    if (keys.back() == "KTXwriter") {
      EXPECT_EQ(pair.substr(nul + 1), std::string(kKtx2WriterName) + '\0') << "a NUL-terminated UTF-8 value";
    }
    at += 4 + length;
    for (; at % 4 != 0; ++at) EXPECT_EQ(file.bytes.at(at), 0) << "valuePadding";
  }
  EXPECT_EQ(at, end) << "kvdByteLength";
  EXPECT_EQ(keys, std::vector<std::string>{"KTXwriter"});
  EXPECT_TRUE(std::is_sorted(keys.begin(), keys.end()));
}

TEST_F(CubeTextureWriters, Ktx2FieldsAreTheSpecificationsForAnRgba16fCube) {
  const CubeMap cube = MakeTestCube(kFaceSize);
  ASSERT_EQ(WriteKtx2Cube(cube, Path("map.ktx2")).message(), "");
  Ktx2File file{FileBytes(Path("map.ktx2"))};
  ASSERT_GE(file.bytes.size(), 104u);
  ExpectKtx2HeaderAndIndex(file, kFaceSize);
  ExpectKtx2DataFormatDescriptor(file);
  ExpectKtx2KeyValueData(file);
  ExpectTexels(file.bytes, file.LevelField(0), cube);  // faces +X -X +Y -Y +Z -Z, rows from the top
  EXPECT_EQ(FolderContents(), std::vector<std::string>{"map.ktx2"});
}

// A face size that is no power of two, and the 1 x 1 map, keep every rule.
TEST_F(CubeTextureWriters, Ktx2OfOddAndSingleTexelFacesStaysValid) {
  for (int size : {1, 3}) {
    SCOPED_TRACE(size);
    const CubeMap cube = MakeTestCube(size);
    Ktx2File file{EncodeKtx2CubeRgba16f(cube)};
    ExpectKtx2HeaderAndIndex(file, static_cast<std::uint32_t>(size));
    ExpectKtx2DataFormatDescriptor(file);
    ExpectTexels(file.bytes, file.LevelField(0), cube);
  }
}

TEST(MapFileFormats, NamesFilesAndRefusesOthers) {
  EXPECT_EQ(kMapFileFormatNames.Find("exr"), MapFileFormat::kExr);
  EXPECT_EQ(kMapFileFormatNames.Find("dds"), MapFileFormat::kDds);
  EXPECT_EQ(kMapFileFormatNames.Find("ktx2"), MapFileFormat::kKtx2);
  EXPECT_EQ(kMapFileFormatNames.Find("ktx1"), std::nullopt);
  EXPECT_EQ(kMapFileFormatNames.Find("DDS"), std::nullopt);
  EXPECT_EQ(kMapFileFormatNames.Find("hdr-faces"), MapFileFormat::kHdrFaces);
  EXPECT_EQ(kMapFileFormatNames.Find("hdr"), std::nullopt);
  EXPECT_EQ(kMapFileFormatNames.Find("ktx"), MapFileFormat::kKtx);
  for (MapFileFormat format : {MapFileFormat::kExr, MapFileFormat::kDds, MapFileFormat::kKtx2, MapFileFormat::kKtx}) {
    EXPECT_THAT(IrradianceMapFileNames(format),
                testing::ElementsAre("irradiance." + std::string(MapFileFormatName(format))));
  }
  EXPECT_THAT(IrradianceMapFileNames(MapFileFormat::kHdrFaces),
              testing::ElementsAre("irradiance_px.hdr", "irradiance_nx.hdr", "irradiance_py.hdr", "irradiance_ny.hdr",
                                   "irradiance_pz.hdr", "irradiance_nz.hdr"));
}

// ---- Six Radiance faces ------------------------------------------------------------------------

// The six files, read back by irrmap's own six-face loader as "irradiance_{face}.hdr", are the cube
// to RGBE's precision (8 bits of mantissa: within 1/128 of a texel's largest channel).
TEST_F(CubeTextureWriters, HdrFacesLoadAsTheSameCubeThroughTheEnvironmentLoader) {
  const CubeMap cube = MakeTestCube(kFaceSize);
  const std::span<const std::string_view> files = IrradianceMapFileNames(MapFileFormat::kHdrFaces);
  for (std::size_t file = 0; file < files.size(); ++file) {
    ASSERT_EQ(WriteMapFile(cube, MapFileFormat::kHdrFaces, file, Path(std::string(files[file]))).message(), "");
  }
  const Result<LoadedEnvironment> loaded = LoadEnvironment(Path("irradiance_{face}.hdr"));
  ASSERT_TRUE(loaded.ok()) << loaded.message();
  for (CubeFace face : kAllCubeFaces) {
    for (int y = 0; y < kFaceSize; ++y) {
      for (int x = 0; x < kFaceSize; ++x) {
        const glm::vec3 want = cube.face(face).at(x, y);
        const glm::vec3 got = loaded->cube.face(face).at(x, y);
        const float largest = std::max({want.r, want.g, want.b});
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(got[c], want[c], largest / 128.0f) << CubeFaceName(face) << " (" << x << ", " << y << ")";
        }
      }
    }
  }
}

// RGBE holds no negative value: a nine-term irradiance's dips below 0 are written as 0 and counted.
TEST_F(CubeTextureWriters, HdrFacesWriteNegativeValuesAsZeroAndCountThem) {
  CubeMap cube = MakeTestCube(2);
  cube.face(CubeFace::kNegativeZ).at(1, 0) = glm::vec3(-0.5f, 2.0f, -1e-3f);
  const std::span<const std::string_view> files = IrradianceMapFileNames(MapFileFormat::kHdrFaces);
  for (std::size_t file = 0; file < files.size(); ++file) {
    ASSERT_EQ(WriteMapFile(cube, MapFileFormat::kHdrFaces, file, Path(std::string(files[file]))).message(), "");
  }
  const Result<LoadedEnvironment> loaded = LoadEnvironment(Path("irradiance_{face}.hdr"));
  ASSERT_TRUE(loaded.ok()) << loaded.message();
  const glm::vec3 texel = loaded->cube.face(CubeFace::kNegativeZ).at(1, 0);
  EXPECT_EQ(texel.r, 0.0f);
  EXPECT_NEAR(texel.g, 2.0f, 2.0f / 128.0f);
  EXPECT_EQ(texel.b, 0.0f);
  const std::optional<std::string> warning = MapRangeWarning(cube, MapFileFormat::kHdrFaces, "irradiance_nz.hdr");
  ASSERT_TRUE(warning.has_value());
  EXPECT_THAT(*warning, HasSubstr("irradiance_nz.hdr: 2 colour values are negative"));
  EXPECT_EQ(MapRangeWarning(MakeTestCube(2), MapFileFormat::kHdrFaces, "irradiance_nz.hdr"), std::nullopt);
  EXPECT_EQ(MapRangeWarning(cube, MapFileFormat::kExr, "irradiance.exr"), std::nullopt);
}

}  // namespace
}  // namespace vs11::irradiance

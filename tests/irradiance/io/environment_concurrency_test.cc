// Reading environments from several threads at once (as `irrmap batch` does) gives every thread
// the pixels a serial read gives, bit for bit, in every format vs11 reads: OpenEXR with each
// compression OpenImageIO writes, Radiance HDR, PFM, TIFF, PNG, JPEG, and DDS as 8-bit, BC1-BC7 and
// the float formats, as cube maps and plain images. OpenImageIO 2.4's DDS cube maps failed this
// (environment_io.cc, ReadImage, says why and how they are read now).
#include <cstdint>
#include <cstring>
#include <functional>
#include <latch>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "irradiance/io/environment_io.h"
#include "tests/irradiance/io/dds_test_files.h"
#include "tests/irradiance/io/environment_test_support.h"

namespace vs11::irradiance {
namespace {

using namespace envtest;

constexpr int kThreads = 4;
// Rounds of kThreads simultaneous reads. Read by OpenImageIO's cube-map path without a lock, the
// 128-texel BC and 8-bit cube maps here gave 2 to 22 wrong reads of the 48 (2-core AMD EPYC).
constexpr int kRounds = 12;
constexpr int kCubeFace = 128;
constexpr int kImageWidth = 256;  // plain images: a 2:1 lat-long
constexpr int kImageHeight = 128;

struct FormatCase {
  const char* name;
  const char* file;
  std::function<void(const fs::path&)> write;
};

// Radiance noise in 0 .. 4, different in every texel, so that a texel from elsewhere shows.
Image NoiseImage() {
  Image image(kImageWidth, kImageHeight);
  std::mt19937 random(11);
  std::uniform_real_distribution<float> value(0.0f, 4.0f);
  for (glm::vec3& p : image.pixels) p = glm::vec3(value(random), value(random), value(random));
  return image;
}

void WriteOiio(const fs::path& path, OIIO::TypeDesc type, const char* compression = nullptr) {
  const Image image = NoiseImage();
  std::vector<float> data = Interleave(image);
  std::vector<std::uint8_t> bytes;
  if (type == OIIO::TypeDesc::UINT8) {
    for (float v : data) bytes.push_back(static_cast<std::uint8_t>(std::min(255.0f, v * 64.0f)));
  }
  auto out = OIIO::ImageOutput::create(path.string());
  ASSERT_TRUE(out) << path;
  OIIO::ImageSpec spec(image.width, image.height, 3, type);
  if (compression) spec.attribute("compression", compression);
  ASSERT_TRUE(out->open(path.string(), spec)) << out->geterror();
  ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, data.data()) && out->close()) << out->geterror();
}

FormatCase Exr(const char* name, const char* compression) {
  return {name, "image.exr", [compression](const fs::path& p) { WriteOiio(p, OIIO::TypeDesc::HALF, compression); }};
}

FormatCase OiioFormat(const char* name, const char* file, OIIO::TypeDesc type) {
  return {name, file, [type](const fs::path& p) { WriteOiio(p, type); }};
}

// A cube map of random blocks: `four_cc` in the legacy header, or "DX10" and `dxgi`. Faces of a
// multiple of 4 texels are read as one image of stacked faces, others face by face (environment_io.cc).
FormatCase BlockCube(const char* name, std::uint32_t four_cc, std::uint32_t dxgi, int block_bytes,
                     int face = kCubeFace) {
  return {name, "cube.dds", [=](const fs::path& p) {
            DdsFields fields = four_cc == kFourCcDx10 ? Dx10Cube(face, dxgi) : LegacyCube(face, four_cc);
            WriteBytes(p, RandomBlockDds(fields, block_bytes, 5));
          }};
}

// The same as a plain 2:1 image of random blocks (OpenImageIO reads it by scanlines, not tiles).
FormatCase BlockLatLong(const char* name, std::uint32_t four_cc, int block_bytes) {
  return {name, "latlong.dds", [=](const fs::path& p) {
            DdsFields fields = LegacyCube(kImageWidth, four_cc);
            fields.height = kImageHeight;
            fields.caps2 = 0;
            WriteBytes(p, RandomBlockDds(fields, block_bytes, 6, /*faces=*/1));
          }};
}

// An uncompressed cube map of random texels (a 1 x 1 "block" of `texel_bytes`): any bits are texels
// of these formats, NaN and Inf among them for the float ones, which are compared bit for bit too.
FormatCase UncompressedCube(const char* name, DdsFields fields, int texel_bytes) {
  return {name, "cube.dds", [=](const fs::path& p) {
            std::string bytes = DdsBytes(fields);
            std::mt19937 random(9);
            for (int i = 0; i < 6 * kCubeFace * kCubeFace * texel_bytes; ++i) {
              bytes.push_back(static_cast<char>(random() & 0xff));
            }
            WriteBytes(p, bytes);
          }};
}

FormatCase EightBitCube() {
  return {"Dds8BitCube", "cube.dds", [](const fs::path& p) {
            WriteBytes(p, Dds8BitCube(kCubeFace, {kAllCubeFaces.begin(), kAllCubeFaces.end()},
                                      [](CubeFace face, int x, int y) {
                                        return std::array<std::uint8_t, 3>{
                                            static_cast<std::uint8_t>(x * 7 + y), static_cast<std::uint8_t>(y * 5),
                                            static_cast<std::uint8_t>(40 * static_cast<int>(face) + x)};
                                      }));
          }};
}

constexpr std::uint32_t kDxgiBc4Unorm = 80;
constexpr std::uint32_t kDxgiBc5Unorm = 83;
constexpr std::uint32_t kDxgiBc7Unorm = 98;

void PrintTo(const FormatCase& format, std::ostream* out) { *out << format.name; }

class ConcurrentRead : public TempFolderTest, public testing::WithParamInterface<FormatCase> {};

TEST_P(ConcurrentRead, EveryThreadGetsTheSerialReadsPixels) {
  const fs::path path = Path(GetParam().file);
  GetParam().write(path);
  const Result<ImageRead> serial = ReadImage(path);
  ASSERT_TRUE(serial.ok()) << serial.message();
  const std::vector<glm::vec3>& expected = serial->image.pixels;

  int wrong = 0;
  for (int round = 0; round < kRounds; ++round) {
    std::vector<std::optional<Result<ImageRead>>> reads(kThreads);
    std::latch start(kThreads);  // all threads read at once
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t) {
      threads.emplace_back([&, t] {
        start.arrive_and_wait();
        reads[t] = ReadImage(path);
      });
    }
    for (std::thread& thread : threads) thread.join();
    for (const std::optional<Result<ImageRead>>& read : reads) {
      ASSERT_TRUE(read->ok()) << read->message();
      const std::vector<glm::vec3>& pixels = (*read)->image.pixels;
      if (pixels.size() != expected.size() ||
          std::memcmp(pixels.data(), expected.data(), expected.size() * sizeof(glm::vec3)) != 0) {
        ++wrong;
      }
    }
  }
  EXPECT_EQ(wrong, 0) << wrong << " of " << kRounds * kThreads << " concurrent reads differ from a serial one";
}

INSTANTIATE_TEST_SUITE_P(
    Formats, ConcurrentRead,
    testing::Values(Exr("ExrNone", "none"), Exr("ExrRle", "rle"), Exr("ExrZip", "zip"), Exr("ExrZips", "zips"),
                    Exr("ExrPiz", "piz"), Exr("ExrPxr24", "pxr24"), Exr("ExrB44", "b44"), Exr("ExrB44a", "b44a"),
                    Exr("ExrDwaa", "dwaa"), Exr("ExrDwab", "dwab"),
                    OiioFormat("RadianceHdr", "image.hdr", OIIO::TypeDesc::FLOAT),
                    FormatCase{"Pfm", "image.pfm", [](const fs::path& p) { WritePfm(p, NoiseImage()); }},
                    OiioFormat("TiffFloat", "image.tif", OIIO::TypeDesc::FLOAT),
                    OiioFormat("Tiff8Bit", "image8.tif", OIIO::TypeDesc::UINT8),
                    OiioFormat("Png", "image.png", OIIO::TypeDesc::UINT8),
                    OiioFormat("Jpeg", "image.jpg", OIIO::TypeDesc::UINT8),
                    EightBitCube(),
                    UncompressedCube("DdsRgba32FloatCube", Dx10Cube(kCubeFace, kDxgiRgba32Float), 16),
                    UncompressedCube("DdsRgb32FloatCube", Dx10Cube(kCubeFace, kDxgiRgb32Float), 12),
                    UncompressedCube("DdsRgba16FloatCube", Dx10Cube(kCubeFace, kDxgiRgba16Float), 8),
                    UncompressedCube("DdsR11G11B10FloatCube", Dx10Cube(kCubeFace, kDxgiR11G11B10Float), 4),
                    UncompressedCube("DdsRgb9e5Cube", Dx10Cube(kCubeFace, kDxgiRgb9e5), 4),
                    UncompressedCube("DdsLegacyA32B32G32R32FCube", LegacyCube(kCubeFace, kD3dFmtA32B32G32R32F), 16),
                    UncompressedCube("DdsLegacyA16B16G16R16FCube", LegacyCube(kCubeFace, kD3dFmtA16B16G16R16F), 8),
                    BlockCube("DdsBc1Dxt1Cube", FourCcCode("DXT1"), 0, 8),
                    BlockCube("DdsBc2Dxt3Cube", FourCcCode("DXT3"), 0, 16),
                    BlockCube("DdsBc3Dxt5Cube", FourCcCode("DXT5"), 0, 16),
                    BlockCube("DdsBc4UCube", FourCcCode("BC4U"), 0, 8),
                    BlockCube("DdsBc5UCube", FourCcCode("BC5U"), 0, 16),
                    BlockCube("DdsBc4Ati1Cube", FourCcCode("ATI1"), 0, 8),
                    BlockCube("DdsBc5Ati2Cube", FourCcCode("ATI2"), 0, 16),
                    BlockCube("DdsBc4Dx10Cube", kFourCcDx10, kDxgiBc4Unorm, 8),
                    BlockCube("DdsBc5Dx10Cube", kFourCcDx10, kDxgiBc5Unorm, 16),
                    BlockCube("DdsBc6hUnsignedCube", kFourCcDx10, kDxgiBc6hUf16, 16),
                    BlockCube("DdsBc6hSignedCube", kFourCcDx10, kDxgiBc6hSf16, 16),
                    BlockCube("DdsBc7Cube", kFourCcDx10, kDxgiBc7Unorm, 16),
                    BlockCube("DdsBc6hCubeOfFacesThatDoNotStack", kFourCcDx10, kDxgiBc6hUf16, 16, kCubeFace + 2),
                    BlockLatLong("DdsBc1LatLong", FourCcCode("DXT1"), 8)),
    [](const testing::TestParamInfo<FormatCase>& info) { return info.param.name; });

}  // namespace
}  // namespace vs11::irradiance

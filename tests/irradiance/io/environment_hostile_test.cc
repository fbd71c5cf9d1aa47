// Hostile environment files (issue #6): cut short, lying headers, odd sizes, bad values. Each must
// fail with a message naming the file and the problem, or load with the documented warning; none
// may crash, hang or allocate what a header merely claims.
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "irradiance/io/environment_io.h"
#include "tests/irradiance/io/environment_test_support.h"

namespace vs11::irradiance {
namespace {

using namespace envtest;
using testing::HasSubstr;
using EnvironmentHostile = TempFolderTest;

// A horizontal cross written in every format the loader is expected to read, as (name, bytes).
std::vector<std::pair<std::string, std::string>> CrossInEveryFormat(const fs::path& folder) {
  const Image cross = CubeMapToImage(MakeTestCube(16), EnvironmentLayout::kHorizontalCross);
  std::vector<std::pair<std::string, std::string>> files;
  for (const char* name : {"cross.exr", "cross.hdr", "cross.tif", "cross.png", "cross.jpg"}) {
    EXPECT_EQ(WriteImage(cross, folder / name).message(), "");
    files.emplace_back(name, ReadBytes(folder / name));
  }
  std::vector<std::uint8_t> bytes;
  for (const glm::vec3& p : cross.pixels) {
    for (int c = 0; c < 3; ++c) {
      bytes.push_back(static_cast<std::uint8_t>(std::min(p[c], 1.0f) * 255));
    }
  }
  for (const char* name : {"cross8.tif", "cross.bmp"}) {
    EXPECT_TRUE(WriteWithOiio(folder / name, cross.width, cross.height, 3, OIIO::TypeDesc::UINT8,
                              bytes.data()));
    files.emplace_back(name, ReadBytes(folder / name));
  }
  WritePfm(folder / "cross.pfm", cross);
  files.emplace_back("cross.pfm", ReadBytes(folder / "cross.pfm"));
  return files;
}

TEST_F(EnvironmentHostile, FilesCutShortAtSeveralPointsAreReportedAsTruncated) {
  for (const auto& [name, bytes] : CrossInEveryFormat(folder_)) {
    ASSERT_TRUE(LoadEnvironment(Path(name)).ok()) << name;
    // A PNG ends with a 12-byte IEND chunk after the pixels: cutting only that loses nothing.
    const std::size_t trailer = name.ends_with(".png") ? 12 : 0;
    for (std::size_t length : {std::size_t{24}, bytes.size() / 3, bytes.size() / 2,
                               bytes.size() - trailer - 2}) {
      const std::string short_name = "short_" + name;
      WriteBytes(Path(short_name), bytes.substr(0, length));
      const Result<LoadedEnvironment> result = LoadEnvironment(Path(short_name));
      ASSERT_FALSE(result.ok()) << name << " cut to " << length << " of " << bytes.size();
      EXPECT_THAT(result.message(), HasSubstr(short_name));
      EXPECT_THAT(result.message(), HasSubstr("truncated")) << length;
    }
  }
}

// A little-endian baseline TIFF header claiming an uncompressed 8-bit grey image of size x size in
// one strip.
std::string TiffHeader(std::uint32_t size) {
  struct Entry {
    std::uint16_t tag;
    std::uint16_t type;  // 3 SHORT, 4 LONG
    std::uint32_t value;
  };
  const std::vector<Entry> entries = {
      {256, 4, size}, {257, 4, size}, {258, 3, 8},    {259, 3, 1},           {262, 3, 1},
      {273, 4, 200},  {277, 3, 1},    {278, 4, size}, {279, 4, size * size},
  };
  std::string bytes = "II*";
  bytes.push_back('\0');
  Append(bytes, std::uint32_t{8});  // offset of the first IFD
  Append(bytes, static_cast<std::uint16_t>(entries.size()));
  for (const Entry& entry : entries) {
    Append(bytes, entry.tag);
    Append(bytes, entry.type);
    Append(bytes, std::uint32_t{1});  // count
    if (entry.type == 3) {
      Append(bytes, static_cast<std::uint16_t>(entry.value));
      Append(bytes, std::uint16_t{0});
    } else {
      Append(bytes, entry.value);
    }
  }
  Append(bytes, std::uint32_t{0});  // no next IFD
  return bytes;
}

// Headers that claim 2^30 x 2^30 pixels (and more) followed by a few bytes: refused by the size
// limit (kMaxImagePixels), or by OpenImageIO's own limit for TIFF, before anything is allocated.
TEST_F(EnvironmentHostile, HeadersClaimingHugeImagesAreRefusedBeforeAllocating) {
  const std::string padding(4096, '\x40');
  const std::vector<std::tuple<std::string, std::string, std::string>> files = {
      {"huge.pfm", "PF\n1073741824 1073741824\n-1.0\n" + padding, "larger than"},
      {"wide.pfm", "PF\n4294967295 1\n-1.0\n" + padding, "larger than"},
      {"huge.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1073741824 +X 1073741824\n" + padding,
       "larger than"},
      {"huge.tif", TiffHeader(std::uint32_t{1} << 30) + padding, "corrupt"},
      // Within the pixel limit, but the file cannot hold them: refused before the pixel buffer
      // (3 GB as float) is allocated.
      {"big.tif", TiffHeader(16384) + padding, "uncompressed pixels its header declares"},
      {"big.pfm", "PF\n16384 16384\n-1.0\n" + padding, "uncompressed pixels its header declares"},
  };
  for (const auto& [name, bytes, problem] : files) {
    WriteBytes(Path(name), bytes);
    const Result<LoadedEnvironment> result = LoadEnvironment(Path(name));
    ASSERT_FALSE(result.ok()) << name;
    EXPECT_THAT(result.message(), HasSubstr(name));
    EXPECT_THAT(result.message(), HasSubstr(problem));
  }
}

// OpenImageIO reads a short uncompressed TIFF without an error: its size is checked instead.
TEST_F(EnvironmentHostile, UncompressedTiffCutShortIsReportedAsTruncated) {
  const Image cross = CubeMapToImage(MakeTestCube(4), EnvironmentLayout::kHorizontalCross);
  const std::vector<float> floats = Interleave(cross);
  std::vector<std::uint16_t> words;
  for (float value : floats) words.push_back(static_cast<std::uint16_t>(value * 1000.0f));
  std::vector<std::uint8_t> bytes;
  for (float value : floats) bytes.push_back(static_cast<std::uint8_t>(value * 20.0f));
  struct Variant {
    const char* name;
    int channels;
    OIIO::TypeDesc type;
    const void* data;
  };
  for (const Variant& v : {Variant{"f32.tif", 3, OIIO::TypeDesc::FLOAT, floats.data()},
                           Variant{"u16.tif", 1, OIIO::TypeDesc::UINT16, words.data()},
                           Variant{"u8.tif", 3, OIIO::TypeDesc::UINT8, bytes.data()}}) {
    auto out = OIIO::ImageOutput::create(v.name);
    ASSERT_TRUE(out);
    OIIO::ImageSpec spec(cross.width, cross.height, v.channels, v.type);
    spec.attribute("compression", "none");
    ASSERT_TRUE(out->open(Path(v.name).string(), spec) && out->write_image(v.type, v.data) &&
                out->close());
    ASSERT_TRUE(LoadEnvironment(Path(v.name)).ok()) << v.name;
    const std::string file = ReadBytes(Path(v.name));
    for (std::size_t length : {file.size() / 2, file.size() - 1}) {
      WriteBytes(Path(v.name), file.substr(0, length));
      const std::string error = LoadError(Path(v.name));
      EXPECT_THAT(error, HasSubstr(v.name));
      EXPECT_THAT(error, HasSubstr("truncated")) << v.name << " cut to " << length;
    }
  }
}

TEST_F(EnvironmentHostile, EveryRefusalNamesTheFileAndTheProblem) {
  ASSERT_TRUE(WriteFloatImage(Path("odd.exr"), Image(7, 5, glm::vec3(1.0f))));
  ASSERT_TRUE(WriteFloatImage(Path("square.exr"), Image(6, 6, glm::vec3(1.0f))));
  WriteBytes(Path("empty.hdr"), "");
  WriteBytes(Path("noise.tif"), std::string(300, '\x5a'));
  WriteBytes(Path("model.obj"), "v 0 0 0\n");
  fs::create_directory(Path("folder.exr"));
  LoadOptions cross;
  cross.layout = EnvironmentLayout::kHorizontalCross;
  const std::vector<std::tuple<std::string, LoadOptions, std::string>> cases = {
      {"missing.exr", {}, "not found"},
      {"empty.hdr", {}, "empty"},
      {"noise.tif", {}, "corrupt"},
      {"model.obj", {}, "unsupported image format"},
      {"folder.exr", {}, "not a regular file"},
      {"odd.exr", {}, "cannot detect the layout of a 7 x 5 image"},
      {"square.exr", cross, "4N x 3N"},
  };
  for (const auto& [name, options, problem] : cases) {
    const Result<LoadedEnvironment> result = LoadEnvironment(Path(name), options);
    ASSERT_FALSE(result.ok()) << name;
    EXPECT_THAT(result.message(), HasSubstr(Path(name).string()));
    EXPECT_THAT(result.message(), HasSubstr(problem));
  }
}

TEST_F(EnvironmentHostile, BadTexelsInAFaceFileAreZeroedWithAWarningNamingThatFile) {
  for (std::string_view name : kFaceFileNames) {
    Image face(4, 4, glm::vec3(1.0f));
    if (name == "py") {
      face.at(0, 0).r = std::numeric_limits<float>::quiet_NaN();
      face.at(1, 0).g = -std::numeric_limits<float>::infinity();
      face.at(2, 0).b = -1.0f;
    }
    ASSERT_TRUE(WriteFloatImage(Path(fmt::format("f_{}.exr", name)), face));
  }
  const LoadedEnvironment& loaded = Load(Path("f_{face}.exr"));
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_THAT(loaded.warnings[0], HasSubstr("f_py.exr"));
  EXPECT_THAT(loaded.warnings[0], HasSubstr("3 of 16 texels"));
  for (int x = 0; x < 3; ++x) {
    const glm::vec3 texel = loaded.cube.face(CubeFace::kPositiveY).at(x, 0);
    EXPECT_EQ(texel[x], 0.0f);
    EXPECT_EQ(texel[(x + 1) % 3], 1.0f);
  }
}

TEST_F(EnvironmentHostile, AnImageOfOnlyBadTexelsLoadsBlackWithEveryTexelCounted) {
  Image cross(8, 6, glm::vec3(std::numeric_limits<float>::quiet_NaN()));
  ASSERT_TRUE(WriteFloatImage(Path("nan.exr"), cross));
  const LoadedEnvironment& loaded = Load(Path("nan.exr"));
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_THAT(loaded.warnings[0], HasSubstr("48 of 48 texels"));
  for (CubeFace face : kAllCubeFaces) {
    for (const glm::vec3& texel : loaded.cube.face(face).pixels) EXPECT_EQ(texel, glm::vec3(0.0f));
  }
}

// Bytes overwritten at random places: every load must come back, loaded or refused with a message
// naming the file. (A crash or a hang here fails the whole run.)
TEST_F(EnvironmentHostile, CorruptedBytesInEveryFormatAreLoadedOrRefusedNeverFatal) {
  constexpr int kMutantsPerFormat = 40;
  std::mt19937 random(2026);
  std::vector<std::pair<std::string, std::string>> files = CrossInEveryFormat(folder_);
  files.emplace_back("cube.dds", Dds8BitCube(4, {kAllCubeFaces.begin(), kAllCubeFaces.end()},
                                             DdsTestBytes));
  const DdsPixelFormat float_format = {kDdpfFourCc, kD3dFmtA32B32G32R32F, 0, {0, 0, 0, 0}};
  std::string float_dds = DdsHeader(4, kDdsCaps2Cubemap | 0xfc00, float_format, 4 * 16);
  const CubeMap cube = MakeTestCube(4);
  for (CubeFace face : kAllCubeFaces) {
    for (const glm::vec3& p : cube.face(face).pixels) {
      for (float value : {p.r, p.g, p.b, 1.0f}) Append(float_dds, value);
    }
  }
  files.emplace_back("float.dds", float_dds);
  int refused = 0;
  for (const auto& [name, bytes] : files) {
    for (int mutant = 0; mutant < kMutantsPerFormat; ++mutant) {
      std::string damaged = bytes;
      const int changes = 1 + static_cast<int>(random() % 4);
      for (int i = 0; i < changes; ++i) {
        // Mostly the first 200 bytes, where the headers are.
        const std::size_t span = random() % 2 ? std::min<std::size_t>(200, damaged.size())
                                              : damaged.size();
        damaged[random() % span] = static_cast<char>(random());
      }
      const std::string damaged_name = "damaged_" + name;
      WriteBytes(Path(damaged_name), damaged);
      const Result<LoadedEnvironment> result = LoadEnvironment(Path(damaged_name));
      if (!result.ok()) {
        ++refused;
        EXPECT_THAT(result.message(), HasSubstr(damaged_name));
      }
    }
  }
  EXPECT_GT(refused, 0);
}

}  // namespace
}  // namespace vs11::irradiance

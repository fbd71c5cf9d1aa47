// Inputs fuzz_environment (tests/fuzz) found, replayed through the loader. Run under .ci/sanitize
// they also check that reading them stays clean under ASan and UBSan.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "irradiance/io/environment_io.h"
#include "tests/irradiance/io/environment_test_support.h"

namespace vs11::irradiance {
namespace {

using envtest::Append;
using envtest::ReadBytes;
using envtest::WriteWithOiio;

// A 3 x 4 PNG whose cHRM chunk runs into a run of 'r' bytes: libpng fails on a CRC, and OpenImageIO
// 2.4 leaks its error string (hence tests/fuzz/lsan.supp). The loader must refuse it with a message.
constexpr char kCorruptPngHex[] =
    "89504E470D0A1A0A0000000D4948445200000003000000040802000000C44F12500000000467414D410000B18F0BFC61"
    "0500000001735247420336C74D53000000206348524D00007A2600008084007272727272727272727272727272727272"
    "727272727272727272727272727272727272727272727272727272727272727272727272727272727272727272727272"
    "727272727272727272727272727272727272727272727272727272727200FA00000080E8000075300000EA6000003A98"
    "000017709CBA513C000000096F464673000000000000000000DA2AB6CE00000014744558746F69696F3A436F6C6F7253"
    "7061634D4D4D4D47425E2D4BBB0000001F49444154089963644449B0DF13C9C0A0CCC0C0C2E0C500012C0C5A70960294"
    "050042D9021909D6D0830000000049454E44AE426082";

// A 435-byte zip EXR whose header claims 8257538 x 12 float RGB pixels (under the pixel limit): the
// loader used to allocate 1.2 GB and OpenImageIO asked for 25 GB more before finding no data. No
// layout has that shape, so it is refused from the header, before any pixel is read.
constexpr char kHugeHeaderExrHex[] =
    "762F3101020000006361704461746500737472696E670013000000323032363A31313A32322030373A31303A32356368"
    "616E6E656C730063686C6973740037000000420002000000000000000100000001000000470002000000000000000100"
    "00000100000052000200000000000000010000000100000000636F6D7072657373696F6E00636F6D7072657373696F6E"
    "0001000000036461746157696E646F7700626F7832690010000000000000000000000001007E000B000000646973706C"
    "617957696E646F7700626F78326900100000000000000000000000010000000B000000646B73706C61795769006C696E"
    "654F72646572000100000000706978656C417370656374526174696F00666C6F617400040000000000803F7363726565"
    "6E57696E646F7743656E746572007632660008000000000000000000000073637265656E57696E646F77576964746800"
    "666C6F617400040000000000803F006701000000000000000000009E000000785E63686868F0FDCFF8DFA4C1B77E0B90"
    "DDC0000450F673A0F82C18DBFEA07D14942D0564AB43D9CF16240363F37EE6FD0C17EF2DEE7580E93DE07000C40600A4"
    "7B8EBE";

std::string FromHex(std::string_view hex) {
  std::string bytes;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2) {
    bytes += static_cast<char>(std::stoi(std::string(hex.substr(i, 2)), nullptr, 16));
  }
  return bytes;
}

TEST(EnvironmentFuzzRegression, CorruptPngWithABrokenChunkIsRefused) {
  std::filesystem::path path = std::filesystem::path(::testing::TempDir()) / "vs11_fuzz_corrupt_png.img";
  std::ofstream(path, std::ios::binary) << FromHex(kCorruptPngHex);
  Result<LoadedEnvironment> result = LoadEnvironment(path);
  std::filesystem::remove(path);
  EXPECT_FALSE(result.ok());
  EXPECT_NE(result.message().find(path.string()), std::string::npos) << result.message();
}

TEST(EnvironmentFuzzRegression, ExrClaimingAHugeImageOfNoLayoutIsRefusedFromItsHeader) {
  std::filesystem::path path = std::filesystem::path(::testing::TempDir()) / "vs11_fuzz_huge_header.exr";
  std::ofstream(path, std::ios::binary) << FromHex(kHugeHeaderExrHex);
  Result<LoadedEnvironment> result = LoadEnvironment(path);
  std::filesystem::remove(path);
  EXPECT_FALSE(result.ok());
  EXPECT_NE(result.message().find("8257538 x 12"), std::string::npos) << result.message();
  EXPECT_NE(result.message().find("cannot detect the layout"), std::string::npos) << result.message();
}

// ---- Compressed files too small for the image their header declares (CheckCompressionRatio) --------
// OpenImageIO allocates the whole image a header declares before it finds the data missing, so
// without the check each of these made fuzz_environment run out of memory (with 4 GB).

std::filesystem::path WriteScratch(const std::string& name, const std::string& bytes) {
  std::filesystem::path path = std::filesystem::path(::testing::TempDir()) / name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

void ExpectRefusedAsTooSmall(const std::filesystem::path& path, const std::string& size) {
  Result<LoadedEnvironment> result = LoadEnvironment(path);
  std::filesystem::remove(path);
  EXPECT_FALSE(result.ok());
  EXPECT_NE(result.message().find(path.string()), std::string::npos) << result.message();
  EXPECT_NE(result.message().find("declares a " + size + " image"), std::string::npos) << result.message();
  EXPECT_NE(result.message().find("cannot hold"), std::string::npos) << result.message();
}

// A real 8 x 4 file written by OpenImageIO, read back as bytes.
std::string SmallImageBytes(const std::string& name) {
  const std::filesystem::path path = std::filesystem::path(::testing::TempDir()) / name;
  const std::vector<float> pixels(8 * 4 * 3, 0.25f);
  EXPECT_TRUE(WriteWithOiio(path, 8, 4, 3, OIIO::TypeDesc::FLOAT, pixels.data()));
  std::string bytes = ReadBytes(path);
  std::filesystem::remove(path);
  return bytes;
}

TEST(EnvironmentFuzzRegression, SmallZipExrClaimingALatLongNearThePixelLimitIsRefused) {
  // Both windows of an 8 x 4 zip EXR made 8192 x 4096, a lat-long shape (2^25 pixels).
  std::string bytes = SmallImageBytes("vs11_small.exr");
  for (const std::string window : {"dataWindow", "displayWindow"}) {
    const std::size_t at = bytes.find(window + '\0' + "box2i");
    ASSERT_NE(at, std::string::npos) << window;
    std::string box;  // x min, y min, x max, y max (little-endian int32)
    for (std::int32_t value : {0, 0, 8191, 4095}) Append(box, value);
    bytes.replace(at + window.size() + 1 + 6 + 4, box.size(), box);
  }
  bytes += std::string(4096, '\0');  // room for the 256 chunk offsets OpenEXR reads when it opens the file
  ExpectRefusedAsTooSmall(WriteScratch("vs11_fuzz_small_latlong.exr", bytes), "8192 x 4096");
}

TEST(EnvironmentFuzzRegression, HdrHeaderWithoutPixelsClaimingALatLongIsRefused) {
  const std::string bytes = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8192 +X 16384\n" + std::string(64, '\x02');
  ExpectRefusedAsTooSmall(WriteScratch("vs11_fuzz_small_latlong.hdr", bytes), "16384 x 8192");
}

// PNG chunk checksum (ISO 3309 CRC-32), so that the patched header below is a valid chunk.
std::uint32_t Crc32(std::string_view bytes) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (unsigned char byte : bytes) {
    crc ^= byte;
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

std::string BigEndian(std::uint32_t value) {
  return {static_cast<char>(value >> 24), static_cast<char>(value >> 16), static_cast<char>(value >> 8),
          static_cast<char>(value)};
}

TEST(EnvironmentFuzzRegression, SmallPngClaimingAHugeCrossIsRefused) {
  // An 8 x 4 PNG whose IHDR chunk (valid checksum) declares a 16384 x 12288 horizontal cross.
  std::string bytes = SmallImageBytes("vs11_small.png");
  ASSERT_EQ(bytes.substr(12, 4), "IHDR");
  const std::string ihdr = "IHDR" + BigEndian(16384) + BigEndian(12288) + bytes.substr(24, 5);
  bytes.replace(12, ihdr.size(), ihdr);
  bytes.replace(12 + ihdr.size(), 4, BigEndian(Crc32(ihdr)));
  ExpectRefusedAsTooSmall(WriteScratch("vs11_fuzz_small_cross.png", bytes), "16384 x 12288");
}

}  // namespace
}  // namespace vs11::irradiance

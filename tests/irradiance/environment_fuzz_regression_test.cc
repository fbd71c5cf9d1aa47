// Inputs fuzz_environment (tests/fuzz) found, replayed through the loader. Run under .ci/sanitize
// they also check that reading them stays clean under ASan and UBSan.
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "irradiance/environment_io.h"

namespace vs11::irradiance {
namespace {

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
  LoadResult result = LoadEnvironment(path);
  std::filesystem::remove(path);
  EXPECT_FALSE(result.ok());
  EXPECT_NE(result.error.find(path.string()), std::string::npos) << result.error;
}

}  // namespace
}  // namespace vs11::irradiance

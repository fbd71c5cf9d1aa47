// The sRGB tables of image_reader.cc against the formula they replace, for every code value, and
// whole 8- and 16-bit images read through them against the float path read_image used before.
#include "irradiance/io/image_reader.h"

#include <bit>
#include <cstdint>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "tests/irradiance/io/environment_test_support.h"

namespace vs11::irradiance {
namespace {

using ImageReader = envtest::TempFolderTest;

// The decode before the tables: the code normalised to [0, 1] in float as OpenImageIO does it (times
// the reciprocal of the largest code, which differs from dividing by it in the last bit for some
// codes: 3 of 255, 257 of 65535), then SrgbToLinear in double.
float FormulaDecode(std::uint32_t code, float max_code) {
  return static_cast<float>(SrgbToLinear(static_cast<float>(code) * (1.0f / max_code)));
}

TEST(ImageReaderSrgb, ByteTableIsTheFormulaForEveryCode) {
  for (std::uint32_t code = 0; code <= 0xff; ++code) {
    ASSERT_EQ(std::bit_cast<std::uint32_t>(SrgbByteToLinear(static_cast<std::uint8_t>(code))),
              std::bit_cast<std::uint32_t>(FormulaDecode(code, 255.0f)))
        << code;
  }
}

TEST(ImageReaderSrgb, WordTableIsTheFormulaForEveryCode) {
  for (std::uint32_t code = 0; code <= 0xffff; ++code) {
    ASSERT_EQ(std::bit_cast<std::uint32_t>(SrgbWordToLinear(static_cast<std::uint16_t>(code))),
              std::bit_cast<std::uint32_t>(FormulaDecode(code, 65535.0f)))
        << code;
  }
}

// Writes a 256 x `rows` RGB image of every code value of `Code` (red counts up, green down, blue
// scrambled), reads it with ReadImage and with read_image as float decoded by SrgbToLinear (the
// path before the tables), and compares the bits.
template <class Code>
void ExpectTableReadMatchesFloatRead(const std::filesystem::path& path, OIIO::TypeDesc type) {
  constexpr std::uint32_t kCodes = std::uint32_t{1} << (8 * sizeof(Code));
  constexpr int kWidth = 256;
  constexpr int kRows = static_cast<int>(kCodes / kWidth);
  std::vector<Code> samples;
  for (std::uint32_t i = 0; i < kCodes; ++i) {
    samples.push_back(static_cast<Code>(i));
    samples.push_back(static_cast<Code>(kCodes - 1 - i));
    samples.push_back(static_cast<Code>((i * 40503u) & (kCodes - 1)));
  }
  auto output = OIIO::ImageOutput::create(path.string());
  ASSERT_TRUE(output);
  ASSERT_TRUE(output->open(path.string(), OIIO::ImageSpec(kWidth, kRows, 3, type)));
  ASSERT_TRUE(output->write_image(type, samples.data()));
  ASSERT_TRUE(output->close());

  const Result<ImageRead> read = ReadImage(path);
  ASSERT_TRUE(read.ok()) << read.message();
  auto input = OIIO::ImageInput::open(path.string());
  ASSERT_TRUE(input);
  ASSERT_EQ(input->spec().format, type);
  std::vector<float> floats(samples.size());
  ASSERT_TRUE(input->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, floats.data()));
  for (std::size_t i = 0; i < floats.size(); ++i) {
    const float expected = static_cast<float>(SrgbToLinear(floats[i]));
    ASSERT_EQ(std::bit_cast<std::uint32_t>(read->image.pixels[i / 3][static_cast<int>(i % 3)]),
              std::bit_cast<std::uint32_t>(expected))
        << "sample " << i << ", code " << samples[i];
  }
}

TEST_F(ImageReader, EightBitPngDecodesAsTheFloatPathDid) {
  ExpectTableReadMatchesFloatRead<std::uint8_t>(Path("codes8.png"), OIIO::TypeDesc::UINT8);
}

TEST_F(ImageReader, SixteenBitPngDecodesAsTheFloatPathDid) {
  ExpectTableReadMatchesFloatRead<std::uint16_t>(Path("codes16.png"), OIIO::TypeDesc::UINT16);
}

TEST_F(ImageReader, SixteenBitTiffDecodesAsTheFloatPathDid) {
  ExpectTableReadMatchesFloatRead<std::uint16_t>(Path("codes16.tif"), OIIO::TypeDesc::UINT16);
}

}  // namespace
}  // namespace vs11::irradiance

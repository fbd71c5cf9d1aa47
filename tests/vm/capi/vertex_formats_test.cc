// Every D3DDECLTYPE read against values computed by hand from the D3D9 documentation's "expanded
// to" rules, the half floats against a double computation, and D3DCOLOR written.
#include "vm/capi/vertex_formats.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

namespace vs11::capi {
namespace {

template <class T>
std::vector<std::uint8_t> Bytes(std::initializer_list<T> values) {
  std::vector<std::uint8_t> bytes(values.size() * sizeof(T));
  std::memcpy(bytes.data(), std::data(values), bytes.size());
  return bytes;
}

void ExpectVec(const Vec4f& actual, const Vec4f& expected) {
  for (int c = 0; c < 4; ++c) EXPECT_FLOAT_EQ(actual[c], expected[c]) << "component " << c;
}

TEST(VertexFormats, FloatsFillMissingComponentsWith0001) {
  const auto bytes = Bytes<float>({1.5f, -2.0f, 3.25f, 7.0f});
  ExpectVec(ReadElement(DeclType::kFloat1, bytes.data()), {1.5f, 0, 0, 1});
  ExpectVec(ReadElement(DeclType::kFloat2, bytes.data()), {1.5f, -2.0f, 0, 1});
  ExpectVec(ReadElement(DeclType::kFloat3, bytes.data()), {1.5f, -2.0f, 3.25f, 1});
  ExpectVec(ReadElement(DeclType::kFloat4, bytes.data()), {1.5f, -2.0f, 3.25f, 7.0f});
}

TEST(VertexFormats, D3dColorReadsBgraBytesAsRgba) {
  const auto bytes = Bytes<std::uint8_t>({0x10, 0x20, 0xFF, 0x80});  // B, G, R, A in memory
  ExpectVec(ReadElement(DeclType::kD3dColor, bytes.data()), {1.0f, 0.1254902f, 0.0627451f, 0.5019608f});
}

TEST(VertexFormats, UnsignedBytesAsIntegersOrOver255) {
  const auto bytes = Bytes<std::uint8_t>({0, 255, 51, 102});
  ExpectVec(ReadElement(DeclType::kUbyte4, bytes.data()), {0, 255, 51, 102});
  ExpectVec(ReadElement(DeclType::kUbyte4n, bytes.data()), {0, 1, 0.2f, 0.4f});
}

TEST(VertexFormats, ShortsAsIntegers) {
  const auto bytes = Bytes<std::int16_t>({-32768, 32767, -3, 4});
  ExpectVec(ReadElement(DeclType::kShort2, bytes.data()), {-32768, 32767, 0, 1});
  ExpectVec(ReadElement(DeclType::kShort4, bytes.data()), {-32768, 32767, -3, 4});
}

TEST(VertexFormats, NormalizedShortsDivideBy32767WithoutClamping) {
  const auto bytes = Bytes<std::int16_t>({-32768, 32767, 16384, -32767});
  // -32768 / 32767 = -1.000030518...: D3D9 divides and does not clamp to -1 (D3D10's rule).
  ExpectVec(ReadElement(DeclType::kShort2n, bytes.data()), {-1.0000305f, 1, 0, 1});
  ExpectVec(ReadElement(DeclType::kShort4n, bytes.data()), {-1.0000305f, 1, 0.50001526f, -1});
  EXPECT_LT(ReadElement(DeclType::kShort2n, bytes.data())[0], -1.0f);
}

TEST(VertexFormats, NormalizedUnsignedShortsDivideBy65535) {
  const auto bytes = Bytes<std::uint16_t>({65535, 0, 32768, 1});
  ExpectVec(ReadElement(DeclType::kUshort2n, bytes.data()), {1, 0, 0, 1});
  ExpectVec(ReadElement(DeclType::kUshort4n, bytes.data()), {1, 0, 0.50000763f, 1.5259022e-05f});
}

TEST(VertexFormats, Udec3ReadsThreeTenBitFieldsAndIgnoresTheTopTwo) {
  const std::uint32_t word = 1023u | 0u << 10 | 512u << 20 | 3u << 30;
  const auto bytes = Bytes<std::uint32_t>({word});
  ExpectVec(ReadElement(DeclType::kUdec3, bytes.data()), {1023, 0, 512, 1});
}

TEST(VertexFormats, Dec3nSignExtendsTenBitsAndDividesBy511) {
  const std::uint32_t word = 0x200u | 0x1FFu << 10 | 0x3FFu << 20 | 1u << 30;  // -512, 511, -1
  const auto bytes = Bytes<std::uint32_t>({word});
  ExpectVec(ReadElement(DeclType::kDec3n, bytes.data()), {-1.0019569f, 1, -0.0019569471f, 1});
}

TEST(VertexFormats, HalvesKeepInfinityNanAndDenormals) {
  const auto two = Bytes<std::uint16_t>({0x3C00, 0xC000});
  ExpectVec(ReadElement(DeclType::kFloat16x2, two.data()), {1, -2, 0, 1});
  const auto four = Bytes<std::uint16_t>({0x7C00, 0xFC00, 0x0001, 0x7E00});
  const Vec4f value = ReadElement(DeclType::kFloat16x4, four.data());
  EXPECT_EQ(value[0], INFINITY);
  EXPECT_EQ(value[1], -INFINITY);
  EXPECT_EQ(value[2], std::ldexp(1.0f, -24));  // the smallest denormal half
  EXPECT_TRUE(std::isnan(value[3]));
}

double HalfByDefinition(std::uint16_t half) {
  const int sign = half >> 15, exponent = (half >> 10) & 0x1F, mantissa = half & 0x3FF;
  double magnitude;
  if (exponent == 0) {
    magnitude = std::ldexp(static_cast<double>(mantissa), -24);
  } else if (exponent == 0x1F) {
    magnitude = mantissa == 0 ? INFINITY : NAN;
  } else {
    magnitude = std::ldexp(1.0 + mantissa / 1024.0, exponent - 15);
  }
  return sign ? -magnitude : magnitude;
}

TEST(VertexFormats, EveryHalfConvertsExactly) {
  for (std::uint32_t h = 0; h <= 0xFFFF; ++h) {
    const auto half = static_cast<std::uint16_t>(h);
    const float value = HalfToFloat(half);
    const double expected = HalfByDefinition(half);
    const std::uint32_t bits = std::bit_cast<std::uint32_t>(value);
    if (std::isnan(expected)) {
      ASSERT_TRUE(std::isnan(value)) << std::hex << h;
      ASSERT_EQ((bits >> 13) & 0x3FF, h & 0x3FFu) << "NaN payload of " << std::hex << h;
    } else {
      ASSERT_EQ(static_cast<double>(value), expected) << std::hex << h;
    }
    ASSERT_EQ(bits >> 31, h >> 15) << "sign of " << std::hex << h;
  }
}

TEST(VertexFormats, ColoursAreClampedRoundedAndPackedAsArgb) {
  EXPECT_EQ(PackD3dColor({1.0f, 0.5f, 0.0f, 2.0f}), 0xFFFF8000u);  // 127.5 rounds to even 128
  EXPECT_EQ(PackD3dColor({-1.0f, NAN, 0.25f, 0.0f}), 0x00000040u);  // 63.75 -> 64
  std::uint8_t bytes[4];
  WriteElement(DeclType::kD3dColor, {1.0f, 0.0f, 0.0f, 0.0f}, bytes);
  EXPECT_EQ(bytes[2], 0xFF);  // R is the third byte, as D3DCOLOR's BGRA memory order
}

TEST(VertexFormats, SizesAreD3d9s) {
  EXPECT_EQ(DeclTypeSize(static_cast<int>(DeclType::kFloat3)), 12u);
  EXPECT_EQ(DeclTypeSize(static_cast<int>(DeclType::kShort4n)), 8u);
  EXPECT_EQ(DeclTypeSize(static_cast<int>(DeclType::kDec3n)), 4u);
  EXPECT_EQ(DeclTypeSize(static_cast<int>(DeclType::kFloat16x4)), 8u);
  EXPECT_FALSE(DeclTypeSize(static_cast<int>(DeclType::kUnused)));
  EXPECT_FALSE(DeclTypeSize(-1));
}

}  // namespace
}  // namespace vs11::capi

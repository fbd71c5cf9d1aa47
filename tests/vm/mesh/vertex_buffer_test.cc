// Raw interleaved buffers (vm/mesh/vertex_buffer.h): every offset and count a user gives is checked
// without wrapping around before a byte is read. Under ASan (CI's sanitizer stage) a read outside
// the buffer fails these tests even where the values happen to look right.
#include "vm/mesh/vertex_buffer.h"

#include <cstring>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

namespace vs11::mesh {
namespace {

constexpr std::size_t kHuge = std::numeric_limits<std::size_t>::max();

std::vector<std::uint8_t> Floats(int count) {
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(count) * 4);
  for (int i = 0; i < count; ++i) {
    const float value = static_cast<float>(i);
    std::memcpy(bytes.data() + 4 * i, &value, 4);
  }
  return bytes;
}

TEST(VertexBuffer, RefusesAnOffsetWhoseEndWrapsAround) {
  // 2^64 - 16 + 4 * 4 wraps to 0, which passed the old check and read 16 bytes before the buffer.
  BufferElement element;
  ASSERT_TRUE(ParseBufferElement("v0=18446744073709551600:4", element).ok());
  const std::vector<std::uint8_t> bytes = Floats(8);
  RegisterData registers;
  const Status error = ReadInterleaved(bytes, 16, {element}, "seq.bin", registers);
  ASSERT_FALSE(error.ok());
  EXPECT_EQ(error.error().code, DiagnosticCode::kBufferLayout);
  EXPECT_NE(error.message().find("--element v0=18446744073709551600:4 ends past the 16-byte stride"), std::string::npos)
      << error.message();
  EXPECT_TRUE(registers.empty());
}

TEST(VertexBuffer, RefusesEveryOffsetAndCountNearTheTopOfTheAddressSpace) {
  const std::vector<std::uint8_t> bytes = Floats(8);
  for (std::size_t offset : {kHuge, kHuge - 3, kHuge - 4, kHuge - 15, kHuge / 4 + 1, std::size_t{17}, std::size_t{13}}) {
    for (int components = 1; components <= 4; ++components) {
      RegisterData registers;
      EXPECT_FALSE(ReadInterleaved(bytes, 16, {{0, offset, components}}, "b", registers).ok())
          << offset << ":" << components;
      EXPECT_TRUE(registers.empty());
    }
  }
}

TEST(VertexBuffer, RefusesLayoutsNoParserWouldMake) {
  const std::vector<std::uint8_t> bytes = Floats(8);
  const struct {
    std::size_t stride;
    std::vector<BufferElement> elements;
    const char* message;
  } cases[] = {
      {16, {{0, 0, 0}}, "1 to 4 floats"},
      {16, {{0, 0, 5}}, "1 to 4 floats"},
      {16, {{0, 0, -2147483647 - 1}}, "1 to 4 floats"},
      {16, {{16, 0, 4}}, "not an input register"},
      {16, {{-1, 0, 4}}, "not an input register"},
      {16, {{3, 0, 2}, {3, 8, 2}}, "--element v3 is given twice"},
      {0, {{0, 0, 1}}, "--stride 0"},
      {kHuge, {{0, 0, 1}}, "must be 1 to"},
      {16, {}, "at least one --element"},
  };
  for (const auto& c : cases) {
    RegisterData registers;
    const Status error = ReadInterleaved(bytes, c.stride, c.elements, "b", registers);
    ASSERT_FALSE(error.ok()) << c.message;
    EXPECT_NE(error.message().find(c.message), std::string::npos) << error.message();
    EXPECT_EQ(CheckBufferLayout(c.stride, c.elements).message(), error.message());
  }
}

TEST(VertexBuffer, ElementEndingExactlyAtTheStrideReadsTheLastFloats) {
  const std::vector<std::uint8_t> bytes = Floats(8);
  RegisterData registers;
  ASSERT_TRUE(ReadInterleaved(bytes, 16, {{2, 12, 1}, {5, 0, 4}}, "b", registers).ok());
  ASSERT_EQ(registers.size(), 2u);
  EXPECT_EQ(registers[0].second[1], (Vec4f{7, 0, 0, 1}));
  EXPECT_EQ(registers[1].second[1], (Vec4f{4, 5, 6, 7}));
}

TEST(VertexBuffer, ParserRefusesOffsetsBeyondSizeT) {
  BufferElement element;
  const Status error = ParseBufferElement("v0=18446744073709551616:4", element);
  ASSERT_FALSE(error.ok());
  EXPECT_EQ(error.error().code, DiagnosticCode::kBufferElement);
  EXPECT_NE(error.message().find("the offset is not a byte count"), std::string::npos) << error.message();
  EXPECT_FALSE(ParseBufferElement("v0=-16:4", element).ok());
  EXPECT_FALSE(ParseBufferElement("v0=0:-1", element).ok());
  EXPECT_FALSE(ParseBufferElement("v0=0:4294967297", element).ok());
}

}  // namespace
}  // namespace vs11::mesh

#include "vm/mesh/npy.h"

#include <cstring>
#include <limits>
#include <string>

#include <gtest/gtest.h>

namespace vs11::mesh {
namespace {

std::vector<std::uint8_t> Bytes(const std::string& text) { return {text.begin(), text.end()}; }

// A version 1.0 file with the given header dict and data bytes.
std::vector<std::uint8_t> NpyWithHeader(const std::string& dict, std::size_t data_bytes, int major = 1) {
  std::string header = dict + "\n";
  std::vector<std::uint8_t> bytes = Bytes(std::string("\x93NUMPY", 6));
  bytes.push_back(static_cast<std::uint8_t>(major));
  bytes.push_back(0);
  const int length_bytes = major == 1 ? 2 : 4;
  for (int i = 0; i < length_bytes; ++i) bytes.push_back(static_cast<std::uint8_t>(header.size() >> (8 * i)));
  bytes.insert(bytes.end(), header.begin(), header.end());
  bytes.resize(bytes.size() + data_bytes, 0);
  return bytes;
}

TEST(Npy, FormatThenParseIsExactForEveryFloat) {
  NpyArray array;
  array.rows = 5;
  array.columns = 3;
  array.values = {0.0f, -0.0f, 1.0f, std::numeric_limits<float>::denorm_min(), std::numeric_limits<float>::max(),
                  -1e-30f, std::numeric_limits<float>::infinity(), 3.25f, -7.5f, 0.1f, 1e30f, -2.0f,
                  std::numeric_limits<float>::quiet_NaN(), 5.0f, 6.0f};
  std::vector<std::uint8_t> bytes = FormatNpy(array);
  ASSERT_EQ(bytes.size() % 64, (array.values.size() * 4) % 64);  // header padded to 64 bytes
  Result<NpyArray> parsed = ParseNpy(bytes, "a.npy");
  ASSERT_TRUE(parsed.ok()) << parsed.message();
  EXPECT_EQ(parsed->rows, 5u);
  EXPECT_EQ(parsed->columns, 3);
  ASSERT_EQ(parsed->values.size(), array.values.size());
  EXPECT_EQ(std::memcmp(parsed->values.data(), array.values.data(), array.values.size() * 4), 0);
  EXPECT_EQ(parsed->Row(1), (Vec4f{std::numeric_limits<float>::denorm_min(), std::numeric_limits<float>::max(),
                                         -1e-30f, 1.0f}));  // the fourth component from (0, 0, 0, 1)
}

TEST(Npy, ReadsVectorsFortranOrderAndLaterVersions) {
  std::vector<std::uint8_t> vector = NpyWithHeader("{'descr': '<f4', 'fortran_order': False, 'shape': (2,), }", 8);
  Result<NpyArray> one = ParseNpy(vector, "v.npy");
  ASSERT_TRUE(one.ok()) << one.message();
  EXPECT_EQ(one->columns, 1);
  EXPECT_EQ(one->Row(0), (Vec4f{0, 0, 0, 1}));

  std::vector<std::uint8_t> fortran = NpyWithHeader("{'shape': (2, 2), 'fortran_order': True, 'descr': '<f4'}", 16, 2);
  const float column_major[4] = {1, 2, 3, 4};  // columns (1, 2) and (3, 4)
  std::memcpy(fortran.data() + fortran.size() - 16, column_major, 16);
  Result<NpyArray> f = ParseNpy(fortran, "f.npy");
  ASSERT_TRUE(f.ok()) << f.message();
  EXPECT_EQ(f->values, (std::vector<float>{1, 3, 2, 4}));
}

TEST(Npy, RefusesAnythingButFloat32RowsOfOneToFour) {
  const struct {
    std::vector<std::uint8_t> bytes;
    const char* message;
  } cases[] = {
      {Bytes("not numpy at all"), "magic"},
      {NpyWithHeader("{'descr': '<f8', 'fortran_order': False, 'shape': (2, 3), }", 48), "not float32"},
      {NpyWithHeader("{'descr': '>f4', 'fortran_order': False, 'shape': (2, 3), }", 24), "not float32"},
      {NpyWithHeader("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 5), }", 40), "1 to 4"},
      {NpyWithHeader("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3, 1), }", 24), "more than two dimensions"},
      {NpyWithHeader("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }", 20), "needs 24 bytes"},
      {NpyWithHeader("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }", 28), "needs 24 bytes"},
      {NpyWithHeader("{'descr': '<f4', 'fortran_order': False, 'shape': (), }", 4), "scalar"},
      {NpyWithHeader("{'descr': '<f4', 'shape': (2, 3), }", 24), "lacks"},
      {NpyWithHeader("{'descr': '<f4', 'fortran_order': Maybe, 'shape': (2, 3), }", 24), "neither True"},
      {NpyWithHeader("{'descr': '<f4', 'fortran_order': False, 'shape': (-2, 3), }", 24), "non-negative"},
      {NpyWithHeader("{'descr': '<f4', 'fortran_order': False, 'shape': (99999999999, 3), }", 24), "over the limit"},
      // rows * 4 * 4 wraps to 0 bytes of data; rows beyond size_t.
      {NpyWithHeader("{'descr': '<f4', 'fortran_order': False, 'shape': (1152921504606846976, 4), }", 0), "over the limit"},
      {NpyWithHeader("{'descr': '<f4', 'fortran_order': True, 'shape': (4611686018427387904, 4), }", 0), "over the limit"},
      {NpyWithHeader("{'descr': '<f4', 'fortran_order': False, 'shape': (18446744073709551616,), }", 0), "non-negative"},
      {NpyWithHeader("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 4611686018427387905), }", 0), "1 to 4"},
      {NpyWithHeader("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), 'extra': 1}", 24), "unknown header key"},
      {NpyWithHeader("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }", 24, 4), "version 4"},
  };
  for (const auto& c : cases) {
    Result<NpyArray> result = ParseNpy(c.bytes, "bad.npy");
    ASSERT_FALSE(result.ok()) << c.message;
    EXPECT_EQ(result.error().code, DiagnosticCode::kCannotReadFile) << c.message;
    EXPECT_NE(result.message().find(c.message), std::string::npos) << result.message();
    EXPECT_EQ(result.message().rfind("bad.npy: ", 0), 0u) << result.message();
  }
  std::vector<std::uint8_t> truncated = NpyWithHeader("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }", 24);
  for (std::size_t size = 0; size < 20; ++size) {
    EXPECT_FALSE(ParseNpy(std::span(truncated).first(size), "cut.npy").ok()) << size;
  }
}

TEST(NpyGrid, ReadsThreeDimensionsInCAndFortranOrder) {
  std::vector<std::uint8_t> c_order = NpyWithHeader("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3, 4), }", 96);
  std::vector<float> values(24);
  for (int i = 0; i < 24; ++i) values[static_cast<std::size_t>(i)] = static_cast<float>(i);
  std::memcpy(c_order.data() + c_order.size() - 96, values.data(), 96);
  Result<NpyGrid> c = ParseNpyGrid(c_order, "c.npy");
  ASSERT_TRUE(c.ok()) << c.message();
  EXPECT_EQ(c->shape, (std::vector<std::size_t>{2, 3, 4}));
  EXPECT_EQ(c->values, values);

  // Element (i, j, k) of a (2, 3, 4) Fortran array lies at i + 2 (j + 3 k) in the file.
  std::vector<std::uint8_t> fortran = NpyWithHeader("{'descr': '<f4', 'fortran_order': True, 'shape': (2, 3, 4), }", 96);
  std::vector<float> column_major(24);
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 3; ++j) {
      for (int k = 0; k < 4; ++k) column_major[static_cast<std::size_t>(i + 2 * (j + 3 * k))] = values[static_cast<std::size_t>((i * 3 + j) * 4 + k)];
    }
  }
  std::memcpy(fortran.data() + fortran.size() - 96, column_major.data(), 96);
  Result<NpyGrid> f = ParseNpyGrid(fortran, "f.npy");
  ASSERT_TRUE(f.ok()) << f.message();
  EXPECT_EQ(f->values, values);
}

TEST(NpyGrid, RefusesFourDimensionsAndShapesOverTheLimit) {
  const Result<NpyGrid> four = ParseNpyGrid(NpyWithHeader("{'descr': '<f4', 'fortran_order': False, 'shape': (1, 1, 1, 1), }", 4), "g.npy");
  ASSERT_FALSE(four.ok());
  EXPECT_NE(four.message().find("more than three dimensions"), std::string::npos) << four.message();
  const Result<NpyGrid> huge = ParseNpyGrid(
      NpyWithHeader("{'descr': '<f4', 'fortran_order': False, 'shape': (65536, 65536, 4), }", 0), "g.npy");
  ASSERT_FALSE(huge.ok());
  EXPECT_NE(huge.message().find("over the limit"), std::string::npos) << huge.message();
}

}  // namespace
}  // namespace vs11::mesh

#include "vm/core/checked_arithmetic.h"

#include <cstddef>
#include <cstdint>
#include <limits>

#include <gtest/gtest.h>

#include "vm/core/machine.h"

namespace vs11 {
namespace {

constexpr std::size_t kMax = std::numeric_limits<std::size_t>::max();

TEST(CheckedArithmetic, GivesTheExactResultOrNothing) {
  EXPECT_EQ(CheckedAdd<std::size_t>(kMax - 1, 1), kMax);
  EXPECT_EQ(CheckedAdd<std::size_t>(kMax, 1), std::nullopt);
  EXPECT_EQ(CheckedMul<std::size_t>(kMax / 4 + 1, 4), std::nullopt);
  EXPECT_EQ(CheckedMul<std::size_t>(kMax / 4, 4), kMax / 4 * 4);
  EXPECT_EQ(CheckedEnd<std::size_t>(std::size_t{18446744073709551600u}, 4, 4), std::nullopt);  // wraps to 0
  EXPECT_EQ(CheckedEnd<std::size_t>(12, 1, 4), 16u);
  // A negative int is outside an unsigned result, not a huge number.
  EXPECT_EQ(CheckedMul<std::size_t>(-1, 4), std::nullopt);
  EXPECT_EQ(CheckedAdd<int>(std::int64_t{1} << 40, 0), std::nullopt);
}

// A vertex count from a caller's array (a NumPy view broadcast to 2^62 rows costs nothing) made
// the size wrap around to a few floats, which the arrays then filled far beyond.
TEST(VertexArrays, RefuseCountsWhoseSizeWrapsAround) {
  const int registers[] = {0, 1, 2};
  for (std::size_t count : {kMax, kMax - 15, std::size_t{1} << 62, std::size_t{1} << 60}) {
    EXPECT_THROW(VertexArrays(count, registers, kInputRegisterCount), std::length_error) << count;
    EXPECT_THROW(MakeInputArrays(count, registers), std::length_error) << count;
  }
  const VertexArrays small = MakeInputArrays(3, registers);
  EXPECT_EQ(small.count(), 3u);
  EXPECT_EQ(small.lane(2, 3)[2], 1.0f);
}

}  // namespace
}  // namespace vs11

#include "vm/core/result.h"

#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace vs11 {
namespace {

Result<int> Half(int n) {
  if (n % 2 != 0) return Failure(DiagnosticCode::kNumberOutOfRange, "odd", {"n.txt", 3, 7});
  return n / 2;
}

TEST(Result, HoldsTheValueOfASuccessfulCall) {
  Result<int> half = Half(8);
  ASSERT_TRUE(half.ok());
  EXPECT_TRUE(static_cast<bool>(half));
  EXPECT_EQ(*half, 4);
  EXPECT_EQ(half.value(), 4);
  EXPECT_EQ(half.message(), "");
}

TEST(Result, HoldsTheDiagnosticOfAFailedCallWithItsCodeAndPlace) {
  Result<int> half = Half(7);
  ASSERT_FALSE(half.ok());
  EXPECT_EQ(half.error().code, DiagnosticCode::kNumberOutOfRange);
  EXPECT_EQ(half.error().severity, Severity::kError);
  EXPECT_EQ(half.message(), "odd");
  EXPECT_EQ(half.error().loc, (SourceLoc{"n.txt", 3, 7}));
  EXPECT_EQ(FormatDiagnostic(half.error()), "n.txt:3:7: error: odd [number-out-of-range]");
}

TEST(Result, TakesAValueItsTypeIsMadeFromAndMovesItOut) {
  struct Base {
    virtual ~Base() = default;
  };
  struct Derived : Base {};
  Result<std::unique_ptr<Base>> made = std::make_unique<Derived>();
  ASSERT_TRUE(made.ok());
  std::unique_ptr<Base> taken = std::move(made).value();
  EXPECT_NE(taken, nullptr);

  Result<std::vector<float>> floats = std::vector<float>{1.0f, 2.0f};
  EXPECT_EQ(floats->size(), 2u);
  Result<std::string> text = "words";
  EXPECT_EQ(*text, "words");
}

TEST(Status, IsOkByDefaultAndCarriesTheDiagnosticOfAFailure) {
  Status fine;
  EXPECT_TRUE(fine.ok());
  EXPECT_EQ(fine.message(), "");
  Status failed = Failure(DiagnosticCode::kCannotReadFile, "no such file");
  ASSERT_FALSE(failed.ok());
  EXPECT_FALSE(static_cast<bool>(failed));
  EXPECT_EQ(failed.error().code, DiagnosticCode::kCannotReadFile);
  EXPECT_EQ(failed.message(), "no such file");
}

TEST(ResultDeathTest, ReadingTheValueOfAFailedResultAbortsWithItsMessage) {
  // The child re-runs this test alone: other tests' thread pools may hold locks at a plain fork.
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_DEATH((void)Half(5).value(), "the value of a failed Result was read: n.txt:3:7: error: odd");
  EXPECT_DEATH((void)Half(4).error(), "the error of a successful Result was read");
  EXPECT_DEATH((void)Status().error(), "the error of a successful Result was read");
}

}  // namespace
}  // namespace vs11

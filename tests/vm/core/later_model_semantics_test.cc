// The later models' arithmetic kernels (vm/core/semantics.h) on floats, under both float rules,
// against values computed by hand, edge cases included.
#include <bit>
#include <cfloat>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "vm/core/semantics.h"

namespace vs11::semantics {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

template <class S>
float Lane(float a, float b = 0.0f, float c = 0.0f, FloatRules rules = FloatRules::kD3d9) {
  return rules == FloatRules::kD3d9 ? RunLane<FloatRules::kD3d9, S>(a, b, c) : RunLane<FloatRules::kLegacy, S>(a, b, c);
}
template <class S>
Vec4<float> Vector(const Vec4<float>& a, const Vec4<float>& b = {}, FloatRules rules = FloatRules::kD3d9) {
  return rules == FloatRules::kD3d9 ? RunVector<FloatRules::kD3d9, S>(a, b) : RunVector<FloatRules::kLegacy, S>(a, b);
}

class LaterModelSemantics : public ::testing::TestWithParam<FloatRules> {};
INSTANTIATE_TEST_SUITE_P(Rules, LaterModelSemantics, ::testing::Values(FloatRules::kD3d9, FloatRules::kLegacy));

TEST_P(LaterModelSemantics, AbsClearsTheSign) {
  EXPECT_EQ(Lane<AbsSemantics>(-2.5f), 2.5f);
  EXPECT_EQ(std::bit_cast<std::uint32_t>(Lane<AbsSemantics>(-0.0f)), 0u);
  EXPECT_EQ(Lane<AbsSemantics>(-kInf), kInf);
}

TEST_P(LaterModelSemantics, LrpIsS0TimesS1MinusS2PlusS2) {
  EXPECT_EQ(Lane<LrpSemantics>(0.25f, 8.0f, 4.0f, GetParam()), 5.0f);   // 0.25 * 4 + 4
  EXPECT_EQ(Lane<LrpSemantics>(0.0f, 8.0f, 4.0f, GetParam()), 4.0f);
  EXPECT_EQ(Lane<LrpSemantics>(1.0f, 8.0f, 4.0f, GetParam()), 8.0f);
  EXPECT_EQ(Lane<LrpSemantics>(-1.0f, 3.0f, 1.0f, GetParam()), -1.0f);  // -1 * 2 + 1
}

TEST_P(LaterModelSemantics, LrpOfZeroWeightAndInfiniteSpanFollowsTheFloatRules) {
  const float result = Lane<LrpSemantics>(0.0f, kInf, 1.0f, GetParam());
  if (GetParam() == FloatRules::kLegacy) {
    EXPECT_EQ(result, 1.0f);  // 0 * inf = 0
  } else {
    EXPECT_TRUE(std::isnan(result));
  }
}

TEST_P(LaterModelSemantics, CrsIsTheCrossProduct) {
  const Vec4<float> r = Vector<CrsSemantics>({1, 2, 3, 9}, {4, 5, 6, 9}, GetParam());
  EXPECT_EQ(r[0], 2 * 6 - 3 * 5);  // -3
  EXPECT_EQ(r[1], 3 * 4 - 1 * 6);  // 6
  EXPECT_EQ(r[2], 1 * 5 - 2 * 4);  // -3
  const Vec4<float> xy = Vector<CrsSemantics>({1, 0, 0, 0}, {0, 1, 0, 0}, GetParam());
  EXPECT_EQ(xy[2], 1.0f);
}

TEST_P(LaterModelSemantics, NrmScalesAllFourLanes) {
  const Vec4<float> r = Vector<NrmSemantics>({3, 0, 4, 10}, {}, GetParam());
  EXPECT_FLOAT_EQ(r[0], 0.6f);
  EXPECT_EQ(r[1], 0.0f);
  EXPECT_FLOAT_EQ(r[2], 0.8f);
  EXPECT_FLOAT_EQ(r[3], 2.0f);  // w * 1/5 too
  const Vec4<float> unit = Vector<NrmSemantics>({0, 0, 2, 0}, {}, GetParam());
  EXPECT_EQ(unit[2], 1.0f);  // 1/sqrt(4) and 2 * 0.5 are exact
}

TEST_P(LaterModelSemantics, NrmOfAZeroVectorScalesByFltMax) {
  const Vec4<float> zero = Vector<NrmSemantics>({0, -0.0f, 0, 0}, {}, GetParam());
  for (int lane = 0; lane < 4; ++lane) EXPECT_EQ(zero[lane], 0.0f) << lane;
  const Vec4<float> w_only = Vector<NrmSemantics>({0, 0, 0, 1e-30f}, {}, GetParam());
  EXPECT_FLOAT_EQ(w_only[3], 1e-30f * FLT_MAX);
  const Vec4<float> w_one = Vector<NrmSemantics>({0, 0, 0, 1}, {}, GetParam());
  EXPECT_EQ(w_one[3], FLT_MAX);
}

TEST_P(LaterModelSemantics, PowIsTheAbsoluteBaseRaisedAndReplicated) {
  const Vec4<float> r = Vector<PowSemantics>({0, 0, 0, 2}, {0, 0, 0, 3}, GetParam());
  for (float v : r) EXPECT_EQ(v, 8.0f);  // exact: log2 2 = 1, exp2 3 = 8
  EXPECT_EQ(Vector<PowSemantics>({0, 0, 0, -2}, {0, 0, 0, 3}, GetParam())[0], 8.0f);  // |-2|^3, not -8
  EXPECT_EQ(Vector<PowSemantics>({0, 0, 0, -4}, {0, 0, 0, 0.5f}, GetParam())[0], 2.0f);
  EXPECT_NEAR(Vector<PowSemantics>({0, 0, 0, 3}, {0, 0, 0, 2}, GetParam())[0], 9.0f, 9.0f * 2e-7f);
  EXPECT_NEAR(Vector<PowSemantics>({0, 0, 0, 10}, {0, 0, 0, -1}, GetParam())[0], 0.1f, 0.1f * 2e-7f);
}

TEST_P(LaterModelSemantics, PowEdgesOfZeroBase) {
  EXPECT_EQ(Vector<PowSemantics>({0, 0, 0, 0}, {}, GetParam())[0], 1.0f);                // 0^0
  EXPECT_EQ(Vector<PowSemantics>({0, 0, 0, 0}, {0, 0, 0, 2}, GetParam())[0], 0.0f);      // 0^2
  EXPECT_EQ(Vector<PowSemantics>({0, 0, 0, -0.0f}, {0, 0, 0, -1}, GetParam())[0], kInf);  // 0^-1
}

TEST(LaterModelSemantics, SgnGivesMinusOneZeroOrOne) {
  EXPECT_EQ(Lane<SgnSemantics>(-3.0f), -1.0f);
  EXPECT_EQ(Lane<SgnSemantics>(1e-40f), 1.0f);  // a denormal is not zero
  EXPECT_EQ(Lane<SgnSemantics>(kInf), 1.0f);
  EXPECT_EQ(std::bit_cast<std::uint32_t>(Lane<SgnSemantics>(0.0f)), 0u);
  EXPECT_EQ(std::bit_cast<std::uint32_t>(Lane<SgnSemantics>(-0.0f)), 0u);  // +0 for both zeros
  EXPECT_EQ(Lane<SgnSemantics>(kNaN), 1.0f);  // neither < 0 nor == 0
}

// Ties away from zero, the reading we chose; ties to even, the other reading, differs at 2.5 and -2.5.
float TiesToEven(float x) { return std::nearbyint(x); }

TEST(LaterModelSemantics, MovaRoundsTiesAwayFromZero) {
  EXPECT_EQ(Lane<MovaSemantics>(0.5f), 1.0f);
  EXPECT_EQ(Lane<MovaSemantics>(-0.5f), -1.0f);
  EXPECT_EQ(Lane<MovaSemantics>(1.5f), 2.0f);
  EXPECT_EQ(Lane<MovaSemantics>(2.5f), 3.0f);
  EXPECT_EQ(Lane<MovaSemantics>(-2.5f), -3.0f);
  EXPECT_EQ(TiesToEven(2.5f), 2.0f);  // where the readings part
  EXPECT_EQ(TiesToEven(-2.5f), -2.0f);
  EXPECT_EQ(Lane<MovaSemantics>(2.4999998f), 2.0f);
  EXPECT_EQ(Lane<MovaSemantics>(0.49999997f), 0.0f);  // floor(x + 0.5) would give 1
  EXPECT_EQ(Lane<MovaSemantics>(-1.7f), -2.0f);
  EXPECT_EQ(Lane<MovaSemantics>(8388609.0f), 8388609.0f);
  EXPECT_TRUE(std::isnan(Lane<MovaSemantics>(kNaN)));
}

TEST(LaterModelSemantics, CompareHasSixComparisonsAndNaNFailsAllButNe) {
  const float one = 1.0f, two = 2.0f;
  EXPECT_EQ(Compare(1, two, one), 1.0f);
  EXPECT_EQ(Compare(1, one, one), 0.0f);
  EXPECT_EQ(Compare(2, one, one), 1.0f);
  EXPECT_EQ(Compare(3, one, one), 1.0f);
  EXPECT_EQ(Compare(4, one, two), 1.0f);
  EXPECT_EQ(Compare(5, one, two), 1.0f);
  EXPECT_EQ(Compare(5, one, one), 0.0f);
  EXPECT_EQ(Compare(6, one, one), 1.0f);
  EXPECT_EQ(Compare(6, two, one), 0.0f);
  for (int comparison = 1; comparison <= 6; ++comparison) {
    EXPECT_EQ(Compare(comparison, kNaN, one), comparison == 5 ? 1.0f : 0.0f) << comparison;
  }
}

TEST(LaterModelSemantics, SincosGivesCosInXAndSinInY) {
  for (float angle : {-3.14159265f, -2.0f, -0.5f, 0.0f, 0.25f, 1.0f, 1.57079633f, 3.0f, 3.14159265f, 10.0f, -100.0f}) {
    const Vec4<float> r = Vector<SincosSemantics>({0, 0, 0, angle});
    EXPECT_NEAR(r[0], std::cos(static_cast<double>(angle)), 3e-7) << angle;
    EXPECT_NEAR(r[1], std::sin(static_cast<double>(angle)), 3e-7) << angle;
  }
  const Vec4<float> zero = Vector<SincosSemantics>({0, 0, 0, 0});
  EXPECT_EQ(zero[0], 1.0f);
  EXPECT_EQ(zero[1], 0.0f);
  EXPECT_TRUE(std::isnan(Vector<SincosSemantics>({0, 0, 0, kInf})[0]));
  EXPECT_TRUE(std::isnan(Vector<SincosSemantics>({0, 0, 0, kNaN})[1]));
}

}  // namespace
}  // namespace vs11::semantics

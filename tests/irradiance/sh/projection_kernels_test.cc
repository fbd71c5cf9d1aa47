// The SIMD projection kernels (irradiance/sh/projection_kernels.cc) on every Highway target this build
// compiled and the CPU supports: level-0 projection against the double direct projection, and the
// mip halving against its scalar definition, bit for bit.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hwy/highway.h"
#include "hwy/tests/hwy_gtest.h"
#include "irradiance/io/environments.h"
#include "irradiance/sh/projection_kernels.h"
#include "irradiance/sh/sh_projection.h"
#include "tests/irradiance/sh/level_baseline.h"

namespace vs11::irradiance {
namespace {

using baseline::RelativeDifference;

// Texels of every face different and every coefficient non-zero: a sky with a tinted +x column
// and a blue -z face.
CubeMap Asymmetric(int size) {
  CubeMap map = MakeSky(size);
  for (int y = 0; y < size; ++y) map.face(CubeFace::kPositiveX).at(size / 3, y) += glm::vec3(2.0f, 0.0f, 1.0f);
  for (glm::vec3& texel : map.face(CubeFace::kNegativeZ).pixels) texel *= glm::vec3(0.5f, 0.8f, 1.5f);
  return map;
}

// Float terms summed in double per block of a row: measured 1e-9 to 9e-8 of the largest coefficient
// at faces 1 to 512, 3e-7 to 7e-7 at 2048 with a 1e6 sun (by target; the XML output records it).
constexpr double kFinestRelative = 1e-6;
// Every level against its texel-by-texel baseline: the same bound as level 0's (the weights and the
// terms are rounded to float once each, and float sums are kept as short as level 0's).
constexpr double kLevelRelative = 1e-6;

class ProjectionKernels : public hwy::TestWithParamTarget {};
HWY_TARGET_INSTANTIATE_TEST_SUITE_P(ProjectionKernels);

// Sizes below, at and above a vector's lanes and a 256-texel block.
TEST_P(ProjectionKernels, FinestMatchesDirectProjection) {
  for (int size : {1, 2, 4, 8, 16, 32, 64, 512}) {
    const CubeMap env = Asymmetric(size);
    const double difference = RelativeDifference(ProjectFinest(env, BuildFinestWeights(size)), ProjectDirect(env));
    RecordProperty(fmt::format("relative_difference_{}", size), fmt::format("{:.3g}", difference));
    EXPECT_LT(difference, kFinestRelative) << "face " << size;
  }
}

TEST_P(ProjectionKernels, ProjectLevelZeroIsProjectFinest) {
  constexpr int kSize = 32;
  const CubeMap env = Asymmetric(kSize);
  const std::optional<CubeMipChain> chain = BuildEnvironmentMips(env);
  const std::optional<BasisPyramid> basis = BuildBasisPyramid(kSize);
  ASSERT_TRUE(chain && basis);
  const Sh9Rgb level = ProjectLevel(*chain, *basis, 0);
  const Sh9Rgb finest = ProjectFinest(env, BuildFinestWeights(kSize));
  for (int i = 0; i < kSh9Coefficients; ++i) EXPECT_EQ(level.coefficients[i], finest.coefficients[i]) << i;
}

TEST_P(ProjectionKernels, WhiteFurnaceIsExactToFloatRounding) {
  constexpr int kSize = 128;
  const Sh9Rgb sh = ProjectFinest(MakeConstant(kSize, glm::vec3(1.0f)), BuildFinestWeights(kSize));
  const double l00 = 2.0 * std::sqrt(std::numbers::pi);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sh.at(0, 0)[c], l00, 1e-7 * l00);
  for (int i = 1; i < kSh9Coefficients; ++i) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(sh.coefficients[i][c], 0.0, 1e-7 * l00) << i;
  }
}

// A dim sky with a 1e6 sun of 4 x 4 texels at face 2048, its mip pyramid, its pyramid of weights
// and every level's texel-by-texel baseline (level 0's is ProjectDirect's sum, added in another
// order); built once (about 500 MB and 4 s of one core in a Release build) and shared by the tests
// below.
struct HdrSunAt2048 {
  static constexpr int kSize = 2048;
  CubeMipChain chain;
  BasisPyramid basis;
  std::vector<Sh9Rgb> baselines;

  static const HdrSunAt2048& Get() {
    static const HdrSunAt2048 fixture = [] {
      CubeMap map(kSize);
      for (int f = 0; f < kCubeFaceCount; ++f) {
        for (int y = 0; y < kSize; ++y) {
          for (int x = 0; x < kSize; ++x) {
            map.faces[f].at(x, y) = glm::vec3(0.2f + 0.1f * f, 0.5f * y / kSize, 0.3f + 0.2f * x / kSize);
          }
        }
      }
      for (int y = 900; y < 904; ++y) {
        for (int x = 1300; x < 1304; ++x) map.face(CubeFace::kPositiveY).at(x, y) = glm::vec3(1e6f, 9e5f, 8e5f);
      }
      HdrSunAt2048 built;
      built.chain = *BuildEnvironmentMips(std::move(map));
      built.basis = *BuildBasisPyramid(kSize, 2);
      built.baselines = baseline::LevelBaselines(built.chain);
      return built;
    }();
    return fixture;
  }
};

// The stability report's precision finding: one float sum per coefficient over 6 x 2048^2 texels
// loses the sky (116 % irradiance error). Short float blocks summed in double do not: level 0 at
// 2048, with a 1e6 sun over a dim sky, stays within the same bound as at small sizes.
TEST_P(ProjectionKernels, FinestKeepsPrecisionAt2048WithAnHdrSun) {
  const HdrSunAt2048& sun = HdrSunAt2048::Get();
  const CubeMap& env = sun.chain.levels[0];
  const double difference =
      RelativeDifference(ProjectFinest(env, BuildFinestWeights(HdrSunAt2048::kSize)), sun.baselines[0]);
  RecordProperty("relative_difference", fmt::format("{:.3g}", difference));
  EXPECT_LT(difference, kFinestRelative);
}

// Every level's projection against its texel-by-texel double baseline (tests/irradiance/sh/level_baseline.h):
// the float rounding of the weights and of the terms, not the mip method's blur, which the baseline
// shares. Faces 1 to 256 of an asymmetric sky, every level; the XML output records each difference.
TEST_P(ProjectionKernels, EveryLevelMatchesItsTexelByTexelBaseline) {
  // The baselines do not depend on the target: computed once for all of them.
  static std::map<int, std::vector<Sh9Rgb>> baselines_by_size;
  for (int size : {1, 2, 4, 8, 16, 32, 64, 256}) {
    const std::optional<CubeMipChain> chain = BuildEnvironmentMips(Asymmetric(size));
    const std::optional<BasisPyramid> basis = BuildBasisPyramid(size);
    ASSERT_TRUE(chain && basis);
    std::vector<Sh9Rgb>& baselines = baselines_by_size[size];
    if (baselines.empty()) baselines = baseline::LevelBaselines(*chain);
    for (int level = 0; level < LevelCount(size); ++level) {
      const double difference = RelativeDifference(ProjectLevel(*chain, *basis, level), baselines[level]);
      RecordProperty(fmt::format("face_{}_level_{}", size, level), fmt::format("{:.3g}", difference));
      EXPECT_LT(difference, kLevelRelative) << "face " << size << " level " << level;
    }
  }
}

// The same with the 1e6 sun at 2048, every level from 2048 x 2048 down to 1 x 1.
TEST_P(ProjectionKernels, EveryLevelKeepsPrecisionAt2048WithAnHdrSun) {
  const HdrSunAt2048& sun = HdrSunAt2048::Get();
  for (int level = 0; level < LevelCount(HdrSunAt2048::kSize); ++level) {
    const double difference = RelativeDifference(ProjectLevel(sun.chain, sun.basis, level), sun.baselines[level]);
    RecordProperty(fmt::format("level_{}", level), fmt::format("{:.3g}", difference));
    EXPECT_LT(difference, kLevelRelative) << "level " << level;
  }
}

TEST_P(ProjectionKernels, HalvingIsTheScalarBoxMeanBitForBit) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> value(-10.0f, 1000.0f);
  // Widths below, at and above one group of 2 L texels (L = 4, 8, 16 lanes) and several groups.
  for (int width : {1, 3, 4, 8, 15, 16, 17, 32, 33, 48, 64, 100}) {
    std::vector<float> upper(6 * width), lower(6 * width), out(3 * width, -1.0f);
    for (float& v : upper) v = value(random);
    for (float& v : lower) v = value(random);
    std::vector<float> copied_out(3 * width, -1.0f), copied_upper(6 * width, -1.0f), copied_lower(6 * width, -1.0f);
    kernels::HalveRowPair(upper.data(), lower.data(), out.data(), width);
    kernels::CopyAndHalveRowPair(upper.data(), lower.data(), copied_upper.data(), copied_lower.data(),
                                 copied_out.data(), width);
    EXPECT_EQ(copied_upper, upper) << "width " << width;
    EXPECT_EQ(copied_lower, lower) << "width " << width;
    for (int x = 0; x < width; ++x) {
      for (int c = 0; c < 3; ++c) {
        const float expected =
            ((upper[6 * x + c] + upper[6 * x + 3 + c]) + (lower[6 * x + c] + lower[6 * x + 3 + c])) * 0.25f;
        ASSERT_EQ(out[3 * x + c], expected) << "width " << width << " texel " << x << " channel " << c;
        ASSERT_EQ(copied_out[3 * x + c], expected) << "width " << width << " texel " << x << " channel " << c;
      }
    }
  }
}

TEST_P(ProjectionKernels, HalvingOfTexelsAtFloatMaxStaysFinite) {
  // ((a + b) + (c + d)) / 4 overflows above FLT_MAX / 4; the mean of finite texels never does.
  for (int width : {1, 4, 16, 33}) {
    std::vector<float> upper(6 * width, std::numeric_limits<float>::max()), lower(6 * width, 3e38f);
    std::vector<float> out(3 * width, -1.0f);
    kernels::HalveRowPair(upper.data(), lower.data(), out.data(), width);
    for (float v : out) {
      ASSERT_TRUE(std::isfinite(v)) << "width " << width;
      ASSERT_EQ(v, std::numeric_limits<float>::max() * 0.5f + 1.5e38f) << "width " << width;
    }
  }
}

}  // namespace
}  // namespace vs11::irradiance

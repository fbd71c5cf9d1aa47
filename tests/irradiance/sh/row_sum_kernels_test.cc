// The row-sum kernels (irradiance/sh/row_sum_kernels.h) on every Highway target this build compiled
// and the CPU supports: each equals the definition in the header (eight partial sums in texel order,
// folded in lane order) bit for bit, over row lengths around every vector width and with terms whose
// sum depends on the order of the additions; ProjectLevel and GroundTruthIrradiance, which call them,
// give the same bits on every target.
#include "irradiance/sh/row_sum_kernels.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "hwy/highway.h"
#include "hwy/tests/hwy_gtest.h"
#include "irradiance/io/environments.h"
#include "irradiance/sh/ground_truth.h"
#include "irradiance/sh/sh_projection.h"

namespace vs11::irradiance::kernels {
namespace {

using Lanes = std::array<ChannelSums, kRowSumLanes>;

ChannelSums FoldInLaneOrder(const Lanes& lanes) {
  ChannelSums total{0.0, 0.0, 0.0};
  for (const ChannelSums& lane : lanes) {
    for (int c = 0; c < 3; ++c) total[c] += lane[c];
  }
  return total;
}

// The header's definition of a weighted row sum, one texel at a time.
ChannelSums WeightedRowSumByDefinition(const float* w, const RadianceRow& radiance, int n) {
  Lanes lanes{};
  for (int x = 0; x < n; ++x) {
    ChannelSums& lane = lanes[x % kRowSumLanes];
    const double weight = w[x];
    lane[0] += weight * radiance.red[x];
    lane[1] += weight * radiance.green[x];
    lane[2] += weight * radiance.blue[x];
  }
  return FoldInLaneOrder(lanes);
}

ChannelSums CosineRowSumByDefinition(const CosineTable& t, int row, const ChannelSums& n) {
  Lanes lanes{};
  for (int x = 0; x < t.row_size; ++x) {
    const std::size_t i = static_cast<std::size_t>(row) * t.row_size + x;
    const double dot = (n[0] * t.wx[i] + n[1] * t.wy[i]) + n[2] * t.wz[i];
    const double cosine = dot > 0.0 ? dot : 0.0;
    ChannelSums& lane = lanes[x % kRowSumLanes];
    lane[0] += t.radiance.red[i] * cosine;
    lane[1] += t.radiance.green[i] * cosine;
    lane[2] += t.radiance.blue[i] * cosine;
  }
  return FoldInLaneOrder(lanes);
}

// Values over twelve orders of magnitude and both signs: their sums round differently in any other order.
double Wild(std::mt19937& random) {
  const double mantissa = std::uniform_real_distribution<double>(-1.0, 1.0)(random);
  return static_cast<float>(mantissa * std::pow(10.0, std::uniform_int_distribution<int>(-6, 6)(random)));
}

void ExpectSameBits(const ChannelSums& actual, const ChannelSums& expected, int n) {
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(std::bit_cast<std::uint64_t>(actual[c]), std::bit_cast<std::uint64_t>(expected[c]))
        << "row of " << n << ", channel " << c << ": " << actual[c] << " vs " << expected[c];
  }
}

constexpr int kLengths[] = {0, 1, 2, 3, 4, 5, 7, 8, 9, 15, 16, 17, 31, 33, 64, 100, 257};

class RowSumKernels : public hwy::TestWithParamTarget {};
HWY_TARGET_INSTANTIATE_TEST_SUITE_P(RowSumKernels);

TEST_P(RowSumKernels, WeightedSumsAreTheDefinitionBitForBit) {
  std::mt19937 random(19);
  for (int n : kLengths) {
    constexpr int kRows = 3;
    std::vector<float> weights[kRows];
    std::vector<double> r(n), g(n), b(n);
    for (auto& w : weights) {
      w.resize(n);
      for (float& v : w) v = static_cast<float>(Wild(random));
    }
    for (int x = 0; x < n; ++x) r[x] = Wild(random), g[x] = Wild(random), b[x] = Wild(random);
    const RadianceRow radiance{r.data(), g.data(), b.data()};
    const float* rows[kRows] = {weights[0].data(), weights[1].data(), weights[2].data()};
    // The sums are added to what is there.
    ChannelSums sums[kRows] = {{1.0, -2.0, 0.5}, {0.0, 0.0, 0.0}, {-0.0, 1e-3, 7.0}};
    ChannelSums expected[kRows];
    for (int i = 0; i < kRows; ++i) {
      const ChannelSums row = WeightedRowSumByDefinition(rows[i], radiance, n);
      for (int c = 0; c < 3; ++c) expected[i][c] = sums[i][c] + row[c];
    }
    AddWeightedRowSums(rows, kRows, radiance, n, sums);
    for (int i = 0; i < kRows; ++i) ExpectSameBits(sums[i], expected[i], n);
  }
}

TEST_P(RowSumKernels, ClampedCosineSumsAreTheDefinitionBitForBit) {
  std::mt19937 random(23);
  for (int n : kLengths) {
    constexpr int kRows = 4;
    const std::size_t size = static_cast<std::size_t>(n) * kRows;
    std::vector<double> wx(size), wy(size), wz(size), r(size), g(size), b(size);
    for (std::size_t i = 0; i < size; ++i) {
      wx[i] = Wild(random), wy[i] = Wild(random), wz[i] = Wild(random);
      r[i] = std::abs(Wild(random)), g[i] = std::abs(Wild(random)), b[i] = std::abs(Wild(random));
    }
    // A NaN cosine counts as 0, and a direction at right angles to the normal adds +0.
    if (size > 3) {
      wx[1] = std::numeric_limits<double>::quiet_NaN();
      wx[2] = 0.0, wy[2] = 0.0, wz[2] = -0.0;
    }
    const CosineTable table{wx.data(), wy.data(), wz.data(), {r.data(), g.data(), b.data()}, n, kRows};
    const ChannelSums normals[] = {{0.0, 1.0, 0.0}, {0.6, -0.48, 0.64}, {-1.0, 0.0, 0.0}};
    constexpr int kNormals = 3;
    ChannelSums sums[kNormals] = {{0.25, 0.0, 1.0}, {}, {}};
    ChannelSums expected[kNormals];
    for (int k = 0; k < kNormals; ++k) {
      expected[k] = sums[k];
      for (int row = 0; row < kRows; ++row) {
        const ChannelSums term = CosineRowSumByDefinition(table, row, normals[k]);
        for (int c = 0; c < 3; ++c) expected[k][c] += term[c];
      }
    }
    AddClampedCosineSums(table, normals, kNormals, sums);
    for (int k = 0; k < kNormals; ++k) ExpectSameBits(sums[k], expected[k], n);
  }
}

// The callers, with every target the CPU supports forced in turn, against the first.
TEST(RowSumKernelCallers, GiveTheSameBitsOnEveryTarget) {
  constexpr int kSize = 32;
  CubeMap env = MakeSky(kSize);
  for (int y = 0; y < kSize; ++y) env.faces[1].at(kSize / 3, y) += glm::vec3(2.0f, 0.0f, 1.0f);
  const std::optional<CubeMipChain> mips = BuildEnvironmentMips(env);
  const std::optional<BasisPyramid> basis = BuildBasisPyramid(kSize);
  ASSERT_TRUE(mips && basis);
  const std::vector<glm::dvec3> normals = SphereNormals(37);
  std::optional<std::vector<Sh9Rgb>> first_levels;
  std::optional<std::vector<glm::dvec3>> first_truth;
  const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  ASSERT_FALSE(targets.empty());
  for (std::int64_t target : targets) {
    hwy::SetSupportedTargetsForTest(target);
    std::vector<Sh9Rgb> levels;
    for (int level = 1; level < LevelCount(kSize); ++level) levels.push_back(ProjectLevel(*mips, *basis, level));
    const std::vector<glm::dvec3> truth = GroundTruthIrradiance(env, normals, 1);
    if (!first_levels) {
      first_levels = levels;
      first_truth = truth;
      continue;
    }
    for (std::size_t k = 0; k < levels.size(); ++k) {
      for (int i = 0; i < kSh9Coefficients; ++i) {
        EXPECT_EQ(levels[k].coefficients[i], (*first_levels)[k].coefficients[i])
            << hwy::TargetName(target) << " level " << k + 1 << " coefficient " << i;
      }
    }
    for (std::size_t i = 0; i < truth.size(); ++i) EXPECT_EQ(truth[i], (*first_truth)[i]) << hwy::TargetName(target) << " normal " << i;
  }
  hwy::SetSupportedTargetsForTest(0);
}

}  // namespace
}  // namespace vs11::irradiance::kernels

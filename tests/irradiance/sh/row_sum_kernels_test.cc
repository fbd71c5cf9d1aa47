// The row-sum kernels (irradiance/sh/row_sum_kernels.h) on every Highway target this build compiled
// and the CPU supports: each equals the definition in the header (eight partial sums in texel order,
// folded in lane order) bit for bit, over row lengths around every vector width and with terms whose
// sum depends on the order of the additions; GroundTruthIrradiance, which calls them, gives the same
// bits on every target.
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

// The caller, with every target the CPU supports forced in turn, against the first.
TEST(RowSumKernelCallers, GiveTheSameBitsOnEveryTarget) {
  constexpr int kSize = 32;
  CubeMap env = MakeSky(kSize);
  for (int y = 0; y < kSize; ++y) env.faces[1].at(kSize / 3, y) += glm::vec3(2.0f, 0.0f, 1.0f);
  const std::vector<glm::dvec3> normals = SphereNormals(37);
  std::optional<std::vector<glm::dvec3>> first_truth;
  const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  ASSERT_FALSE(targets.empty());
  for (std::int64_t target : targets) {
    hwy::SetSupportedTargetsForTest(target);
    const std::vector<glm::dvec3> truth = GroundTruthIrradiance(env, normals, 1);
    if (!first_truth) {
      first_truth = truth;
      continue;
    }
    for (std::size_t i = 0; i < truth.size(); ++i) EXPECT_EQ(truth[i], (*first_truth)[i]) << hwy::TargetName(target) << " normal " << i;
  }
  hwy::SetSupportedTargetsForTest(0);
}

}  // namespace
}  // namespace vs11::irradiance::kernels

// The lat-long projection in place: its row kernel against its definition on every SIMD target,
// the projection against a double projection of the same pixels and against an exact
// high-resolution reference, the coarse levels against their definition, and the pyramid's shape.
#include "irradiance/sh/latlong_projection.h"

#include <algorithm>
#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "hwy/highway.h"
#include "hwy/tests/hwy_gtest.h"
#include "irradiance/io/environment_io.h"
#include "irradiance/sh/sh_projection.h"

namespace vs11::irradiance {
namespace {

constexpr double kPi = std::numbers::pi;

// ---- the row kernel ---------------------------------------------------------------------------

kernels::LatLongRowSums RowSumsByDefinition(const std::vector<float>& row,
                                            const std::array<std::vector<float>, 5>& tables) {
  kernels::LatLongRowSums result{};
  const int n = static_cast<int>(row.size());
  for (int j = 0; j < 5; ++j) {
    std::array<double, kernels::kLatLongPartialSums> partial{};
    std::array<float, kernels::kLatLongPartialSums> run{};
    int in_run = 0;  // chunks of kLatLongPartialSums floats added to `run`
    const int padded = (n + kernels::kLatLongPartialSums - 1) / kernels::kLatLongPartialSums *
                       kernels::kLatLongPartialSums;
    for (int i = 0; i < padded; ++i) {
      const float product = i < n ? row[static_cast<std::size_t>(i)] * tables[j][static_cast<std::size_t>(i)] : 0.0f;
      run[static_cast<std::size_t>(i % kernels::kLatLongPartialSums)] += product;
      if ((i + 1) % kernels::kLatLongPartialSums != 0) continue;
      // A run ends after kLatLongFloatRun chunks, or with the whole chunks, and the tail is its own run.
      const int whole_chunks = n / kernels::kLatLongPartialSums;
      const int chunk = i / kernels::kLatLongPartialSums;
      ++in_run;
      if (in_run == kernels::kLatLongFloatRun || chunk + 1 == whole_chunks || chunk + 1 > whole_chunks) {
        for (int p = 0; p < kernels::kLatLongPartialSums; ++p) partial[static_cast<std::size_t>(p)] += run[static_cast<std::size_t>(p)];
        run.fill(0.0f);
        in_run = 0;
      }
    }
    for (int p = 0; p < kernels::kLatLongPartialSums; ++p) result[j][p % 3] += partial[static_cast<std::size_t>(p)];
  }
  return result;
}

class LatLongKernels : public hwy::TestWithParamTarget {};
HWY_TARGET_INSTANTIATE_TEST_SUITE_P(LatLongKernels);

TEST_P(LatLongKernels, RowSumsAreTheDefinitionBitForBit) {
  std::mt19937 random(31);
  // Floats of a row: 3 x widths, around the chunk (48) and run (16 chunks) boundaries.
  for (int width : {1, 2, 15, 16, 17, 32, 256, 257, 272, 512, 600, 2048}) {
    const int n = 3 * width;
    std::vector<float> row(static_cast<std::size_t>(n));
    std::array<std::vector<float>, 5> tables;
    for (float& value : row) {
      value = static_cast<float>(std::ldexp(std::uniform_real_distribution<double>(0.0, 1.0)(random),
                                            std::uniform_int_distribution<int>(-20, 20)(random)));
    }
    for (std::vector<float>& table : tables) {
      table.resize(static_cast<std::size_t>(n));
      for (float& value : table) value = std::uniform_real_distribution<float>(-1.0f, 1.0f)(random);
    }
    const kernels::LatLongRowSums expected = RowSumsByDefinition(row, tables);
    const kernels::LatLongRowSums actual = kernels::SumLatLongRow(
        row.data(), {tables[0].data(), tables[1].data(), tables[2].data(), tables[3].data(), tables[4].data()}, n);
    for (int j = 0; j < 5; ++j) {
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(std::bit_cast<std::uint64_t>(actual[j][c]), std::bit_cast<std::uint64_t>(expected[j][c]))
            << "width " << width << ", function " << j << ", channel " << c;
      }
    }
  }
}

// ---- projections --------------------------------------------------------------------------------

// A sky-like panorama: a smooth gradient, a warm sun at (sun_u, sun_v) spread over a few pixels and
// a cool band near the horizon, every pixel from the direction of its centre.
Image TestPanorama(int width, double sun_u = 0.3, double sun_v = 0.35, double sun = 1e3) {
  Image image(width, width / 2);
  const glm::dvec3 sun_direction = LatLongDirection(sun_u, sun_v);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < width; ++x) {
      const glm::dvec3 d = LatLongDirection((x + 0.5) / width, (y + 0.5) / image.height);
      const double lobe = sun * std::exp(400.0 * (glm::dot(d, sun_direction) - 1.0));
      const double sky = 0.5 + 0.5 * d.y + 0.2 * std::exp(-20.0 * d.y * d.y);
      image.at(x, y) = glm::vec3(glm::dvec3(sky + lobe, sky + 0.8 * lobe, 1.3 * sky + 0.5 * lobe));
    }
  }
  return image;
}

// The definition in double: radiance x basis at the pixel centre x the pixel's exact solid angle.
Sh9Rgb ProjectByDefinition(const Image& image) {
  Sh9Rgb sh;
  const int w = image.width, h = image.height;
  for (int y = 0; y < h; ++y) {
    const double solid_angle = 2.0 * kPi / w * (std::cos(kPi * y / h) - std::cos(kPi * (y + 1) / h));
    for (int x = 0; x < w; ++x) {
      const std::array<double, kSh9Coefficients> basis =
          ShBasis(LatLongDirection((x + 0.5) / w, (y + 0.5) / h));
      for (int i = 0; i < kSh9Coefficients; ++i) sh.coefficients[i] += glm::dvec3(image.at(x, y)) * basis[i] * solid_angle;
    }
  }
  return sh;
}

double LargestCoefficient(const Sh9Rgb& sh) {
  double largest = 0.0;
  for (const glm::dvec3& c : sh.coefficients) largest = std::max({largest, std::abs(c.r), std::abs(c.g), std::abs(c.b)});
  return largest;
}

// The largest difference, as a fraction of the largest coefficient of `reference`.
double RelativeDifference(const Sh9Rgb& actual, const Sh9Rgb& reference) {
  double worst = 0.0;
  for (int i = 0; i < kSh9Coefficients; ++i) {
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(actual.coefficients[i][c] - reference.coefficients[i][c]));
  }
  return worst / LargestCoefficient(reference);
}

TEST(LatLongProjection, IsTheDoubleProjectionOfItsPixels) {
  for (int width : {2, 4, 6, 64, 200, 2048}) {
    const Image image = TestPanorama(width);
    EXPECT_LT(RelativeDifference(ProjectLatLong(image), ProjectByDefinition(image)), 1e-6) << width;
  }
  // A sun of 1e6 over a dim sky: the float sums must not lose the sky.
  const Image bright = TestPanorama(1024, 0.7, 0.2, 1e6);
  EXPECT_LT(RelativeDifference(ProjectLatLong(bright), ProjectByDefinition(bright)), 1e-6);
}

// The test panorama's own function, integrated over the sphere at four times the test image's
// resolution, in double from the function itself: the exact reference the pixel grid converges to.
Sh9Rgb HighResolutionReference() {
  constexpr int kWidth = 4096, kHeight = kWidth / 2;
  const glm::dvec3 sun_direction = LatLongDirection(0.3, 0.35);
  std::vector<double> sin_phi(kWidth), cos_phi(kWidth);
  for (int x = 0; x < kWidth; ++x) {
    const double phi = 2.0 * kPi * ((x + 0.5) / kWidth - 0.5);
    sin_phi[static_cast<std::size_t>(x)] = std::sin(phi), cos_phi[static_cast<std::size_t>(x)] = std::cos(phi);
  }
  Sh9Rgb sh;
  for (int y = 0; y < kHeight; ++y) {
    const double solid_angle = 2.0 * kPi / kWidth * (std::cos(kPi * y / kHeight) - std::cos(kPi * (y + 1) / kHeight));
    const double theta = kPi * (y + 0.5) / kHeight;
    const double sky = 0.5 + 0.5 * std::cos(theta) + 0.2 * std::exp(-20.0 * std::cos(theta) * std::cos(theta));
    for (int x = 0; x < kWidth; ++x) {
      const glm::dvec3 d(sin_phi[static_cast<std::size_t>(x)] * std::sin(theta), std::cos(theta),
                         cos_phi[static_cast<std::size_t>(x)] * std::sin(theta));
      const double cosine = glm::dot(d, sun_direction);
      const double lobe = cosine > 0.95 ? 1e3 * std::exp(400.0 * (cosine - 1.0)) : 0.0;  // below 1e-5 elsewhere
      const glm::dvec3 radiance(sky + lobe, sky + 0.8 * lobe, 1.3 * sky + 0.5 * lobe);
      const std::array<double, kSh9Coefficients> basis = ShBasis(d);
      for (int i = 0; i < kSh9Coefficients; ++i) sh.coefficients[i] += radiance * (basis[i] * solid_angle);
    }
  }
  return sh;
}

// The accuracy irrmap states for a panorama. Measured (fraction of the largest coefficient): from
// 1024 x 512, 1.8e-6 in place against 8.8e-5 through a cube of face 128 (ResampleLatLong, then
// ProjectDirect); from 2048 x 1024 against an 8192-wide reference, 3.5e-7 against 2.2e-5 at face
// 256 (the 0.003 % of the cube route). The bound below is 0.001 %.
TEST(LatLongProjection, MatchesAHighResolutionExactReferenceAsCloselyAsTheCubeRoute) {
  const Sh9Rgb reference = HighResolutionReference();
  const Image image = TestPanorama(1024);
  const double in_place = RelativeDifference(ProjectLatLong(image), reference);
  const double via_cube = RelativeDifference(ProjectDirect(ResampleLatLong(image, 128)), reference);
  char figures[80];
  std::snprintf(figures, sizeof figures, "in place %.3g, via a cube %.3g", in_place, via_cube);
  RecordProperty("relative_difference", figures);
  EXPECT_LT(in_place, 1e-5);
  EXPECT_LT(in_place, via_cube);
}

// A coarse level's projection is the definition's: its radiance constant over each of its pixels,
// times y_lm x solid angle summed over the finest pixels, here evaluated by giving every finest pixel
// its coarse parent's radiance and projecting that in double.
TEST(LatLongProjection, CoarseLevelsHoldTheBasisSummedOverTheirFinestPixels) {
  const LatLongLevel finest = MakeLatLongLevel(TestPanorama(256));
  const LatLongLevel level1 = ReduceLatLongLevel(finest, 64);
  const LatLongLevel level2 = ReduceLatLongLevel(level1, 32);
  for (const LatLongLevel* level : {&level1, &level2}) {
    const int ratio = finest.image.width / level->image.width;
    Image spread(finest.image.width, finest.image.height);
    for (int y = 0; y < spread.height; ++y) {
      for (int x = 0; x < spread.width; ++x) spread.at(x, y) = level->image.at(x / ratio, y / ratio);
    }
    EXPECT_LT(RelativeDifference(ProjectLatLongLevel(*level), ProjectByDefinition(spread)), 1e-6) << ratio;
  }
}

// Sizes that do not divide: each coarse pixel takes fractions of the fine ones at its edges, so the
// panorama's integral (L00) is kept, and a uniform panorama stays uniform.
TEST(LatLongProjection, ReducingBySizesThatDoNotDivideKeepsTheIntegral) {
  const LatLongLevel finest = MakeLatLongLevel(TestPanorama(200));
  const LatLongLevel coarse = ReduceLatLongLevel(finest, 64);
  const Sh9Rgb fine_sh = ProjectLatLongLevel(finest), coarse_sh = ProjectLatLongLevel(coarse);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(coarse_sh.coefficients[0][c], fine_sh.coefficients[0][c], 1e-6 * fine_sh.coefficients[0][c]);
  EXPECT_LT(RelativeDifference(coarse_sh, fine_sh), 2e-2);  // the blur of 3 x 3 pixels around a sun
  const LatLongLevel uniform = ReduceLatLongLevel(MakeLatLongLevel(Image(300, 150, glm::vec3(2.0f))), 64);
  for (const glm::vec3& pixel : uniform.image.pixels) EXPECT_NEAR(pixel.r, 2.0f, 1e-5f);
}

TEST(LatLongProjection, PyramidLevelsHaveTheGridsOfTheCubeFaceSizes) {
  const LatLongPyramid big = BuildLatLongPyramid(TestPanorama(2048), 256);
  ASSERT_EQ(big.levels.size(), 9u);
  EXPECT_EQ(big.level(0).image.width, 2048);  // the panorama itself
  for (int k = 1; k < 9; ++k) EXPECT_EQ(big.level(k).image.width, 4 * (256 >> k)) << k;
  // A panorama coarser than a level's grid is that level: 256 columns are the grid of face 64.
  const LatLongPyramid small = BuildLatLongPyramid(TestPanorama(256), 256);
  ASSERT_EQ(small.levels.size(), 9u);
  EXPECT_EQ(small.levels[1], 0);
  EXPECT_EQ(small.levels[2], 0);
  EXPECT_EQ(small.level(3).image.width, 128);
  EXPECT_EQ(small.distinct.size(), 7u);
}

TEST(LatLongProjection, PixelsNearFloatMaxGiveFiniteExactCoefficients) {
  Image image(64, 32, glm::vec3(FLT_MAX));
  const Sh9Rgb sh = ProjectLatLong(image);
  // The integral of a constant over the sphere: L00 = 4 pi L / (2 sqrt pi) = 2 sqrt(pi) L.
  for (int c = 0; c < 3; ++c) {
    EXPECT_TRUE(std::isfinite(sh.coefficients[0][c]));
    EXPECT_NEAR(sh.coefficients[0][c] / FLT_MAX, 2.0 * std::sqrt(kPi), 1e-6);
  }
}

}  // namespace
}  // namespace vs11::irradiance

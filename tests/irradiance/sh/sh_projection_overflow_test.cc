// Projection of finite texels up to FLT_MAX: the float terms of the mip pyramid and of the moment
// kernels must not overflow, and where the fallback scales the weights, the result must be the one
// a float without an upper exponent limit gives (checked against the map scaled down by 2^64,
// where nothing overflows, scaled back up: powers of two scale float arithmetic exactly).
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "irradiance/io/cube_map.h"
#include "irradiance/sh/sh_projection.h"

namespace vs11::irradiance {
namespace {

constexpr float kFloatMax = std::numeric_limits<float>::max();
constexpr int kScaleDown = 64;

CubeMap Filled(int size, glm::vec3 value) {
  CubeMap cube(size);
  for (Image& face : cube.faces) {
    for (glm::vec3& texel : face.pixels) texel = value;
  }
  return cube;
}

CubeMap ScaledDown(CubeMap cube) {
  for (Image& face : cube.faces) {
    for (glm::vec3& texel : face.pixels) {
      for (int c = 0; c < 3; ++c) texel[c] = std::ldexp(texel[c], -kScaleDown);
    }
  }
  return cube;
}

void ExpectEveryLevelIsTheScaledDownProjectionScaledUp(const CubeMap& huge) {
  const std::optional<CubeMipChain> chain = BuildEnvironmentMips(huge);
  const std::optional<CubeMipChain> small_chain = BuildEnvironmentMips(ScaledDown(huge));
  const std::optional<BasisPyramid> basis = BuildBasisPyramid(huge.face_size);
  ASSERT_TRUE(chain && small_chain && basis);
  for (const CubeMap& level : chain->levels) {
    for (const Image& face : level.faces) {
      for (const glm::vec3& texel : face.pixels) {
        ASSERT_TRUE(std::isfinite(texel.r) && std::isfinite(texel.g) && std::isfinite(texel.b))
            << "mip of face " << level.face_size;
      }
    }
  }
  for (int level = 0; level < LevelCount(huge.face_size); ++level) {
    const Sh9Rgb sh = ProjectLevel(*chain, *basis, level);
    const Sh9Rgb small = ProjectLevel(*small_chain, *basis, level);
    for (int i = 0; i < kSh9Coefficients; ++i) {
      for (int c = 0; c < 3; ++c) {
        ASSERT_TRUE(std::isfinite(sh.coefficients[i][c])) << "level " << level << " coefficient " << i;
        ASSERT_EQ(sh.coefficients[i][c], std::ldexp(small.coefficients[i][c], kScaleDown))
            << "level " << level << " coefficient " << i << " channel " << c;
      }
    }
  }
}

TEST(ShProjectionOverflow, EveryTexelAtFloatMaxGivesFiniteCoefficientsAtEveryLevel) {
  ExpectEveryLevelIsTheScaledDownProjectionScaledUp(Filled(32, glm::vec3(kFloatMax)));
}

TEST(ShProjectionOverflow, AllTexelsAt3e38GiveFiniteCoefficientsOnSmallFaces) {
  for (int size : {1, 2, 4, 8}) ExpectEveryLevelIsTheScaledDownProjectionScaledUp(Filled(size, glm::vec3(3e38f)));
}

TEST(ShProjectionOverflow, TwoNeighbouringHugeTexelsAmongOrdinaryOnesGiveFiniteCoefficients) {
  CubeMap cube = Filled(32, glm::vec3(1.0f, 0.5f, 0.25f));
  cube.face(CubeFace::kPositiveY).at(10, 3) = glm::vec3(3e38f);
  cube.face(CubeFace::kPositiveY).at(11, 3) = glm::vec3(3e38f, 0.0f, 3e38f);
  ExpectEveryLevelIsTheScaledDownProjectionScaledUp(cube);
}

TEST(ShProjectionOverflow, OneTexelAtFloatMaxInEachFaceCornerGivesFiniteCoefficients) {
  CubeMap cube = Filled(16, glm::vec3(2.0f));
  for (Image& face : cube.faces) face.at(15, 0) = glm::vec3(kFloatMax, 1.0f, kFloatMax);
  ExpectEveryLevelIsTheScaledDownProjectionScaledUp(cube);
}

TEST(ShProjectionOverflow, ProjectionOfOrdinaryMapsKeepsItsBits) {
  // The fallback runs only where the float terms overflowed: a map that does not overflow gives the
  // same bits as before (the stored weights, unscaled).
  const CubeMap cube = Filled(8, glm::vec3(1e30f, 3.0f, 0.5f));
  const std::optional<CubeMipChain> chain = BuildEnvironmentMips(cube);
  const std::optional<BasisPyramid> basis = BuildBasisPyramid(8);
  ASSERT_TRUE(chain && basis);
  const Sh9Rgb sh = ProjectLevel(*chain, *basis, 0);
  const Sh9Rgb finest = ProjectFinest(cube, basis->finest);
  for (int i = 0; i < kSh9Coefficients; ++i) EXPECT_EQ(sh.coefficients[i], finest.coefficients[i]);
}

}  // namespace
}  // namespace vs11::irradiance

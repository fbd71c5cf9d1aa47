#include "irradiance/io/cube_map.h"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace vs11::irradiance {
namespace {

// Double sums of ~10^7 positive terms of similar size stay well within this of 4 pi.
constexpr double kSolidAngleSumTolerance = 1e-12;

double FaceSolidAngleSum(int size) {
  double total = 0.0;
  for (int y = 0; y < size; ++y) {
    double row = 0.0;
    for (int x = 0; x < size; ++x) row += TexelSolidAngle(x, y, size);
    total += row;
  }
  return total;
}

class SolidAngleSum : public testing::TestWithParam<int> {};

TEST_P(SolidAngleSum, SixFacesAddToFourPi) {
  const int size = GetParam();
  EXPECT_NEAR(kCubeFaceCount * FaceSolidAngleSum(size), 4.0 * std::numbers::pi,
              kSolidAngleSumTolerance);
}

INSTANTIATE_TEST_SUITE_P(CubeMap, SolidAngleSum, testing::Values(1, 2, 3, 7, 64, 255, 2048));

TEST(CubeMap, OneTexelFaceSeesASixthOfTheSphere) {
  EXPECT_NEAR(TexelSolidAngle(0, 0, 1), 4.0 * std::numbers::pi / 6.0, 1e-15);
}

TEST(CubeMap, SolidAngleHasTheSquaresSymmetries) {
  constexpr int kSize = 9;
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      const double a = TexelSolidAngle(x, y, kSize);
      EXPECT_NEAR(a, TexelSolidAngle(kSize - 1 - x, y, kSize), 1e-16);
      EXPECT_NEAR(a, TexelSolidAngle(x, kSize - 1 - y, kSize), 1e-16);
      EXPECT_NEAR(a, TexelSolidAngle(y, x, kSize), 1e-16);
    }
  }
}

TEST(CubeMap, SmallTexelSolidAngleIsAreaTimesCosineOverDistanceSquared) {
  // For a small texel of area (2 / size)^2 at distance r = |(s, t, 1)|, dOmega ~ area / r^3.
  constexpr int kSize = 1024;
  const int x = 100;
  const int y = 700;
  const double s = 2.0 * (x + 0.5) / kSize - 1.0;
  const double t = 2.0 * (y + 0.5) / kSize - 1.0;
  const double r = std::sqrt(s * s + t * t + 1.0);
  const double area = (2.0 / kSize) * (2.0 / kSize);
  EXPECT_NEAR(TexelSolidAngle(x, y, kSize) / (area / (r * r * r)), 1.0, 1e-5);
}

TEST(CubeMap, TexelDirectionFollowsTheD3DFaceTable) {
  // The centre texel of an odd face looks along the face axis.
  constexpr int kSize = 5;
  EXPECT_EQ(TexelDirection(CubeFace::kPositiveX, 2, 2, kSize), glm::dvec3(1, 0, 0));
  EXPECT_EQ(TexelDirection(CubeFace::kNegativeX, 2, 2, kSize), glm::dvec3(-1, 0, 0));
  EXPECT_EQ(TexelDirection(CubeFace::kPositiveY, 2, 2, kSize), glm::dvec3(0, 1, 0));
  EXPECT_EQ(TexelDirection(CubeFace::kNegativeY, 2, 2, kSize), glm::dvec3(0, -1, 0));
  EXPECT_EQ(TexelDirection(CubeFace::kPositiveZ, 2, 2, kSize), glm::dvec3(0, 0, 1));
  EXPECT_EQ(TexelDirection(CubeFace::kNegativeZ, 2, 2, kSize), glm::dvec3(0, 0, -1));
  // Top-left texel of +z: s < 0 (towards -x), t < 0 (row 0 is up, towards +y).
  const glm::dvec3 top_left = TexelDirection(CubeFace::kPositiveZ, 0, 0, kSize);
  EXPECT_LT(top_left.x, 0.0);
  EXPECT_GT(top_left.y, 0.0);
  // Top-left of +x looks towards +z (s = -1 maps to z = +1) and up.
  const glm::dvec3 px = TexelDirection(CubeFace::kPositiveX, 0, 0, kSize);
  EXPECT_GT(px.z, 0.0);
  EXPECT_GT(px.y, 0.0);
  EXPECT_NEAR(glm::length(px), 1.0, 1e-15);
}

TEST(CubeMap, DirectionToFaceInvertsFaceDirection) {
  const double coords[] = {-0.999, -0.6, -0.1, 0.0, 0.3, 0.75, 0.999};
  for (CubeFace face : kAllCubeFaces) {
    for (double s : coords) {
      for (double t : coords) {
        const FacePoint p = DirectionToFace(3.5 * FaceDirection(face, s, t));
        EXPECT_EQ(p.face, face) << CubeFaceName(face) << " s=" << s << " t=" << t;
        EXPECT_NEAR(p.s, s, 1e-15);
        EXPECT_NEAR(p.t, t, 1e-15);
      }
    }
  }
}

TEST(CubeMap, DirectionToFaceHandlesZeroWithoutNaN) {
  const FacePoint p = DirectionToFace(glm::dvec3(0.0));
  EXPECT_EQ(p.face, CubeFace::kPositiveX);
  EXPECT_EQ(p.s, 0.0);
  EXPECT_EQ(p.t, 0.0);
}

TEST(CubeMap, FaceNamesFollowFaceOrder) {
  EXPECT_EQ(CubeFaceName(CubeFace::kPositiveX), "+x");
  EXPECT_EQ(CubeFaceName(CubeFace::kNegativeX), "-x");
  EXPECT_EQ(CubeFaceName(CubeFace::kPositiveY), "+y");
  EXPECT_EQ(CubeFaceName(CubeFace::kNegativeY), "-y");
  EXPECT_EQ(CubeFaceName(CubeFace::kPositiveZ), "+z");
  EXPECT_EQ(CubeFaceName(CubeFace::kNegativeZ), "-z");
}

TEST(CubeMap, ConstructorFillsSixSquareFaces) {
  const CubeMap map(4, glm::vec3(0.5f, 1.0f, 2.0f));
  EXPECT_EQ(map.face_size, 4);
  for (const Image& face : map.faces) {
    EXPECT_EQ(face.width, 4);
    EXPECT_EQ(face.height, 4);
    ASSERT_EQ(face.pixels.size(), 16u);
    EXPECT_EQ(face.at(3, 2), glm::vec3(0.5f, 1.0f, 2.0f));
  }
}

}  // namespace
}  // namespace vs11::irradiance

#include "vm/mesh/smooth_normals.h"

#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

namespace vs11::mesh {
namespace {

// Normalised in double: a unit vector's components to the last bits of double.
constexpr double kUnitTolerance = 1e-15;

void ExpectNormal(const Vec3d& actual, const Vec3d& direction) {
  const double length = std::sqrt(direction[0] * direction[0] + direction[1] * direction[1] + direction[2] * direction[2]);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(actual[k], direction[k] / length, kUnitTolerance) << "component " << k;
}

TEST(AreaWeightedNormals, CounterClockwiseTriangleFacesItsViewer) {
  const std::vector<Vec3f> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<std::uint32_t> triangles = {0, 1, 2};
  const std::vector<Vec3d> normals = AreaWeightedNormals(positions, triangles);
  ASSERT_EQ(normals.size(), 3u);
  for (const Vec3d& n : normals) ExpectNormal(n, {0, 0, 1});
}

// At the origin: a triangle of area 2 facing +z and one of area 1/2 facing +y, both with a right
// angle there. Area weighting gives (0, 1, 4); weighting by angle or not at all gives (0, 1, 1).
TEST(AreaWeightedNormals, EachFaceWeighsByItsArea) {
  const std::vector<Vec3f> positions = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 1}, {1, 0, 0}};
  const std::vector<std::uint32_t> triangles = {0, 1, 2, 0, 3, 4};
  const std::vector<Vec3d> normals = AreaWeightedNormals(positions, triangles);
  ExpectNormal(normals[0], {0, 1, 4});
  ExpectNormal(normals[2], {0, 0, 1});  // in the first triangle only
  ExpectNormal(normals[3], {0, 1, 0});
  // (1, 0, 0) is a corner of the second triangle; (2, 0, 0) of the first: different positions.
  ExpectNormal(normals[4], {0, 1, 0});
  ExpectNormal(normals[1], {0, 0, 1});
}

// Two triangles of a folded quad, each with corners of its own (as an STL stores them): the copies
// of a shared corner get one normal, -0 and +0 being one position.
TEST(AreaWeightedNormals, CornersRepeatedPerTriangleAreSmoothedTogether) {
  const std::vector<Vec3f> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0},        // facing +z
                                        {-0.0f, 1, 0}, {1, 0, -0.0f}, {1, 1, 1}};  // facing (-1, -1, 1)
  const std::vector<std::uint32_t> triangles = {0, 1, 2, 3, 4, 5};
  const std::vector<Vec3d> normals = AreaWeightedNormals(positions, triangles);
  for (int shared : {1, 2, 3, 4}) ExpectNormal(normals[shared], {-1, -1, 2});
  ExpectNormal(normals[0], {0, 0, 1});
  ExpectNormal(normals[5], {-1, -1, 1});
  EXPECT_EQ(normals[1], normals[4]);
  EXPECT_EQ(normals[2], normals[3]);
}

TEST(AreaWeightedNormals, VerticesWithoutATriangleWithAreaGetZero) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const std::vector<Vec3f> positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0},  // collinear: no area
                                        {5, 5, 5},                        // in no triangle
                                        {nan, 0, 0}, {0, inf, 0}, {3, 0, 0}, {3, 1, 0}};
  const std::vector<std::uint32_t> triangles = {0, 1, 2, 4, 6, 7, 5, 6, 7};
  const std::vector<Vec3d> normals = AreaWeightedNormals(positions, triangles);
  for (int v : {0, 1, 2, 3, 4, 5, 6, 7}) {
    EXPECT_EQ(normals[v], (Vec3d{0, 0, 0})) << "vertex " << v;
    EXPECT_FALSE(IsUsableNormal({static_cast<float>(normals[v][0]), static_cast<float>(normals[v][1]),
                                 static_cast<float>(normals[v][2])}));
  }
}

TEST(IsUsableNormal, RefusesZeroAndNonFiniteOnly) {
  EXPECT_TRUE(IsUsableNormal({0, 0, 1}));
  EXPECT_TRUE(IsUsableNormal({1e-30f, 0, 0}));
  EXPECT_TRUE(IsUsableNormal({0, -3, 0}));
  EXPECT_FALSE(IsUsableNormal({0, 0, 0}));
  EXPECT_FALSE(IsUsableNormal({-0.0f, 0, -0.0f}));
  EXPECT_FALSE(IsUsableNormal({std::numeric_limits<float>::quiet_NaN(), 0, 1}));
  EXPECT_FALSE(IsUsableNormal({0, std::numeric_limits<float>::infinity(), 0}));
}

}  // namespace
}  // namespace vs11::mesh

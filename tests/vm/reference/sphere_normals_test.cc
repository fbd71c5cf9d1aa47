#include "vm/reference/sphere_normals.h"

#include <vector>

#include <gtest/gtest.h>

namespace vs11 {
namespace {

TEST(SphereNormals, AreUnitDeterministicAndBalanced) {
  const std::vector<glm::dvec3> a = SphereNormals(1000);
  EXPECT_EQ(a, SphereNormals(1000));
  ASSERT_EQ(a.size(), 1000u);
  glm::dvec3 mean(0.0);
  for (const glm::dvec3& n : a) {
    EXPECT_NEAR(glm::length(n), 1.0, 1e-15);
    mean += n / 1000.0;
  }
  EXPECT_LT(glm::length(mean), 1e-2);
  EXPECT_TRUE(SphereNormals(0).empty());
  EXPECT_TRUE(SphereNormals(-3).empty());
}

}  // namespace
}  // namespace vs11

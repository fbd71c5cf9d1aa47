// The projection's threads: the basis pyramid built by several threads (with its progress calls,
// promised one at a time), one pyramid shared read-only by projections on several threads (as
// `irrmap batch` shares it), and ground truths that split their own work while others run. Every
// result equals the one-thread result bit for bit. CI's ThreadSanitizer stage (.ci/tsan) runs these.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "irradiance/io/environments.h"
#include "irradiance/sh/ground_truth.h"
#include "irradiance/sh/sh_projection.h"
#include "tests/run_threads.h"

namespace vs11::irradiance {
namespace {

using vs11::testing::RunOnThreads;

constexpr int kFace = 32;

std::vector<CubeMap> FourEnvironments() {
  SkyParams sky;
  sky.sun_azimuth_degrees = 40.0;
  return {MakeSky(kFace, sky), MakeStudio(kFace), MakeSpot(kFace), MakeGradient(kFace)};
}

// ProjectDirect, then ProjectLevel at every level: what one environment's projections give.
std::vector<Sh9Rgb> AllProjections(const CubeMap& env, const BasisPyramid& basis) {
  std::vector<Sh9Rgb> projections = {ProjectDirect(env)};
  const std::optional<CubeMipChain> mips = BuildEnvironmentMips(env);
  EXPECT_TRUE(mips.has_value());
  if (!mips) return projections;
  for (int level = 0; level < LevelCount(env.face_size); ++level) projections.push_back(ProjectLevel(*mips, basis, level));
  return projections;
}

void ExpectSameProjections(const std::vector<Sh9Rgb>& actual, const std::vector<Sh9Rgb>& expected,
                           const std::string& context) {
  ASSERT_EQ(actual.size(), expected.size()) << context;
  for (std::size_t k = 0; k < expected.size(); ++k) {
    EXPECT_EQ(actual[k].coefficients, expected[k].coefficients)  // bit for bit
        << context << (k == 0 ? ", direct" : ", level " + std::to_string(k - 1));
  }
}

TEST(ProjectionConcurrent, PyramidBuiltByThreadsReportsProgressOneCallAtATime) {
  // 256 is built in 64 tiles, so that the four threads all take part.
  constexpr int kPyramidFace = 256;
  const std::optional<BasisPyramid> one = BuildBasisPyramid(kPyramidFace, 1);
  ASSERT_TRUE(one.has_value());
  // Plain (unsynchronised) state: the header promises one call at a time, which ThreadSanitizer
  // checks here.
  std::vector<double> reports;
  const std::optional<BasisPyramid> many =
      BuildBasisPyramid(kPyramidFace, 4, [&](double done) { reports.push_back(done); });
  ASSERT_TRUE(many.has_value());
  EXPECT_EQ(reports.size(), 64u);
  ASSERT_EQ(many->levels.size(), one->levels.size());
  for (std::size_t k = 0; k < one->levels.size(); ++k) {
    EXPECT_EQ(many->levels[k].weights, one->levels[k].weights) << "level " << k;
  }
  EXPECT_EQ(many->finest.q, one->finest.q);
  EXPECT_EQ(many->finest.qr, one->finest.qr);
  EXPECT_EQ(many->finest.qr2, one->finest.qr2);
}

TEST(ProjectionConcurrent, ProjectionsOnSeveralThreadsShareOneBasisPyramid) {
  const std::optional<BasisPyramid> basis = BuildBasisPyramid(kFace, 2);
  ASSERT_TRUE(basis.has_value());
  const std::vector<CubeMap> environments = FourEnvironments();
  std::vector<std::vector<Sh9Rgb>> alone;
  for (const CubeMap& env : environments) alone.push_back(AllProjections(env, *basis));
  // Each thread projects every environment, starting with its own, so that all four are in flight.
  const int threads = static_cast<int>(environments.size());
  RunOnThreads(threads, [&](int t) {
    for (int k = 0; k < threads; ++k) {
      const std::size_t e = static_cast<std::size_t>((t + k) % threads);
      ExpectSameProjections(AllProjections(environments[e], *basis), alone[e],
                            "environment " + std::to_string(e) + " on thread " + std::to_string(t));
    }
  });
}

TEST(ProjectionConcurrent, GroundTruthsThatSplitTheirWorkRunSideBySide) {
  const std::vector<CubeMap> environments = FourEnvironments();
  const std::vector<glm::dvec3> normals = SphereNormals(61);
  std::vector<std::vector<glm::dvec3>> alone;
  for (const CubeMap& env : environments) alone.push_back(GroundTruthIrradiance(env, normals, 1));
  RunOnThreads(2, [&](int t) {
    for (std::size_t e = static_cast<std::size_t>(t); e < environments.size(); e += 2) {
      double last_progress = 0.0;
      EXPECT_EQ(GroundTruthIrradiance(environments[e], normals, 3, [&](double done) { last_progress = done; }),
                alone[e])
          << "environment " << e;
      EXPECT_EQ(last_progress, 1.0);
    }
  });
}

}  // namespace
}  // namespace vs11::irradiance

// The lat-long projection and reduction on several threads: every result equals the one-thread result
// bit for bit. CI's ThreadSanitizer stage (.ci/tsan) runs these.
#include <bit>
#include <cstdint>

#include <gtest/gtest.h>

#include "irradiance/io/environment_io.h"
#include "irradiance/sh/latlong_projection.h"

namespace vs11::irradiance {
namespace {

Image Panorama(int width) {
  Image image(width, width / 2);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < width; ++x) {
      const glm::dvec3 d = LatLongDirection((x + 0.5) / width, (y + 0.5) / image.height);
      image.at(x, y) = glm::vec3(1.0 + d.x, 2.0 + d.y * d.z, 0.5 + (d.z > 0.9 ? 1e4 : 0.0));
    }
  }
  return image;
}

void ExpectSameBits(const Sh9Rgb& actual, const Sh9Rgb& expected, int threads) {
  for (int i = 0; i < kSh9Coefficients; ++i) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(std::bit_cast<std::uint64_t>(actual.coefficients[i][c]),
                std::bit_cast<std::uint64_t>(expected.coefficients[i][c]))
          << threads << " threads, coefficient " << i << ", channel " << c;
    }
  }
}

TEST(LatLongProjectionThreads, EveryThreadCountGivesTheSameBits) {
  const LatLongPyramid one = BuildLatLongPyramid(Panorama(600), 64, 1);
  for (int threads : {2, 3, 8}) {
    const LatLongPyramid many = BuildLatLongPyramid(Panorama(600), 64, threads);
    for (std::size_t k = 0; k < one.levels.size(); ++k) {
      ExpectSameBits(ProjectLatLongLevel(many.level(static_cast<int>(k)), threads),
                     ProjectLatLongLevel(one.level(static_cast<int>(k)), 1), threads);
    }
  }
}

}  // namespace
}  // namespace vs11::irradiance

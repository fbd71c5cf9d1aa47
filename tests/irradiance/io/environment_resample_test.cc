// The resamplers of irradiance/io/environment_resample.cc on their own: a quarter turn of the source
// turns the cube (the lat-long wrap and the poles, the angular disk), and the bilinear cube lookup
// returns texels at their centres, means between them and the edge texel beyond the last centre.
// (Energy conservation and the orientation of real files are environment_io_test.cc's.)
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "irradiance/io/cube_map.h"
#include "irradiance/io/environment_io.h"

namespace vs11::irradiance {
namespace {

// A radiance with no symmetry a quarter turn could keep: a slope in every axis and a bright spot.
glm::vec3 Radiance(glm::dvec3 d) {
  const glm::dvec3 spot = glm::normalize(glm::dvec3(0.3, 0.5, 0.8));
  const double peak = std::exp(-12.0 * (1.0 - glm::dot(d, spot)));
  return glm::vec3(static_cast<float>(1.0 + 0.5 * d.x + 0.2 * d.y + 3.0 * peak),
                   static_cast<float>(1.0 - 0.3 * d.z + 0.4 * d.x * d.y), static_cast<float>(0.5 + 0.4 * d.y * d.y + peak));
}

// The texel of `cube` that direction `d` falls in.
glm::vec3 TexelAt(const CubeMap& cube, glm::dvec3 d) {
  const FacePoint point = DirectionToFace(d);
  const int n = cube.face_size;
  const int x = std::clamp(static_cast<int>(std::floor((point.s + 1.0) * 0.5 * n)), 0, n - 1);
  const int y = std::clamp(static_cast<int>(std::floor((point.t + 1.0) * 0.5 * n)), 0, n - 1);
  return cube.face(point.face).at(x, y);
}

// Every texel of `turned` equals the texel of `cube` in direction back(texel direction): a quarter
// turn maps texel centres onto texel centres, so only the rounding of the sample directions differs.
void ExpectTurnedCube(const CubeMap& turned, const CubeMap& cube, const std::function<glm::dvec3(glm::dvec3)>& back) {
  constexpr double kRelative = 1e-5;
  for (CubeFace face : kAllCubeFaces) {
    for (int y = 0; y < turned.face_size; ++y) {
      for (int x = 0; x < turned.face_size; ++x) {
        const glm::vec3 actual = turned.face(face).at(x, y);
        const glm::vec3 expected = TexelAt(cube, back(TexelDirection(face, x, y, turned.face_size)));
        for (int c = 0; c < 3; ++c) {
          ASSERT_NEAR(actual[c], expected[c], kRelative * std::abs(expected[c]))
              << "face " << static_cast<int>(face) << " texel " << x << "," << y << " channel " << c;
        }
      }
    }
  }
}

TEST(EnvironmentResample, ALatLongMapShiftedAQuarterTurnGivesTheCubeTurnedAboutY) {
  constexpr int kHeight = 64, kWidth = 2 * kHeight, kFace = 8;
  Image latlong(kWidth, kHeight), shifted(kWidth, kHeight);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      latlong.at(x, y) = Radiance(LatLongDirection((x + 0.5) / kWidth, (y + 0.5) / kHeight));
    }
  }
  // Column x of the shifted map is column x - W/4 of the original: azimuth turned by a quarter.
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) shifted.at(x, y) = latlong.at((x + kWidth - kWidth / 4) % kWidth, y);
  }
  const CubeMap cube = ResampleLatLong(latlong, kFace);
  const CubeMap turned = ResampleLatLong(shifted, kFace);
  // u grows with atan2(x, z); a quarter less is the direction turned from +x back to +z.
  ExpectTurnedCube(turned, cube, [](glm::dvec3 d) { return glm::dvec3(-d.z, d.y, d.x); });
}

TEST(EnvironmentResample, AnAngularMapTurnedAQuarterGivesTheCubeTurnedAboutZ) {
  constexpr int kSize = 64, kFace = 8;
  Image angular(kSize, kSize), turned_map(kSize, kSize);
  const auto back = [](glm::dvec3 d) { return glm::dvec3(d.y, -d.x, d.z); };  // +y back to +x
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      double a = 2.0 * (x + 0.5) / kSize - 1.0, b = 1.0 - 2.0 * (y + 0.5) / kSize;
      const double r = std::sqrt(a * a + b * b);
      if (r > 1.0) a /= r, b /= r;  // pixels outside the disk are not read; give them rim values
      const glm::dvec3 d = AngularDirection(a, b);
      angular.at(x, y) = Radiance(d);
      turned_map.at(x, y) = Radiance(back(d));
    }
  }
  ExpectTurnedCube(ResampleAngular(turned_map, kFace), ResampleAngular(angular, kFace), back);
}

// A cube whose texel (x, y) of face f holds (f, x, y).
CubeMap IndexCube(int size) {
  CubeMap cube(size);
  for (int f = 0; f < kCubeFaceCount; ++f) {
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) cube.faces[f].at(x, y) = glm::vec3(static_cast<float>(f), x, y);
    }
  }
  return cube;
}

TEST(EnvironmentResample, CubeLookupReturnsTexelsAtTheirCentres) {
  constexpr int kSize = 4;
  const CubeMap cube = IndexCube(kSize);
  for (CubeFace face : kAllCubeFaces) {
    for (int y = 0; y < kSize; ++y) {
      for (int x = 0; x < kSize; ++x) {
        const glm::vec3 value = SampleCubeMap(cube, TexelDirection(face, x, y, kSize));
        EXPECT_NEAR(value.x, static_cast<float>(face), 1e-5f);
        EXPECT_NEAR(value.y, x, 1e-5f);
        EXPECT_NEAR(value.z, y, 1e-5f);
      }
    }
  }
}

TEST(EnvironmentResample, CubeLookupIsLinearBetweenCentresAndClampsAtTheFaceEdge) {
  constexpr int kSize = 4;
  const CubeMap cube = IndexCube(kSize);
  const CubeFace face = CubeFace::kPositiveY;
  // Halfway between the centres of texels 1 and 2 in s, at the centre row 1 in t.
  const double s_centre_1 = 2.0 * 1.5 / kSize - 1.0, s_centre_2 = 2.0 * 2.5 / kSize - 1.0;
  const double t_centre_1 = s_centre_1;
  glm::vec3 value = SampleCubeMap(cube, FaceDirection(face, 0.5 * (s_centre_1 + s_centre_2), t_centre_1));
  EXPECT_NEAR(value.y, 1.5f, 1e-5f);
  EXPECT_NEAR(value.z, 1.0f, 1e-5f);
  // A quarter of the way from centre 1 to centre 2 in t.
  value = SampleCubeMap(cube, FaceDirection(face, s_centre_1, t_centre_1 + 0.25 * (s_centre_2 - s_centre_1)));
  EXPECT_NEAR(value.y, 1.0f, 1e-5f);
  EXPECT_NEAR(value.z, 1.25f, 1e-5f);
  // Beyond the outermost centres, towards the face's corner: the corner texel, nothing from the
  // neighbouring faces.
  value = SampleCubeMap(cube, FaceDirection(face, 0.99, -0.99));
  EXPECT_EQ(value, glm::vec3(static_cast<float>(face), kSize - 1, 0));
}

TEST(EnvironmentResample, DirectionsNeedNotBeUnitAndTheAngularPoleIsTheRim) {
  const glm::dvec3 d(0.3, -0.4, 0.5);
  const glm::dvec2 unit = DirectionToLatLong(glm::normalize(d)), scaled = DirectionToLatLong(7.0 * d);
  EXPECT_NEAR(unit.x, scaled.x, 1e-15);
  EXPECT_NEAR(unit.y, scaled.y, 1e-15);
  const glm::dvec2 angular = DirectionToAngular(3.0 * d), angular_unit = DirectionToAngular(glm::normalize(d));
  EXPECT_NEAR(angular.x, angular_unit.x, 1e-15);
  EXPECT_NEAR(angular.y, angular_unit.y, 1e-15);
  EXPECT_EQ(DirectionToAngular(glm::dvec3(0, 0, -2)), glm::dvec2(1.0, 0.0));
  EXPECT_EQ(DirectionToAngular(glm::dvec3(0, 0, 5)), glm::dvec2(0.0, 0.0));
}

}  // namespace
}  // namespace vs11::irradiance

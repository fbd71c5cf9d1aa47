#include "irradiance/io/environments.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "irradiance/sh/ground_truth.h"

namespace vs11::irradiance {
namespace {

// Brightest texel of a map and the direction of its centre.
struct Brightest {
  float luminance = -1.0f;
  glm::dvec3 direction{0.0};
};
Brightest FindBrightest(const CubeMap& map) {
  Brightest best;
  for (CubeFace face : kAllCubeFaces) {
    for (int y = 0; y < map.face_size; ++y) {
      for (int x = 0; x < map.face_size; ++x) {
        const glm::vec3 v = map.face(face).at(x, y);
        const float sum = v.x + v.y + v.z;
        if (sum > best.luminance) best = {sum, TexelDirection(face, x, y, map.face_size)};
      }
    }
  }
  return best;
}

glm::dvec3 IrradianceFacing(const CubeMap& map, glm::dvec3 normal) {
  const std::vector<glm::dvec3> normals = {normal};
  return GroundTruthIrradiance(map, normals, 1)[0];
}

TEST(Environments, AzimuthElevationFollowTheDocumentedFrame) {
  const glm::dvec3 front = DirectionFromAzimuthElevation(0.0, 0.0);
  const glm::dvec3 right = DirectionFromAzimuthElevation(90.0, 0.0);
  const glm::dvec3 up = DirectionFromAzimuthElevation(123.0, 90.0);
  EXPECT_NEAR(glm::distance(front, glm::dvec3(0, 0, 1)), 0.0, 1e-15);
  EXPECT_NEAR(glm::distance(right, glm::dvec3(1, 0, 0)), 0.0, 1e-15);
  EXPECT_NEAR(glm::distance(up, glm::dvec3(0, 1, 0)), 0.0, 1e-15);
}

TEST(Environments, FunctionMapAveragesTheFunctionInsideEachTexel) {
  constexpr int kSize = 8;
  const CubeMap map = CubeMapFromFunction(kSize, [](glm::dvec3 d) { return glm::vec3(d); });
  for (CubeFace face : kAllCubeFaces) {
    for (int y = 0; y < kSize; ++y) {
      for (int x = 0; x < kSize; ++x) {
        // The mean of four unit vectors spread over a texel is close to the centre direction.
        const glm::dvec3 centre = TexelDirection(face, x, y, kSize);
        EXPECT_NEAR(glm::distance(glm::dvec3(map.face(face).at(x, y)), centre), 0.0, 0.02);
      }
    }
  }
}

TEST(Environments, ConstantIsTheSameEverywhere) {
  const CubeMap map = MakeConstant(4, glm::vec3(0.25f, 0.5f, 2.0f));
  for (const Image& face : map.faces) {
    for (const glm::vec3& v : face.pixels) EXPECT_EQ(v, glm::vec3(0.25f, 0.5f, 2.0f));
  }
}

TEST(Environments, SkyIsBrightestAtTheSunAndGroundBelowTheHorizon) {
  constexpr int kSize = 64;
  SkyParams params;
  params.sun_azimuth_degrees = 200.0;
  params.sun_elevation_degrees = 20.0;
  params.sun_angular_radius_degrees = 4.0;
  const CubeMap sky = MakeSky(kSize, params);
  const glm::dvec3 sun = DirectionFromAzimuthElevation(200.0, 20.0);
  EXPECT_GT(glm::dot(FindBrightest(sky).direction, sun), std::cos(4.0 * std::numbers::pi / 180.0));
  EXPECT_EQ(sky.face(CubeFace::kNegativeY).at(kSize / 2, kSize / 2), params.ground_radiance);
  const glm::vec3 zenith = sky.face(CubeFace::kPositiveY).at(kSize / 2, kSize / 2);
  EXPECT_NEAR(zenith.z, params.zenith_radiance.z, 0.02f);
  EXPECT_GT(zenith.z, zenith.x);  // blue sky
}

TEST(Environments, SunPowerIsTheIrradianceFacingItWhateverItsSize) {
  // The disk is resolved by about 4 texels per degree at 256 and supersampled 2 x 2; its edge
  // texels make the integral uneven by about 1%.
  constexpr double kDiskQuadratureRelative = 0.02;
  for (double radius : {2.0, 6.0}) {
    SpotParams params;
    params.angular_radius_degrees = radius;
    params.irradiance = glm::vec3(5.0f, 2.0f, 1.0f);
    const CubeMap spot = MakeSpot(256, params);
    const glm::dvec3 axis = DirectionFromAzimuthElevation(params.azimuth_degrees, params.elevation_degrees);
    const glm::dvec3 e = IrradianceFacing(spot, axis);
    EXPECT_NEAR(e.x, 5.0, 5.0 * kDiskQuadratureRelative) << "radius " << radius;
    EXPECT_NEAR(e.y, 2.0, 2.0 * kDiskQuadratureRelative) << "radius " << radius;
    EXPECT_NEAR(e.z, 1.0, 1.0 * kDiskQuadratureRelative) << "radius " << radius;
  }
}

TEST(Environments, SpotIsBlackAwayFromTheLight) {
  const CubeMap spot = MakeSpot(32);
  const glm::dvec3 axis = DirectionFromAzimuthElevation(SpotParams{}.azimuth_degrees,
                                                        SpotParams{}.elevation_degrees);
  EXPECT_GT(glm::dot(FindBrightest(spot).direction, axis), 0.99);
  EXPECT_EQ(spot.face(CubeFace::kNegativeY).at(3, 3), glm::vec3(0.0f));
}

TEST(Environments, StudioShowsEachLightsColourInItsDirection) {
  constexpr int kSize = 64;
  const StudioParams params;
  const CubeMap studio = MakeStudio(kSize, params);
  for (const RectLight& light : params.lights) {
    const FacePoint p = DirectionToFace(light.center);
    const int x = std::clamp(static_cast<int>((p.s + 1.0) * kSize / 2.0), 0, kSize - 1);
    const int y = std::clamp(static_cast<int>((p.t + 1.0) * kSize / 2.0), 0, kSize - 1);
    EXPECT_EQ(studio.face(p.face).at(x, y), light.radiance);
  }
  EXPECT_EQ(studio.face(CubeFace::kNegativeY).at(kSize / 2, kSize / 2), params.room_radiance);
}

TEST(Environments, BuiltinsGiveIrradianceOfOrderOneToTen) {
  const std::vector<glm::dvec3> normals = SphereNormals(64);
  for (const std::string& name : BuiltinEnvironmentNames()) {
    const std::optional<CubeMap> map = MakeBuiltinEnvironment(name, 32);
    ASSERT_TRUE(map.has_value()) << name;
    EXPECT_EQ(map->face_size, 32);
    double largest = 0.0;
    for (const glm::dvec3& e : GroundTruthIrradiance(*map, normals, 2)) {
      largest = std::max({largest, e.x, e.y, e.z});
    }
    EXPECT_GE(largest, 1.0) << name;
    EXPECT_LE(largest, 10.0) << name;
  }
}

TEST(Environments, RegistryRejectsUnknownNamesAndEmptySizes) {
  EXPECT_FALSE(MakeBuiltinEnvironment("moon", 16).has_value());
  EXPECT_FALSE(MakeBuiltinEnvironment("sky", 0).has_value());
  const std::vector<std::string> names = BuiltinEnvironmentNames();
  EXPECT_NE(std::find(names.begin(), names.end(), "sky"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "studio"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "spot"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "constant"), names.end());
}

}  // namespace
}  // namespace vs11::irradiance

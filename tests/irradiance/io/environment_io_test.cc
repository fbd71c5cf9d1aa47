#include "irradiance/io/environment_io.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <OpenImageIO/imageio.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "irradiance/io/cube_map.h"
#include "tests/irradiance/io/environment_test_support.h"

namespace vs11::irradiance {
namespace {

namespace fs = std::filesystem;
using namespace envtest;
using testing::HasSubstr;

// Tolerances, each with its reason.
// RGBE keeps an 8-bit mantissa per channel under a shared exponent: 1/256 of the largest channel,
// doubled for the rounding of the encoder.
constexpr float kRgbeRelativeError = 2.0f / 256.0f;
// JPEG at quality 100 of flat 8 x 8 blocks is off by a code value or two.
constexpr float kJpegError = 0.03f;
// sRGB decode in double, rounded to float.
constexpr float kSrgbDecodeError = 1e-6f;
// Resampled smooth (linear in the direction) maps: the texel average of a linear function differs
// from its value at the texel centre by the curvature of the footprint, ~1e-3 at face size 32.
constexpr float kSmoothResampleError = 0.01f;
// The energy the resamplers must keep: 0.1% (measured: 2e-5 .. 1.5e-4 in these tests).
constexpr double kEnergyRelativeError = 1e-3;
// Exported lat-long / angular maps resampled back: two bilinear passes over a smooth map.
constexpr float kExportRoundTripError = 0.02f;
// 8-bit 128 decoded from sRGB: ((128 / 255 + 0.055) / 1.055)^2.4.
constexpr float kSrgb128 = 0.2158605f;

// Sum of radiance x texel solid angle over the cube, per channel.
glm::dvec3 CubeIntegral(const CubeMap& cube) {
  glm::dvec3 sum(0.0);
  for (CubeFace face : kAllCubeFaces) {
    for (int y = 0; y < cube.face_size; ++y) {
      for (int x = 0; x < cube.face_size; ++x) {
        sum += glm::dvec3(cube.face(face).at(x, y)) * TexelSolidAngle(x, y, cube.face_size);
      }
    }
  }
  return sum;
}

void ExpectEnergyPreserved(const CubeMap& cube, glm::dvec3 source) {
  const glm::dvec3 resampled = CubeIntegral(cube);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(resampled[c] / source[c], 1.0, kEnergyRelativeError)
        << "channel " << c << ": cube " << resampled[c] << ", source " << source[c];
  }
}


// ---- Layout names ----------------------------------------------------------------------------

TEST(EnvironmentIoLayout, NamesParseBackToTheSameLayout) {
  for (EnvironmentLayout layout :
       {EnvironmentLayout::kAuto, EnvironmentLayout::kFaces, EnvironmentLayout::kHorizontalCross,
        EnvironmentLayout::kVerticalCross, EnvironmentLayout::kHorizontalStrip,
        EnvironmentLayout::kVerticalStrip, EnvironmentLayout::kLatLong,
        EnvironmentLayout::kAngular}) {
    EXPECT_EQ(kLayoutNames.Find(LayoutName(layout)), layout) << LayoutName(layout);
  }
  EXPECT_EQ(kLayoutNames.Find("hcross"), EnvironmentLayout::kHorizontalCross);
  EXPECT_EQ(kLayoutNames.Find("latlong"), EnvironmentLayout::kLatLong);
}

TEST(EnvironmentIoLayout, ParseRejectsUnknownNames) {
  EXPECT_FALSE(kLayoutNames.Find("cross").has_value());
  EXPECT_FALSE(kLayoutNames.Find("").has_value());
  EXPECT_FALSE(kLayoutNames.Find("HCROSS").has_value());
}

TEST(EnvironmentIoSrgb, DecodesCodeValue128ToKnownLinearValue) {
  EXPECT_NEAR(SrgbToLinear(128.0 / 255.0), kSrgb128, kSrgbDecodeError);
  EXPECT_DOUBLE_EQ(SrgbToLinear(0.0), 0.0);
  EXPECT_DOUBLE_EQ(SrgbToLinear(1.0), 1.0);
  EXPECT_NEAR(LinearToSrgb(SrgbToLinear(0.7)), 0.7, 1e-12);
}

// ---- Directions ------------------------------------------------------------------------------

TEST(EnvironmentIoDirections, LatLongCentreLooksAtPositiveZWithPositiveXToTheRight) {
  const auto near = [](glm::dvec3 a, glm::dvec3 b) { return glm::length(a - b) < 1e-12; };
  EXPECT_TRUE(near(LatLongDirection(0.5, 0.5), {0, 0, 1}));
  EXPECT_TRUE(near(LatLongDirection(0.75, 0.5), {1, 0, 0}));
  EXPECT_TRUE(near(LatLongDirection(0.25, 0.5), {-1, 0, 0}));
  EXPECT_TRUE(near(LatLongDirection(0.0, 0.5), {0, 0, -1}));
  EXPECT_TRUE(near(LatLongDirection(0.3, 0.0), {0, 1, 0}));
  EXPECT_TRUE(near(LatLongDirection(0.3, 1.0), {0, -1, 0}));
  for (double u : {0.1, 0.4, 0.6, 0.9}) {
    for (double v : {0.2, 0.5, 0.7}) {
      const glm::dvec2 back = DirectionToLatLong(LatLongDirection(u, v));
      EXPECT_NEAR(back.x, u, 1e-12);
      EXPECT_NEAR(back.y, v, 1e-12);
    }
  }
}

TEST(EnvironmentIoDirections, AngularCentreLooksAtPositiveZAndRimAtNegativeZ) {
  const auto near = [](glm::dvec3 a, glm::dvec3 b) { return glm::length(a - b) < 1e-12; };
  EXPECT_TRUE(near(AngularDirection(0.0, 0.0), {0, 0, 1}));
  EXPECT_TRUE(near(AngularDirection(0.5, 0.0), {1, 0, 0}));
  EXPECT_TRUE(near(AngularDirection(0.0, 0.5), {0, 1, 0}));
  EXPECT_TRUE(near(AngularDirection(-0.5, 0.0), {-1, 0, 0}));
  EXPECT_TRUE(near(AngularDirection(0.0, -1.0), {0, 0, -1}));
  for (double a : {-0.6, 0.1, 0.7}) {
    for (double b : {-0.5, 0.3}) {
      const glm::dvec2 back = DirectionToAngular(AngularDirection(a, b));
      EXPECT_NEAR(back.x, a, 1e-12);
      EXPECT_NEAR(back.y, b, 1e-12);
    }
  }
}

// ---- Cube layouts and formats ----------------------------------------------------------------

using EnvironmentIoLoad = TempFolderTest;

TEST_F(EnvironmentIoLoad, HorizontalCrossExrRoundTripIsExact) {
  const CubeMap cube = MakeTestCube(8);
  ASSERT_EQ(WriteCrossExr(cube, Path("cross.exr")).message(), "");
  const LoadedEnvironment& loaded = Load(Path("cross.exr"));
  EXPECT_EQ(loaded.layout, EnvironmentLayout::kHorizontalCross);
  EXPECT_TRUE(loaded.warnings.empty());
  ExpectCubesEqual(loaded.cube, cube);
}

TEST_F(EnvironmentIoLoad, HorizontalCrossIsReadAsDrawnInCubeMapHeader) {
  const CubeMap cube = MakeTestCube(4);
  const Image cross = PlaceFaces(cube, 4, 3, {{{2, 1}, {0, 1}, {1, 0}, {1, 2}, {1, 1}, {3, 1}}});
  ASSERT_TRUE(WriteFloatImage(Path("cross.exr"), cross));
  ExpectCubesEqual(Load(Path("cross.exr")).cube, cube);
}

TEST_F(EnvironmentIoLoad, VerticalCrossStoresNegativeZRotated180Degrees) {
  const CubeMap cube = MakeTestCube(4);
  const Image cross =
      PlaceFaces(cube, 3, 4, {{{2, 1}, {0, 1}, {1, 0}, {1, 2}, {1, 1}, {1, 3, true}}});
  // The stored top-left texel of the -z cell is the -z face's bottom-right texel.
  ASSERT_EQ(cross.at(4, 12), cube.face(CubeFace::kNegativeZ).at(3, 3));
  ASSERT_TRUE(WriteFloatImage(Path("vcross.exr"), cross));
  const LoadedEnvironment& loaded = Load(Path("vcross.exr"));
  EXPECT_EQ(loaded.layout, EnvironmentLayout::kVerticalCross);
  ExpectCubesEqual(loaded.cube, cube);
}

TEST_F(EnvironmentIoLoad, VerticalCrossNegativeZMeetsNegativeYSeamlessly) {
  // The bottom edge of -y and the stored top edge of -z look the same way: along the seam the
  // texel directions of both sides agree to within a texel.
  const int n = 8;
  const Image cross = CubeMapToImage(MakeTestCube(n), EnvironmentLayout::kVerticalCross);
  for (int x = 0; x < n; ++x) {
    const glm::dvec3 bottom_of_ny = TexelDirection(CubeFace::kNegativeY, x, n - 1, n);
    // Stored (x, 0) of the rotated -z cell is face texel (n - 1 - x, n - 1).
    const glm::dvec3 top_of_nz = TexelDirection(CubeFace::kNegativeZ, n - 1 - x, n - 1, n);
    EXPECT_LT(glm::length(bottom_of_ny - top_of_nz), 2.0 * 2.0 / n) << x;
  }
  EXPECT_EQ(cross.at(n, 3 * n), MakeTestCube(n).face(CubeFace::kNegativeZ).at(n - 1, n - 1));
}

TEST_F(EnvironmentIoLoad, HorizontalStripFloatTiffLoadsExactly) {
  const CubeMap cube = MakeTestCube(4);
  const Image strip = PlaceFaces(cube, 6, 1, {{{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}, {5, 0}}});
  ASSERT_TRUE(WriteFloatImage(Path("strip.tif"), strip));
  const LoadedEnvironment& loaded = Load(Path("strip.tif"));
  EXPECT_EQ(loaded.layout, EnvironmentLayout::kHorizontalStrip);
  ExpectCubesEqual(loaded.cube, cube);
}

TEST_F(EnvironmentIoLoad, VerticalStripPfmLoadsExactlyTopRowFirst) {
  const CubeMap cube = MakeTestCube(4);
  const Image strip = PlaceFaces(cube, 1, 6, {{{0, 0}, {0, 1}, {0, 2}, {0, 3}, {0, 4}, {0, 5}}});
  WritePfm(Path("strip.pfm"), strip);
  const LoadedEnvironment& loaded = Load(Path("strip.pfm"));
  EXPECT_EQ(loaded.layout, EnvironmentLayout::kVerticalStrip);
  ExpectCubesEqual(loaded.cube, cube);
}

TEST_F(EnvironmentIoLoad, RadianceHdrCrossLoadsWithinRgbePrecision) {
  const CubeMap cube = MakeTestCube(4);
  ASSERT_TRUE(WriteFloatImage(Path("cross.hdr"),
                              CubeMapToImage(cube, EnvironmentLayout::kHorizontalCross)));
  const LoadedEnvironment& loaded = Load(Path("cross.hdr"));
  EXPECT_EQ(loaded.layout, EnvironmentLayout::kHorizontalCross);
  ExpectCubesNear(loaded.cube, cube, kRgbeRelativeError, /*relative=*/true);
}

TEST_F(EnvironmentIoLoad, SixFaceFilesWithShortNames) {
  const CubeMap cube = MakeTestCube(4);
  for (CubeFace face : kAllCubeFaces) {
    ASSERT_TRUE(WriteFloatImage(
        Path(fmt::format("sky_{}.exr", kFaceFileNames[static_cast<int>(face)])), cube.face(face)));
  }
  const LoadedEnvironment& loaded = Load(Path("sky_{face}.exr"));
  EXPECT_EQ(loaded.layout, EnvironmentLayout::kFaces);
  ExpectCubesEqual(loaded.cube, cube);
}

TEST_F(EnvironmentIoLoad, SixFaceFilesWithSignedNamesInRadianceHdr) {
  const CubeMap cube = MakeTestCube(4);
  for (CubeFace face : kAllCubeFaces) {
    ASSERT_TRUE(WriteFloatImage(Path(fmt::format("{}.hdr", CubeFaceName(face))), cube.face(face)));
  }
  LoadOptions options;
  options.layout = EnvironmentLayout::kFaces;
  const LoadedEnvironment& loaded = Load(Path("{face}.hdr"), options);
  ExpectCubesNear(loaded.cube, cube, kRgbeRelativeError, /*relative=*/true);
}

TEST_F(EnvironmentIoLoad, EightBitPngIsDecodedFromSrgb) {
  const int n = 4;
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(4 * n) * 3 * n * 3);
  for (std::size_t i = 0; i < bytes.size(); ++i)
    bytes[i] = static_cast<std::uint8_t>((i * 37) % 256);
  bytes[(static_cast<std::size_t>(n) * 4 * n + n) * 3] = 128;  // +z face, texel (0, 0), red
  ASSERT_TRUE(
      WriteWithOiio(Path("cross.png"), 4 * n, 3 * n, 3, OIIO::TypeDesc::UINT8, bytes.data()));
  const LoadedEnvironment& loaded = Load(Path("cross.png"));
  EXPECT_NEAR(loaded.cube.face(CubeFace::kPositiveZ).at(0, 0).r, kSrgb128, kSrgbDecodeError);
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const std::size_t at = (static_cast<std::size_t>(y + n) * 4 * n + 2 * n + x) * 3;  // +x
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(loaded.cube.face(CubeFace::kPositiveX).at(x, y)[c],
                    SrgbToLinear(bytes[at + c] / 255.0), kSrgbDecodeError);
      }
    }
  }
}

TEST_F(EnvironmentIoLoad, JpegStripLoadsWithinLooseTolerance) {
  const int n = 8;
  const std::array<std::array<std::uint8_t, 3>, 6> colours = {{{200, 40, 40},
                                                               {40, 200, 40},
                                                               {40, 40, 200},
                                                               {200, 200, 40},
                                                               {40, 200, 200},
                                                               {128, 128, 128}}};
  std::vector<std::uint8_t> bytes;
  for (int y = 0; y < n; ++y) {
    for (int f = 0; f < 6; ++f) {
      for (int x = 0; x < n; ++x) bytes.insert(bytes.end(), colours[f].begin(), colours[f].end());
    }
  }
  ASSERT_TRUE(WriteWithOiio(Path("strip.jpg"), 6 * n, n, 3, OIIO::TypeDesc::UINT8, bytes.data()));
  const LoadedEnvironment& loaded = Load(Path("strip.jpg"));
  EXPECT_EQ(loaded.layout, EnvironmentLayout::kHorizontalStrip);
  for (CubeFace face : kAllCubeFaces) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(loaded.cube.face(face).at(3, 5)[c],
                  SrgbToLinear(colours[static_cast<int>(face)][c] / 255.0), kJpegError)
          << CubeFaceName(face);
    }
  }
}

TEST_F(EnvironmentIoLoad, OneChannelImageIsReplicatedToGrey) {
  const int n = 2;
  std::vector<float> grey(static_cast<std::size_t>(6 * n) * n);
  for (std::size_t i = 0; i < grey.size(); ++i) grey[i] = 0.5f * static_cast<float>(i);
  ASSERT_TRUE(WriteWithOiio(Path("grey.exr"), 6 * n, n, 1, OIIO::TypeDesc::FLOAT, grey.data()));
  const LoadedEnvironment& loaded = Load(Path("grey.exr"));
  const glm::vec3 texel = loaded.cube.face(CubeFace::kNegativeX).at(1, 1);  // column 3, row 1
  EXPECT_EQ(texel, glm::vec3(grey[6 * n + 3]));
}

TEST_F(EnvironmentIoLoad, DdsCubeMapLoadsSixFacesInD3dOrder) {
  const int n = 4;
  WriteBytes(Path("cube.dds"),
             Dds8BitCube(n, {kAllCubeFaces.begin(), kAllCubeFaces.end()}, DdsTestBytes));
  const LoadedEnvironment& loaded = Load(Path("cube.dds"));
  EXPECT_EQ(loaded.layout, EnvironmentLayout::kVerticalStrip);
  ASSERT_EQ(loaded.cube.face_size, n);
  for (CubeFace face : kAllCubeFaces) {
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        const std::array<std::uint8_t, 3> rgb = DdsTestBytes(face, x, y);
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(loaded.cube.face(face).at(x, y)[c], SrgbToLinear(rgb[c] / 255.0),
                      kSrgbDecodeError);
        }
      }
    }
  }
}

// Float and BC6H DDS files: dds_reader_test.cc.

TEST_F(EnvironmentIoLoad, NanInfAndNegativeTexelsAreZeroedWithAWarning) {
  CubeMap cube = MakeTestCube(4);
  cube.face(CubeFace::kPositiveY).at(1, 2).g = std::numeric_limits<float>::quiet_NaN();
  cube.face(CubeFace::kNegativeZ).at(0, 0) =
      glm::vec3(std::numeric_limits<float>::infinity(), 1.0f, -2.0f);
  cube.face(CubeFace::kPositiveX).at(3, 3).b = -0.5f;
  ASSERT_EQ(WriteCrossExr(cube, Path("bad.exr")).message(), "");
  const LoadedEnvironment& loaded = Load(Path("bad.exr"));
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_THAT(loaded.warnings[0], HasSubstr("3 of"));
  EXPECT_THAT(loaded.warnings[0], HasSubstr("NaN"));
  CubeMap expected = cube;
  expected.face(CubeFace::kPositiveY).at(1, 2).g = 0.0f;
  expected.face(CubeFace::kNegativeZ).at(0, 0) = glm::vec3(0.0f, 1.0f, 0.0f);
  expected.face(CubeFace::kPositiveX).at(3, 3).b = 0.0f;
  ExpectCubesEqual(loaded.cube, expected);
}

// ---- Automatic layout detection --------------------------------------------------------------

class EnvironmentIoAutoDetect : public TempFolderTest,
                                public testing::WithParamInterface<EnvironmentLayout> {};

TEST_P(EnvironmentIoAutoDetect, DetectsLayoutFromAspectRatio) {
  const EnvironmentLayout layout = GetParam();
  const Image image = CubeMapToImage(MakeTestCube(4), layout);
  ASSERT_TRUE(WriteFloatImage(Path("env.exr"), image));
  LoadOptions options;
  options.face_size = 4;
  const LoadedEnvironment& loaded = Load(Path("env.exr"), options);
  EXPECT_EQ(loaded.layout, layout);
  EXPECT_EQ(loaded.cube.face_size, 4);
}

INSTANTIATE_TEST_SUITE_P(EnvironmentIoImageLayouts, EnvironmentIoAutoDetect,
                         testing::Values(EnvironmentLayout::kHorizontalCross,
                                         EnvironmentLayout::kVerticalCross,
                                         EnvironmentLayout::kHorizontalStrip,
                                         EnvironmentLayout::kVerticalStrip,
                                         EnvironmentLayout::kLatLong),  // a square image is refused
                         [](const testing::TestParamInfo<EnvironmentLayout>& info) {
                           return std::string(LayoutName(info.param));
                         });

// ---- Lat-long and angular resampling ---------------------------------------------------------

Image MakeLatLong(int height, const std::function<glm::vec3(glm::dvec3)>& radiance) {
  Image image(2 * height, height);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      image.at(x, y) =
          radiance(LatLongDirection((x + 0.5) / image.width, (y + 0.5) / image.height));
    }
  }
  return image;
}

// Sum of radiance x exact pixel solid angle, (2 pi / W) (cos(theta_top) - cos(theta_bottom)).
glm::dvec3 LatLongIntegral(const Image& image) {
  glm::dvec3 sum(0.0);
  for (int y = 0; y < image.height; ++y) {
    const double omega = 2.0 * std::numbers::pi / image.width *
                         (std::cos(std::numbers::pi * y / image.height) -
                          std::cos(std::numbers::pi * (y + 1) / image.height));
    for (int x = 0; x < image.width; ++x) sum += glm::dvec3(image.at(x, y)) * omega;
  }
  return sum;
}

// Every pixel gets the radiance of its centre's direction; centres outside the disk take the
// direction of the nearest rim point.
Image MakeAngular(int size, const std::function<glm::vec3(glm::dvec3)>& radiance) {
  Image image(size, size);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      double a = 2.0 * (x + 0.5) / size - 1.0;
      double b = 1.0 - 2.0 * (y + 0.5) / size;
      const double r = std::sqrt(a * a + b * b);
      if (r > 1.0) {
        a /= r;
        b /= r;
      }
      image.at(x, y) = radiance(AngularDirection(a, b));
    }
  }
  return image;
}

// Solid angle of each pixel of an n x n angular map: of the part of the pixel inside the disk,
// integrated with kSub x kSub points, dw = pi sin(pi r) / r da db.
std::vector<double> AngularPixelSolidAngles(int n) {
  constexpr int kSub = 8;
  const double cell = 2.0 / n / kSub;
  std::vector<double> omegas(static_cast<std::size_t>(n) * n, 0.0);
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      double omega = 0.0;
      for (int j = 0; j < kSub; ++j) {
        for (int i = 0; i < kSub; ++i) {
          const double a = -1.0 + 2.0 * x / n + cell * (i + 0.5);
          const double b = 1.0 - 2.0 * y / n - cell * (j + 0.5);
          const double r = std::sqrt(a * a + b * b);
          if (r <= 1.0)
            omega += std::numbers::pi * std::sin(std::numbers::pi * r) / r * cell * cell;
        }
      }
      omegas[static_cast<std::size_t>(y) * n + x] = omega;
    }
  }
  return omegas;
}

// Sum of radiance x pixel solid angle.
glm::dvec3 AngularIntegral(const Image& image, const std::vector<double>& omegas) {
  glm::dvec3 sum(0.0);
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    sum += glm::dvec3(image.pixels[i]) * omegas[i];
  return sum;
}

CubeMap CubeFromFunction(int size, const std::function<glm::vec3(glm::dvec3)>& radiance) {
  CubeMap cube(size);
  for (CubeFace face : kAllCubeFaces) {
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x)
        cube.face(face).at(x, y) = radiance(TexelDirection(face, x, y, size));
    }
  }
  return cube;
}

// One bright pixel (red, half as much green, a quarter as much blue).
Image WithSpot(Image image, int x, int y, float value) {
  image.at(x, y) = glm::vec3(value, 0.5f * value, 0.25f * value);
  return image;
}

constexpr glm::vec3 kDim(0.05f, 0.04f, 0.03f);

using EnvironmentIoResample = TempFolderTest;

TEST_F(EnvironmentIoResample, LatLongFileIsOrientedAsDocumented) {
  ASSERT_TRUE(WriteFloatImage(Path("sky.exr"), MakeLatLong(64, SmoothRadiance)));
  LoadOptions options;
  options.face_size = 16;
  const LoadedEnvironment& loaded = Load(Path("sky.exr"), options);
  EXPECT_EQ(loaded.layout, EnvironmentLayout::kLatLong);
  ExpectCubesNear(loaded.cube, CubeFromFunction(16, SmoothRadiance), kSmoothResampleError);
}

TEST_F(EnvironmentIoResample, AngularFileIsOrientedAsDocumented) {
  ASSERT_TRUE(WriteFloatImage(Path("probe.exr"), MakeAngular(128, SmoothRadiance)));
  LoadOptions options;
  options.face_size = 16;
  options.layout = EnvironmentLayout::kAngular;
  const LoadedEnvironment& loaded = Load(Path("probe.exr"), options);
  EXPECT_EQ(loaded.layout, EnvironmentLayout::kAngular);
  EXPECT_EQ(loaded.layout_reason, "as given");
  ExpectCubesNear(loaded.cube, CubeFromFunction(16, SmoothRadiance), kSmoothResampleError);
}

TEST_F(EnvironmentIoResample, ASquareImageIsNeverGuessedAndAsksForTheLayout) {
  // An angular probe and one cube face are both square: reading either as the other gives
  // plausible wrong numbers, so auto names neither.
  for (int size : {1, 16, 128}) {
    ASSERT_TRUE(WriteFloatImage(Path("cube_px.exr"), Image(size, size, glm::vec3(1.0f))));
    const Result<LoadedEnvironment> result = LoadEnvironment(Path("cube_px.exr"), LoadOptions{});
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().code, DiagnosticCode::kOptionValue);
    EXPECT_THAT(result.message(), HasSubstr(fmt::format("cube_px.exr: cannot tell the layout of a square {} x {} image",
                                                    size, size)));
    EXPECT_THAT(result.message(), HasSubstr("--layout angular"));
  }
}

TEST_F(EnvironmentIoResample, TheLayoutSaysWhyItWasChosen) {
  ASSERT_TRUE(WriteFloatImage(Path("lat.exr"), Image(64, 32, glm::vec3(1.0f))));
  LoadOptions options;
  options.face_size = 8;
  EXPECT_EQ(Load(Path("lat.exr"), options).layout_reason, "detected from the 2:1 aspect ratio of the 64 x 32 image");
  ASSERT_TRUE(WriteFloatImage(Path("strip.exr"), Image(48, 8, glm::vec3(1.0f))));
  EXPECT_EQ(Load(Path("strip.exr"), options).layout_reason, "detected from the 6:1 aspect ratio of the 48 x 8 image");
}

TEST(EnvironmentIoEnergy, LatLongResamplingKeepsTheIntegralOfASmoothMap) {
  const Image latlong = MakeLatLong(128, SmoothRadiance);
  ExpectEnergyPreserved(ResampleLatLong(latlong, 32), LatLongIntegral(latlong));
}

TEST(EnvironmentIoEnergy, LatLongResamplingKeepsTheIntegralOfASharpSpot) {
  // One bright pixel holding about half of the energy: mid-latitude, near each pole, at the seam.
  for (auto [x, y] : {std::pair{77, 40}, {3, 4}, {200, 123}, {255, 64}, {128, 90}}) {
    SCOPED_TRACE(fmt::format("spot at ({}, {})", x, y));
    const float value =
        0.05f * 4.0f * static_cast<float>(std::numbers::pi) /
        static_cast<float>(LatLongIntegral(WithSpot(Image(256, 128), x, y, 1.0f)).x);
    const Image latlong = WithSpot(MakeLatLong(128, [](glm::dvec3) { return kDim; }), x, y, value);
    ExpectEnergyPreserved(ResampleLatLong(latlong, 32), LatLongIntegral(latlong));
  }
}

TEST(EnvironmentIoEnergy, LatLongDownsamplingKeepsTheIntegralOfASharpSpot) {
  // 1024 x 512 to faces of 16: the map is first halved to 256 x 128.
  const Image latlong =
      WithSpot(MakeLatLong(512, [](glm::dvec3) { return kDim; }), 613, 200, 2.0e4f);
  ExpectEnergyPreserved(ResampleLatLong(latlong, 16), LatLongIntegral(latlong));
}

TEST(EnvironmentIoEnergy, LatLongUpsamplingKeepsTheIntegralOfASharpSpot) {
  const Image latlong = WithSpot(MakeLatLong(64, [](glm::dvec3) { return kDim; }), 41, 21, 300.0f);
  ExpectEnergyPreserved(ResampleLatLong(latlong, 96), LatLongIntegral(latlong));
}

TEST(EnvironmentIoEnergy, AngularResamplingKeepsTheIntegralOfASmoothMap) {
  const int n = 256;
  const std::vector<double> omegas = AngularPixelSolidAngles(n);
  double total_solid_angle = 0.0;
  for (double omega : omegas) total_solid_angle += omega;
  ASSERT_NEAR(total_solid_angle / (4.0 * std::numbers::pi), 1.0, 1e-4);
  const Image angular = MakeAngular(n, SmoothRadiance);
  ExpectEnergyPreserved(ResampleAngular(angular, 32), AngularIntegral(angular, omegas));
}

TEST(EnvironmentIoEnergy, AngularResamplingKeepsTheIntegralOfASharpSpot) {
  // One bright pixel holding about half of the energy: near +z, to the side, towards the rim.
  const int n = 256;
  const std::vector<double> omegas = AngularPixelSolidAngles(n);
  for (auto [x, y] : {std::pair{130, 120}, {170, 90}, {40, 128}, {128, 235}}) {
    SCOPED_TRACE(fmt::format("spot at ({}, {})", x, y));
    const double spot_solid_angle = omegas[static_cast<std::size_t>(y) * n + x];
    const Image angular = WithSpot(MakeAngular(n, [](glm::dvec3) { return kDim; }), x, y,
                                   static_cast<float>(0.6 / spot_solid_angle));
    ExpectEnergyPreserved(ResampleAngular(angular, 32), AngularIntegral(angular, omegas));
  }
}

TEST(EnvironmentIoEnergy, ConstantMapsStayConstant) {
  const glm::vec3 grey(0.7f, 0.5f, 0.3f);
  const CubeMap expected(8, grey);
  ExpectCubesNear(ResampleLatLong(Image(32, 16, grey), 8), expected, 1e-6f);
  ExpectCubesNear(ResampleAngular(Image(32, 32, grey), 8), expected, 1e-6f);
}

// ---- Errors ----------------------------------------------------------------------------------

using EnvironmentIoErrors = TempFolderTest;

TEST_F(EnvironmentIoErrors, MissingFileIsReported) {
  EXPECT_THAT(LoadError(Path("nothing.exr")), HasSubstr("not found"));
  EXPECT_EQ(LoadFailure(Path("nothing.exr")).code, DiagnosticCode::kNoSuchInput);
}

TEST_F(EnvironmentIoErrors, EmptyFileIsReported) {
  WriteBytes(Path("empty.exr"), "");
  EXPECT_THAT(LoadError(Path("empty.exr")), HasSubstr("empty"));
}

TEST_F(EnvironmentIoErrors, TruncatedExrIsReported) {
  ASSERT_EQ(WriteCrossExr(MakeTestCube(16), Path("full.exr")).message(), "");
  const std::string bytes = ReadBytes(Path("full.exr"));
  WriteBytes(Path("truncated.exr"), bytes.substr(0, bytes.size() / 2));
  EXPECT_THAT(LoadError(Path("truncated.exr")), HasSubstr("truncated"));
  EXPECT_EQ(LoadFailure(Path("truncated.exr")).code, DiagnosticCode::kCannotReadFile);
}

TEST_F(EnvironmentIoErrors, CorruptFileIsReported) {
  WriteBytes(Path("noise.exr"), "this is not an OpenEXR file at all");
  EXPECT_THAT(LoadError(Path("noise.exr")), HasSubstr("corrupt"));
}

TEST_F(EnvironmentIoErrors, UnsupportedFormatIsReported) {
  WriteBytes(Path("notes.xyz"), std::string(64, '\x17'));
  EXPECT_THAT(LoadError(Path("notes.xyz")), HasSubstr("unsupported image format"));
}

TEST_F(EnvironmentIoErrors, ZeroSizeImageIsReported) {
  WriteBytes(Path("zero.pfm"), "PF\n0 0\n-1.0\n");
  EXPECT_THAT(LoadError(Path("zero.pfm")), HasSubstr("zero-size"));
  EXPECT_THAT(EnvironmentFromImage(Image(), EnvironmentLayout::kAuto, 8).message(),
              HasSubstr("zero-size"));
}

TEST_F(EnvironmentIoErrors, UnknownAspectRatioNamesTheSizeAndTheAcceptedRatios) {
  ASSERT_TRUE(WriteFloatImage(Path("odd.exr"), Image(7, 5, glm::vec3(1.0f))));
  const std::string error = LoadError(Path("odd.exr"));
  EXPECT_THAT(error, HasSubstr("7 x 5"));
  EXPECT_THAT(error, HasSubstr("4:3 horizontal cross"));
  EXPECT_THAT(error, HasSubstr("2:1 lat-long"));
}

TEST_F(EnvironmentIoErrors, CrossOfTheWrongSizeIsReported) {
  ASSERT_TRUE(WriteFloatImage(Path("cross.exr"), Image(10, 6, glm::vec3(1.0f))));
  LoadOptions options;
  options.layout = EnvironmentLayout::kHorizontalCross;
  EXPECT_THAT(LoadError(Path("cross.exr"), options), HasSubstr("4N x 3N"));
  EXPECT_EQ(LoadFailure(Path("cross.exr"), options).code, DiagnosticCode::kCannotReadFile);
  options.layout = EnvironmentLayout::kVerticalStrip;
  EXPECT_THAT(LoadError(Path("cross.exr"), options), HasSubstr("1N x 6N"));
}

TEST_F(EnvironmentIoErrors, LatLongAndAngularOfTheWrongShapeAreReported) {
  ASSERT_TRUE(WriteFloatImage(Path("wide.exr"), Image(12, 4, glm::vec3(1.0f))));
  LoadOptions options;
  options.layout = EnvironmentLayout::kLatLong;
  EXPECT_THAT(LoadError(Path("wide.exr"), options), HasSubstr("2:1"));
  options.layout = EnvironmentLayout::kAngular;
  EXPECT_THAT(LoadError(Path("wide.exr"), options), HasSubstr("1:1"));
}

TEST_F(EnvironmentIoErrors, InvalidFaceSizeForResamplingIsReported) {
  ASSERT_TRUE(WriteFloatImage(Path("sky.exr"), Image(8, 4, glm::vec3(1.0f))));
  LoadOptions options;
  options.face_size = 0;
  EXPECT_THAT(LoadError(Path("sky.exr"), options), HasSubstr("face size 0"));
  EXPECT_EQ(LoadFailure(Path("sky.exr"), options).code, DiagnosticCode::kFaceSize);
}

TEST_F(EnvironmentIoErrors, NonSquareFaceFilesAreReported) {
  for (std::string_view name : kFaceFileNames) {
    ASSERT_TRUE(WriteFloatImage(Path(fmt::format("f_{}.exr", name)), Image(8, 4, glm::vec3(1.0f))));
  }
  EXPECT_THAT(LoadError(Path("f_{face}.exr")), HasSubstr("must be square"));
}

TEST_F(EnvironmentIoErrors, FaceFilesOfDifferentSizesAreReported) {
  for (std::string_view name : kFaceFileNames) {
    const int size = name == "pz" ? 8 : 4;
    ASSERT_TRUE(
        WriteFloatImage(Path(fmt::format("f_{}.exr", name)), Image(size, size, glm::vec3(1.0f))));
  }
  const std::string error = LoadError(Path("f_{face}.exr"));
  EXPECT_THAT(error, HasSubstr("mismatched face sizes"));
  EXPECT_THAT(error, HasSubstr("+z face"));
}

TEST_F(EnvironmentIoErrors, MissingFaceFileIsReported) {
  for (std::string_view name : kFaceFileNames) {
    if (name == "nz") continue;
    ASSERT_TRUE(WriteFloatImage(Path(fmt::format("f_{}.exr", name)), Image(4, 4, glm::vec3(1.0f))));
  }
  const std::string error = LoadError(Path("f_{face}.exr"));
  EXPECT_THAT(error, HasSubstr("missing the -z face"));
  EXPECT_THAT(error, HasSubstr("f_nz.exr"));
  EXPECT_THAT(error, HasSubstr("f_-z.exr"));
  EXPECT_EQ(LoadFailure(Path("f_{face}.exr")).code, DiagnosticCode::kNoSuchInput);
}

TEST_F(EnvironmentIoErrors, CorruptFaceFileIsReportedWithItsFace) {
  for (std::string_view name : kFaceFileNames) {
    ASSERT_TRUE(WriteFloatImage(Path(fmt::format("f_{}.exr", name)), Image(4, 4, glm::vec3(1.0f))));
  }
  WriteBytes(Path("f_py.exr"), "garbage");
  const std::string error = LoadError(Path("f_{face}.exr"));
  EXPECT_THAT(error, HasSubstr("+y face"));
  EXPECT_THAT(error, HasSubstr("corrupt"));
}

TEST_F(EnvironmentIoErrors, SixFaceLayoutWithoutFaceTokenIsReported) {
  LoadOptions options;
  options.layout = EnvironmentLayout::kFaces;
  EXPECT_THAT(LoadError(Path("sky.exr"), options), HasSubstr("{face}"));
}

TEST_F(EnvironmentIoErrors, DdsCubeMapWithMissingFacesIsReported) {
  WriteBytes(Path("partial.dds"),
             Dds8BitCube(4, {CubeFace::kPositiveX, CubeFace::kNegativeX}, DdsTestBytes));
  EXPECT_THAT(LoadError(Path("partial.dds")), HasSubstr("six"));
}

TEST_F(EnvironmentIoErrors, DdsCubeMapRejectsACrossLayout) {
  WriteBytes(Path("cube.dds"),
             Dds8BitCube(4, {kAllCubeFaces.begin(), kAllCubeFaces.end()}, DdsTestBytes));
  LoadOptions options;
  options.layout = EnvironmentLayout::kHorizontalCross;
  EXPECT_THAT(LoadError(Path("cube.dds"), options), HasSubstr("DDS cube map"));
}

TEST_F(EnvironmentIoErrors, TruncatedPngAndHdrAreReported) {
  const Image cross = CubeMapToImage(MakeTestCube(16), EnvironmentLayout::kHorizontalCross);
  for (std::string_view name : {"cross.png", "cross.hdr"}) {
    ASSERT_EQ(WriteImage(cross, Path(name)).message(), "");
    const std::string bytes = ReadBytes(Path(name));
    WriteBytes(Path(name), bytes.substr(0, bytes.size() / 2));
    EXPECT_THAT(LoadError(Path(name)), HasSubstr("truncated")) << name;
  }
}

// ---- Writers ---------------------------------------------------------------------------------

using EnvironmentIoWrite = TempFolderTest;

TEST_F(EnvironmentIoWrite, PngIsEncodedToSrgbBytesWithClamping) {
  Image image(3, 1);
  image.at(0, 0) = glm::vec3(kSrgb128, 0.0f, 1.0f);
  image.at(1, 0) = glm::vec3(-1.0f, 7.0f, std::numeric_limits<float>::quiet_NaN());
  image.at(2, 0) = glm::vec3(SrgbToLinear(200.0 / 255.0), SrgbToLinear(7.0 / 255.0), 0.5f);
  ASSERT_EQ(WriteImage(image, Path("out.png")).message(), "");
  auto input = OIIO::ImageInput::open(Path("out.png").string());
  ASSERT_TRUE(input);
  ASSERT_EQ(input->spec().format, OIIO::TypeDesc::UINT8);
  std::array<std::uint8_t, 9> bytes{};
  ASSERT_TRUE(input->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, bytes.data()));
  EXPECT_THAT(bytes, testing::ElementsAre(128, 0, 255, 0, 255, 0, 200, 7, 188));
  // And it loads back as linear.
  EXPECT_NEAR(ReadImage(Path("out.png"))->image.at(0, 0).r, kSrgb128, kSrgbDecodeError);
}

TEST_F(EnvironmentIoWrite, ExrKeepsFloatsExactly) {
  const Image image = CubeMapToImage(MakeTestCube(3), EnvironmentLayout::kHorizontalStrip);
  ASSERT_EQ(WriteImage(image, Path("strip.exr")).message(), "");
  const Result<ImageRead> read = ReadImage(Path("strip.exr"));
  ASSERT_TRUE(read.ok()) << read.message();
  EXPECT_EQ(read->image.pixels, image.pixels);
}

TEST_F(EnvironmentIoWrite, FailureLeavesNoFileBehind) {
  const Image image(4, 4, glm::vec3(1.0f));
  EXPECT_THAT(WriteImage(image, Path("missing_folder/out.exr")).message(), HasSubstr("out.exr"));
  EXPECT_THAT(WriteImage(image, Path("out.xyz")).message(), HasSubstr("unsupported output format"));
  EXPECT_THAT(WriteImage(Image(), Path("empty.exr")).message(), HasSubstr("zero-size"));
  EXPECT_THAT(FolderContents(), testing::IsEmpty());
}

// What environment_io.h says of the writers: .pfm and .dds are read, not written (OpenImageIO 2.4 has
// no writer for either), and asking for one fails cleanly.
TEST_F(EnvironmentIoWrite, PfmAndDdsAreRefusedAsTheHeaderSays) {
  const Image image(4, 2, glm::vec3(0.25f, 2.5f, 100.0f));
  for (const char* name : {"out.pfm", "out.dds"}) {
    EXPECT_THAT(WriteImage(image, Path(name)).message(), HasSubstr("unsupported output format")) << name;
  }
  EXPECT_THAT(FolderContents(), testing::IsEmpty());
}

TEST_F(EnvironmentIoWrite, ReplacesAnExistingFileAndLeavesNoTemporary) {
  WriteBytes(Path("cross.exr"), "old contents");
  const CubeMap cube = MakeTestCube(4);
  ASSERT_EQ(WriteCrossExr(cube, Path("cross.exr")).message(), "");
  EXPECT_THAT(FolderContents(), testing::ElementsAre("cross.exr"));
  ExpectCubesEqual(Load(Path("cross.exr")).cube, cube);
}

TEST_F(EnvironmentIoWrite, CrossExrIsOpenExrWhateverTheExtension) {
  const CubeMap cube = MakeTestCube(2);
  ASSERT_EQ(WriteCrossExr(cube, Path("cross.bin")).message(), "");
  auto input = OIIO::ImageInput::open(Path("cross.bin").string());
  ASSERT_TRUE(input);
  EXPECT_EQ(std::string(input->format_name()), "openexr");
  EXPECT_EQ(input->spec().format, OIIO::TypeDesc::FLOAT);
  input.reset();
  LoadOptions options;
  options.layout = EnvironmentLayout::kHorizontalCross;
  ExpectCubesEqual(Load(Path("cross.bin"), options).cube, cube);
}

TEST_F(EnvironmentIoWrite, CrossExrUnusedCellsAreBlack) {
  ASSERT_EQ(WriteCrossExr(MakeTestCube(2), Path("cross.exr")).message(), "");
  const Result<ImageRead> read = ReadImage(Path("cross.exr"));
  ASSERT_TRUE(read.ok()) << read.message();
  EXPECT_EQ(read->image.width, 8);
  EXPECT_EQ(read->image.height, 6);
  for (auto [x, y] : {std::pair{0, 0}, {1, 1}, {4, 0}, {7, 1}, {0, 5}, {7, 4}}) {
    EXPECT_EQ(read->image.at(x, y), glm::vec3(0.0f)) << x << ", " << y;
  }
}

class EnvironmentIoWriteLayout : public TempFolderTest,
                                 public testing::WithParamInterface<EnvironmentLayout> {};

TEST_P(EnvironmentIoWriteLayout, CubeLayoutRoundTripsExactly) {
  const CubeMap cube = MakeTestCube(4);
  const fs::path path =
      Path(GetParam() == EnvironmentLayout::kFaces ? "env_{face}.exr" : "env.exr");
  ASSERT_EQ(WriteCubeMap(cube, path, GetParam()).message(), "");
  LoadOptions options;
  options.layout = GetParam();
  const LoadedEnvironment& loaded = Load(path, options);
  EXPECT_EQ(loaded.layout, GetParam());
  ExpectCubesEqual(loaded.cube, cube);
}

INSTANTIATE_TEST_SUITE_P(EnvironmentIoCubeLayouts, EnvironmentIoWriteLayout,
                         testing::Values(EnvironmentLayout::kFaces,
                                         EnvironmentLayout::kHorizontalCross,
                                         EnvironmentLayout::kVerticalCross,
                                         EnvironmentLayout::kHorizontalStrip,
                                         EnvironmentLayout::kVerticalStrip),
                         [](const testing::TestParamInfo<EnvironmentLayout>& info) {
                           return std::string(LayoutName(info.param));
                         });

TEST_F(EnvironmentIoWrite, SixFacesUseShortFileNames) {
  ASSERT_EQ(WriteCubeMap(MakeTestCube(2), Path("sky_{face}.exr"), EnvironmentLayout::kAuto).message(), "");
  EXPECT_THAT(FolderContents(), testing::ElementsAre("sky_nx.exr", "sky_ny.exr", "sky_nz.exr",
                                                     "sky_px.exr", "sky_py.exr", "sky_pz.exr"));
}

TEST_F(EnvironmentIoWrite, SixFacesNeedTheFaceToken) {
  EXPECT_THAT(WriteCubeMap(MakeTestCube(2), Path("sky.exr"), EnvironmentLayout::kFaces).message(), HasSubstr("{face}"));
  EXPECT_THAT(FolderContents(), testing::IsEmpty());
}

TEST_F(EnvironmentIoWrite, LatLongAndAngularExportsResampleBackToTheCube) {
  const CubeMap cube = CubeFromFunction(16, SmoothRadiance);
  for (EnvironmentLayout layout : {EnvironmentLayout::kLatLong, EnvironmentLayout::kAngular}) {
    const fs::path path = Path(fmt::format("{}.exr", LayoutName(layout)));
    ASSERT_EQ(WriteCubeMap(cube, path, layout).message(), "");
    LoadOptions options;
    options.face_size = 16;
    // A square angular map is read only when named (auto refuses a square image).
    if (layout == EnvironmentLayout::kAngular) options.layout = layout;
    const LoadedEnvironment& loaded = Load(path, options);
    EXPECT_EQ(loaded.layout, layout);
    ExpectCubesNear(loaded.cube, cube, kExportRoundTripError);
  }
}

}  // namespace
}  // namespace vs11::irradiance

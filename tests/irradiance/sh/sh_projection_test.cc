#include "irradiance/sh/sh_projection.h"

#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "irradiance/io/environments.h"

namespace vs11::irradiance {
namespace {

// Sums of float-stored basis weights: each weight is rounded once (2^-24 relative), and the sums
// of cancelling weights keep that size relative to the largest coefficient.
constexpr double kFloatStorageRelative = 1e-6;
// Pure double sums over up to ~10^5 texels.
constexpr double kDoubleSumRelative = 1e-12;

double LargestMagnitude(const Sh9Rgb& sh) {
  double largest = 0.0;
  for (const glm::dvec3& c : sh.coefficients) {
    largest = std::max({largest, std::abs(c.x), std::abs(c.y), std::abs(c.z)});
  }
  return largest;
}

void ExpectShNear(const Sh9Rgb& actual, const Sh9Rgb& expected, double tolerance) {
  for (int i = 0; i < kSh9Coefficients; ++i) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(actual.coefficients[i][c], expected.coefficients[i][c], tolerance)
          << "coefficient " << i << " channel " << c;
    }
  }
}

// The environment seen after applying the orthogonal `map` (a cube symmetry) to every direction:
// out(d) = in(map^-1 d). Texel centres go to texel centres, so this only moves texels; the texel
// of `in` is found through DirectionToFace and the face table, and must land on a texel centre.
CubeMap ApplyCubeSymmetry(const CubeMap& in, const glm::dmat3& map) {
  const int size = in.face_size;
  CubeMap out(size);
  std::vector<int> used(static_cast<std::size_t>(kCubeFaceCount) * size * size, 0);
  const glm::dmat3 inverse = glm::transpose(map);
  for (CubeFace face : kAllCubeFaces) {
    for (int y = 0; y < size; ++y) {
      for (int x = 0; x < size; ++x) {
        const FacePoint p = DirectionToFace(inverse * TexelDirection(face, x, y, size));
        const double sx = (p.s + 1.0) * size / 2.0 - 0.5;
        const double ty = (p.t + 1.0) * size / 2.0 - 0.5;
        const int src_x = static_cast<int>(std::lround(sx));
        const int src_y = static_cast<int>(std::lround(ty));
        EXPECT_NEAR(sx, src_x, 1e-9);
        EXPECT_NEAR(ty, src_y, 1e-9);
        out.face(face).at(x, y) = in.face(p.face).at(src_x, src_y);
        ++used[(static_cast<std::size_t>(p.face) * size + src_y) * size + src_x];
      }
    }
  }
  for (int count : used) EXPECT_EQ(count, 1);  // a permutation of the texels
  return out;
}

// A colourful environment with no symmetry, so that every coefficient is non-zero.
CubeMap AsymmetricEnvironment(int size) {
  StudioParams params;
  params.room_radiance = glm::vec3(0.1f, 0.05f, 0.02f);
  CubeMap map = MakeStudio(size, params);
  // Tint one texel column so that the +x/-x and front/back halves differ.
  for (int y = 0; y < size; ++y) map.face(CubeFace::kPositiveX).at(1, y) += glm::vec3(2.0f, 0.0f, 1.0f);
  return map;
}

TEST(ShProjection, LevelCountIsLog2PlusOneForPowersOfTwo) {
  EXPECT_EQ(LevelCount(1), 1);
  EXPECT_EQ(LevelCount(2), 2);
  EXPECT_EQ(LevelCount(256), 9);
  EXPECT_EQ(LevelCount(2048), 12);
  EXPECT_EQ(LevelCount(0), 0);
  EXPECT_EQ(LevelCount(-4), 0);
  EXPECT_EQ(LevelCount(48), 0);
}

TEST(ShProjection, MipsRejectFaceSizesThatAreNotPowersOfTwo) {
  EXPECT_FALSE(BuildEnvironmentMips(CubeMap(6)).has_value());
  EXPECT_FALSE(BuildEnvironmentMips(CubeMap(0)).has_value());
  EXPECT_FALSE(BuildBasisPyramid(12).has_value());
  EXPECT_FALSE(BuildBasisPyramid(0).has_value());
}

TEST(ShProjection, EnvironmentMipsAreBoxMeansDownToOneTexel) {
  CubeMap map(4);
  for (int f = 0; f < kCubeFaceCount; ++f) {
    for (int y = 0; y < 4; ++y) {
      for (int x = 0; x < 4; ++x) map.faces[f].at(x, y) = glm::vec3(x + 4 * y, f, 1.0f);
    }
  }
  const std::optional<CubeMipChain> chain = BuildEnvironmentMips(map);
  ASSERT_TRUE(chain.has_value());
  ASSERT_EQ(chain->levels.size(), 3u);
  EXPECT_EQ(chain->levels[1].face_size, 2);
  EXPECT_EQ(chain->levels[2].face_size, 1);
  // Texel (1, 0) of level 1 covers x in {2, 3}, y in {0, 1}: values 2, 3, 6, 7.
  EXPECT_EQ(chain->levels[1].faces[3].at(1, 0), glm::vec3(4.5f, 3.0f, 1.0f));
  EXPECT_EQ(chain->levels[2].faces[5].at(0, 0), glm::vec3(7.5f, 5.0f, 1.0f));
}

void ExpectSameMips(const CubeMipChain& actual, const CubeMipChain& expected) {
  ASSERT_EQ(actual.levels.size(), expected.levels.size());
  for (std::size_t k = 0; k < actual.levels.size(); ++k) {
    ASSERT_EQ(actual.levels[k].face_size, expected.levels[k].face_size) << "level " << k;
    for (int f = 0; f < kCubeFaceCount; ++f) {
      EXPECT_EQ(actual.levels[k].faces[f].pixels, expected.levels[k].faces[f].pixels)
          << "level " << k << " face " << f;
    }
  }
}

TEST(ShProjection, RefilledMipsEqualAFreshBuildAndReuseTheirBuffers) {
  constexpr int kSize = 16;
  std::optional<CubeMipChain> chain = BuildEnvironmentMips(MakeSky(kSize));
  ASSERT_TRUE(chain.has_value());
  std::vector<const glm::vec3*> buffers;
  for (const CubeMap& level : chain->levels) {
    for (const Image& face : level.faces) buffers.push_back(face.pixels.data());
  }
  SkyParams moved_sun;
  moved_sun.sun_azimuth_degrees += 90.0;
  const CubeMap next = MakeSky(kSize, moved_sun);
  ASSERT_TRUE(RefillEnvironmentMips(next, *chain));
  ExpectSameMips(*chain, *BuildEnvironmentMips(next));
  std::size_t i = 0;
  for (const CubeMap& level : chain->levels) {
    for (const Image& face : level.faces) EXPECT_EQ(face.pixels.data(), buffers[i++]) << "reallocated";
  }
}

TEST(ShProjection, MipsBuiltFromAMovedMapEqualThoseFromACopy) {
  const CubeMap env = AsymmetricEnvironment(16);
  CubeMap moved = env;
  const std::optional<CubeMipChain> from_moved = BuildEnvironmentMips(std::move(moved));
  ASSERT_TRUE(from_moved.has_value());
  ExpectSameMips(*from_moved, *BuildEnvironmentMips(env));
  EXPECT_EQ(moved.face_size, 16);
  EXPECT_FALSE(BuildEnvironmentMips(CubeMap(12)).has_value());
}

TEST(ShProjection, RefillReshapesAChainOfAnotherSizeAndRejectsBadSizes) {
  CubeMipChain chain;
  ASSERT_TRUE(RefillEnvironmentMips(MakeStudio(8), chain));
  ASSERT_TRUE(RefillEnvironmentMips(AsymmetricEnvironment(32), chain));
  ExpectSameMips(chain, *BuildEnvironmentMips(AsymmetricEnvironment(32)));
  EXPECT_FALSE(RefillEnvironmentMips(CubeMap(6), chain));
  EXPECT_EQ(chain.levels.size(), 6u);  // unchanged
}

TEST(ShProjection, BasisPyramidLevelsAreSumsOfTheirChildren) {
  constexpr int kSize = 16;
  const std::optional<BasisPyramid> pyramid = BuildBasisPyramid(kSize);
  ASSERT_TRUE(pyramid.has_value());
  ASSERT_EQ(pyramid->levels.size(), 5u);
  // Level 0 is not stored: ProjectFinest evaluates it from texel coordinates.
  EXPECT_TRUE(pyramid->levels[0].weights[0].empty());
  // A finest texel's nine products, in kernels::kBlockMomentSlots order, written out.
  auto finest = [&](int j, int y, int x) {
    const double q = TexelSolidAngle(x, y, kSize);
    const double s = 2.0 * (x + 0.5) / kSize - 1.0, t = 2.0 * (y + 0.5) / kSize - 1.0;
    const double r = 1.0 / std::sqrt(1.0 + s * s + t * t);
    const double products[kernels::kBlockMoments] = {q,         q * r,         q * r * s,         q * r * t, q * r * r,
                                                     q * r * r * s, q * r * r * t, q * r * r * s * t, q * r * r * t * t};
    return products[j];
  };
  for (int k = 1; k < 5; ++k) {
    const BasisLevel& level = pyramid->levels[k];
    ASSERT_EQ(level.size, kSize >> k);
    const int block = 1 << k;
    for (int j = 0; j < kernels::kBlockMoments; ++j) {
      for (int y = 0; y < level.size; ++y) {
        for (int x = 0; x < level.size; ++x) {
          double sum = 0.0;
          double magnitude = 0.0;
          for (int cy = 0; cy < block; ++cy) {
            for (int cx = 0; cx < block; ++cx) {
              const double w = finest(j, y * block + cy, x * block + cx);
              sum += w;
              magnitude += std::abs(w);
            }
          }
          EXPECT_NEAR(level.Row(j, y)[x], sum, kFloatStorageRelative * magnitude) << "level " << k << " moment " << j;
        }
      }
    }
  }
  // What level 0 keeps: the texel's solid angle q and q r, q r^2 (r = 1 / |(s, t, 1)|).
  const double q = TexelSolidAngle(3, 11, kSize);
  const double s = 2.0 * 3.5 / kSize - 1.0, t = 2.0 * 11.5 / kSize - 1.0;
  const std::size_t i = 11 * kSize + 3;
  EXPECT_EQ(pyramid->finest.q[i], static_cast<float>(q));
  const double r2 = 1.0 / (1.0 + s * s + t * t);
  EXPECT_EQ(pyramid->finest.qr[i], static_cast<float>(q * std::sqrt(r2)));
  EXPECT_EQ(pyramid->finest.qr2[i], static_cast<float>(q * r2));
  // The same as BuildFinestWeights, which ProjectFinest's callers without a pyramid use.
  const FinestWeights alone = BuildFinestWeights(kSize);
  EXPECT_EQ(pyramid->finest.q, alone.q);
  EXPECT_EQ(pyramid->finest.qr, alone.qr);
  EXPECT_EQ(pyramid->finest.qr2, alone.qr2);
}

TEST(ShProjection, BasisPyramidIsTheSameForAnyThreadCount) {
  // 256 is cut into 64 tiles, so that several threads take part.
  constexpr int kSize = 256;
  const std::optional<BasisPyramid> one = BuildBasisPyramid(kSize, 1);
  ASSERT_TRUE(one.has_value());
  for (int threads : {2, 4, 9}) {
    const std::optional<BasisPyramid> many = BuildBasisPyramid(kSize, threads);
    ASSERT_TRUE(many.has_value());
    ASSERT_EQ(many->levels.size(), one->levels.size());
    for (std::size_t k = 0; k < one->levels.size(); ++k) {
      EXPECT_EQ(many->levels[k].weights, one->levels[k].weights) << threads << " threads, level " << k;
    }
    EXPECT_EQ(many->finest.q, one->finest.q);
    EXPECT_EQ(many->finest.qr2, one->finest.qr2);
  }
}

TEST(ShProjection, TexelSolidAnglesFromCornerTablesAreTheClosedFormBitForBit) {
  // BuildFinestWeights and ProjectDirect take each corner's area once (TexelCornerArea); the
  // weights they keep must be TexelSolidAngle's, rounded the same way.
  constexpr int kSize = 24;
  const FinestWeights weights = BuildFinestWeights(kSize);
  for (int y = 0; y < kSize; ++y) {
    for (int x = 0; x < kSize; ++x) {
      ASSERT_EQ(weights.q[static_cast<std::size_t>(y) * kSize + x], static_cast<float>(TexelSolidAngle(x, y, kSize)));
    }
  }
}

TEST(ShProjection, WhiteFurnaceGivesOnlyL00AtEveryLevel) {
  constexpr int kSize = 64;
  const CubeMap env = MakeConstant(kSize, glm::vec3(1.0f));
  const double l00 = 2.0 * std::sqrt(std::numbers::pi);  // integral of 1 / sqrt(4 pi) over 4 pi

  const Sh9Rgb direct = ProjectDirect(env);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(direct.at(0, 0)[c], l00, kDoubleSumRelative * l00);
  for (int i = 1; i < kSh9Coefficients; ++i) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(direct.coefficients[i][c], 0.0, kDoubleSumRelative * l00);
  }

  const std::optional<CubeMipChain> chain = BuildEnvironmentMips(env);
  const std::optional<BasisPyramid> basis = BuildBasisPyramid(kSize);
  ASSERT_TRUE(chain && basis);
  for (int level = 0; level < LevelCount(kSize); ++level) {
    const Sh9Rgb sh = ProjectLevel(*chain, *basis, level);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(sh.at(0, 0)[c], l00, kFloatStorageRelative * l00) << "level " << level;
    }
    for (int i = 1; i < kSh9Coefficients; ++i) {
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(sh.coefficients[i][c], 0.0, kFloatStorageRelative * l00) << "level " << level;
      }
    }
  }
}

TEST(ShProjection, SingleBrightTexelGivesItsBasisTimesSolidAngle) {
  constexpr int kSize = 32;
  const glm::vec3 radiance(5.0f, 3.0f, 0.5f);
  CubeMap env(kSize);
  env.face(CubeFace::kNegativeZ).at(7, 20) = radiance;
  const auto basis = ShBasis(TexelDirection(CubeFace::kNegativeZ, 7, 20, kSize));
  const double solid_angle = TexelSolidAngle(7, 20, kSize);
  Sh9Rgb expected;
  for (int i = 0; i < kSh9Coefficients; ++i) {
    expected.coefficients[i] = basis[i] * solid_angle * glm::dvec3(radiance);
  }
  const double scale = LargestMagnitude(expected);
  ExpectShNear(ProjectDirect(env), expected, kDoubleSumRelative * scale);

  const std::optional<CubeMipChain> chain = BuildEnvironmentMips(env);
  const std::optional<BasisPyramid> pyramid = BuildBasisPyramid(kSize);
  ASSERT_TRUE(chain && pyramid);
  ExpectShNear(ProjectLevel(*chain, *pyramid, 0), expected, kFloatStorageRelative * scale);
  // At level k the texel's light becomes a mean over its 2^k x 2^k block, weighted by the block's
  // summed basis; for the constant y00 that is radiance y00 x (block solid angle) / 4^k.
  for (int level = 1; level < LevelCount(kSize); ++level) {
    const int block = 1 << level;
    double block_solid_angle = 0.0;
    for (int y = (20 / block) * block; y < (20 / block + 1) * block; ++y) {
      for (int x = (7 / block) * block; x < (7 / block + 1) * block; ++x) {
        block_solid_angle += TexelSolidAngle(x, y, kSize);
      }
    }
    const glm::dvec3 l00 = kShN0 * block_solid_angle / (block * block) * glm::dvec3(radiance);
    const Sh9Rgb sh = ProjectLevel(*chain, *pyramid, level);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(sh.at(0, 0)[c], l00[c], kFloatStorageRelative * l00[c]) << "level " << level;
    }
  }
}

TEST(ShProjection, ProjectLevelZeroMatchesProjectDirect) {
  constexpr int kSize = 64;
  const CubeMap env = MakeSky(kSize);
  const Sh9Rgb direct = ProjectDirect(env);
  const std::optional<CubeMipChain> chain = BuildEnvironmentMips(env);
  const std::optional<BasisPyramid> basis = BuildBasisPyramid(kSize);
  ASSERT_TRUE(chain && basis);
  ExpectShNear(ProjectLevel(*chain, *basis, 0), direct, kFloatStorageRelative * LargestMagnitude(direct));
}

TEST(ShProjection, CoarseLevelsStayCloseOnASmoothSky) {
  // The paper's claim (Fig. 3): a 64 x 64 level of a 256 environment already looks right. With a
  // 2-degree sun, level 2 (64 x 64) keeps every coefficient within 1% of the largest one.
  constexpr int kSize = 256;
  constexpr double kCoarseLevelRelative = 0.01;
  const CubeMap env = MakeSky(kSize);
  const Sh9Rgb direct = ProjectDirect(env);
  const std::optional<CubeMipChain> chain = BuildEnvironmentMips(env);
  const std::optional<BasisPyramid> basis = BuildBasisPyramid(kSize);
  ASSERT_TRUE(chain && basis);
  ExpectShNear(ProjectLevel(*chain, *basis, 2), direct, kCoarseLevelRelative * LargestMagnitude(direct));
}

TEST(ShProjection, MirrorXNegatesTheOddInXCoefficients) {
  constexpr int kSize = 16;
  const CubeMap env = AsymmetricEnvironment(kSize);
  const glm::dmat3 mirror(glm::dvec3(-1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1));
  const Sh9Rgb before = ProjectDirect(env);
  const Sh9Rgb after = ProjectDirect(ApplyCubeSymmetry(env, mirror));
  // y_lm(M d) with x -> -x: x, xy, xz change sign; 1, y, z, yz, 3z^2 - 1, x^2 - y^2 do not.
  Sh9Rgb expected = before;
  expected.at(1, 1) = -before.at(1, 1);
  expected.at(2, -2) = -before.at(2, -2);
  expected.at(2, 1) = -before.at(2, 1);
  ExpectShNear(after, expected, kDoubleSumRelative * LargestMagnitude(before));
}

TEST(ShProjection, QuarterTurnAboutYMixesCoefficientsAsTheBasisSays) {
  constexpr int kSize = 16;
  const CubeMap env = AsymmetricEnvironment(kSize);
  // R (x, y, z) = (z, y, -x): +x -> -z, -z -> -x, -x -> +z, +z -> +x (columns are images of axes).
  const glm::dmat3 rotation(glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0), glm::dvec3(1, 0, 0));
  ASSERT_EQ(rotation * glm::dvec3(1, 0, 0), glm::dvec3(0, 0, -1));
  const Sh9Rgb l = ProjectDirect(env);
  const Sh9Rgb rotated = ProjectDirect(ApplyCubeSymmetry(env, rotation));
  // L'_lm = integral of L(d) y_lm(R d): substitute (x, y, z) -> (z, y, -x) into each basis function.
  //   y -> y;  z -> -x;  x -> z;  xy -> yz;  yz -> -xy;  xz -> -xz;
  //   3z^2 - 1 -> 3x^2 - 1 = -(3z^2 - 1)/2 + (3/2)(x^2 - y^2)  (on the sphere)
  //   x^2 - y^2 -> z^2 - y^2 = (3z^2 - 1)/2 + (x^2 - y^2)/2
  // With y20 = n3 (3z^2 - 1), y22 = n4 (x^2 - y^2) and n3 / n4 = 1 / sqrt 3:
  //   y20(R d) = -y20 / 2 + (sqrt 3 / 2) y22,  y22(R d) = (sqrt 3 / 2) y20 + y22 / 2.
  const double half_sqrt3 = 0.5 * std::numbers::sqrt3;
  Sh9Rgb expected;
  expected.at(0, 0) = l.at(0, 0);
  expected.at(1, -1) = l.at(1, -1);
  expected.at(1, 0) = -l.at(1, 1);
  expected.at(1, 1) = l.at(1, 0);
  expected.at(2, -2) = l.at(2, -1);
  expected.at(2, -1) = -l.at(2, -2);
  expected.at(2, 1) = -l.at(2, 1);
  expected.at(2, 0) = -0.5 * l.at(2, 0) + half_sqrt3 * l.at(2, 2);
  expected.at(2, 2) = half_sqrt3 * l.at(2, 0) + 0.5 * l.at(2, 2);
  ExpectShNear(rotated, expected, kDoubleSumRelative * LargestMagnitude(l));

  for (int band = 0; band < kSh9Bands; ++band) {
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(BandNorm(rotated, band, c), BandNorm(l, band, c), kDoubleSumRelative * LargestMagnitude(l));
    }
  }
}

TEST(ShProjection, BandNormsSurviveEveryFaceSwap) {
  // The three quarter turns that carry +z to each other face axis, and a mirror.
  constexpr int kSize = 8;
  const CubeMap env = AsymmetricEnvironment(kSize);
  const Sh9Rgb l = ProjectDirect(env);
  const glm::dmat3 maps[] = {
      glm::dmat3(glm::dvec3(1, 0, 0), glm::dvec3(0, 0, 1), glm::dvec3(0, -1, 0)),   // about x
      glm::dmat3(glm::dvec3(0, 1, 0), glm::dvec3(-1, 0, 0), glm::dvec3(0, 0, 1)),   // about z
      glm::dmat3(glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1), glm::dvec3(1, 0, 0)),    // about (1,1,1)
      glm::dmat3(glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, -1)),   // mirror z
  };
  for (const glm::dmat3& map : maps) {
    const Sh9Rgb moved = ProjectDirect(ApplyCubeSymmetry(env, map));
    for (int band = 0; band < kSh9Bands; ++band) {
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(BandNorm(moved, band, c), BandNorm(l, band, c), kDoubleSumRelative * LargestMagnitude(l));
      }
    }
  }
}

TEST(ShProjection, DirectProjectionKeepsPrecisionOnLargeFaces) {
  // 6 x 2048^2 texels: per-row double sums keep the white furnace exact to about 1e-12.
  constexpr int kSize = 2048;
  constexpr double kLargeSumRelative = 1e-12;
  const Sh9Rgb sh = ProjectDirect(MakeConstant(kSize, glm::vec3(1.0f)));
  const double l00 = 2.0 * std::sqrt(std::numbers::pi);
  EXPECT_NEAR(sh.at(0, 0).x, l00, kLargeSumRelative * l00);
  EXPECT_NEAR(sh.at(2, 0).y, 0.0, kLargeSumRelative * l00);
}

}  // namespace
}  // namespace vs11::irradiance

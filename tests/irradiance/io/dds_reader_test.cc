// DDS environment maps: the float formats read by dds_reader.cc, BC6H (decoded by OpenImageIO)
// from blocks encoded here, and hostile DDS headers and files. Inputs are built byte by byte from
// the DirectDraw Surface and BC6H format references, independently of the code under test.
#include "irradiance/io/dds_reader.h"

#include <cstdint>
#include <cstring>
#include <utility>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "irradiance/io/environment_io.h"
#include "tests/irradiance/io/dds_test_files.h"
#include "tests/irradiance/io/environment_test_support.h"

namespace vs11::irradiance {
namespace {

using namespace envtest;
using testing::HasSubstr;
using DdsReader = TempFolderTest;

constexpr float kSrgbDecodeError = 1e-6f;  // sRGB decode in double, rounded to float
constexpr std::uint32_t kDdsCaps2Volume = 0x200000;
std::uint16_t FloatToHalf(float value) {
  std::uint16_t half;
  OIIO::convert_pixel_values(OIIO::TypeDesc::FLOAT, &value, OIIO::TypeDesc::HALF, &half, 1);
  return half;
}

float HalfToFloat(std::uint16_t half) {
  float value;
  OIIO::convert_pixel_values(OIIO::TypeDesc::HALF, &half, OIIO::TypeDesc::FLOAT, &value, 1);
  return value;
}

// ---- Uncompressed float formats --------------------------------------------------------------

struct FloatFormatCase {
  const char* name;
  DdsFields fields;
  void (*append_texel)(std::string& bytes, glm::vec3 rgb);
};

void AppendRgba32(std::string& bytes, glm::vec3 p) {
  for (float v : {p.r, p.g, p.b, 1.0f}) Append(bytes, v);
}
void AppendRgb32(std::string& bytes, glm::vec3 p) {
  for (float v : {p.r, p.g, p.b}) Append(bytes, v);
}
void AppendRgba16(std::string& bytes, glm::vec3 p) {
  for (float v : {p.r, p.g, p.b, 1.0f}) Append(bytes, FloatToHalf(v));
}
// R11G11B10: half's exponent and top 6 (red, green) or 5 (blue) mantissa bits, no sign; the test
// values use no more mantissa bits, so they are exact.
void AppendR11G11B10(std::string& bytes, glm::vec3 p) {
  const std::uint32_t r = FloatToHalf(p.r);
  const std::uint32_t g = FloatToHalf(p.g);
  const std::uint32_t b = FloatToHalf(p.b);
  EXPECT_EQ(r & 0x800f, 0u);
  EXPECT_EQ(g & 0x800f, 0u);
  EXPECT_EQ(b & 0x801f, 0u);
  Append(bytes, (r >> 4) | (g >> 4) << 11 | (b >> 5) << 22);
}
// R9G9B9E5: value = mantissa * 2^(exponent - 24). With the exponent 18, mantissas are multiples of
// 1/64 up to 511/64, enough for the test cube (multiples of 1/32 up to 6.25).
void AppendRgb9e5(std::string& bytes, glm::vec3 p) {
  constexpr std::uint32_t kExponent = 18;
  std::uint32_t word = kExponent << 27;
  for (int c = 0; c < 3; ++c) {
    const float mantissa = p[c] * 64.0f;
    EXPECT_EQ(mantissa, std::floor(mantissa));
    EXPECT_LE(mantissa, 511.0f);
    word |= static_cast<std::uint32_t>(mantissa) << (9 * c);
  }
  Append(bytes, word);
}

class DdsFloatFormat : public TempFolderTest,
                       public testing::WithParamInterface<FloatFormatCase> {};

TEST_P(DdsFloatFormat, CubeMapLoadsExactlyInD3dFaceOrder) {
  const int n = 2;
  const CubeMap cube = MakeTestCube(n);
  std::string bytes = DdsBytes(GetParam().fields);
  for (CubeFace face : kAllCubeFaces) {
    for (const glm::vec3& p : cube.face(face).pixels) GetParam().append_texel(bytes, p);
  }
  WriteBytes(Path("cube.dds"), bytes);
  const LoadedEnvironment& loaded = Load(Path("cube.dds"));
  EXPECT_EQ(loaded.layout, EnvironmentLayout::kVerticalStrip);
  EXPECT_TRUE(loaded.warnings.empty());
  ExpectCubesEqual(loaded.cube, cube);
}

TEST_P(DdsFloatFormat, CutShortAnywhereIsReportedAsTruncated) {
  std::string bytes = DdsBytes(GetParam().fields);
  const std::size_t header = bytes.size();
  const CubeMap cube = MakeTestCube(2);
  for (const glm::vec3& p : cube.face(CubeFace::kPositiveX).pixels) {
    for (int face = 0; face < 6; ++face) GetParam().append_texel(bytes, p);
  }
  for (std::size_t length : {std::size_t{10}, std::size_t{100}, header - 1, header + 1,
                             bytes.size() / 2, bytes.size() - 1}) {
    WriteBytes(Path("short.dds"), bytes.substr(0, length));
    const std::string error = LoadError(Path("short.dds"));
    EXPECT_THAT(error, HasSubstr("short.dds")) << length;
    EXPECT_THAT(error, HasSubstr("truncated")) << length;
  }
}

INSTANTIATE_TEST_SUITE_P(
    DdsFormats, DdsFloatFormat,
    testing::Values(
        FloatFormatCase{"Dx10Rgba32Float", Dx10Cube(2, kDxgiRgba32Float), AppendRgba32},
        FloatFormatCase{"Dx10Rgb32Float", Dx10Cube(2, kDxgiRgb32Float), AppendRgb32},
        FloatFormatCase{"Dx10Rgba16Float", Dx10Cube(2, kDxgiRgba16Float), AppendRgba16},
        FloatFormatCase{"Dx10R11G11B10Float", Dx10Cube(2, kDxgiR11G11B10Float), AppendR11G11B10},
        FloatFormatCase{"Dx10Rgb9e5", Dx10Cube(2, kDxgiRgb9e5), AppendRgb9e5},
        FloatFormatCase{"LegacyA32B32G32R32F", LegacyCube(2, kD3dFmtA32B32G32R32F), AppendRgba32},
        FloatFormatCase{"LegacyA16B16G16R16F", LegacyCube(2, kD3dFmtA16B16G16R16F), AppendRgba16}),
    [](const testing::TestParamInfo<FloatFormatCase>& info) { return info.param.name; });

TEST_F(DdsReader, DdsFloatLatLongIsAPlainImageNotACube) {
  DdsFields fields;
  fields.width = 8;
  fields.height = 4;
  fields.four_cc = kFourCcDx10;
  fields.dxgi_format = kDxgiRgba32Float;
  std::string bytes = DdsBytes(fields);
  Image image(8, 4);
  for (int i = 0; i < 32; ++i) image.pixels[i] = glm::vec3(0.5f * i, 1.0f, 2.0f);
  for (const glm::vec3& p : image.pixels) AppendRgba32(bytes, p);
  WriteBytes(Path("sky.dds"), bytes);
  const Result<ImageRead> read = ReadImage(Path("sky.dds"));
  ASSERT_TRUE(read.ok()) << read.message();
  EXPECT_FALSE(read->is_dds_cube_map);
  EXPECT_EQ(read->image.pixels, image.pixels);
  EXPECT_EQ(Load(Path("sky.dds")).layout, EnvironmentLayout::kLatLong);
}

TEST_F(DdsReader, DdsMipChainsArePassedOverToEachFaceLevelZero) {
  // Each face stores its whole chain (2 x 2, then 1 x 1): level 0 of face k starts 5 texels on.
  DdsFields fields = Dx10Cube(2, kDxgiRgba32Float);
  fields.mip_count = 2;
  std::string bytes = DdsBytes(fields);
  const CubeMap cube = MakeTestCube(2);
  for (CubeFace face : kAllCubeFaces) {
    for (const glm::vec3& p : cube.face(face).pixels) AppendRgba32(bytes, p);
    AppendRgba32(bytes, glm::vec3(-100.0f));  // the 1 x 1 level, never read
  }
  WriteBytes(Path("mips.dds"), bytes);
  ExpectCubesEqual(Load(Path("mips.dds")).cube, cube);
}

// ---- BC6H --------------------------------------------------------------------------------------
// Mode 11 (PackBc6hMode11 in dds_test_files.h). The unquantisation and interpolation steps are
// those of the BC6H format reference.

constexpr std::array<int, 16> kBc6hWeights = {0,  4,  9,  13, 17, 21, 26, 30,
                                              34, 38, 43, 47, 51, 55, 60, 64};

int Bc6hUnquantize(int q, bool is_signed) {
  if (!is_signed) {
    if (q == 0) return 0;
    if (q == 1023) return 0xffff;
    return ((q << 16) + 0x8000) >> 10;
  }
  const int magnitude = std::abs(q);
  const int u = magnitude == 0 ? 0 : magnitude >= 511 ? 0x7fff : ((magnitude << 15) + 0x4000) >> 9;
  return q < 0 ? -u : u;
}

float Bc6hDecode(int q0, int q1, int index, bool is_signed) {
  const int w = kBc6hWeights[index];
  const int mixed =
      ((64 - w) * Bc6hUnquantize(q0, is_signed) + w * Bc6hUnquantize(q1, is_signed) + 32) >> 6;
  if (!is_signed) return HalfToFloat(static_cast<std::uint16_t>((mixed * 31) >> 6));
  const int scaled = mixed < 0 ? -(((-mixed) * 31) >> 5) : (mixed * 31) >> 5;
  return HalfToFloat(static_cast<std::uint16_t>(scaled < 0 ? 0x8000 | -scaled : scaled));
}

// Encodes a 4 x 4 block (row-major) and sets `decoded` to what a decoder must return for it.
std::array<std::uint8_t, 16> EncodeBc6hMode11(const std::array<glm::vec3, 16>& texels,
                                              bool is_signed, std::array<glm::vec3, 16>& decoded) {
  const int q_min = is_signed ? -511 : 0;
  const int q_max = is_signed ? 511 : 1023;
  const auto quantize = [&](float value) {
    int best = q_min;
    for (int q = q_min; q <= q_max; ++q) {
      if (std::abs(Bc6hDecode(q, q, 0, is_signed) - value) <
          std::abs(Bc6hDecode(best, best, 0, is_signed) - value)) {
        best = q;
      }
    }
    return best;
  };
  std::array<int, 3> e0;
  std::array<int, 3> e1;
  for (int c = 0; c < 3; ++c) {
    float low = texels[0][c];
    float high = texels[0][c];
    for (const glm::vec3& t : texels) {
      low = std::min(low, t[c]);
      high = std::max(high, t[c]);
    }
    e0[c] = quantize(low);
    e1[c] = quantize(high);
  }
  std::array<int, 16> indices;
  for (int i = 0; i < 16; ++i) {
    float best_error = std::numeric_limits<float>::infinity();
    for (int index = 0; index < 16; ++index) {
      glm::vec3 value;
      for (int c = 0; c < 3; ++c) value[c] = Bc6hDecode(e0[c], e1[c], index, is_signed);
      const glm::vec3 difference = glm::abs(value - texels[i]);
      const float error = difference.r + difference.g + difference.b;
      if (error < best_error) {
        best_error = error;
        indices[i] = index;
        decoded[i] = value;
      }
    }
  }
  if (indices[0] >= 8) {  // the anchor index must fit 3 bits: swap the endpoints (weights mirror)
    std::swap(e0, e1);
    for (int& index : indices) index = 15 - index;
  }
  return PackBc6hMode11(e0, e1, indices);
}

// A BC6H cube map of `source` and the cube a decoder must return for it. With `mip_tail`, each
// face is followed by the levels below it down to 1 x 1 (blocks of noise, never to be read).
std::string Bc6hCubeFile(const CubeMap& source, bool is_signed, CubeMap& expected,
                         bool mip_tail = false) {
  const int n = source.face_size;
  DdsFields fields = Dx10Cube(n, is_signed ? kDxgiBc6hSf16 : kDxgiBc6hUf16);
  int tail_blocks = 0;
  if (mip_tail) {
    for (int size = n / 2; size >= 1; size /= 2) {
      ++fields.mip_count;
      tail_blocks += ((size + 3) / 4) * ((size + 3) / 4);
    }
  }
  std::string bytes = DdsBytes(fields);
  std::mt19937 noise(7);
  expected = CubeMap(n);
  for (CubeFace face : kAllCubeFaces) {
    for (int by = 0; by < n; by += 4) {
      for (int bx = 0; bx < n; bx += 4) {
        std::array<glm::vec3, 16> texels;
        for (int i = 0; i < 16; ++i) texels[i] = source.face(face).at(bx + i % 4, by + i / 4);
        std::array<glm::vec3, 16> decoded;
        const std::array<std::uint8_t, 16> block = EncodeBc6hMode11(texels, is_signed, decoded);
        bytes.append(reinterpret_cast<const char*>(block.data()), block.size());
        for (int i = 0; i < 16; ++i) expected.face(face).at(bx + i % 4, by + i / 4) = decoded[i];
      }
    }
    for (int i = 0; i < 16 * tail_blocks; ++i) bytes.push_back(static_cast<char>(noise()));
  }
  return bytes;
}

// Smooth HDR radiance (0.2 .. 4.2), colour x intensity, so that the channels of a block move
// together as in real skies (BC6H draws each block's colours from one line).
CubeMap HdrTestCube(int n) {
  CubeMap cube(n);
  const glm::dvec3 sun = glm::normalize(glm::dvec3(0.3, 0.8, 0.5));
  for (CubeFace face : kAllCubeFaces) {
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        const double facing = glm::dot(TexelDirection(face, x, y, n), sun);
        const double intensity = 0.2 + 4.0 * std::pow(0.5 * (1.0 + facing), 3.0);
        cube.face(face).at(x, y) = glm::vec3(glm::dvec3(1.0, 0.85, 0.6) * intensity);
      }
    }
  }
  return cube;
}

// How far this test's encoder lands from the source: it uses mode 11 only, whose 16 palette
// entries step a fifteenth of a block's range in half-float bits (not in value), with endpoints the
// channels' extremes rather than a fitted line. Measured on this cube: worst 8.1% of the texel's
// largest channel. Enough to catch swapped channels (0.85 and 0.6 of red) or faces.
constexpr float kBc6hMode11RelativeError = 0.1f;

TEST_F(DdsReader, Bc6hUnsignedCubeDecodesAsTheFormatSaysAndCloseToTheSource) {
  const CubeMap source = HdrTestCube(8);
  CubeMap expected;
  WriteBytes(Path("sky_bc6h.dds"), Bc6hCubeFile(source, false, expected));
  const LoadedEnvironment& loaded = Load(Path("sky_bc6h.dds"));
  EXPECT_EQ(loaded.layout, EnvironmentLayout::kVerticalStrip);
  ExpectCubesEqual(loaded.cube, expected);
  ExpectCubesNear(loaded.cube, source, kBc6hMode11RelativeError, /*relative=*/true);
}

TEST_F(DdsReader, Bc6hCubeWithMipChainsReadsLevelZeroOfEachFace) {
  CubeMap expected;
  WriteBytes(Path("mips.dds"), Bc6hCubeFile(HdrTestCube(8), false, expected, /*mip_tail=*/true));
  ExpectCubesEqual(Load(Path("mips.dds")).cube, expected);
}

TEST_F(DdsReader, Bc6hSignedCubeKeepsValuesAndZeroesNegativeTexelsWithAWarning) {
  CubeMap source = HdrTestCube(8);
  for (glm::vec3& texel : source.face(CubeFace::kNegativeY).pixels) texel = -texel;
  CubeMap expected;
  WriteBytes(Path("signed.dds"), Bc6hCubeFile(source, true, expected));
  const LoadedEnvironment& loaded = Load(Path("signed.dds"));
  const std::size_t negative = SanitizeRadiance(expected.face(CubeFace::kNegativeY));
  EXPECT_EQ(negative, 64u);
  ExpectCubesEqual(loaded.cube, expected);
  for (CubeFace face : kAllCubeFaces) {
    if (face == CubeFace::kNegativeY) continue;
    for (std::size_t i = 0; i < source.face(face).pixels.size(); ++i) {
      const glm::vec3 s = source.face(face).pixels[i];
      const glm::vec3 d = glm::abs(loaded.cube.face(face).pixels[i] - s);
      EXPECT_LE(std::max({d.r, d.g, d.b}), kBc6hMode11RelativeError * std::max({s.r, s.g, s.b}));
    }
  }
  ASSERT_EQ(loaded.warnings.size(), 1u);
  EXPECT_THAT(loaded.warnings[0], HasSubstr("signed.dds"));
  EXPECT_THAT(loaded.warnings[0], HasSubstr("64 of 384 texels"));
}

TEST_F(DdsReader, Bc6hCutShortIsReportedAsTruncated) {
  CubeMap expected;
  const std::string bytes = Bc6hCubeFile(HdrTestCube(8), false, expected);
  for (std::size_t length : {std::size_t{140}, std::size_t{149}, bytes.size() / 3,
                             bytes.size() - 16, bytes.size() - 1}) {
    WriteBytes(Path("short.dds"), bytes.substr(0, length));
    EXPECT_THAT(LoadError(Path("short.dds")), HasSubstr("truncated")) << length;
  }
}

// ---- Hostile headers ---------------------------------------------------------------------------

TEST_F(DdsReader, DdsHeaderClaimingAHugeImageIsRefusedBeforeAllocating) {
  for (const DdsFields& base : {Dx10Cube(1, kDxgiRgba32Float), LegacyCube(1, kFourCcDxt1),
                                Dx10Cube(1, kDxgiBc6hUf16)}) {
    for (std::uint32_t size : {std::uint32_t{1} << 30, std::uint32_t{65536}, ~std::uint32_t{0}}) {
      DdsFields fields = base;
      fields.width = fields.height = size;
      WriteBytes(Path("huge.dds"), DdsBytes(fields) + std::string(4096, '\0'));
      const std::string error = LoadError(Path("huge.dds"));
      EXPECT_THAT(error, HasSubstr("huge.dds"));
      EXPECT_THAT(error, HasSubstr("larger than")) << size;
    }
  }
}

TEST_F(DdsReader, DdsHeaderContradictionsAreReported) {
  const auto error_of = [&](const DdsFields& fields) {
    WriteBytes(Path("bad.dds"), DdsBytes(fields) + std::string(4096, '\0'));
    return LoadError(Path("bad.dds"));
  };
  DdsFields fields = Dx10Cube(4, kDxgiRgba16Float);
  fields.header_size = 0;
  EXPECT_THAT(error_of(fields), HasSubstr("corrupt DDS header"));
  fields = Dx10Cube(4, kDxgiRgba16Float);
  fields.mip_count = 40;
  EXPECT_THAT(error_of(fields), HasSubstr("40 mip levels"));
  fields = Dx10Cube(4, kDxgiRgba16Float);
  fields.height = 2;
  EXPECT_THAT(error_of(fields), HasSubstr("must be square"));
  fields = Dx10Cube(4, kDxgiRgba16Float);
  fields.dx10_array_size = 2;
  EXPECT_THAT(error_of(fields), HasSubstr("texture arrays"));
  fields = Dx10Cube(4, kDxgiRgba16Float);
  fields.dx10_misc = 0;
  fields.dx10_dimension = kDx10Texture3D;
  EXPECT_THAT(error_of(fields), HasSubstr("volume"));
  fields = LegacyCube(4, kD3dFmtA32B32G32R32F);
  fields.caps2 = kDdsCaps2Cubemap | 0x400 | 0x800;
  EXPECT_THAT(error_of(fields), HasSubstr("2 of the six faces"));
  fields.caps2 = kDdsCaps2Cubemap;
  EXPECT_THAT(error_of(fields), HasSubstr("0 of the six faces"));
  fields = LegacyCube(4, kD3dFmtA32B32G32R32F);
  fields.caps2 = kDdsCaps2Volume;
  EXPECT_THAT(error_of(fields), HasSubstr("volume"));
  fields = Dx10Cube(4, kDxgiBc6hUf16);
  fields.caps2 = 0;  // OpenImageIO would read the first face as a square image
  EXPECT_THAT(error_of(fields), HasSubstr("DX10 cube map without the DDSCAPS2 cube map flags"));
  fields = Dx10Cube(4, kDxgiRgba16Float);
  fields.width = fields.height = 0;
  EXPECT_THAT(error_of(fields), HasSubstr("zero-size"));
}

// OpenImageIO 2.4 never returns from these (found by the damaged-bytes test in
// environment_hostile_test.cc): a bit count of 0, or a mask in use that is 0.
TEST_F(DdsReader, UncompressedFormatsThatHangOpenImageIoAreRefused) {
  constexpr std::uint32_t kDdpfLuminance = 0x20000;
  const std::array<std::uint32_t, 4> bgra = {0x00ff0000, 0x0000ff00, 0x000000ff, 0xff000000};
  const std::vector<std::pair<DdsPixelFormat, std::string>> cases = {
      {{kDdpfRgb, 0, 0, bgra}, "0 bits per pixel"},
      {{kDdpfRgb, 0, 12, bgra}, "12 bits per pixel"},
      {{kDdpfRgb | kDdpfAlphaPixels, 0, 32, {0, 0, 0, 0}}, "red channel's bit mask is 0"},
      {{kDdpfRgb, 0, 32, {0x00ff0000, 0, 0x000000ff, 0}}, "green channel's bit mask is 0"},
      {{kDdpfRgb | kDdpfAlphaPixels, 0, 32, {0x00ff0000, 0x0000ff00, 0x000000ff, 0}},
       "alpha channel's bit mask is 0"},
      {{kDdpfLuminance, 0, 8, {0, 0, 0, 0}}, "luminance channel's bit mask is 0"},
  };
  std::uint32_t caps2 = kDdsCaps2Cubemap;
  for (std::uint32_t bit : kDdsCaps2Face) caps2 |= bit;
  for (const auto& [format, problem] : cases) {
    WriteBytes(Path("odd.dds"), DdsHeader(4, caps2, format, 16) + std::string(6 * 64, '\x11'));
    const std::string error = LoadError(Path("odd.dds"));
    EXPECT_THAT(error, HasSubstr("odd.dds"));
    EXPECT_THAT(error, HasSubstr(problem));
  }
  // A luminance mask alone is enough.
  WriteBytes(Path("grey.dds"), DdsHeader(4, caps2, {kDdpfLuminance, 0, 8, {0xff, 0, 0, 0}}, 4) +
                                   std::string(6 * 16, '\x80'));
  const LoadedEnvironment& grey = Load(Path("grey.dds"));
  EXPECT_NEAR(grey.cube.face(CubeFace::kNegativeZ).at(3, 3).g, SrgbToLinear(128 / 255.0),
              kSrgbDecodeError);
}

// OpenImageIO 2.4.7 divides a premultiplied texel by its alpha: one texel of alpha 0 in a DXT2 or
// DXT4 file ended the process with SIGFPE.
TEST_F(DdsReader, PremultipliedAlphaDxt2AndDxt4AreRefusedNotDecoded) {
  const std::vector<std::pair<std::uint32_t, std::string>> formats = {{FourCcCode("DXT2"), "DXT2"},
                                                                       {FourCcCode("DXT4"), "DXT4"}};
  for (const auto& [code, name] : formats) {
    WriteBytes(Path("clear.dds"), DdsBytes(LegacyCube(4, code)) + std::string(6 * 16, '\0'));  // alpha 0
    const std::string error = LoadError(Path("clear.dds"));
    EXPECT_THAT(error, HasSubstr("clear.dds"));
    EXPECT_THAT(error, HasSubstr("premultiplied-alpha DDS (" + name + ")"));
  }
}

TEST_F(DdsReader, EightBitDdsCutShortIsReportedAsTruncated) {
  const std::string bytes =
      Dds8BitCube(4, {kAllCubeFaces.begin(), kAllCubeFaces.end()}, DdsTestBytes);
  for (std::size_t length : {std::size_t{64}, std::size_t{129}, bytes.size() / 2,
                             bytes.size() - 1}) {
    WriteBytes(Path("short.dds"), bytes.substr(0, length));
    EXPECT_THAT(LoadError(Path("short.dds")), HasSubstr("truncated")) << length;
  }
}

TEST_F(DdsReader, ReadDdsHeaderLeavesOtherFilesAlone) {
  ASSERT_TRUE(WriteFloatImage(Path("cross.exr"), Image(8, 6, glm::vec3(1.0f))));
  const Result<std::optional<DdsFileHeader>> not_dds = ReadDdsHeader(Path("cross.exr"), kMaxImagePixels);
  ASSERT_TRUE(not_dds.ok()) << not_dds.message();
  EXPECT_FALSE(not_dds->has_value());
  WriteBytes(Path("cube.dds"),
             Dds8BitCube(4, {kAllCubeFaces.begin(), kAllCubeFaces.end()}, DdsTestBytes));
  const Result<std::optional<DdsFileHeader>> header = ReadDdsHeader(Path("cube.dds"), kMaxImagePixels);
  ASSERT_TRUE(header.ok() && header->has_value()) << header.message();
  const Result<DdsPixels> pixels = ReadDdsPixels(Path("cube.dds"), **header);
  ASSERT_TRUE(pixels.ok()) << pixels.message();
  EXPECT_FALSE(pixels->image.has_value());  // left to OpenImageIO
  EXPECT_FALSE(pixels->stacked_faces.empty());
}

TEST_F(DdsReader, ReadDdsHeaderSaysWhatIsWrongWithoutTheFileName) {
  WriteBytes(Path("short.dds"), std::string("DDS ") + std::string(10, '\0'));
  const Result<std::optional<DdsFileHeader>> header = ReadDdsHeader(Path("short.dds"), kMaxImagePixels);
  ASSERT_FALSE(header.ok());
  EXPECT_EQ(header.error().code, DiagnosticCode::kCannotReadFile);
  EXPECT_EQ(header.message(), "truncated DDS file: 14 bytes, shorter than its 128-byte header");
}

// The container reader reports what a cube map holds; refusing a cube map of two faces or of
// oblong faces is environment_io's rule (DdsHeaderContradictionsAreReported sees its messages).
TEST_F(DdsReader, ReadDdsHeaderLeavesCubeMapRulesToTheCaller) {
  DdsFields fields = LegacyCube(4, kD3dFmtA32B32G32R32F);
  fields.caps2 = kDdsCaps2Cubemap | 0x400 | 0x800;
  WriteBytes(Path("two.dds"), DdsBytes(fields) + std::string(4096, '\0'));
  Result<std::optional<DdsFileHeader>> header = ReadDdsHeader(Path("two.dds"), kMaxImagePixels);
  ASSERT_TRUE(header.ok() && header->has_value()) << header.message();
  EXPECT_TRUE((*header)->is_cube_map);
  EXPECT_EQ((*header)->faces, 2u);
  const Result<DdsPixels> pixels = ReadDdsPixels(Path("two.dds"), **header);
  ASSERT_TRUE(pixels.ok() && pixels->image.has_value()) << pixels.message();
  EXPECT_EQ(pixels->image->height, 2 * 4);

  fields = Dx10Cube(4, kDxgiRgba16Float);
  fields.height = 2;
  WriteBytes(Path("oblong.dds"), DdsBytes(fields) + std::string(4096, '\0'));
  header = ReadDdsHeader(Path("oblong.dds"), kMaxImagePixels);
  ASSERT_TRUE(header.ok() && header->has_value()) << header.message();
  EXPECT_EQ((*header)->width, 4u);
  EXPECT_EQ((*header)->height, 2u);
  EXPECT_EQ((*header)->faces, 6u);
}

}  // namespace
}  // namespace vs11::irradiance

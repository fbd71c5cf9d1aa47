// texldl's point sampling (vm/core/texture_sampling.h) on hand-made textures: which texel a coordinate
// reads at texel edges (u * N an exact integer), below 0 and from 1 up under wrap, clamp and border,
// R32F's (r, 1, 1, 1), an unbound sampler's (0, 0, 0, 1), and through the ref engine, s#'s swizzle,
// the write mask and src0.w (the LOD), which one level makes irrelevant.
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "vm/asm/assembler.h"
#include "vm/core/texture_sampling.h"
#include "vm/engines/engine_factory.h"
#include "vm/engines/reference_engine.h"

namespace vs11 {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// A width x height A32B32G32R32F texture whose texel (x, y) holds (x, y, 10 y + x, 1).
std::shared_ptr<const VertexTexture> NumberedTexture(int width, int height) {
  std::vector<float> texels;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) texels.insert(texels.end(), {float(x), float(y), float(10 * y + x), 1.0f});
  }
  Result<VertexTexture> made = VertexTexture::Make(TextureFormat::kA32B32G32R32F, width, height, std::move(texels));
  EXPECT_TRUE(made.ok()) << made.message();
  return std::make_shared<const VertexTexture>(std::move(made).value());
}

ConstantBank BankWith(std::shared_ptr<const VertexTexture> texture, TextureAddress u = TextureAddress::kWrap,
                      TextureAddress v = TextureAddress::kWrap, int sampler = 0) {
  ConstantBank bank;
  bank.sampler(sampler) = {std::move(texture), {u, v}};
  return bank;
}

Vec4f Sample(const ConstantBank& bank, float u, float v, int sampler = 0) {
  return semantics::SampleTexture(BankTextures{bank}, sampler, Vec4f{u, v, 0.0f, 0.0f});
}

// The texel x a coordinate u reads on an axis of 4 texels.
float TexelX(TextureAddress mode, float u) { return Sample(BankWith(NumberedTexture(4, 1), mode, mode), u, 0.5f)[0]; }

TEST(TextureSampling, TexelEdgesBelongToTheTexelOnTheirRight) {
  for (TextureAddress mode : {TextureAddress::kWrap, TextureAddress::kClamp, TextureAddress::kBorder}) {
    EXPECT_EQ(TexelX(mode, 0.0f), 0.0f);
    EXPECT_EQ(TexelX(mode, 0.25f), 1.0f);  // u * 4 = 1 exactly
    EXPECT_EQ(TexelX(mode, std::nextafter(0.25f, 0.0f)), 0.0f);
    EXPECT_EQ(TexelX(mode, 0.5f), 2.0f);
    EXPECT_EQ(TexelX(mode, 0.75f), 3.0f);
    EXPECT_EQ(TexelX(mode, std::nextafter(1.0f, 0.0f)), 3.0f);
  }
}

TEST(TextureSampling, WrapRepeatsOutsideZeroToOne) {
  EXPECT_EQ(TexelX(TextureAddress::kWrap, 1.0f), 0.0f);
  EXPECT_EQ(TexelX(TextureAddress::kWrap, 1.5f), 2.0f);
  EXPECT_EQ(TexelX(TextureAddress::kWrap, 7.25f), 1.0f);
  EXPECT_EQ(TexelX(TextureAddress::kWrap, -0.25f), 3.0f);  // -0.25 - floor(-0.25) = 0.75
  EXPECT_EQ(TexelX(TextureAddress::kWrap, -0.5f), 2.0f);
  EXPECT_EQ(TexelX(TextureAddress::kWrap, -1.0f), 0.0f);
  EXPECT_EQ(TexelX(TextureAddress::kWrap, -1e-9f), 3.0f);  // 1 - 1e-9 rounds to 1: the last texel
  EXPECT_EQ(TexelX(TextureAddress::kWrap, kNaN), 0.0f);
  EXPECT_EQ(TexelX(TextureAddress::kWrap, kInf), 0.0f);  // inf - inf is NaN
}

TEST(TextureSampling, ClampReadsTheEdgeTexels) {
  EXPECT_EQ(TexelX(TextureAddress::kClamp, 1.0f), 3.0f);
  EXPECT_EQ(TexelX(TextureAddress::kClamp, 1e30f), 3.0f);
  EXPECT_EQ(TexelX(TextureAddress::kClamp, kInf), 3.0f);
  EXPECT_EQ(TexelX(TextureAddress::kClamp, -0.25f), 0.0f);
  EXPECT_EQ(TexelX(TextureAddress::kClamp, -kInf), 0.0f);
  EXPECT_EQ(TexelX(TextureAddress::kClamp, kNaN), 0.0f);
}

TEST(TextureSampling, BorderReadsZeroOutsideZeroToOne) {
  const ConstantBank bank = BankWith(NumberedTexture(4, 2), TextureAddress::kBorder, TextureAddress::kClamp);
  EXPECT_EQ(Sample(bank, 0.5f, 0.5f), (Vec4f{2, 1, 12, 1}));
  EXPECT_EQ(Sample(bank, 1.0f, 0.5f), (Vec4f{0, 0, 0, 0}));
  EXPECT_EQ(Sample(bank, -0.01f, 0.5f), (Vec4f{0, 0, 0, 0}));
  EXPECT_EQ(Sample(bank, kNaN, 0.5f), (Vec4f{0, 0, 0, 0}));
  EXPECT_EQ(Sample(bank, 0.5f, 7.0f), (Vec4f{2, 1, 12, 1}));  // v clamps
}

TEST(TextureSampling, BothAxesOfATextureWhoseSizesAreNoPowersOfTwo) {
  const ConstantBank bank = BankWith(NumberedTexture(3, 5));
  EXPECT_EQ(Sample(bank, 0.0f, 0.0f), (Vec4f{0, 0, 0, 1}));
  EXPECT_EQ(Sample(bank, 0.5f, 0.5f), (Vec4f{1, 2, 21, 1}));   // 1.5 -> 1, 2.5 -> 2
  EXPECT_EQ(Sample(bank, 0.99f, 0.99f), (Vec4f{2, 4, 42, 1}));
  EXPECT_EQ(Sample(bank, 0.4f, 0.6f), (Vec4f{1, 3, 31, 1}));   // 1.2 -> 1, 3.0 -> 3 exactly
  EXPECT_EQ(Sample(bank, -0.5f, 1.2f), (Vec4f{1, 1, 11, 1}));  // wrap: 0.5 -> 1.5, 0.2 -> 1.0
}

TEST(TextureSampling, R32FSamplesAsROneOneOne) {
  Result<VertexTexture> made = VertexTexture::Make(TextureFormat::kR32F, 2, 1, {-3.5f, 8.0f});
  ASSERT_TRUE(made.ok()) << made.message();
  const ConstantBank bank = BankWith(std::make_shared<const VertexTexture>(std::move(made).value()));
  EXPECT_EQ(Sample(bank, 0.25f, 0.0f), (Vec4f{-3.5f, 1, 1, 1}));
  EXPECT_EQ(Sample(bank, 0.75f, 0.0f), (Vec4f{8.0f, 1, 1, 1}));
}

TEST(TextureSampling, AnUnboundSamplerReadsZeroZeroZeroOne) {
  const ConstantBank bank = BankWith(NumberedTexture(2, 2), TextureAddress::kWrap, TextureAddress::kWrap, 1);
  EXPECT_EQ(Sample(bank, 0.5f, 0.5f, 0), (Vec4f{0, 0, 0, 1}));
  EXPECT_EQ(Sample(bank, 0.5f, 0.5f, 3), (Vec4f{0, 0, 0, 1}));
  EXPECT_EQ(Sample(bank, 0.5f, 0.5f, 1), (Vec4f{1, 1, 11, 1}));
}

TEST(TextureSampling, MakeRefusesEmptyAndMismatchedTextures) {
  EXPECT_FALSE(VertexTexture::Make(TextureFormat::kR32F, 0, 1, {}).ok());
  EXPECT_FALSE(VertexTexture::Make(TextureFormat::kR32F, 2, 2, {1, 2, 3}).ok());
  const Result<VertexTexture> rgba = VertexTexture::Make(TextureFormat::kA32B32G32R32F, 1, 1, {1, 2, 3});
  ASSERT_FALSE(rgba.ok());
  EXPECT_EQ(rgba.error().code, DiagnosticCode::kTexture);
  EXPECT_NE(rgba.message().find("needs 4 floats"), std::string::npos) << rgba.message();
  EXPECT_FALSE(VertexTexture::Make(TextureFormat::kR32F, 8192, 4096, {}).ok());  // 2^25 texels
}

std::optional<std::string> NoFiles(const std::filesystem::path&) { return std::nullopt; }

// Runs `instruction` (a texldl into r0) on the ref engine at v0 = `coordinate`; r0 lands in oT0.
Vec4f RunTexldl(const std::string& instruction, const ConstantBank& bank, const Vec4f& coordinate) {
  const std::string source = "vs_3_0\ndcl_position v0\ndcl_position o0\ndcl_texcoord0 o1\ndcl_2d s0\ndcl_2d s2\n"
                             "mov r0, c0\n" + instruction + "\nmov o0, v0\nmov o1, r0\n";
  const AssembleResult assembled = AssembleSource(source, "texldl.vsh", {}, NoFiles);
  EXPECT_TRUE(assembled.program) << assembled.diagnostics.ToString();
  if (!assembled.program) return {};
  Result<std::unique_ptr<Engine>> engine = MakeEngine("ref", *assembled.program, bank);
  EXPECT_TRUE(engine.ok()) << engine.message();
  if (!engine.ok()) return {};
  const std::vector<int> registers = {0};
  VertexArrays inputs = MakeInputArrays(1, registers);
  for (int c = 0; c < 4; ++c) inputs.lane(0, c)[0] = coordinate[c];
  VertexArrays outputs = MakeOutputArrays(1, *assembled.program);
  const Status ran = (*engine)->Run(inputs, outputs);
  EXPECT_EQ(ran.message(), "");
  if (!ran) return {};
  Vec4f result;
  for (int c = 0; c < 4; ++c) result[c] = outputs.lane(static_cast<int>(OutputSlot::kTexCoord0), c)[0];
  return result;
}

TEST(TextureSampling, TexldlAppliesTheSamplersSwizzleThenTheWriteMask) {
  ConstantBank bank = BankWith(NumberedTexture(4, 2));
  bank[0] = {-1, -2, -3, -4};
  EXPECT_EQ(RunTexldl("texldl r0, v0, s0", bank, {0.25f, 0.5f, 0, 0}), (Vec4f{1, 1, 11, 1}));
  EXPECT_EQ(RunTexldl("texldl r0, v0, s0.wzyx", bank, {0.25f, 0.5f, 0, 0}), (Vec4f{1, 11, 1, 1}));
  EXPECT_EQ(RunTexldl("texldl r0.xz, v0, s0.zzzz", bank, {0.25f, 0.5f, 0, 0}), (Vec4f{11, -2, 11, -4}));
  EXPECT_EQ(RunTexldl("texldl r0, v0.yxzw, s0", bank, {0.25f, 0.75f, 0, 0}), (Vec4f{3, 0, 3, 1}));
  EXPECT_EQ(RunTexldl("texldl r0, v0, s2", bank, {0.25f, 0.5f, 0, 0}), (Vec4f{0, 0, 0, 1}));  // declared, unbound
}

TEST(TextureSampling, TheLodInSrc0WDoesNotChangeTheTexel) {
  const ConstantBank bank = BankWith(NumberedTexture(4, 2));
  for (float lod : {0.0f, -5.0f, 0.5f, 3.0f, 100.0f, kNaN}) {
    EXPECT_EQ(RunTexldl("texldl r0, v0, s0", bank, {0.5f, 0.5f, 0, lod}), (Vec4f{2, 1, 12, 1})) << lod;
  }
}

TEST(TextureSampling, EnginesRefuseCubeAndVolumeSamplersByName) {
  const AssembleResult cube = AssembleSource("vs_3_0\ndcl_position v0\ndcl_position o0\ndcl_cube s1\ntexldl r0, v0, s1\nmov o0, r0\n",
                                             "cube.vsh", {}, NoFiles);
  ASSERT_TRUE(cube.program) << cube.diagnostics.ToString();
  const Result<std::unique_ptr<Engine>> refused = MakeEngine("ref", *cube.program, ConstantBank());
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.message().find("s1 is declared dcl_cube"), std::string::npos) << refused.message();
}

}  // namespace
}  // namespace vs11

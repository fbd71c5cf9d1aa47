// texldl on the batch and jit engines (batch's texture kernel; jit runs a program with texldl on the
// batch kernels): vs_3_0 programs sampling R32F and A32B32G32R32F textures whose sizes are no powers of
// two, under wrap, clamp and border, with s# swizzles, write masks, negated sources, _sat, an unbound
// sampler and a texldl under a per-vertex branch, at coordinates on texel edges (k / N exactly), below
// 0, from 1 up, huge, infinite and NaN: the same bits as ref under both float rules.
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/vm/engines/later_model_comparison.h"

namespace vs11 {
namespace {

std::shared_ptr<const VertexTexture> RandomTexture(std::mt19937& random, TextureFormat format, int width, int height) {
  std::uniform_real_distribution<float> value(-100.0f, 100.0f);
  std::vector<float> texels(static_cast<std::size_t>(width * height * ChannelCount(format)));
  for (float& texel : texels) texel = value(random);
  Result<VertexTexture> made = VertexTexture::Make(format, width, height, std::move(texels));
  EXPECT_TRUE(made.ok()) << made.message();
  return std::make_shared<const VertexTexture>(std::move(made).value());
}

// Coordinates that land on texel edges of the sizes used (k / 3, k / 5, k / 7, k / 4), around them,
// outside [0, 1), and the special values.
float Coordinate(std::mt19937& random) {
  static const float kSpecial[] = {0.0f, -0.0f, 1.0f, -1.0f, std::nextafter(1.0f, 0.0f), -1e-9f, 1e30f, -1e30f,
                                   std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
                                   std::numeric_limits<float>::quiet_NaN(), std::ldexp(1.0f, -140)};
  const int kind = std::uniform_int_distribution<int>(0, 5)(random);
  if (kind == 0) return kSpecial[std::uniform_int_distribution<std::size_t>(0, std::size(kSpecial) - 1)(random)];
  if (kind <= 2) {
    const int n = std::uniform_int_distribution<int>(3, 7)(random);
    const float edge = static_cast<float>(std::uniform_int_distribution<int>(-2 * n, 3 * n)(random)) / static_cast<float>(n);
    return kind == 1 ? edge : std::nextafter(edge, -INFINITY);
  }
  return std::uniform_real_distribution<float>(-2.0f, 3.0f)(random);
}

constexpr const char* kProgram =
    "vs_3_0\n"
    "dcl_position v0\ndcl_texcoord v1\n"
    "dcl_position o0\ndcl_texcoord0 o1\ndcl_texcoord1 o2\ndcl_texcoord2 o3\ndcl_texcoord3 o4\ndcl_texcoord4 o5\n"
    "dcl_2d s0\ndcl_2d s1\ndcl_2d s2\ndcl_2d s3\n"
    "mov r1, c0\nmov r2, c0\nmov r3, c0\nmov r4, c0\n"
    "texldl r0, v0, s0\n"
    "texldl r1.yw, -v1.yxzw, s1.wzyx\n"
    "mul r5, v0, c1\n"
    "texldl_sat r2.xz, r5, s3.zzxy\n"
    "texldl r3, v1, s2\n"  // declared, never bound: (0, 0, 0, 1)
    "if_gt v0.x, c2.x\n"
    "  texldl r4, v1.zwxy, s0\n"
    "endif\n"
    "texldl r0, r0, s3\n"  // the destination is also the coordinate
    "mov o0, v0\nmov o1, r0\nmov o2, r1\nmov o3, r2\nmov o4, r3\nmov o5, r4\n";

TEST(TexldlEngines, BatchAndJitGiveRefsBitsOnRandomCoordinates) {
  const Program program = later_model::Assemble(kProgram);
  ASSERT_FALSE(program.instructions.empty());
  std::mt19937 random(33);
  for (int round = 0; round < 6; ++round) {
    ConstantBank bank(256);
    bank[0] = {-7, -8, -9, -10};
    bank[1] = {2.5f, -1.5f, 0.0f, 1.0f};
    bank[2] = {0.5f, 0, 0, 0};
    const TextureAddress modes[] = {TextureAddress::kWrap, TextureAddress::kClamp, TextureAddress::kBorder};
    const auto mode = [&] { return modes[std::uniform_int_distribution<int>(0, 2)(random)]; };
    bank.sampler(0) = {RandomTexture(random, TextureFormat::kA32B32G32R32F, 3, 5), {mode(), mode()}};
    bank.sampler(1) = {RandomTexture(random, TextureFormat::kR32F, 7, 1 + round), {mode(), mode()}};
    bank.sampler(3) = {RandomTexture(random, TextureFormat::kA32B32G32R32F, 4, 6), {mode(), mode()}};
    const VertexArrays inputs = later_model::RandomInputs(700, [&] { return Coordinate(random); });
    for (FloatRules rules : {FloatRules::kD3d9, FloatRules::kLegacy}) {
      const VertexArrays expected = later_model::RunOn("ref", program, bank, inputs, {.float_rules = rules});
      for (const later_model::Candidate& candidate : later_model::Candidates(rules)) {
        const VertexArrays actual = later_model::RunOn(candidate.engine, program, bank, inputs, candidate.options);
        EXPECT_EQ(later_model::Difference(expected, actual), "") << candidate.name << ", round " << round;
      }
    }
  }
}

TEST(TexldlEngines, SetConstantsRebindsTheTextures) {
  const Program program = later_model::Assemble(kProgram);
  std::mt19937 random(7);
  ConstantBank first(256), second(256);
  first.sampler(0) = {RandomTexture(random, TextureFormat::kA32B32G32R32F, 3, 5), {}};
  second.sampler(0) = {RandomTexture(random, TextureFormat::kR32F, 2, 2), {TextureAddress::kClamp, TextureAddress::kBorder}};
  const VertexArrays inputs = later_model::RandomInputs(300, [&] { return Coordinate(random); });
  const VertexArrays expected = later_model::RunOn("ref", program, second, inputs, {});
  for (const later_model::Candidate& candidate : later_model::Candidates(FloatRules::kD3d9)) {
    Result<std::unique_ptr<Engine>> engine = MakeEngine(candidate.engine, program, first, candidate.options);
    ASSERT_TRUE(engine.ok()) << engine.message();
    ASSERT_EQ((*engine)->SetConstants(second).message(), "") << candidate.name;
    VertexArrays actual = MakeOutputArrays(inputs.count(), program);
    ASSERT_EQ((*engine)->Run(inputs, actual).message(), "") << candidate.name;
    EXPECT_EQ(later_model::Difference(expected, actual), "") << candidate.name;
  }
}

TEST(TexldlEngines, TheGlEngineRefusesTexldlByName) {
  const Program program = later_model::Assemble(kProgram);
  const Status refusal = EngineRefusal(program, "gl");
  ASSERT_FALSE(refusal.ok());
  EXPECT_NE(refusal.message().find("the gl engine cannot run texldl (instruction 17, line 18): vertex textures run "
                                   "on the ref, batch and jit engines"),
            std::string::npos)
      << refusal.message();
}

}  // namespace
}  // namespace vs11

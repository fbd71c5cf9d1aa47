// `vs11 run --texture` end to end: a vs_3_0 program sampling an R32F and an A32B32G32R32F .npy
// texture on ref, batch and jit with the same numbers, --texture-address, the warning for a declared
// sampler with no texture, and the errors: a shape that is no texture, a texture for a sampler the
// program does not declare, a malformed flag, the gl engine.
#include <cstring>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/run_tool.h"

namespace {

using ::testing::EndsWith;
using ::testing::HasSubstr;
using vs11::testing::CommandResult;
using vs11::testing::RunVs11;

// A version 1.0 .npy file of float32 `values` with the shape `shape` ("(2, 3, 4)").
std::string Npy(const std::string& shape, const std::vector<float>& values) {
  std::string header = "{'descr': '<f4', 'fortran_order': False, 'shape': " + shape + ", }";
  header.append(63 - (10 + header.size()) % 64, ' ');
  header.push_back('\n');
  std::string bytes("\x93NUMPY\x01\x00", 8);
  bytes.push_back(static_cast<char>(header.size() & 0xFF));
  bytes.push_back(static_cast<char>(header.size() >> 8));
  bytes += header;
  bytes.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(float));
  return bytes;
}

// oT0 = s0 at v0's xy, oT1 = s1 at v0's xy; s2 is declared and never bound.
const std::string kProgram =
    "vs_3_0\ndcl_position v0\ndcl_position o0\ndcl_texcoord0 o1\ndcl_texcoord1 o2\ndcl_texcoord2 o3\n"
    "dcl_2d s0\ndcl_2d s1\ndcl_2d s2\n"
    "texldl r0, v0, s0\ntexldl r1, v0, s1\ntexldl r2, v0, s2\n"
    "mov o0, v0\nmov o1, r0\nmov o2, r1\nmov o3, r2\n";

class TextureRun : public vs11::testing::ToolFolderTest {
 protected:
  void SetUp() override {
    ToolFolderTest::SetUp();
    program_ = Write("textured.vsh", kProgram);
    // (0, 0), (0.5, 0.5) on texel edges, (-0.25, 1.25) outside [0, 1).
    positions_ = Write("p.csv", "x,y\n0,0\n0.5,0.5\n-0.25,1.25\n");
    heights_ = Write("heights.npy", Npy("(2, 2)", {1, 2, 3, 4}));  // R32F, rows v = 0 and v = 0.5
    std::vector<float> rgba;
    for (int i = 0; i < 4 * 4; ++i) rgba.push_back(static_cast<float>(i));
    colours_ = Write("colours.npy", Npy("(1, 4, 4)", rgba));  // 4 x 1 A32B32G32R32F
  }
  std::string Run(const std::string& flags) { return "run " + program_ + " --input v0=" + positions_ + " " + flags; }
  std::string program_, positions_, heights_, colours_;
};

TEST_F(TextureRun, RefBatchAndJitSampleNpyTexturesAlike) {
  for (const char* engine : {"ref", "batch", "jit"}) {
    const CommandResult r = RunVs11(Run("--texture s0=" + heights_ + " --texture s1=" + colours_ +
                                        " --texture-address s1=clamp,wrap --engine " + std::string(engine)));
    ASSERT_EQ(r.status, 0) << engine << ": " << r.output;
    // s0 (wrap): (0,0) texel 0; (0.5,0.5) texel (1,1); (-0.25,1.25) wraps to (0.75,0.25): texel (1,0).
    // s1 (clamp u): u 0 -> 0, 0.5 -> 2, -0.25 -> 0.
    EXPECT_THAT(r.output, EndsWith("oPos.x,oPos.y,oPos.z,oPos.w,oT0.x,oT0.y,oT0.z,oT0.w,oT1.x,oT1.y,oT1.z,oT1.w,"
                                   "oT2.x,oT2.y,oT2.z,oT2.w\n"
                                   "0,0,0,1,1,1,1,1,0,1,2,3,0,0,0,1\n"
                                   "0.5,0.5,0,1,4,1,1,1,8,9,10,11,0,0,0,1\n"
                                   "-0.25,1.25,0,1,2,1,1,1,0,1,2,3,0,0,0,1\n"))
        << engine;
    EXPECT_THAT(r.output, HasSubstr("warning: s2 is declared but no --texture binds it")) << engine;
  }
}

TEST_F(TextureRun, AShapeThatIsNoTextureIsAnErrorNamingTheFile) {
  const std::string three = Write("three.npy", Npy("(1, 2, 3)", {0, 0, 0, 0, 0, 0}));
  const CommandResult r = RunVs11(Run("--texture s0=" + three));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr(three + ": shape (1, 2, 3) is no vertex texture"));
  const std::string vector = Write("vector.npy", Npy("(2,)", {0, 0}));
  EXPECT_EQ(RunVs11(Run("--texture s0=" + vector)).status, 1);
}

TEST_F(TextureRun, ATextureForASamplerTheProgramDoesNotDeclareIsAUsageError) {
  const CommandResult r = RunVs11(Run("--texture s3=" + heights_));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_THAT(r.output, HasSubstr("--texture " + heights_ + ": " + program_ + " declares no sampler s3"));
}

TEST_F(TextureRun, MalformedFlagsAreUsageErrors) {
  for (const std::string& flags : std::vector<std::string>{"--texture s4=" + heights_, "--texture " + heights_, "--texture-address s0=mirror",
                                  "--texture s0=" + heights_ + " --texture s0=" + heights_}) {
    const CommandResult r = RunVs11(Run(flags));
    EXPECT_EQ(r.status, 2) << flags << ": " << r.output;
  }
}

TEST_F(TextureRun, TheGlEngineRefusesTexldlByName) {
  const CommandResult r = RunVs11(Run("--texture s0=" + heights_ + " --engine gl"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("the gl engine cannot run texldl"));
}

}  // namespace

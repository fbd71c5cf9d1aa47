// The compute form of the translation (vm/translate/compute_interface.h): what it stores, `precise`
// where the dialect has it, the targets that cannot hold it, and the dispatch size for any vertex
// count. That it compiles for every program is translate_test.cc's CheckTranslations; that it runs
// and gives the engines' bits is tests/vm/gl (the gl engine's compute path on llvmpipe).
#include <string>

#include <gtest/gtest.h>

#include "vm/asm/assembler.h"
#include "vm/translate/compute_interface.h"
#include "vm/translate/translate.h"

namespace vs11::translate {
namespace {

Program WritesOnlyOD0AndOT1() {
  AssembleOptions assemble;
  assemble.require_position = false;
  AssembleResult assembled = AssembleSource("vs.1.1\nmov r1, v1\nmad oD0, v0, c0, r1\nmov oT1.xy, v2\n", "two_outputs.vsh", assemble);
  EXPECT_TRUE(assembled.program) << assembled.diagnostics.ToString();
  return assembled.program ? std::move(*assembled.program) : Program();
}

TranslateOptions ComputeOn(Target target) {
  TranslateOptions options;
  options.target = target;
  options.stage = Stage::kCompute;
  return options;
}

TEST(ComputeTranslation, StoresExactlyTheOutputRegistersTheProgramWrites) {
  const std::string glsl =
      TranslateToGlsl(WritesOnlyOD0AndOT1(), ComputeOn(Target::kGlslEs310));
  const int diffuse = static_cast<int>(OutputSlot::kDiffuse), texcoord1 = static_cast<int>(OutputSlot::kTexCoord0) + 1;
  EXPECT_NE(glsl.find("vs11_store(" + std::to_string(diffuse) + ", vs11_vertex, oD0);"), std::string::npos) << glsl;
  EXPECT_NE(glsl.find("vs11_store(" + std::to_string(texcoord1) + ", vs11_vertex, oT1);"), std::string::npos) << glsl;
  int stores = 0;
  for (std::size_t at = glsl.find("  vs11_store("); at != std::string::npos; at = glsl.find("  vs11_store(", at + 1)) ++stores;
  EXPECT_EQ(stores, 2) << glsl;
  EXPECT_EQ(glsl.find("gl_Position"), std::string::npos);
  EXPECT_NE(glsl.find("#version 310 es"), std::string::npos);
  EXPECT_NE(glsl.find("layout(local_size_x = 64) in;"), std::string::npos);
  EXPECT_EQ(glsl.find("precise vec4 oD0"), std::string::npos) << "GLSL ES 3.10 has no precise";
}

TEST(ComputeTranslation, OutputsArePreciseWhereTheDialectHasIt) {
  for (Target target : {Target::kGlslEs320, Target::kSpirv}) {
    const std::string glsl = TranslateToGlsl(WritesOnlyOD0AndOT1(), ComputeOn(target));
    EXPECT_NE(glsl.find("  precise vec4 oD0 = vec4("), std::string::npos) << TargetName(target) << "\n" << glsl;
    EXPECT_NE(glsl.find("  precise vec4 oT1 = vec4("), std::string::npos) << TargetName(target);
  }
}

TEST(ComputeTranslation, TargetsWithoutComputeShadersAreRefused) {
  for (Target target : {Target::kGlsl330, Target::kGlslEs300}) {
    ASSERT_FALSE(StageProblem(target, Stage::kCompute).ok()) << TargetName(target);
    EXPECT_EQ(StageProblem(target, Stage::kCompute).error().code, DiagnosticCode::kOptionValue);
    const Result<Artifact> artifact = Translate(WritesOnlyOD0AndOT1(), ComputeOn(target));
    ASSERT_FALSE(artifact.ok());
    EXPECT_EQ(artifact.error().code, DiagnosticCode::kOptionValue);
    EXPECT_NE(artifact.message().find("no compute shaders"), std::string::npos) << artifact.message();
  }
  EXPECT_TRUE(StageProblem(Target::kGlslEs310, Stage::kCompute).ok());
  EXPECT_TRUE(StageProblem(Target::kGlsl330, Stage::kVertex).ok());
  EXPECT_EQ(kStageNames.Find("compute"), Stage::kCompute);
  EXPECT_EQ(kStageNames.Find("fragment"), std::nullopt);
}

TEST(ComputeTranslation, DispatchCoversEveryVertexInTwoDimensionsPastTheLimit) {
  EXPECT_EQ(ComputeDispatchSize(0, 65535), (std::array<std::uint32_t, 2>{0, 0}));
  EXPECT_EQ(ComputeDispatchSize(1, 65535), (std::array<std::uint32_t, 2>{1, 1}));
  EXPECT_EQ(ComputeDispatchSize(65, 65535), (std::array<std::uint32_t, 2>{2, 1}));
  const std::size_t huge = std::size_t{65535} * kComputeWorkGroupSize * 3 + 1;
  const std::array<std::uint32_t, 2> size = ComputeDispatchSize(huge, 65535);
  EXPECT_EQ(size[0], 65535u);
  EXPECT_EQ(size[1], 4u);
  for (std::size_t count : {std::size_t{1}, std::size_t{63}, std::size_t{64}, std::size_t{1000}, huge}) {
    const std::array<std::uint32_t, 2> groups = ComputeDispatchSize(count, 7);
    const std::size_t covered = std::size_t{groups[0]} * groups[1] * kComputeWorkGroupSize;
    EXPECT_GE(covered, count);
    EXPECT_LT(covered - count, std::size_t{groups[0]} * kComputeWorkGroupSize) << count;  // at most one row spare
    EXPECT_LE(groups[0], 7u);
  }
}

TEST(ComputeTranslation, LayoutBlockHasTheStd140Offsets) {
  ComputeLayoutBlock block;
  block.SetInterleavedInput(3, 8, 12);
  EXPECT_EQ(block.input_base[3], (ComputeLayoutBlock::UVec4{8, 9, 10, 11}));
  EXPECT_EQ(block.input_stride[3][0], 12u);
  EXPECT_EQ(block.input_stride[3][1], 1u);
  EXPECT_EQ(block.input_stride[2][1], 0u);
  EXPECT_EQ(offsetof(ComputeLayoutBlock, vertex_count), std::size_t{16} * (2 * 16 + 2 * 13));
}

}  // namespace
}  // namespace vs11::translate

// vs11 translate end to end: what it writes where, and that a bad program gets vs11 asm's diagnostics.
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/run_tool.h"
#include "vm/translate/glslang_compiler.h"

namespace vs11 {
namespace {

namespace fs = std::filesystem;
using testing::RunVs11;

class TranslateCommand : public testing::ToolFolderTest {};

const std::string kProgram = "vs_1_1\ndcl_position v0\ndcl_normal v1\nm4x4 oPos, v0, c0\nmul oD0.xyz, v1, c4\n";

TEST_F(TranslateCommand, WritesGlslToStdoutWithItsInterface) {
  const testing::CommandResult glsl = RunVs11("translate " + Write("p.vsh", kProgram) + " --to glsles300");
  ASSERT_EQ(glsl.status, 0) << glsl.output;
  // GLSL ES wants #version first; the interface comment follows it.
  EXPECT_EQ(glsl.output.rfind("#version 300 es\n", 0), 0u) << glsl.output;
  EXPECT_LT(glsl.output.find("// vs_1_1 program"), glsl.output.find("in vec4")) << glsl.output;
  EXPECT_NE(glsl.output.find("layout(location = 1) in vec4 v1;  // dcl_normal"), std::string::npos) << glsl.output;
  EXPECT_TRUE(translate::CompileWithGlslang(glsl.output, translate::Target::kGlslEs300).ok());
}

// --to and --clip parse with their name tables: an unknown name is a usage error
// listing the valid ones.
TEST_F(TranslateCommand, AnUnknownChoiceListsTheValidNames) {
  const std::string input = Write("p.vsh", kProgram);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--to hlsl", "unknown target 'hlsl' (use glsl330, glsles300, glsles310, glsles320 or spirv)"},
      {"--to glsles310 --stage fragment", "unknown stage 'fragment' (use vertex or compute)"},
      {"--to glsl330 --clip dx", "unknown clip space 'dx' (use d3d, gl or vulkan)"}};
  for (const auto& [flags, message] : cases) {
    const testing::CommandResult run = RunVs11("translate " + input + " " + flags);
    EXPECT_EQ(run.status, 2) << flags << "\n" << run.output;
    EXPECT_NE(run.output.find(message), std::string::npos) << flags << "\n" << run.output;
  }
  const testing::CommandResult clip = RunVs11("translate " + input + " --to glsl330 --clip vulkan");
  EXPECT_EQ(clip.status, 0) << clip.output;
}

TEST_F(TranslateCommand, WritesValidSpirvToAFileOnly) {
  const std::string input = Write("p.vsh", kProgram);
  const testing::CommandResult to_stdout = RunVs11("translate " + input + " --to spirv");
  EXPECT_EQ(to_stdout.status, 2) << to_stdout.output;
  EXPECT_NE(to_stdout.output.find("-o"), std::string::npos) << to_stdout.output;

  const fs::path output = dir_ / "p.spv";
  const testing::CommandResult written = RunVs11("translate " + input + " --to spirv -o " + output.string());
  ASSERT_EQ(written.status, 0) << written.output;
  std::ifstream in(output, std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(bytes.size() % 4, 0u);
  std::vector<std::uint32_t> words(bytes.size() / 4);
  std::memcpy(words.data(), bytes.data(), bytes.size());
  ASSERT_FALSE(words.empty());
  EXPECT_EQ(words[0], 0x07230203u) << "SPIR-V magic";
  EXPECT_EQ(translate::ValidateSpirv(words).message(), "");
}

TEST_F(TranslateCommand, StageComputeWritesACompileableComputeShader) {
  const std::string input = Write("p.vsh", kProgram);
  const testing::CommandResult glsl = RunVs11("translate " + input + " --to glsles310 --stage compute");
  ASSERT_EQ(glsl.status, 0) << glsl.output;
  EXPECT_EQ(glsl.output.rfind("#version 310 es\n", 0), 0u) << glsl.output;
  EXPECT_NE(glsl.output.find("vec4 v1 = vs11_input(1, vs11_vertex);  // dcl_normal"), std::string::npos) << glsl.output;
  EXPECT_TRUE(
      translate::CompileWithGlslang(glsl.output, translate::Target::kGlslEs310, translate::Stage::kCompute).ok());
  const fs::path spirv = dir_ / "p_comp.spv";
  const testing::CommandResult written = RunVs11("translate " + input + " --to spirv --stage compute -o " + spirv.string());
  ASSERT_EQ(written.status, 0) << written.output;
  EXPECT_TRUE(fs::exists(spirv));
  const testing::CommandResult refused =
      RunVs11("translate " + input + " --to glsles300 --stage compute -o " + (dir_ / "x.comp").string());
  EXPECT_EQ(refused.status, 2) << refused.output;
  EXPECT_NE(refused.output.find("glsles300 has no compute shaders"), std::string::npos) << refused.output;
  EXPECT_FALSE(fs::exists(dir_ / "x.comp"));
  const testing::CommandResult clipped = RunVs11("translate " + input + " --to glsles320 --stage compute --clip gl");
  EXPECT_EQ(clipped.status, 0) << clipped.output;
  EXPECT_NE(clipped.output.find("warning: --clip applies to the vertex stage only"), std::string::npos) << clipped.output;
}

TEST_F(TranslateCommand, BadProgramGetsTheAssemblersDiagnosticsAndNoFile) {
  const std::string input = Write("bad.vsh", "vs_1_1\nmov oPos, v0\nadd r0, c1, c2\nfrob r1, r0\n");
  const testing::CommandResult assembled = RunVs11("asm " + input + " -o " + (dir_ / "bad.vso").string());
  const testing::CommandResult translated = RunVs11("translate " + input + " --to glsl330 -o " + (dir_ / "bad.vert").string());
  EXPECT_EQ(assembled.status, 1);
  EXPECT_EQ(translated.status, 1);
  EXPECT_NE(translated.output.find("bad.vsh:4:"), std::string::npos) << translated.output;
  EXPECT_EQ(translated.output, assembled.output);
  EXPECT_FALSE(fs::exists(dir_ / "bad.vert"));
}

}  // namespace
}  // namespace vs11

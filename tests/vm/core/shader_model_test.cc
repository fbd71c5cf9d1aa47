// The shader-model table (vm/core/shader_model.h) and the opcode table's model column
// (vm/core/isa.h): every model assembles and decodes, only vs_1_1 runs, its register counts are the
// machine's, and the register files of the later models are spelled and encoded but refused in a vs_1_1
// program by the assembler, the validator and the decoder, with a message that says which model has them.
#include "vm/core/shader_model.h"

#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "vm/asm/assembler.h"
#include "vm/asm/bytecode.h"
#include "vm/asm/lexer.h"
#include "vm/core/isa.h"
#include "vm/core/program.h"

namespace vs11 {
namespace {

std::string FirstMessage(const Diagnostics& diagnostics) {
  return diagnostics.all().empty() ? std::string() : FormatDiagnostic(diagnostics.all().front());
}

TEST(ShaderModel, NamesTokensEveryModelEnabledAndOnlyVs11Runs) {
  const std::vector<std::pair<std::string_view, std::uint32_t>> expected = {
      {"vs_1_1", 0xFFFE0101}, {"vs_2_0", 0xFFFE0200}, {"vs_2_x", 0xFFFE0201}, {"vs_3_0", 0xFFFE0300}};
  ASSERT_EQ(kShaderModels.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(kShaderModels[i].name, expected[i].first);
    EXPECT_EQ(kShaderModels[i].version_token, expected[i].second);
    EXPECT_TRUE(kShaderModels[i].enabled) << expected[i].first;
    EXPECT_EQ(kShaderModels[i].runs, i == 0) << expected[i].first;
    EXPECT_EQ(ShaderModelOfVersion(expected[i].second), kShaderModels[i].model);
  }
  EXPECT_EQ(ShaderModelOfVersion(kVersionVs10), ShaderModel::kVs11);
  EXPECT_EQ(ShaderModelOfVersion(0xFFFF0200), std::nullopt);  // ps_2_0
  EXPECT_TRUE(VersionEnabled(kVersionVs11) && VersionEnabled(kVersionVs10));
  EXPECT_TRUE(VersionEnabled(0xFFFE0200) && VersionEnabled(0xFFFE0201) && VersionEnabled(0xFFFE0300));
  EXPECT_FALSE(VersionEnabled(0xFFFF0101) || VersionEnabled(0xFFFE0400));
  EXPECT_EQ(Program{}.model(), ShaderModel::kVs11);
  EXPECT_TRUE(Program{}.regions.empty());
}

TEST(ShaderModel, Vs11RegisterCountsAreTheMachinesAndLaterFilesAreAbsent) {
  EXPECT_EQ(RegisterCount(RegisterFile::kTemp, ShaderModel::kVs11), kTempRegisterCount);
  EXPECT_EQ(RegisterCount(RegisterFile::kTemp, ShaderModel::kVs30), 32);
  EXPECT_EQ(RegisterCount(RegisterFile::kConst, ShaderModel::kVs11), kDefaultConstantCount);
  for (RegisterFile file : {RegisterFile::kConstInt, RegisterFile::kConstBool, RegisterFile::kLoop,
                            RegisterFile::kPredicate}) {
    EXPECT_EQ(RegisterCount(file, ShaderModel::kVs11), 0) << static_cast<int>(file);
    EXPECT_GT(RegisterCount(file, ShaderModel::kVs30), 0) << static_cast<int>(file);
  }
  EXPECT_EQ(RegisterCount(RegisterFile::kPredicate, ShaderModel::kVs20), 0);
  EXPECT_EQ(RegisterCount(RegisterFile::kPredicate, ShaderModel::kVs2x), 1);
  // The D3D9 register type numbers (§4.6): 7 CONSTINT, 14 CONSTBOOL, 15 LOOP, 19 PREDICATE.
  EXPECT_EQ(RegisterFileOfType(7, ShaderModel::kVs20), RegisterFile::kConstInt);
  EXPECT_EQ(RegisterFileOfType(14, ShaderModel::kVs20), RegisterFile::kConstBool);
  EXPECT_EQ(RegisterFileOfType(15, ShaderModel::kVs20), RegisterFile::kLoop);
  EXPECT_EQ(RegisterFileOfType(19, ShaderModel::kVs2x), RegisterFile::kPredicate);
  for (std::uint32_t type : {7u, 14u, 15u, 19u, 8u}) {
    EXPECT_EQ(RegisterFileOfType(type, ShaderModel::kVs11), std::nullopt) << type;
  }
  for (std::uint32_t type = 0; type <= 6; ++type) EXPECT_TRUE(RegisterFileOfType(type, ShaderModel::kVs11)) << type;
}

TEST(ShaderModel, EveryOpcodeStaysInLaterModels) {
  for (const OpcodeInfo& info : kOpcodeTable) {
    for (const ShaderModelInfo& model : kShaderModels) {
      EXPECT_EQ(OpcodeAllowed(info, model.model), model.model >= info.since) << info.mnemonic;
    }
  }
  EXPECT_EQ(Info(Opcode::kLrp).since, ShaderModel::kVs20);
  EXPECT_EQ(Info(Opcode::kSetp).since, ShaderModel::kVs2x);
  EXPECT_EQ(Info(Opcode::kTexldl).since, ShaderModel::kVs30);
  EXPECT_EQ(SourceCount(Info(Opcode::kSincos), ShaderModel::kVs20), 3);
  EXPECT_EQ(SourceCount(Info(Opcode::kSincos), ShaderModel::kVs30), 1);
  OpcodeInfo later = Info(Opcode::kMov);
  later.since = ShaderModel::kVs20;
  EXPECT_FALSE(OpcodeAllowed(later, ShaderModel::kVs11));
  EXPECT_TRUE(OpcodeAllowed(later, ShaderModel::kVs30));
}

TEST(ShaderModel, LaterRegistersAreSpelledButRefusedInVs11) {
  EXPECT_EQ(RegisterName(RegisterFile::kConstInt, 3), "i3");
  EXPECT_EQ(RegisterName(RegisterFile::kConstBool, 0), "b0");
  EXPECT_EQ(RegisterName(RegisterFile::kLoop, 0), "aL");
  EXPECT_EQ(RegisterName(RegisterFile::kPredicate, 0), "p0");
  const struct {
    std::string source;
    std::string message;
  } cases[] = {
      {"vs_1_1\nmov r0, i0\n",
       "src0 names i0, which vs_1_1 does not have (integer constant registers exist from vs_2_0 on)"},
      {"vs_1_1\nmov r0, b1\n", "names b1, which vs_1_1 does not have (boolean constant registers exist from vs_2_0 on)"},
      {"vs_1_1\nadd r0, r1, aL\n", "names aL, which vs_1_1 does not have (loop counter registers exist from vs_2_0 on)"},
      {"vs_1_1\nmov p0, r1\n", "names p0, which vs_1_1 does not have (predicate registers exist from vs_2_x on)"},
      {"vs_1_1\nmov i0, r1\n", "names i0, which vs_1_1 does not have"},
  };
  for (const auto& c : cases) {
    const AssembleResult result = AssembleSource(c.source, "t.vsh", {});
    EXPECT_FALSE(result.program) << c.source;
    EXPECT_NE(FirstMessage(result.diagnostics).find(c.message), std::string::npos)
        << c.source << FirstMessage(result.diagnostics);
  }
  // A version beyond the vertex models is named.
  const AssembleResult vs40 = AssembleSource("vs_4_0\nmov oPos, v0\n", "t.vsh", {});
  const std::string expected = "unsupported shader version 'vs_4_0'";
  EXPECT_NE(FirstMessage(vs40.diagnostics).find(expected), std::string::npos) << FirstMessage(vs40.diagnostics);
}

TEST(ShaderModel, TheDecoderRefusesLaterRegisterTypesAndVersions) {
  // mov r0, <type 7 register 0>: a CONSTINT source (type bits 28-30 = 7, bits 11-12 = 0).
  const std::vector<std::uint32_t> constint = {kVersionVs11, 0x00000001, 0x800F0000, 0xF0E40000, 0x0000FFFF};
  const DecodeResult result = Decode(constint);
  EXPECT_FALSE(result.program);
  EXPECT_NE(FirstMessage(result.diagnostics).find("register type 7 is not used by vs_1_1"), std::string::npos)
      << FirstMessage(result.diagnostics);
  const std::vector<std::uint32_t> vs20 = {0xFFFE0200, 0x0000FFFF};
  EXPECT_TRUE(Decode(vs20).program);
  const std::vector<std::uint32_t> vs40 = {0xFFFE0400, 0x0000FFFF};
  EXPECT_FALSE(Decode(vs40).program);
}

}  // namespace
}  // namespace vs11

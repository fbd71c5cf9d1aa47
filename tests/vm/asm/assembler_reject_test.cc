// Sources the assembler must reject for their syntax (spec §2), each with the place and the code of
// the first error, and what it must name. Rules that need the whole program (read ports, ranges, dcl) belong to the
// validator and are tested there; these cases run with validation off.
#include <gtest/gtest.h>

#include <string>

#include "vm/asm/assembler.h"

namespace vs11 {
namespace {

std::optional<std::string> NoFiles(const std::filesystem::path&) { return std::nullopt; }

AssembleResult AssembleUnvalidated(const std::string& source) {
  AssembleOptions options;
  options.validate = false;
  return AssembleSource(source, "bad.vsh", options, NoFiles);
}

struct RejectCase {
  std::string name;
  std::string source;
  int line;
  int column;  // 0: not checked (e.g. the error comes from the preprocessor)
  DiagnosticCode code;
  std::string fact;  // what the first error must name (a token, a number); "" when the code says it all
};

void PrintTo(const RejectCase& c, std::ostream* os) { *os << c.name; }

class AssemblerReject : public testing::TestWithParam<RejectCase> {};

TEST_P(AssemblerReject, ReportsTheErrorWhereItIs) {
  const RejectCase& c = GetParam();
  AssembleResult result = AssembleUnvalidated(c.source);
  EXPECT_FALSE(result.program);
  ASSERT_TRUE(result.diagnostics.HasErrors());
  const Diagnostic& first = result.diagnostics.all().front();
  EXPECT_EQ(first.severity, Severity::kError);
  EXPECT_EQ(first.loc.file, "bad.vsh");
  EXPECT_EQ(first.loc.line, c.line) << first.message;
  if (c.column != 0) {
    EXPECT_EQ(first.loc.column, c.column) << first.message;
  }
  EXPECT_EQ(first.code, c.code) << DiagnosticCodeName(first.code) << ": " << first.message;
  EXPECT_NE(first.message.find(c.fact), std::string::npos) << "message: " << first.message;
}

const RejectCase kStructure[] = {
    {"EmptySource", "", 1, 1, DiagnosticCode::kVersionStatement, ""},
    {"InstructionBeforeVersion", "mov oPos, v0\nvs_1_1\n", 1, 1, DiagnosticCode::kVersionStatement, ""},
    {"SecondVersion", "vs_1_1\nmov oPos, v0\nvs_1_1\n", 3, 1, DiagnosticCode::kVersionStatement, ""},
    {"PixelShaderVersion", "ps_1_1\n", 1, 1, DiagnosticCode::kVersionStatement, "'ps_1_1'"},
    {"LaterVertexVersion", "vs_4_0\n", 1, 1, DiagnosticCode::kVersionStatement, "'vs_4_0'"},
    {"Dx8LaterVersion", "vs.4.0\n", 1, 1, DiagnosticCode::kVersionStatement, "'vs.4.0'"},
    {"InstructionOnVersionLine", "vs_1_1 mov oPos, v0\n", 1, 8, DiagnosticCode::kVersionStatement, "'mov'"},
    {"BadDx8VersionNumber", "vs.1.1.1\n", 1, 4, DiagnosticCode::kMalformedNumber, "'1.1.1'"},
    {"UnknownInstruction", "vs_1_1\nfoo r0, r1\n", 2, 1, DiagnosticCode::kUnknownInstruction, "'foo'"},
    {"UnexpectedCharacter", "vs_1_1\nmov r0, r1 @\n", 2, 12, DiagnosticCode::kUnexpectedCharacter, "'@'"},
    {"MalformedNumber", "vs_1_1\ndef c0, 1x, 0, 0, 0\n", 2, 9, DiagnosticCode::kMalformedNumber, "'1x'"},
    {"PreprocessorMissingInclude", "#include \"nowhere.h\"\nvs_1_1\n", 1, 0, DiagnosticCode::kIncludeNotFound, "nowhere.h"},
};
INSTANTIATE_TEST_SUITE_P(AssemblerRejectStructure, AssemblerReject, testing::ValuesIn(kStructure),
                         [](const auto& info) { return info.param.name; });

// §2.5-§2.6 and §4.7: modifiers and instructions that vs_1_1 does not have.
const RejectCase kNotInVs11[] = {
    {"SaturateModifier", "vs_1_1\nmov_sat r0, r1\n", 2, 1, DiagnosticCode::kNotInVs11, "'_sat'"},
    {"ShiftModifier", "vs_1_1\nmul_x2 r0, r1, r2\n", 2, 1, DiagnosticCode::kNotInVs11, "'_x2'"},
    {"PartialPrecision", "vs_1_1\nadd_pp r0, r1, r2\n", 2, 1, DiagnosticCode::kNotInVs11, "'_pp'"},
    {"AbsSourceModifier", "vs_1_1\nmov r0, r1_abs\n", 2, 9, DiagnosticCode::kSourceModifier, "'_abs'"},
    {"BiasSourceModifier", "vs_1_1\nadd r0, r1, c0_bias\n", 2, 13, DiagnosticCode::kSourceModifier, "'_bias'"},
    {"SignedScaleModifier", "vs_1_1\nmov r0, v0_bx2\n", 2, 9, DiagnosticCode::kSourceModifier, "'_bx2'"},
    {"TimesTwoModifier", "vs_1_1\nmov r0, r1_x2\n", 2, 9, DiagnosticCode::kSourceModifier, "'_x2'"},
    {"ModifierAfterSwizzle", "vs_1_1\nmov r0, r1.x_abs\n", 2, 12, DiagnosticCode::kSourceModifier, "'_abs'"},
    {"ComplementModifier", "vs_1_1\nadd r0, 1-r1, r2\n", 2, 9, DiagnosticCode::kSourceModifier, "'1-'"},
    {"NotModifier", "vs_1_1\nmov r0, !r1\n", 2, 9, DiagnosticCode::kSourceModifier, "'!'"},
    {"CoIssue", "vs_1_1\nmov r0, r1\n+mov r2, r1\n", 3, 1, DiagnosticCode::kNotInVs11, ""},
    {"Predicate", "vs_1_1\n(p0) mov r0, r1\n", 2, 1, DiagnosticCode::kNotInVs11, ""},
    {"Lrp", "vs_1_1\nlrp r0, r1, r2, r3\n", 2, 1, DiagnosticCode::kNotInVs11, "'lrp'"},
    {"Pow", "vs_1_1\npow r0, r1.x, r2.x\n", 2, 1, DiagnosticCode::kNotInVs11, "'pow'"},
    {"Mova", "vs_1_1\nmova a0.x, r1.x\n", 2, 1, DiagnosticCode::kNotInVs11, "'mova'"},
    {"Sincos", "vs_1_1\nsincos r0.xy, r1.x\n", 2, 1, DiagnosticCode::kNotInVs11, "'sincos'"},
    {"Nrm", "vs_1_1\nnrm r0, r1\n", 2, 1, DiagnosticCode::kNotInVs11, "'nrm'"},
    {"PixelTexld", "vs_1_1\ntexld r0, t0\n", 2, 1, DiagnosticCode::kNotInVs11, "'texld'"},
};
INSTANTIATE_TEST_SUITE_P(AssemblerRejectNotInVs11, AssemblerReject, testing::ValuesIn(kNotInVs11),
                         [](const auto& info) { return info.param.name; });

// Operands: counts, masks, swizzles, register names, constant indices (§2.2-§2.4).
const RejectCase kOperands[] = {
    {"TooFewOperands", "vs_1_1\nmov r0\n", 2, 1, DiagnosticCode::kOperandCount, "2"},
    {"TooManyOperands", "vs_1_1\nadd r0, r1, r2, r3\n", 2, 1, DiagnosticCode::kOperandCount, "3"},
    {"OperandForNop", "vs_1_1\nnop r0\n", 2, 1, DiagnosticCode::kOperandCount, "0"},
    {"MissingComma", "vs_1_1\nmov r0 r1\n", 2, 8, DiagnosticCode::kUnexpectedToken, "'r1'"},
    {"EmptyOperand", "vs_1_1\nmov r0,, r1\n", 2, 8, DiagnosticCode::kOperandCount, ""},
    {"TrailingComma", "vs_1_1\nmov r0, r1,\n", 2, 12, DiagnosticCode::kOperandCount, ""},
    {"DefTooFewValues", "vs_1_1\ndef c0, 1, 2, 3\n", 2, 1, DiagnosticCode::kOperandCount, "5"},
    {"DefRegisterAsValue", "vs_1_1\ndef c0, 1, 2, 3, r0\n", 2, 18, DiagnosticCode::kExpectedNumber, "'r0'"},
    {"DefFloatTooLarge", "vs_1_1\ndef c0, 1e50, 0, 0, 0\n", 2, 9, DiagnosticCode::kNumberOutOfRange, ""},
    {"DclWithoutUsage", "vs_1_1\ndcl v0\n", 2, 1, DiagnosticCode::kDeclarationUsage, ""},
    {"DclUnknownUsage", "vs_1_1\ndcl_2d v0\n", 2, 1, DiagnosticCode::kDeclarationUsage, "'2d'"},
    {"DclUsageIndexTooLarge", "vs_1_1\ndcl_texcoord16 v0\n", 2, 1, DiagnosticCode::kDeclarationUsage, "16"},
    {"MaskRepeatsComponent", "vs_1_1\nmov r0.xxyz, r1\n", 2, 8, DiagnosticCode::kWriteMaskSyntax, ""},
    {"MaskOutOfOrder", "vs_1_1\nmov r0.yx, r1\n", 2, 8, DiagnosticCode::kWriteMaskSyntax, ""},
    {"MaskEmpty", "vs_1_1\nmov r0., r1\n", 2, 8, DiagnosticCode::kWriteMaskSyntax, ""},
    {"MaskBadLetter", "vs_1_1\nmov r0.xq, r1\n", 2, 8, DiagnosticCode::kWriteMaskSyntax, "'q'"},
    {"SwizzleTooLong", "vs_1_1\nmov r0, r1.xyzwx\n", 2, 12, DiagnosticCode::kSwizzleSyntax, ""},
    {"SwizzleEmpty", "vs_1_1\nmov r0, r1.\n", 2, 12, DiagnosticCode::kSwizzleSyntax, ""},
    {"SwizzleBadLetter", "vs_1_1\nmov r0, r1.xk\n", 2, 12, DiagnosticCode::kSwizzleSyntax, "'k'"},
    {"SwizzleNumber", "vs_1_1\nmov r0, r1.5\n", 2, 12, DiagnosticCode::kSwizzleSyntax, "'5'"},
    {"NegatedDestination", "vs_1_1\nmov -r0, r1\n", 2, 5, DiagnosticCode::kDestinationSyntax, ""},
    {"DoubleNegation", "vs_1_1\nmov r0, --r1\n", 2, 10, DiagnosticCode::kSourceModifier, ""},
    {"ImmediateSource", "vs_1_1\nadd r0, r1, 2.0\n", 2, 13, DiagnosticCode::kExpectedRegister, "'2.0'"},
    {"UnknownRegister", "vs_1_1\nmov r0, q1\n", 2, 9, DiagnosticCode::kUnknownRegister, "'q1'"},
    {"NumberOnFixedOutput", "vs_1_1\nmov oPos1, r0\n", 2, 5, DiagnosticCode::kUnknownRegister, "'oPos1'"},
    {"RegisterWithoutNumber", "vs_1_1\nmov r, r1\n", 2, 5, DiagnosticCode::kUnknownRegister, "'r'"},
    {"RegisterBeyondField", "vs_1_1\nmov r0, c5000\n", 2, 9, DiagnosticCode::kRegisterNumberTooLarge, "11"},
    {"HugeRegisterNumber", "vs_1_1\nmov r99999999999999999999, r0\n", 2, 5, DiagnosticCode::kRegisterNumberTooLarge, "11"},
    {"IndexSumBeyondField", "vs_1_1\nmov r0, c[2047 + 1]\n", 2, 10, DiagnosticCode::kRegisterNumberTooLarge, "2048"},
    {"NegativeIndex", "vs_1_1\nmov r0, c[a0.x - 3]\n", 2, 10, DiagnosticCode::kConstantIndexSyntax, "3"},
    {"FloatOffset", "vs_1_1\nmov r0, c[a0.x + 1.5]\n", 2, 18, DiagnosticCode::kConstantIndexSyntax, "'1.5'"},
    {"FloatIndex", "vs_1_1\nmov r0, c[2.0]\n", 2, 11, DiagnosticCode::kConstantIndexSyntax, "'2.0'"},
    {"AddressWithoutComponent", "vs_1_1\nmov r0, c0[a0]\n", 2, 12, DiagnosticCode::kConstantIndexSyntax, ""},
    {"AddressOtherComponent", "vs_1_1\nmov r0, c[a0.y]\n", 2, 14, DiagnosticCode::kConstantIndexSyntax, ""},
    {"IndexByTemporary", "vs_1_1\nmov r0, c[r0.x]\n", 2, 11, DiagnosticCode::kConstantIndexSyntax, "'r0'"},
    {"AddressTwice", "vs_1_1\nmov r0, c[a0.x + a0.x]\n", 2, 18, DiagnosticCode::kConstantIndexSyntax, ""},
    {"AddressSubtracted", "vs_1_1\nmov r0, c[5 - a0.x]\n", 2, 15, DiagnosticCode::kConstantIndexSyntax, ""},
    {"EmptyIndex", "vs_1_1\nmov r0, c[]\n", 2, 11, DiagnosticCode::kConstantIndexSyntax, ""},
    {"UnclosedIndex", "vs_1_1\nmov r0, c[1\n", 2, 12, DiagnosticCode::kConstantIndexSyntax, "']'"},
    {"JunkInIndex", "vs_1_1\nmov r0, c[1 2]\n", 2, 13, DiagnosticCode::kConstantIndexSyntax, "'+'"},
    {"RelativeInput", "vs_1_1\nmov r0, v[a0.x]\n", 2, 10, DiagnosticCode::kConstantIndexSyntax, ""},
    {"RelativeTemporary", "vs_1_1\nmov r0, r0[a0.x]\n", 2, 11, DiagnosticCode::kConstantIndexSyntax, ""},
    {"RelativeDestination", "vs_1_1\nmov c[a0.x], r0\n", 2, 5, DiagnosticCode::kDestinationSyntax, ""},
    {"RelativeOutput", "vs_1_1\nmov oT0[a0.x], r0\n", 2, 8, DiagnosticCode::kConstantIndexSyntax, ""},
};
INSTANTIATE_TEST_SUITE_P(AssemblerRejectOperands, AssemblerReject, testing::ValuesIn(kOperands),
                         [](const auto& info) { return info.param.name; });

TEST(AssemblerRejects, ReportsEveryBadLineInOneRun) {
  AssembleResult result = AssembleUnvalidated(
      "vs_1_1\nmov_sat r0, r1\nmov r0, r1\nlrp r0, r1, r2, r3\nmov r0.yx, r1\nmov oPos, v0\nmov r0, c[a0]\n");
  EXPECT_FALSE(result.program);
  ASSERT_EQ(result.diagnostics.error_count(), 4);
  const std::vector<Diagnostic>& all = result.diagnostics.all();
  EXPECT_EQ(all[0].loc.line, 2);
  EXPECT_EQ(all[1].loc.line, 4);
  EXPECT_EQ(all[2].loc.line, 5);
  EXPECT_EQ(all[3].loc.line, 7);
}

TEST(AssemblerRejects, ColumnsFollowTheOriginalTextThroughMacros) {
  // The expansion of BAD takes the column of the macro name (vm/asm/preprocessor.h).
  AssembleResult result = AssembleUnvalidated("#define BAD r1_abs\nvs_1_1\nmov r0,   BAD\n");
  ASSERT_TRUE(result.diagnostics.HasErrors());
  EXPECT_EQ(result.diagnostics.all().front().loc, (SourceLoc{"bad.vsh", 3, 11}));
}

TEST(AssemblerRejects, AcceptsNothingAfterAnError) {
  // One bad line withholds the whole program even though the rest is fine.
  AssembleResult result = AssembleUnvalidated("vs_1_1\nmov oPos, v0\nmov oPos, v0 v1\n");
  EXPECT_FALSE(result.program);
  EXPECT_EQ(result.diagnostics.error_count(), 1);
}

}  // namespace
}  // namespace vs11

// Sources the assembler must reject for their syntax (spec §2), each with the place and the words of
// the first error. Rules that need the whole program (read ports, ranges, dcl) belong to the
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
  int column;           // 0: not checked (e.g. the error comes from the preprocessor)
  std::string message;  // a distinctive part of the first error's text
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
  EXPECT_NE(first.message.find(c.message), std::string::npos) << "message: " << first.message;
}

const RejectCase kStructure[] = {
    {"EmptySource", "", 1, 1, "missing version statement"},
    {"InstructionBeforeVersion", "mov oPos, v0\nvs_1_1\n", 1, 1, "first statement must be the version"},
    {"SecondVersion", "vs_1_1\nmov oPos, v0\nvs_1_1\n", 3, 1, "must come first and only once"},
    {"PixelShaderVersion", "ps_1_1\n", 1, 1, "unsupported shader version 'ps_1_1'"},
    {"LaterVertexVersion", "vs_2_0\n", 1, 1, "unsupported shader version 'vs_2_0'"},
    {"Dx8LaterVersion", "vs.2.0\n", 1, 1, "unsupported shader version 'vs.2.0'"},
    {"InstructionOnVersionLine", "vs_1_1 mov oPos, v0\n", 1, 8, "unexpected 'mov' after the version"},
    {"BadDx8VersionNumber", "vs.1.1.1\n", 1, 4, "malformed number '1.1.1'"},
    {"UnknownInstruction", "vs_1_1\nfoo r0, r1\n", 2, 1, "unknown instruction 'foo'"},
    {"UnexpectedCharacter", "vs_1_1\nmov r0, r1 @\n", 2, 12, "unexpected character '@'"},
    {"MalformedNumber", "vs_1_1\ndef c0, 1x, 0, 0, 0\n", 2, 9, "malformed number '1x'"},
    {"PreprocessorMissingInclude", "#include \"nowhere.h\"\nvs_1_1\n", 1, 0, "nowhere.h"},
};
INSTANTIATE_TEST_SUITE_P(AssemblerRejectStructure, AssemblerReject, testing::ValuesIn(kStructure),
                         [](const auto& info) { return info.param.name; });

// §2.5-§2.6 and §4.7: modifiers and instructions that vs_1_1 does not have.
const RejectCase kNotInVs11[] = {
    {"SaturateModifier", "vs_1_1\nmov_sat r0, r1\n", 2, 1, "instruction modifier '_sat' is not available"},
    {"ShiftModifier", "vs_1_1\nmul_x2 r0, r1, r2\n", 2, 1, "instruction modifier '_x2' is not available"},
    {"PartialPrecision", "vs_1_1\nadd_pp r0, r1, r2\n", 2, 1, "instruction modifier '_pp'"},
    {"AbsSourceModifier", "vs_1_1\nmov r0, r1_abs\n", 2, 9, "source modifier '_abs' is not available"},
    {"BiasSourceModifier", "vs_1_1\nadd r0, r1, c0_bias\n", 2, 13, "source modifier '_bias'"},
    {"SignedScaleModifier", "vs_1_1\nmov r0, v0_bx2\n", 2, 9, "source modifier '_bx2'"},
    {"TimesTwoModifier", "vs_1_1\nmov r0, r1_x2\n", 2, 9, "source modifier '_x2'"},
    {"ModifierAfterSwizzle", "vs_1_1\nmov r0, r1.x_abs\n", 2, 12, "source modifier '_abs'"},
    {"ComplementModifier", "vs_1_1\nadd r0, 1-r1, r2\n", 2, 9, "complement source modifier '1-'"},
    {"NotModifier", "vs_1_1\nmov r0, !r1\n", 2, 9, "'!' source modifier"},
    {"CoIssue", "vs_1_1\nmov r0, r1\n+mov r2, r1\n", 3, 1, "co-issue"},
    {"Predicate", "vs_1_1\n(p0) mov r0, r1\n", 2, 1, "predication"},
    {"Lrp", "vs_1_1\nlrp r0, r1, r2, r3\n", 2, 1, "'lrp' is not a vs_1_1 instruction"},
    {"Pow", "vs_1_1\npow r0, r1.x, r2.x\n", 2, 1, "'pow' is not a vs_1_1 instruction"},
    {"Mova", "vs_1_1\nmova a0.x, r1.x\n", 2, 1, "'mova' is not a vs_1_1 instruction"},
    {"Sincos", "vs_1_1\nsincos r0.xy, r1.x\n", 2, 1, "'sincos' is not a vs_1_1 instruction"},
    {"Nrm", "vs_1_1\nnrm r0, r1\n", 2, 1, "'nrm' is not a vs_1_1 instruction"},
    {"PixelTexld", "vs_1_1\ntexld r0, t0\n", 2, 1, "'texld' is not a vs_1_1 instruction"},
};
INSTANTIATE_TEST_SUITE_P(AssemblerRejectNotInVs11, AssemblerReject, testing::ValuesIn(kNotInVs11),
                         [](const auto& info) { return info.param.name; });

// Operands: counts, masks, swizzles, register names, constant indices (§2.2-§2.4).
const RejectCase kOperands[] = {
    {"TooFewOperands", "vs_1_1\nmov r0\n", 2, 1, "mov takes 2 operands (dest, src), found 1"},
    {"TooManyOperands", "vs_1_1\nadd r0, r1, r2, r3\n", 2, 1, "add takes 3 operands (dest, src, src), found 4"},
    {"OperandForNop", "vs_1_1\nnop r0\n", 2, 1, "nop takes 0 operands"},
    {"MissingComma", "vs_1_1\nmov r0 r1\n", 2, 8, "unexpected 'r1' after the destination"},
    {"EmptyOperand", "vs_1_1\nmov r0,, r1\n", 2, 8, "missing operand"},
    {"TrailingComma", "vs_1_1\nmov r0, r1,\n", 2, 12, "missing operand"},
    {"DefTooFewValues", "vs_1_1\ndef c0, 1, 2, 3\n", 2, 1, "def takes 5 operands"},
    {"DefRegisterAsValue", "vs_1_1\ndef c0, 1, 2, 3, r0\n", 2, 18, "expected a number, found 'r0'"},
    {"DefFloatTooLarge", "vs_1_1\ndef c0, 1e50, 0, 0, 0\n", 2, 9, "too large for a 32-bit float"},
    {"DclWithoutUsage", "vs_1_1\ndcl v0\n", 2, 1, "dcl needs a usage"},
    {"DclUnknownUsage", "vs_1_1\ndcl_2d v0\n", 2, 1, "unknown dcl usage '2d'"},
    {"DclUsageIndexTooLarge", "vs_1_1\ndcl_texcoord16 v0\n", 2, 1, "dcl usage index 16 is out of range"},
    {"MaskRepeatsComponent", "vs_1_1\nmov r0.xxyz, r1\n", 2, 8, "repeats a component"},
    {"MaskOutOfOrder", "vs_1_1\nmov r0.yx, r1\n", 2, 8, "not in xyzw order"},
    {"MaskEmpty", "vs_1_1\nmov r0., r1\n", 2, 8, "empty write mask"},
    {"MaskBadLetter", "vs_1_1\nmov r0.xq, r1\n", 2, 8, "'q' is not a write mask letter"},
    {"SwizzleTooLong", "vs_1_1\nmov r0, r1.xyzwx\n", 2, 12, "more than four components"},
    {"SwizzleEmpty", "vs_1_1\nmov r0, r1.\n", 2, 12, "empty swizzle"},
    {"SwizzleBadLetter", "vs_1_1\nmov r0, r1.xk\n", 2, 12, "'k' is not a swizzle letter"},
    {"SwizzleNumber", "vs_1_1\nmov r0, r1.5\n", 2, 12, "expected swizzle letters, found '5'"},
    {"NegatedDestination", "vs_1_1\nmov -r0, r1\n", 2, 5, "a destination cannot be negated"},
    {"DoubleNegation", "vs_1_1\nmov r0, --r1\n", 2, 10, "double negation"},
    {"ImmediateSource", "vs_1_1\nadd r0, r1, 2.0\n", 2, 13, "not the number '2.0'"},
    {"UnknownRegister", "vs_1_1\nmov r0, q1\n", 2, 9, "unknown register 'q1'"},
    {"NumberOnFixedOutput", "vs_1_1\nmov oPos1, r0\n", 2, 5, "unknown register 'oPos1'"},
    {"RegisterWithoutNumber", "vs_1_1\nmov r, r1\n", 2, 5, "register 'r' needs a number"},
    {"RegisterBeyondField", "vs_1_1\nmov r0, c5000\n", 2, 9, "does not fit the 11-bit register field"},
    {"HugeRegisterNumber", "vs_1_1\nmov r99999999999999999999, r0\n", 2, 5, "does not fit the 11-bit"},
    {"IndexSumBeyondField", "vs_1_1\nmov r0, c[2047 + 1]\n", 2, 10, "constant index 2048 does not fit"},
    {"NegativeIndex", "vs_1_1\nmov r0, c[a0.x - 3]\n", 2, 10, "constant index -3 is negative"},
    {"FloatOffset", "vs_1_1\nmov r0, c[a0.x + 1.5]\n", 2, 18, "must be an integer, not '1.5'"},
    {"FloatIndex", "vs_1_1\nmov r0, c[2.0]\n", 2, 11, "must be an integer, not '2.0'"},
    {"AddressWithoutComponent", "vs_1_1\nmov r0, c0[a0]\n", 2, 12, "needs a0.x"},
    {"AddressOtherComponent", "vs_1_1\nmov r0, c[a0.y]\n", 2, 14, "only a0.x can index constants"},
    {"IndexByTemporary", "vs_1_1\nmov r0, c[r0.x]\n", 2, 11, "only integers and a0.x, not 'r0'"},
    {"AddressTwice", "vs_1_1\nmov r0, c[a0.x + a0.x]\n", 2, 18, "a0.x appears twice"},
    {"AddressSubtracted", "vs_1_1\nmov r0, c[5 - a0.x]\n", 2, 15, "a0.x cannot be subtracted"},
    {"EmptyIndex", "vs_1_1\nmov r0, c[]\n", 2, 11, "missing value in the constant index"},
    {"UnclosedIndex", "vs_1_1\nmov r0, c[1\n", 2, 12, "missing ']'"},
    {"JunkInIndex", "vs_1_1\nmov r0, c[1 2]\n", 2, 13, "expected '+', '-' or ']'"},
    {"RelativeInput", "vs_1_1\nmov r0, v[a0.x]\n", 2, 10, "only constant registers can be indexed"},
    {"RelativeTemporary", "vs_1_1\nmov r0, r0[a0.x]\n", 2, 11, "only constant registers can be indexed"},
    {"RelativeDestination", "vs_1_1\nmov c[a0.x], r0\n", 2, 5, "a destination cannot be relatively addressed"},
    {"RelativeOutput", "vs_1_1\nmov oT0[a0.x], r0\n", 2, 8, "only constant registers can be indexed"},
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

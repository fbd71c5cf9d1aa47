// The later models' read ports (vm/asm/read_ports.h), their reads of unwritten temporaries, a0 and p0 along
// the flow control (vm/asm/temporary_dataflow.h) and the operand rules of sgn, nrm, mova and the conditions
// (validator_models.cc):
// for each rule a program that keeps it and one that breaks it, in each model the rule applies to.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "vm/asm/assembler.h"
#include "vm/asm/validator.h"

namespace vs11 {
namespace {

std::optional<std::string> NoFiles(const std::filesystem::path&) { return std::nullopt; }

std::string Messages(const Diagnostics& diagnostics) {
  std::string text;
  for (const Diagnostic& d : diagnostics.all()) text += FormatDiagnostic(d) + "\n";
  return text;
}

// `body` after a head that declares v0 and v1 and writes the position (lines 1-5): the body starts at
// line 6.
AssembleResult Check(const std::string& model, const std::string& body) {
  const std::string position =
      model == "vs_3_0" ? "dcl_position o0\nmov o0, v0\n" : "mov oPos, v0\nmov oD0, c0\n";
  return AssembleSource(model + "\ndcl_position v0\ndcl_normal v1\n" + position + body, "m.vsh", {}, NoFiles);
}
constexpr int kBodyLine = 6;

const Diagnostic* Find(const Diagnostics& diagnostics, Severity severity, DiagnosticCode code, int line) {
  for (const Diagnostic& d : diagnostics.all()) {
    if (d.severity == severity && d.code == code && d.loc.line == line && d.loc.column >= 1) return &d;
  }
  return nullptr;
}

int CountWithCode(const Diagnostics& diagnostics, DiagnosticCode code) {
  int count = 0;
  for (const Diagnostic& d : diagnostics.all()) count += d.code == code;
  return count;
}

const std::vector<std::string> kLaterModels = {"vs_2_0", "vs_2_x", "vs_3_0"};

void ExpectClean(const std::string& model, const std::string& body) {
  const AssembleResult result = Check(model, body);
  EXPECT_TRUE(result.program) << model << "\n" << body << Messages(result.diagnostics);
  EXPECT_TRUE(result.diagnostics.all().empty()) << model << "\n" << body << Messages(result.diagnostics);
}

// The error `code` on body line `body_line` (1 = the first body line); returns its message.
std::string ExpectError(const std::string& model, const std::string& body, DiagnosticCode code, int body_line) {
  const AssembleResult result = Check(model, body);
  EXPECT_FALSE(result.program) << model << "\n" << body;
  const Diagnostic* d = Find(result.diagnostics, Severity::kError, code, kBodyLine + body_line - 1);
  EXPECT_NE(d, nullptr) << model << " " << DiagnosticCodeName(code) << " at body line " << body_line << ":\n"
                        << body << Messages(result.diagnostics);
  return d ? d->message : "";
}

std::string ExpectWarningOnly(const std::string& model, const std::string& body, DiagnosticCode code, int body_line) {
  const AssembleResult result = Check(model, body);
  EXPECT_TRUE(result.program) << model << "\n" << body << Messages(result.diagnostics);
  const Diagnostic* d = Find(result.diagnostics, Severity::kWarning, code, kBodyLine + body_line - 1);
  EXPECT_NE(d, nullptr) << model << " " << DiagnosticCodeName(code) << " warning at body line " << body_line
                        << ":\n" << body << Messages(result.diagnostics);
  return d ? d->message : "";
}

// --- read ports ----------------------------------------------------------------------------------

TEST(LaterModelReadPorts, OneConstantAndOneInputPerInstructionInEveryLaterModel) {
  for (const std::string& model : kLaterModels) {
    ExpectClean(model, "mad r0, c0, c0, v0\nadd r1, v0, c1\nmad r2, v1, v1, r0\nm4x4 r3, v0, c4\n");
    const std::string message = ExpectError(model, "add r0, c0, c1\n", DiagnosticCode::kReadPorts, 1);
    EXPECT_NE(message.find("reads two different constant registers (c0, c1); " + model +
                           " allows one per instruction (the read-port limit of the D3D9 reference's " + model +
                           " registers page)"),
              std::string::npos)
        << message;
    ExpectError(model, "add r0, v0, v1\n", DiagnosticCode::kReadPorts, 1);
    ExpectError(model, "mad r0, c0, c1, c2\n", DiagnosticCode::kReadPorts, 1);
    // m4x4's rows are counted one at a time (§3.4): row 0 reads c4 and c0.
    const std::string row = ExpectError(model, "m4x4 r0, c4, c0\n", DiagnosticCode::kReadPorts, 1);
    EXPECT_NE(row.find("row 0 of the macro expansion"), std::string::npos) << row;
  }
}

// The reference's "# reads/inst": vs_2_0 and vs_2_x read c# at most twice per instruction, the same
// register or not; vs_3_0 without limit.
TEST(LaterModelReadPorts, Vs2ReadsAConstantAtMostTwicePerInstruction) {
  for (const std::string& model : {std::string("vs_2_0"), std::string("vs_2_x")}) {
    const std::string message = ExpectError(model, "mad r0, c0, c0, c0\n", DiagnosticCode::kReadPorts, 1);
    EXPECT_NE(message.find("reads constant registers 3 times (c0, c0, c0); " + model +
                           " allows 2 constant reads per instruction"),
              std::string::npos)
        << message;
  }
  ExpectClean("vs_3_0", "mad r0, c0, c0, c0\n");
}

TEST(LaterModelReadPorts, RelativeConstantsCountAsDifferentUnlessTheSameOperand) {
  for (const std::string& model : kLaterModels) {
    ExpectClean(model, "mova a0, c0\nadd r0, c1[a0.x], c1[a0.x]\n");
    // Wine's vs_2_0 case 11, which Microsoft's validator refuses: two relative constants.
    ExpectError(model, "mova a0, c0\nadd r0, c0[a0.x], c1[a0.y]\n", DiagnosticCode::kReadPorts, 2);
    ExpectError(model, "mova a0, c0\nadd r0, c1[a0.x], c1[a0.y]\n", DiagnosticCode::kReadPorts, 2);
    ExpectError(model, "mova a0, c0\nadd r0, c1, c1[a0.x]\n", DiagnosticCode::kReadPorts, 2);
  }
}

TEST(LaterModelReadPorts, SincosConstantOperandsAreNotPorts) {
  for (const std::string& model : {std::string("vs_2_0"), std::string("vs_2_x")}) {
    ExpectClean(model, "mov r0, c0\nsincos r1.xy, r0.x, c3, c4\n");
    ExpectError(model, "sincos r1.xy, v0.x, c3, c4\nsincos r2.xy, v1.x, c3, c4\nadd r0, v0, v1\n",
                DiagnosticCode::kReadPorts, 3);
  }
}

TEST(LaterModelReadPorts, Vs11MessageIsUnchanged) {
  const AssembleResult result =
      AssembleSource("vs_1_1\ndcl_position v0\nadd oPos, c0, c1\n", "m.vsh", {}, NoFiles);
  ASSERT_FALSE(result.program);
  const Diagnostic* d = Find(result.diagnostics, Severity::kError, DiagnosticCode::kReadPorts, 3);
  ASSERT_NE(d, nullptr) << Messages(result.diagnostics);
  EXPECT_EQ(d->message, "add: reads two different constant registers (c0, c1); vs_1_1 allows one per instruction "
                        "— copy one of them into a temporary first");
}

// --- sgn, nrm, mova ------------------------------------------------------------------------------

TEST(LaterModelOperandRules, SgnScratchRegistersAreTwoDifferentTemporaries) {
  for (const std::string& model : kLaterModels) {
    ExpectClean(model, "sgn r0, c0, r1, r2\n");  // the scratch registers need not be written
    ExpectError(model, "sgn r0, c0, r1, r1\n", DiagnosticCode::kBadOperand, 1);
    ExpectError(model, "mov r1, c0\nsgn r0, r1, c1, r2\n", DiagnosticCode::kBadOperand, 2);
  }
}

// "Their contents are undefined after execution": a read of a scratch register after sgn is a warning.
TEST(LaterModelOperandRules, SgnLeavesItsScratchRegistersUndefined) {
  for (const std::string& model : kLaterModels) {
    const std::string message = ExpectWarningOnly(model, "mov r1, c0\nsgn r0, c0, r1, r2\nadd r3, r1, c1\n",
                                                  DiagnosticCode::kUninitializedLanes, 3);
    EXPECT_NE(message.find("an earlier sgn left undefined"), std::string::npos) << message;
    ExpectClean(model, "sgn r0, c0, r1, r2\nmov r1, c1\nadd r3, r1, c1\n");
    ExpectWarningOnly(model, "mov r1, c0\ncall l0\nadd r3, r1, c1\nret\nlabel l0\nsgn r0, c0, r1, r2\nret\n",
                      DiagnosticCode::kUninitializedLanes, 3);
    ExpectWarningOnly(model, "mov r1, c0\nif b0\nsgn r0, c0, r1, r2\nendif\nadd r3, r1, c1\n",
                      DiagnosticCode::kUninitializedLanes, 5);
  }
}

TEST(LaterModelOperandRules, NrmWritesATemporaryOtherThanItsSource) {
  for (const std::string& model : kLaterModels) {
    ExpectClean(model, "mov r0, c0\nnrm r1, r0\nmov r2.xyz, c0\nnrm r3.xyz, r2\n");
    ExpectError(model, "mov r0, c0\nnrm r0, r0\n", DiagnosticCode::kBadOperand, 2);
  }
  ExpectError("vs_2_0", "mov r0, c0\nnrm oT0, r0\n", DiagnosticCode::kBadOperand, 2);
  ExpectError("vs_3_0", "mov r0, c0\nnrm o1, r0\n", DiagnosticCode::kBadOperand, 2);
}

TEST(LaterModelOperandRules, MovaWritesA0WithAnyMask) {
  for (const std::string& model : kLaterModels) {
    ExpectClean(model, "mova a0.xz, c0\nmova a0.y, c0.z\nmova a0, c1\n");
    ExpectError(model, "mova r0, c0\n", DiagnosticCode::kBadOperand, 1);
  }
}

// --- unwritten temporaries along the flow control --------------------------------------------------

TEST(LaterModelUnwrittenTemporaries, StraightLineReads) {
  for (const std::string& model : kLaterModels) {
    ExpectClean(model, "mov r1, c0\nmov r0, r1\n");
    const std::string never = ExpectError(model, "mov r0, r1\n", DiagnosticCode::kUninitializedRegister, 1);
    EXPECT_NE(never.find("reads r1.xyzw before it is written on any path"), std::string::npos) << never;
    const std::string lanes = ExpectError(model, "mov r1.xy, c0\nmov r0, r1\n", DiagnosticCode::kUninitializedLanes, 2);
    EXPECT_NE(lanes.find("r1.zw"), std::string::npos) << lanes;
    ExpectClean(model, "mov r1.xy, c0\nmov r0.xy, r1\nmul r2, r1.xxyy, c1\n");
  }
}

TEST(LaterModelUnwrittenTemporaries, LanesOfTheLaterInstructions) {
  for (const std::string& model : kLaterModels) {
    ExpectClean(model, "mov r1.xyz, c0\nmov r2.xyz, c1\ncrs r3.xyz, r1, r2\nnrm r4.xyz, r1\nmov r5.x, c0\n"
                       "pow r6, r5.x, r5.x\nabs r7.xy, r5.xxxx\nlrp r8.x, r5.x, r5.x, r5.x\n");
    ExpectError(model, "mov r1.xy, c0\nmov r2.xyz, c1\ncrs r3.xyz, r1, r2\n", DiagnosticCode::kUninitializedLanes, 3);
    ExpectError(model, "mov r5.x, c0\npow r6, r5.y, r5.x\n", DiagnosticCode::kUninitializedLanes, 2);
  }
  ExpectError("vs_3_0", "dcl_2d s0\nmov r1.xyz, c0\ntexldl r0, r1, s0\n", DiagnosticCode::kUninitializedLanes, 3);
  ExpectError("vs_2_x", "mov r1.x, c0\nif_gt r1.x, r2.x\nendif\n", DiagnosticCode::kUninitializedRegister, 2);
}

TEST(LaterModelUnwrittenTemporaries, IfSidesJoin) {
  for (const std::string& model : kLaterModels) {
    // Written in both sides: fine.
    ExpectClean(model, "if b0\nmov r1, c0\nelse\nmov r1, c1\nendif\nmov r0, r1\n");
    // Written in the if side only: a warning that says so.
    const std::string some = ExpectWarningOnly(model, "if b0\nmov r1, c0\nendif\nmov r0, r1\n",
                                               DiagnosticCode::kUninitializedLanes, 4);
    EXPECT_NE(some.find("only some paths write"), std::string::npos) << some;
    ExpectWarningOnly(model, "if b0\nelse\nmov r1, c0\nendif\nmov r0, r1\n", DiagnosticCode::kUninitializedLanes, 5);
    // Written in neither: an error.
    ExpectError(model, "if b0\nmov r2, c0\nendif\nmov r0, r1\n", DiagnosticCode::kUninitializedRegister, 4);
  }
}

TEST(LaterModelUnwrittenTemporaries, LoopBodiesAreCheckedOnTheirFirstIteration) {
  for (const std::string& model : kLaterModels) {
    for (const std::string& loop : {std::string("rep i0\n"), std::string("loop aL, i0\n")}) {
      const std::string end = loop[0] == 'r' ? "endrep\n" : "endloop\n";
      ExpectClean(model, "mov r0, c0\n" + loop + "add r0, r0, c1\n" + end + "mov r2, r0\n");
      // Written after the read in the body: unwritten on the first iteration.
      const std::string first = ExpectError(model, loop + "add r0, r1, c0\nmov r1, c1\n" + end,
                                            DiagnosticCode::kUninitializedRegister, 2);
      EXPECT_NE(first.find("first iteration"), std::string::npos) << first;
      // Written only in the body, read after it: the loop may run no iteration.
      ExpectWarningOnly(model, loop + "mov r1, c0\n" + end + "mov r0, r1\n", DiagnosticCode::kUninitializedLanes, 4);
    }
  }
}

TEST(LaterModelUnwrittenTemporaries, BreakEndsItsPath) {
  for (const std::string& model : {std::string("vs_2_x"), std::string("vs_3_0")}) {
    ExpectClean(model, "rep i0\nif b0\nmov r1, c0\nelse\nbreak\nendif\nadd r2, r1, c1\nendrep\n");
    ExpectWarningOnly(model,
                      "setp_gt p0, v0, c0\nrep i0\nif b0\nmov r1, c0\nelse\nbreakp p0.x\nendif\nadd r2, r1, c1\n"
                      "endrep\n",
                      DiagnosticCode::kUninitializedLanes, 8);
  }
}

TEST(LaterModelUnwrittenTemporaries, PredicatedWritesMayNotHappen) {
  for (const std::string& model : {std::string("vs_2_x"), std::string("vs_3_0")}) {
    ExpectWarningOnly(model, "setp_gt p0, v0, c0\n(p0) mov r1, c0\nmov r0, r1\n", DiagnosticCode::kUninitializedLanes,
                      3);
    ExpectClean(model, "setp_gt p0, v0, c0\nmov r1, c1\n(p0) mov r1, c0\nmov r0, r1\n");
  }
}

TEST(LaterModelUnwrittenTemporaries, Subroutines) {
  for (const std::string& model : kLaterModels) {
    // Written in a subroutine before the call site reads it: fine.
    ExpectClean(model, "call l0\nmov r0, r1\nret\nlabel l0\nmov r1, c0\nret\n");
    // callnz may not call it.
    ExpectWarningOnly(model, "callnz l0, b0\nmov r0, r1\nret\nlabel l0\nmov r1, c0\nret\n",
                      DiagnosticCode::kUninitializedLanes, 2);
    // The subroutine reads what every call site wrote first: fine.
    ExpectClean(model, "mov r1, c0\ncall l0\ncall l0\nret\nlabel l0\nadd r2, r1, c1\nret\n");
    // Only the second call site wrote it: a warning in the subroutine.
    const std::string some = ExpectWarningOnly(model, "call l0\nmov r1, c0\ncall l0\nret\nlabel l0\nadd r2, r1, c1\nret\n",
                                               DiagnosticCode::kUninitializedLanes, 6);
    EXPECT_NE(some.find("a call of l0 without it"), std::string::npos) << some;
    // No call site wrote it: an error on the subroutine's line.
    const std::string none = ExpectError(model, "call l0\nret\nlabel l0\nadd r2, r1, c1\nret\n",
                                         DiagnosticCode::kUninitializedRegister, 4);
    EXPECT_NE(none.find("on entry to l0"), std::string::npos) << none;
    // A subroutine called by another, and one never called (never checked).
    ExpectClean(model, "call l1\nmov r0, r3\nret\nlabel l1\nmov r2, c0\ncall l2\nret\nlabel l2\nmov r3, r2\nret\n"
                       "label l3\nmov r0, r9\nret\n");
  }
}

TEST(LaterModelUnwrittenTemporaries, CallsInLoopsAndLoopsInSubroutines) {
  for (const std::string& model : kLaterModels) {
    ExpectClean(model, "rep i0\ncall l0\nadd r2, r1, c0\nendrep\nret\nlabel l0\nmov r1, c0\nret\n");
    ExpectError(model, "rep i0\nadd r2, r1, c0\ncall l0\nendrep\nret\nlabel l0\nmov r1, c0\nret\n",
                DiagnosticCode::kUninitializedRegister, 2);
    ExpectError(model, "call l0\nret\nlabel l0\nrep i0\nadd r0, r1, c0\nmov r1, c0\nendrep\nret\n",
                DiagnosticCode::kUninitializedRegister, 5);
  }
}

// Hostile shapes the validator refuses for their nesting: the walk still ends, and still reports the reads
// (bounded by design: each section is walked once for its effect and once for its reads, and neither the
// call chain nor the loop notes go deeper than any model allows).
TEST(LaterModelUnwrittenTemporaries, DeepNestingAndLongCallChainsFinish) {
  std::string nested;
  for (int i = 0; i < 3000; ++i) nested += "rep i0\nadd r0, r1, c0\n";
  for (int i = 0; i < 3000; ++i) nested += "mov r1, c0\nendrep\n";
  const AssembleResult loops = Check("vs_2_0", nested);
  EXPECT_FALSE(loops.program);
  // 2996 loops past the depth of 4, then every add's read of r1 (past the kept errors, counted).
  EXPECT_GE(loops.diagnostics.error_count(), 2996 + 3000);

  std::string chain = "call l0\nmov r0, r5\nret\n";
  for (int i = 0; i < 2000; ++i) chain += fmt::format("label l{}\ncall l{}\nret\n", i, i + 1);
  chain += "label l2000\nmov r5, c0\nret\n";
  const AssembleResult calls = Check("vs_2_0", chain);
  EXPECT_FALSE(calls.program);
  EXPECT_GE(CountWithCode(calls.diagnostics, DiagnosticCode::kNestingTooDeep), 1) << Messages(calls.diagnostics);
}

TEST(LaterModelUnwrittenTemporaries, BytecodeWithoutSourceNamesTheInstruction) {
  AssembleOptions options;
  options.validate = false;
  const AssembleResult assembled = AssembleSource("vs_2_0\ndcl_position v0\nmov oPos, v0\nmov r0, r1\n", "m.vsh",
                                                  options, NoFiles);
  ASSERT_TRUE(assembled.program);
  Program program = *assembled.program;
  program.source_locs.clear();
  const Diagnostics diagnostics = Validate(program);
  ASSERT_EQ(CountWithCode(diagnostics, DiagnosticCode::kUninitializedRegister), 1) << Messages(diagnostics);
  EXPECT_NE(diagnostics.all().front().message.find("instruction 2 (mov)"), std::string::npos)
      << Messages(diagnostics);
}

// --- a0 and p0 read before mova and setp write them ------------------------------------------------

TEST(LaterModelRegisterDataflow, AddressReadBeforeMovaWritesItAlongTheFlowControl) {
  for (const std::string& model : kLaterModels) {
    ExpectClean(model, "mova a0.x, c0.x\nmov r0, c1[a0.x]\n");
    ExpectClean(model, "mova a0.x, c0.x\ncall l0\nret\nlabel l0\nmov r0, c1[a0.x]\nret\n");
    std::string message = ExpectError(model, "mov r0, c1[a0.x]\n", DiagnosticCode::kAddressNotWritten, 1);
    EXPECT_NE(message.find("reads a0.x, which no path writes before this read; write a0 with mova earlier"),
              std::string::npos)
        << message;
    message = ExpectError(model, "mova a0.x, c0.x\nmov r0, c1[a0.y]\n", DiagnosticCode::kAddressNotWritten, 2);
    EXPECT_NE(message.find("reads a0.y, which no path writes before this read (mova wrote other lanes)"),
              std::string::npos)
        << message;
    message = ExpectError(model, "rep i0\nmov r0, c1[a0.x]\nmova a0.x, c0.x\nendrep\n",
                          DiagnosticCode::kAddressNotWritten, 2);
    EXPECT_NE(message.find("its first iteration reads it unwritten"), std::string::npos) << message;
    message = ExpectWarningOnly(model, "if b0\nmova a0.x, c0.x\nendif\nmov r0, c1[a0.x]\n",
                                DiagnosticCode::kAddressNotWritten, 4);
    EXPECT_NE(message.find("reads a0.x, which only some paths write"), std::string::npos) << message;
  }
}

TEST(LaterModelRegisterDataflow, Vs11AddressRuleIsUnchanged) {
  const AssembleResult result = AssembleSource("vs_1_1\ndcl_position v0\nmov oPos, c[a0.x]\n", "m.vsh", {}, NoFiles);
  const Diagnostic* d = Find(result.diagnostics, Severity::kError, DiagnosticCode::kAddressNotWritten, 3);
  ASSERT_NE(d, nullptr) << Messages(result.diagnostics);
  EXPECT_NE(d->message.find("before a0 is written; put `mov a0.x, <src>` earlier in the program"), std::string::npos)
      << d->message;
}

TEST(LaterModelRegisterDataflow, PredicateReadBeforeSetpWritesIt) {
  for (const std::string& model : {std::string("vs_2_x"), std::string("vs_3_0")}) {
    ExpectClean(model, "setp_gt p0.xw, v0, c0\n(p0.x) mov r0, c1\nif p0.w\nendif\n");
    ExpectError(model, "if p0.x\nendif\n", DiagnosticCode::kUninitializedRegister, 1);
    const std::string message = ExpectError(model, "(!p0) mov r0, c1\n", DiagnosticCode::kUninitializedRegister, 1);
    EXPECT_NE(message.find("reads p0.xyzw, which no path writes before this read; write p0 with setp"),
              std::string::npos)
        << message;
    // The lanes a predicated write takes from p0 are those its mask writes, through the swizzle.
    ExpectError(model, "setp_gt p0.x, v0, c0\n(p0) mov r0.y, c1\n", DiagnosticCode::kUninitializedLanes, 2);
    ExpectClean(model, "setp_gt p0.x, v0, c0\n(p0) mov r0.x, c1\n");
    ExpectError(model, "setp_gt p0.x, v0, c0\nrep i0\nbreakp p0.y\nendrep\n", DiagnosticCode::kUninitializedLanes, 3);
    ExpectWarningOnly(model, "if b0\nsetp_gt p0, v0, c0\nendif\ncallnz l0, p0.x\nret\nlabel l0\nret\n",
                      DiagnosticCode::kUninitializedLanes, 4);
  }
}

// --- conditions and comparisons read one component ------------------------------------------------

TEST(LaterModelOperandRules, ConditionsAndComparisonsReadOneComponent) {
  for (const std::string& model : {std::string("vs_2_x"), std::string("vs_3_0")}) {
    // setp compares lane by lane: any swizzle. A predicate is p0 lane for lane or one lane.
    ExpectClean(model,
                "setp_lt p0, v0.yxwz, c0.zzxy\nif_gt v0.x, c0.y\nendif\nif !p0.z\nendif\nrep i0\n"
                "break_le v0.w, -c0.x\nbreakp !p0.y\nendrep\ncallnz l0, !p0.w\n(p0.y) mov r0, c0\n"
                "(!p0) mov r1, c0\n(p0.xyzw) mov r2, c0\nret\nlabel l0\nret\n");
    for (const auto& [body, line] : std::vector<std::pair<std::string, int>>{
             {"if_gt v0, c0.x\nendif\n", 1},
             {"if_ge v0.x, c0.xy\nendif\n", 1},
             {"rep i0\nbreak_ne v0.x, c0\nendrep\n", 2},
             {"setp_gt p0, v0, c0\nif p0\nendif\n", 2},
             {"setp_gt p0, v0, c0\nrep i0\nbreakp p0.xy\nendrep\n", 3},
             {"setp_gt p0, v0, c0\ncallnz l0, p0\nret\nlabel l0\nret\n", 2},
             {"setp_gt p0, v0, c0\n(p0.yx) mov r0, c0\n", 2},
         }) {
      ExpectError(model, body, DiagnosticCode::kScalarSwizzle, line);
    }
  }
}

}  // namespace
}  // namespace vs11

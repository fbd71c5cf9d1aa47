#include "vm/asm/validator.h"

#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "vm/asm/assembler.h"
#include "vm/core/isa.h"
#include "vm/core/machine.h"
#include "vm/core/program.h"

namespace vs11 {
namespace {

using enum Opcode;
using Dialect = ValidatorOptions::Dialect;

// ---------------------------------------------------------------------------------------------
// A compact way to write programs: Op(kDp4, D(R(1), "x"), C(0), S(R(0), "xyzz")).

constexpr std::string_view kFileName = "test.vsh";
constexpr int kFirstInstructionLine = 2;  // line 1 holds the version statement

RegisterRef R(int i) { return {RegisterFile::kTemp, i, false}; }
RegisterRef V(int i) { return {RegisterFile::kInput, i, false}; }
RegisterRef C(int i) { return {RegisterFile::kConst, i, false}; }
RegisterRef CRel(int offset) { return {RegisterFile::kConst, offset, true}; }  // c[a0.x + offset]
RegisterRef A0() { return {RegisterFile::kAddress, 0, false}; }
RegisterRef OPos() { return {RegisterFile::kRasterOut, kRasterOutPosition, false}; }
RegisterRef OFog() { return {RegisterFile::kRasterOut, kRasterOutFog, false}; }
RegisterRef OPts() { return {RegisterFile::kRasterOut, kRasterOutPointSize, false}; }
RegisterRef OD(int i) { return {RegisterFile::kAttributeOut, i, false}; }
RegisterRef OT(int i) { return {RegisterFile::kTexCoordOut, i, false}; }

int LaneOf(char letter) { return static_cast<int>(std::string_view("xyzw").find(letter)); }

// "xz" -> lanes x and z; "" -> the empty mask.
WriteMask Mask(std::string_view letters) {
  std::uint8_t bits = 0;
  for (char letter : letters) bits |= static_cast<std::uint8_t>(1 << LaneOf(letter));
  return WriteMask(bits);
}

// 1-4 letters, the last one repeated (§2.4): "xy" = .xyyy.
Swizzle Swz(std::string_view letters) {
  std::uint8_t bits = 0;
  for (int lane = 0; lane < 4; ++lane) {
    char letter = letters[std::min<std::size_t>(lane, letters.size() - 1)];
    bits |= static_cast<std::uint8_t>(LaneOf(letter) << (2 * lane));
  }
  return Swizzle(bits);
}

DestOperand D(RegisterRef reg, std::string_view mask = "xyzw") { return {reg, Mask(mask)}; }

struct Src {
  Src(RegisterRef reg, std::string_view swizzle = "xyzw") : operand{reg, Swz(swizzle), false} {}  // NOLINT
  SourceOperand operand;
};
Src S(RegisterRef reg, std::string_view swizzle = "xyzw") { return Src(reg, swizzle); }
Src Neg(Src src) {
  src.operand.negate = true;
  return src;
}

template <class... Sources>
Instruction Op(Opcode opcode, DestOperand dest, Sources... sources) {
  Instruction instruction;
  instruction.opcode = opcode;
  instruction.dest = dest;
  int s = 0;
  ((instruction.sources[s++] = Src(sources).operand), ...);
  return instruction;
}
Instruction Nop() { return Instruction{}; }

Instruction Dcl(std::string_view usage, int usage_index, RegisterRef reg) {
  Instruction instruction;
  instruction.opcode = kDcl;
  instruction.dest = D(reg);
  instruction.usage = *DeclUsageFromName(usage);
  instruction.usage_index = usage_index;
  return instruction;
}
Instruction Def(RegisterRef reg) {
  Instruction instruction;
  instruction.opcode = kDef;
  instruction.dest = D(reg);
  return instruction;
}

// The usual last statement of a test program, so that the oPos rule stays quiet.
Instruction WritePosition() { return Op(kMov, D(OPos()), C(0)); }

// A program as the assembler would build it: instruction i sits on line kFirstInstructionLine + i.
Program Prog(std::vector<Instruction> instructions, std::uint32_t version = kVersionVs11) {
  Program program;
  program.version = version;
  program.instructions = std::move(instructions);
  for (int i = 0; i < static_cast<int>(program.instructions.size()); ++i) {
    program.source_locs.push_back({std::string(kFileName), kFirstInstructionLine + i, 1});
  }
  return program;
}

// A program decoded from bytecode: no source locations.
Program Bytecode(std::vector<Instruction> instructions) {
  Program program;
  program.instructions = std::move(instructions);
  return program;
}

int LineOf(int instruction_index) { return kFirstInstructionLine + instruction_index; }

// ---------------------------------------------------------------------------------------------
// Checks.

// Tests assert the code of a diagnostic, its line and the registers, lanes or numbers it names
// (`facts`), not its wording, which may change.
testing::AssertionResult Has(const Diagnostics& diagnostics, Severity severity, DiagnosticCode code, int line,
                             std::initializer_list<std::string_view> facts) {
  for (const Diagnostic& d : diagnostics.all()) {
    if (d.severity != severity || d.code != code || d.loc.line != line) continue;
    if (std::all_of(facts.begin(), facts.end(),
                    [&](std::string_view fact) { return d.message.find(fact) != std::string::npos; })) {
      return testing::AssertionSuccess();
    }
  }
  std::string wanted;
  for (std::string_view fact : facts) wanted += " \"" + std::string(fact) + "\"";
  return testing::AssertionFailure() << "no " << (severity == Severity::kError ? "error" : "warning") << " ["
                                     << DiagnosticCodeName(code) << "] at line " << line << " naming" << wanted
                                     << " in:\n"
                                     << diagnostics.ToString();
}
testing::AssertionResult HasError(const Diagnostics& d, DiagnosticCode code, int line,
                                  std::initializer_list<std::string_view> facts = {}) {
  return Has(d, Severity::kError, code, line, facts);
}
testing::AssertionResult HasWarning(const Diagnostics& d, DiagnosticCode code, int line,
                                    std::initializer_list<std::string_view> facts = {}) {
  return Has(d, Severity::kWarning, code, line, facts);
}
// For the few messages whose advice is the contract (the --max-constants hint, the a0 fix).
testing::AssertionResult HasErrorText(const Diagnostics& d, DiagnosticCode code, int line, std::string_view text) {
  return Has(d, Severity::kError, code, line, {text});
}
testing::AssertionResult Clean(const Diagnostics& diagnostics) {
  if (diagnostics.all().empty()) return testing::AssertionSuccess();
  return testing::AssertionFailure() << "expected no diagnostics, got:\n" << diagnostics.ToString();
}

// ---------------------------------------------------------------------------------------------
// Programs from .vsh text, through the assembler with its own validation switched off.

Program Assemble(std::string_view text) {
  AssembleOptions options;
  options.validate = false;
  AssembleResult result = AssembleSource(text, std::string(kFileName), options);
  EXPECT_TRUE(result.program.has_value()) << result.diagnostics.ToString();
  return result.program.value_or(Program{});
}

// The irradiance paper's program (spec §9): x1 = cA* . n, vB = n.xyzz * n.yzzx, x2 = cB* . vB,
// vC = x^2 - y^2, result x1 + x2 + cC * vC. The normal arrives in v0; a FLOAT3 element gives v0.w = 1
// (§1.2), which the dp4 of the constant band needs. The first nine instructions, then the last two.
constexpr std::string_view kIrradianceHead = R"(vs_1_1
#define cAr c0
#define cAg c1
#define cAb c2
#define cBr c3
#define cBg c4
#define cBb c5
#define cC  c6
dcl_normal v0
dcl_position v1
dp4 r1.r, cAr, v0          ; x1 = constant + linear terms
dp4 r1.g, cAg, v0
dp4 r1.b, cAb, v0
mul r2, v0.xyzz, v0.yzzx   ; vB = (xy, yz, zz, zx)
dp4 r3.r, cBr, r2          ; x2 = four quadratic terms
dp4 r3.g, cBg, r2
dp4 r3.b, cBb, r2
mul r0.xy, v0.xy, v0.xy    ; (x^2, y^2)
add r0.x, r0.x, -r0.y      ; vC = x^2 - y^2
)";

TEST(Validator, AcceptsPaperIrradianceProgram) {
  // Corrected last two lines (§9): x2 + x3 into r2, then x1 + r2.
  const std::string text = std::string(kIrradianceHead) +
                           "mad r2.rgb, cC.rgb, r0.x, r3.rgb\n"
                           "add oD0.rgb, r1.rgb, r2.rgb\n"
                           "m4x4 oPos, v1, c8\n";
  EXPECT_TRUE(Clean(Validate(Assemble(text))));
}

TEST(Validator, AcceptsPaperIrradianceProgramAsPrinted) {
  // The printed last two lines compute the wrong sum (§9) but break no validation rule: `.rgb` reads
  // .rgbb, and r1.b and r2.b have been written.
  const std::string text = std::string(kIrradianceHead) +
                           "mad r1.rgb, cC.rgb, r0.x, r3.rgb\n"
                           "add r0, r1.rgb, r2.rgb\n"
                           "m4x4 oPos, v1, c8\n";
  EXPECT_TRUE(Clean(Validate(Assemble(text))));
}

TEST(Validator, RejectsPaperProgramThatExpectsTheNormalInR0) {
  // As listed in the paper the normal is already in r0; a whole shader must load it first.
  Program program = Assemble(
      "vs_1_1\n"
      "dcl_position v1\n"
      "dp4 r1.r, c0, r0\n"
      "m4x4 oPos, v1, c8\n");
  EXPECT_TRUE(HasError(Validate(program), DiagnosticCode::kUninitializedRegister, 3, {"r0.xyzw"}));
}

TEST(Validator, PointsAtTheLineAndColumnTheAssemblerRecorded) {
  Program program = Assemble(
      "vs_1_1\n"
      "dcl_position v0\n"
      "\n"
      "    add r0, c4, c3   ; two constants\n"
      "mov oPos, v0\n");
  Diagnostics d = Validate(program);
  ASSERT_EQ(d.all().size(), 1u) << d.ToString();
  EXPECT_EQ(d.all().front().loc, (SourceLoc{std::string(kFileName), 4, 5}));
  EXPECT_NE(d.all().front().message.find("reads two different constant registers (c4, c3)"), std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// Structure (§6.1).

TEST(Validator, AcceptsMinimalDx9Program) {
  EXPECT_TRUE(Clean(Validate(Prog({Dcl("position", 0, V(0)), Op(kMov, D(OPos()), V(0))}))));
}

TEST(Validator, RejectsUnknownVersion) {
  Diagnostics d = Validate(Prog({WritePosition()}, 0xFFFE0400));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kVersionToken, 0));
  ASSERT_FALSE(d.all().empty());
  EXPECT_EQ(d.all().front().loc.file, kFileName);
}

TEST(Validator, AcceptsVersion10WithoutAddressRegister) {
  EXPECT_TRUE(Clean(Validate(Prog({WritePosition()}, kVersionVs10))));
}

TEST(Validator, RejectsAddressRegisterInVersion10) {
  Diagnostics d = Validate(Prog({Op(kMov, D(A0(), "x"), S(C(0), "x")), Op(kMov, D(OPos()), CRel(1))}, kVersionVs10));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kAddressWrite, LineOf(0), {"a0"}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kRelativeAddressing, LineOf(1), {"a0"}));
}

TEST(Validator, RejectsDclAfterFirstInstruction) {
  Diagnostics d = Validate(Prog({Op(kMov, D(OPos()), V(0)), Dcl("position", 0, V(0))}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kMisplacedDeclaration, LineOf(1)));
}

TEST(Validator, RejectsDefAfterFirstInstruction) {
  Diagnostics d = Validate(Prog({WritePosition(), Def(C(0))}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kMisplacedDeclaration, LineOf(1)));
}

TEST(Validator, AcceptsDclAndDefBeforeInstructions) {
  EXPECT_TRUE(Clean(Validate(Prog({Def(C(4)), Dcl("position", 0, V(0)), Def(C(5)), Op(kMov, D(OPos()), V(0))}))));
}

std::vector<Instruction> Repeat(const Instruction& instruction, int count) {
  return std::vector<Instruction>(count, instruction);
}

TEST(Validator, AcceptsExactly128Slots) {
  // 32 x m4x4 = 128 slots (each macro costs 4).
  EXPECT_TRUE(Clean(Validate(Prog(Repeat(Op(kM4x4, D(OPos()), V(0), C(0)), 32)))));
}

TEST(Validator, RejectsMoreThan128Slots) {
  std::vector<Instruction> code = Repeat(Op(kM4x4, D(OPos()), V(0), C(0)), 32);
  code.push_back(Nop());
  Diagnostics d = Validate(Prog(code));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kTooManySlots, LineOf(32), {"129", "128"}));
  EXPECT_EQ(d.error_count(), 1);
}

TEST(Validator, CountsMacroSlotsFromTheOpcodeTable) {
  // exp costs 10 slots: the 13th brings the total to 130. dcl/def cost nothing.
  std::vector<Instruction> code = {Def(C(1))};
  for (Instruction& exp : Repeat(Op(kExp, D(R(0)), S(C(1), "x")), 13)) code.push_back(exp);
  code.push_back(WritePosition());
  Diagnostics d = Validate(Prog(code));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kTooManySlots, LineOf(13)));
  EXPECT_EQ(d.error_count(), 1);
}

// ---------------------------------------------------------------------------------------------
// Register ranges (§6.2.1).

TEST(Validator, RejectsTemporaryBeyondR11) {
  Diagnostics d = Validate(Prog({Op(kMov, D(R(12)), C(0)), WritePosition()}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kNoSuchRegister, LineOf(0), {"r12", "r0"}));
}

TEST(Validator, RejectsInputBeyondV15) {
  Diagnostics d = Validate(Prog({Op(kMov, D(OPos()), V(16))}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kNoSuchRegister, LineOf(0), {"v16", "v0"}));
}

TEST(Validator, RejectsConstantBeyondConstantCount) {
  Diagnostics d = Validate(Prog({Op(kMov, D(OPos()), C(96))}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kNoSuchRegister, LineOf(0), {"c96", "c0"}));
}

TEST(Validator, SuggestsMaxConstantsForADefBeyondTheDevice) {
  // Real vs_1_1 shaders define c100 and beyond for devices with 256 constants.
  Diagnostics d = Validate(Prog({Def(C(100)), WritePosition()}));
  EXPECT_TRUE(HasErrorText(d, DiagnosticCode::kNoSuchRegister, LineOf(0), "def: the definition names c100, but the device has only c0-c95 (MaxVertexShaderConst = 96); "
                       "for a device with more, give its count with --max-constants (e.g. --max-constants 256)"));
  d = Validate(Prog({Def(C(300)), WritePosition()}));
  EXPECT_TRUE(HasErrorText(d, DiagnosticCode::kNoSuchRegister, LineOf(0), "(e.g. --max-constants 301)"));
  d = Validate(Prog({Op(kMov, D(A0(), "x"), S(C(0), "x")), Op(kMov, D(OPos()), CRel(100))}));
  EXPECT_TRUE(HasErrorText(d, DiagnosticCode::kNoSuchRegister, LineOf(1), "outside 0-95 (the device has 96 constants); for a device with more, give its count "
                          "with --max-constants"));
}

TEST(Validator, AcceptsConstantWithinConfiguredCount) {
  ValidatorOptions options;
  options.constant_count = 256;
  EXPECT_TRUE(Clean(Validate(Prog({Op(kMov, D(OPos()), C(255))}), options)));
}

TEST(Validator, RejectsRelativeOffsetBeyondConstantCount) {
  Diagnostics d = Validate(Prog({Op(kMov, D(A0(), "x"), S(C(0), "x")), Op(kMov, D(OPos()), CRel(96))}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kNoSuchRegister, LineOf(1)));
}

TEST(Validator, RejectsMatrixRowsPastLastConstant) {
  // m4x4 reads c94, c95, c96, c97.
  Diagnostics d = Validate(Prog({Op(kM4x4, D(OPos()), V(0), C(94))}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kNoSuchRegister, LineOf(0), {"c96", "c0"}));
}

TEST(Validator, RejectsOutputRegistersBeyondTheirRange) {
  Diagnostics d = Validate(Prog({Op(kMov, D(OT(8)), C(0)), Op(kMov, D(OD(2)), C(0)),
                                 Op(kMov, D({RegisterFile::kRasterOut, 3, false}), C(0)), WritePosition()}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kNoSuchRegister, LineOf(0), {"oT8", "oT0"}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kNoSuchRegister, LineOf(1), {"oD2", "oD0"}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kNoSuchRegister, LineOf(2), {"oPos"}));
}

TEST(Validator, AcceptsScalarOutputsWithAnyMaskHoldingLaneX) {
  // Shipped DX8 shaders write `mov oFog.x, r11.x`; Microsoft's assembler keeps the mask.
  EXPECT_TRUE(Clean(Validate(Prog({WritePosition(), Op(kMov, D(OFog(), "x"), S(C(0), "x")),
                                   Op(kMov, D(OPts(), "xy"), S(C(0), "y"))}))));
}

TEST(Validator, WarnsWhenAScalarOutputMissesLaneX) {
  // Encodable and round-trips through text, but the rasterizer reads lane x only (§7).
  Diagnostics d = Validate(Prog({WritePosition(), Op(kMov, D(OFog(), "zw"), S(C(0), "w"))}));
  EXPECT_EQ(d.error_count(), 0) << d.ToString();
  EXPECT_TRUE(HasWarning(d, DiagnosticCode::kScalarOutputMask, LineOf(1), {"oFog.zw", "oFog"}));
}

TEST(Validator, AcceptsEveryOutputRegister) {
  std::vector<Instruction> code = {WritePosition(), Op(kMov, D(OFog()), S(C(0), "x")),
                                   Op(kMov, D(OPts()), S(C(0), "y")), Op(kMov, D(OD(0)), C(1)),
                                   Op(kMov, D(OD(1)), C(1))};
  for (int i = 0; i < kTexCoordOutputCount; ++i) code.push_back(Op(kMov, D(OT(i), "xy"), C(2)));
  EXPECT_TRUE(Clean(Validate(Prog(code))));
}

// ---------------------------------------------------------------------------------------------
// Register types (§6.2.2, §6.2.4).

TEST(Validator, RejectsWriteToInputRegister) {
  Diagnostics d = Validate(Prog({Op(kMov, D(V(0)), C(0)), WritePosition()}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kReadOnlyDestination, LineOf(0), {"v0"}));
}

TEST(Validator, RejectsWriteToConstantRegister) {
  Diagnostics d = Validate(Prog({Op(kMov, D(C(3)), C(0)), WritePosition()}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kReadOnlyDestination, LineOf(0), {"c3"}));
}

TEST(Validator, RejectsOutputAsSource) {
  Diagnostics d = Validate(Prog({WritePosition(), Op(kMov, D(OD(0)), OPos())}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kWriteOnlySource, LineOf(1), {"oPos"}));
}

TEST(Validator, RejectsAddressRegisterAsSource) {
  Diagnostics d =
      Validate(Prog({Op(kMov, D(A0(), "x"), S(C(0), "x")), Op(kMov, D(R(0)), S(A0(), "x")), WritePosition()}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kWriteOnlySource, LineOf(1), {"a0"}));
}

TEST(Validator, RejectsAddressRegisterWrittenByOtherThanMov) {
  Diagnostics d = Validate(Prog({Op(kAdd, D(A0(), "x"), C(0), C(0)), WritePosition()}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kAddressWrite, LineOf(0), {"a0"}));
}

TEST(Validator, RejectsRelativeAddressingOfInput) {
  Diagnostics d = Validate(
      Prog({Op(kMov, D(A0(), "x"), S(C(0), "x")), Op(kMov, D(OPos()), RegisterRef{RegisterFile::kInput, 2, true})}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kRelativeAddressing, LineOf(1), {"v2"}));
}

TEST(Validator, RejectsRelativeDestination) {
  Diagnostics d = Validate(Prog({Op(kMov, D({RegisterFile::kTemp, 0, true}), C(0)), WritePosition()}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kRelativeAddressing, LineOf(0)));
}

TEST(Validator, RejectsDefOfNonConstantOrRelativeConstant) {
  Diagnostics d = Validate(Prog({Def(R(0)), Def(CRel(1)), Def(C(96)), WritePosition()}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kBadDefinition, LineOf(0), {"r0"}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kBadDefinition, LineOf(1), {"c1[a0.x]"}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kNoSuchRegister, LineOf(2), {"c96", "c0"}));
}

TEST(Validator, RejectsDclOfNonInput) {
  Diagnostics d = Validate(Prog({Dcl("position", 0, R(0)), WritePosition()}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kBadDeclaration, LineOf(0), {"r0", "v0", "v15"}));
}

// ---------------------------------------------------------------------------------------------
// The address register (§1.5).

TEST(Validator, RejectsRelativeReadBeforeA0IsWritten) {
  Diagnostics d = Validate(Prog({Op(kMov, D(OPos()), CRel(3)), Op(kMov, D(A0(), "x"), S(C(0), "x"))}));
  EXPECT_TRUE(HasErrorText(d, DiagnosticCode::kAddressNotWritten, LineOf(0), "reads c3[a0.x] before a0 is written; put `mov a0.x, <src>` earlier"));
}

TEST(Validator, RejectsRelativeReadInTheMovThatWritesA0) {
  Diagnostics d = Validate(Prog({Op(kMov, D(A0(), "x"), S(CRel(0), "x")), WritePosition()}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kAddressNotWritten, LineOf(0), {"a0"}));
}

TEST(Validator, AcceptsRelativeReadAfterMovToA0) {
  Diagnostics d = Validate(Prog({Op(kMov, D(A0(), "x"), S(C(0), "x")), Op(kMov, D(OPos()), CRel(95))}));
  EXPECT_TRUE(Clean(d));
}

// ---------------------------------------------------------------------------------------------
// Read ports (§1.7, §3.4).

TEST(Validator, RejectsSecondConstantRegisterRead) {
  Diagnostics d = Validate(Prog({Op(kAdd, D(R(0)), C(4), C(3)), WritePosition()}));
  EXPECT_TRUE(
      HasError(d, DiagnosticCode::kReadPorts, LineOf(0), {"c4", "c3"}));
}

TEST(Validator, ListsEveryDistinctConstantOfTheInstruction) {
  Diagnostics d = Validate(Prog({Op(kMad, D(R(0)), C(1), C(2), C(3)), WritePosition()}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kReadPorts, LineOf(0), {"c1", "c2", "c3"}));
  EXPECT_EQ(d.error_count(), 1);
  d = Validate(Prog({Op(kMad, D(R(0)), V(1), V(2), V(3)), WritePosition()}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kReadPorts, LineOf(0), {"v1", "v2", "v3"}));
  // A register named twice counts once.
  d = Validate(Prog({Op(kMad, D(R(0)), C(1), S(C(2), "x"), C(1)), WritePosition()}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kReadPorts, LineOf(0), {"c1", "c2"}));
}

TEST(Validator, AcceptsSameConstantWithDifferentSwizzles) {
  Diagnostics d = Validate(
      Prog({Op(kMov, D(R(1)), C(0)), Op(kMad, D(R(0)), S(C(4), "x"), R(1), Neg(S(C(4), "yyyy"))), WritePosition()}));
  EXPECT_TRUE(Clean(d));
}

TEST(Validator, RejectsSecondInputRegisterRead) {
  Diagnostics d = Validate(Prog({Op(kAdd, D(OPos()), V(1), V(2))}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kReadPorts, LineOf(0), {"v1", "v2"}));
}

TEST(Validator, AcceptsSameInputTwiceAndOneConstant) {
  EXPECT_TRUE(Clean(Validate(Prog({Op(kMad, D(OPos()), S(V(1), "x"), Neg(V(1)), C(7))}))));
}

TEST(Validator, RejectsAbsoluteAndRelativeConstantTogether) {
  Diagnostics d = Validate(Prog({Op(kMov, D(A0(), "x"), S(C(0), "x")), Op(kAdd, D(OPos()), C(5), CRel(5))}));
  EXPECT_TRUE(HasErrorText(d, DiagnosticCode::kReadPorts, LineOf(1), "(c5, c5[a0.x]) (an absolute and a relative constant count as two)"));
}

TEST(Validator, RejectsTwoConstantsInOneExpandedMatrixRow) {
  Diagnostics d = Validate(Prog({Op(kM4x4, D(R(0)), C(0), C(4)), WritePosition()}));
  EXPECT_TRUE(
      HasError(d, DiagnosticCode::kReadPorts, LineOf(0), {"c0", "c4"}));
  EXPECT_EQ(d.error_count(), 1);  // reported once, not per row
}

TEST(Validator, RejectsTwoInputsInOneExpandedMatrixRow) {
  Diagnostics d = Validate(Prog({Op(kM3x3, D(OPos(), "xyz"), V(0), V(4))}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kReadPorts, LineOf(0), {"v0", "v4"}));
}

TEST(Validator, AcceptsMatrixOfConstantsAppliedToInput) {
  EXPECT_TRUE(Clean(Validate(Prog({Op(kM4x4, D(OPos()), V(0), C(0))}))));
}

TEST(Validator, AcceptsMatrixOfInputsAppliedToConstant) {
  // Each expanded row reads c0 and one of v0..v3.
  EXPECT_TRUE(Clean(Validate(Prog({Op(kM4x4, D(OPos()), C(0), V(0))}))));
}

// ---------------------------------------------------------------------------------------------
// Write masks (§6.2.6).

TEST(Validator, RejectsEmptyWriteMask) {
  Diagnostics d = Validate(Prog({Op(kMov, D(R(0), ""), C(0)), WritePosition()}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kWriteMask, LineOf(0), {"r0"}));
}

TEST(Validator, RejectsFrcWithMaskX) {
  Diagnostics d = Validate(Prog({Op(kFrc, D(R(0), "x"), C(0)), WritePosition()}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kWriteMask, LineOf(0), {".x", ".y", ".xy"}));
}

TEST(Validator, AcceptsFrcWithMaskYOrXy) {
  EXPECT_TRUE(Clean(Validate(Prog({Op(kFrc, D(R(0), "y"), C(0)), Op(kFrc, D(R(1), "xy"), C(0)), WritePosition()}))));
}

TEST(Validator, RejectsPartialMaskOnMatrixMacro) {
  Diagnostics d = Validate(Prog({Op(kM4x4, D(OPos(), "xyz"), V(0), C(0)), Op(kM3x2, D(R(0), "xyz"), V(0), C(0))}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kWriteMask, LineOf(0), {".xyz", ".xyzw"}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kWriteMask, LineOf(1), {".xyz", ".xy"}));
}

TEST(Validator, AcceptsTheMaskEachMatrixMacroRequires) {
  EXPECT_TRUE(Clean(Validate(Prog({Op(kM3x2, D(R(0), "xy"), V(0), C(0)), Op(kM3x3, D(R(1), "xyz"), V(0), C(0)),
                                   Op(kM4x3, D(R(2), "xyz"), V(0), C(0)), Op(kM3x4, D(R(3)), V(0), C(0)),
                                   Op(kM4x4, D(OPos()), V(0), C(0))}))));
}

TEST(Validator, RejectsAddressRegisterMaskOtherThanX) {
  Diagnostics d = Validate(Prog({Op(kMov, D(A0(), "xy"), C(0)), WritePosition()}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kAddressWrite, LineOf(0), {"a0.xy", "a0", ".x"}));
}

// ---------------------------------------------------------------------------------------------
// Matrix macro operands (§3.3).

TEST(Validator, RejectsSwizzledMatrixOperand) {
  Diagnostics d = Validate(Prog({Op(kM4x4, D(OPos()), V(0), S(C(0), "yzwx"))}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kMatrixOperand, LineOf(0), {"c0.yzwx"}));
}

TEST(Validator, RejectsNegatedMatrixOperand) {
  Diagnostics d = Validate(Prog({Op(kM4x4, D(OPos()), V(0), Neg(C(0)))}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kMatrixOperand, LineOf(0), {"c0"}));
}

TEST(Validator, AcceptsSwizzledAndNegatedFirstSourceOfMatrixMacro) {
  EXPECT_TRUE(Clean(Validate(Prog({Op(kM4x4, D(OPos()), Neg(S(V(0), "wzyx")), C(0))}))));
}

TEST(Validator, RejectsMatrixDestinationEqualToFirstSource) {
  Diagnostics d = Validate(Prog({Op(kMov, D(R(0)), V(0)), Op(kM4x4, D(R(0)), R(0), C(0)), WritePosition()}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kMatrixOperand, LineOf(1), {"r0"}));
}

TEST(Validator, RejectsMatrixDestinationAmongMatrixRows) {
  std::vector<Instruction> code = {Op(kMov, D(R(0)), C(0)), Op(kMov, D(R(1)), C(1)), Op(kMov, D(R(2)), C(2)),
                                   Op(kM3x3, D(R(1), "xyz"), V(0), R(0)), WritePosition()};
  Diagnostics d = Validate(Prog(code));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kMatrixOperand, LineOf(3), {"r1"}));
}

TEST(Validator, AcceptsMatrixDestinationJustPastTheRows) {
  std::vector<Instruction> code = {Op(kMov, D(R(0)), C(0)), Op(kMov, D(R(1)), C(1)), Op(kMov, D(R(2)), C(2)),
                                   Op(kM3x3, D(R(3), "xyz"), V(0), R(0)), WritePosition()};
  EXPECT_TRUE(Clean(Validate(Prog(code))));
}

// ---------------------------------------------------------------------------------------------
// Scalar sources (§3.1).

TEST(Validator, WarnsWhenScalarSourceLacksReplicateSwizzle) {
  Diagnostics d = Validate(Prog({Op(kRcp, D(R(0)), C(1)), WritePosition()}));
  EXPECT_TRUE(
      HasWarning(d, DiagnosticCode::kScalarSwizzle, LineOf(0), {"c1"}));
  EXPECT_FALSE(d.HasErrors());
}

TEST(Validator, WarnsForExppAndLogpWithoutReplicateSwizzle) {
  Diagnostics d = Validate(Prog({Op(kExpp, D(R(0)), S(C(1), "xy")), Op(kLogp, D(R(1)), C(1)), WritePosition()}));
  EXPECT_TRUE(HasWarning(d, DiagnosticCode::kScalarSwizzle, LineOf(0)));
  EXPECT_TRUE(HasWarning(d, DiagnosticCode::kScalarSwizzle, LineOf(1)));
}

TEST(Validator, AcceptsScalarSourceWithReplicateSwizzle) {
  EXPECT_TRUE(Clean(Validate(Prog({Op(kRsq, D(R(0)), S(C(1), "x")), Op(kExp, D(R(1)), S(C(1), "w")),
                                   Op(kLogp, D(R(2)), S(C(1), "zzzz")), WritePosition()}))));
}

TEST(Validator, DoesNotWarnForVectorInstructions) {
  // lit and dst read several lanes; mov r0.w reads one lane, but because of its mask.
  EXPECT_TRUE(Clean(Validate(
      Prog({Op(kLit, D(R(0)), C(1)), Op(kDst, D(R(1)), C(1), V(0)), Op(kMov, D(R(2), "w"), C(1)), WritePosition()}))));
}

// ---------------------------------------------------------------------------------------------
// Data flow of temporaries (§6.3). A read of lanes that nothing wrote, of a partly written temporary,
// is only a warning in a DX8 program (see uninitialized_read_test.cc); these tests check which lanes
// each instruction consumes, so they validate with `strict`, which makes it an error.

Diagnostics ValidateStrict(const Program& program) {
  ValidatorOptions options;
  options.strict = true;
  return Validate(program, options);
}

TEST(Validator, RejectsReadOfUnwrittenTemporary) {
  Diagnostics d = Validate(Prog({Op(kAdd, D(R(0)), R(1), C(0)), WritePosition()}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kUninitializedRegister, LineOf(0), {"r1.xyzw"}));
}

TEST(Validator, RejectsReadOfUnwrittenLanes) {
  Diagnostics d = ValidateStrict(Prog({Op(kMov, D(R(0), "xy"), C(0)), Op(kMov, D(R(1)), R(0)), WritePosition()}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kUninitializedLanes, LineOf(1), {"r0.zw"}));
}

TEST(Validator, ReportsEachUnwrittenRegisterOncePerInstruction) {
  // mul r2, r0.xyzz, r0.yzzx with r0 unwritten: one error naming lanes x, y, z.
  Diagnostics d = Validate(Prog({Op(kMul, D(R(2)), S(R(0), "xyzz"), S(R(0), "yzzx")), WritePosition()}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kUninitializedRegister, LineOf(0), {"r0.xyz"}));
  EXPECT_EQ(d.error_count(), 1);
}

TEST(Validator, AcceptsReadOfWrittenLaneThroughSwizzle) {
  EXPECT_TRUE(Clean(Validate(Prog({Op(kMov, D(R(0), "x"), C(0)), Op(kMov, D(R(1)), S(R(0), "x")),
                                   Op(kAdd, D(R(1), "yz"), S(R(0), "wxxw"), C(0)), WritePosition()}))));
}

TEST(Validator, ComponentwiseReadsOnlyTheMaskedLanes) {
  Diagnostics ok = Validate(Prog({Op(kMov, D(R(0), "xy"), C(0)), Op(kMul, D(R(1), "xy"), R(0), R(0)),
                                  Op(kFrc, D(R(2), "y"), R(0)), WritePosition()}));
  EXPECT_TRUE(Clean(ok));
  Diagnostics bad =
      ValidateStrict(Prog({Op(kMov, D(R(0), "xy"), C(0)), Op(kMul, D(R(1), "xz"), R(0), C(0)), WritePosition()}));
  EXPECT_TRUE(HasError(bad, DiagnosticCode::kUninitializedLanes, LineOf(1), {"r0.z"}));
}

TEST(Validator, Dp3ReadsThreeLanesAndDp4Four) {
  std::vector<Instruction> code = {Op(kMov, D(R(0), "xyz"), C(0)), Op(kDp3, D(R(1)), R(0), C(0)),
                                   Op(kDp4, D(R(2)), R(0), C(0)), WritePosition()};
  Diagnostics d = ValidateStrict(Prog(code));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kUninitializedLanes, LineOf(2), {"r0.w"}));
  EXPECT_EQ(d.error_count(), 1);
}

TEST(Validator, ScalarInstructionReadsTheWLaneSelector) {
  Diagnostics d = ValidateStrict(
      Prog({Op(kMov, D(R(0), "x"), C(0)), Op(kRcp, D(R(1)), S(R(0), "x")), Op(kRsq, D(R(2)), R(0)), WritePosition()}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kUninitializedLanes, LineOf(2), {"r0.w"}));
  EXPECT_EQ(d.error_count(), 1);
}

TEST(Validator, LitReadsLanesXYAndW) {
  Diagnostics ok = Validate(Prog({Op(kMov, D(R(0), "xyw"), C(0)), Op(kLit, D(R(1)), R(0)), WritePosition()}));
  EXPECT_TRUE(Clean(ok));
  Diagnostics bad = ValidateStrict(Prog({Op(kMov, D(R(0), "xy"), C(0)), Op(kLit, D(R(1)), R(0)), WritePosition()}));
  EXPECT_TRUE(HasError(bad, DiagnosticCode::kUninitializedLanes, LineOf(1), {"r0.w"}));
}

TEST(Validator, DstReadsOnlyTheLanesItsMaskNeeds) {
  // dest.y needs s0.y and s1.y; dest.z needs s0.z; dest.w needs s1.w.
  std::vector<Instruction> code = {Op(kMov, D(R(0), "y"), C(0)), Op(kMov, D(R(1), "y"), C(0)),
                                   Op(kDst, D(R(2), "xy"), R(0), R(1)), Op(kDst, D(R(3), "zw"), R(0), R(1)),
                                   WritePosition()};
  Diagnostics d = ValidateStrict(Prog(code));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kUninitializedLanes, LineOf(3), {"r0.z", "r1.w"}));
  EXPECT_EQ(d.error_count(), 1);
}

TEST(Validator, MatrixReadsEveryRowRegister) {
  // m3x3 reads lanes xyz of s0 and of r4, r5, r6; r6 is never written.
  std::vector<Instruction> code = {Op(kMov, D(R(0), "xyz"), V(0)), Op(kMov, D(R(4), "xyz"), C(0)),
                                   Op(kMov, D(R(5), "xyz"), C(1)), Op(kM3x3, D(R(1), "xyz"), R(0), R(4)),
                                   WritePosition()};
  Diagnostics d = Validate(Prog(code));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kUninitializedRegister, LineOf(3), {"r6.xyz"}));
  EXPECT_EQ(d.error_count(), 1);
}

TEST(Validator, MovToAddressRegisterReadsLaneX) {
  EXPECT_TRUE(Clean(
      Validate(Prog({Op(kMov, D(R(0), "x"), C(0)), Op(kMov, D(A0(), "x"), R(0)), Op(kMov, D(OPos()), CRel(0))}))));
}

TEST(Validator, ConsumedLanesFollowsTheResultKind) {
  const Swizzle identity;
  const WriteMask full;
  EXPECT_EQ(ConsumedLanes(Info(kMad), 2, Mask("xw"), identity), Mask("xw").bits());
  EXPECT_EQ(ConsumedLanes(Info(kMov), 0, Mask("yz"), Swz("wxxw")), Mask("x").bits());
  EXPECT_EQ(ConsumedLanes(Info(kDp3), 1, Mask("x"), identity), Mask("xyz").bits());
  EXPECT_EQ(ConsumedLanes(Info(kDp4), 0, Mask("x"), Swz("yzzx")), Mask("xyz").bits());
  EXPECT_EQ(ConsumedLanes(Info(kRcp), 0, full, Swz("xyzy")), Mask("y").bits());
  EXPECT_EQ(ConsumedLanes(Info(kLit), 0, Mask("x"), identity), Mask("xyw").bits());
  EXPECT_EQ(ConsumedLanes(Info(kDst), 0, full, identity), Mask("yz").bits());
  EXPECT_EQ(ConsumedLanes(Info(kDst), 1, full, identity), Mask("yw").bits());
  EXPECT_EQ(ConsumedLanes(Info(kDst), 1, Mask("xz"), identity), 0);
  EXPECT_EQ(ConsumedLanes(Info(kExpp), 0, Mask("xy"), Swz("z")), Mask("z").bits());
  EXPECT_EQ(ConsumedLanes(Info(kM3x2), 1, Mask("xy"), identity), Mask("xyz").bits());
  EXPECT_EQ(ConsumedLanes(Info(kM4x3), 0, Mask("xyz"), identity), Mask("xyzw").bits());
}

// ---------------------------------------------------------------------------------------------
// oPos (§6.3.2).

TEST(Validator, RejectsProgramThatNeverWritesPosition) {
  Diagnostics d = Validate(Prog({Op(kMov, D(OD(0)), C(0))}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kPositionNotWritten, 0, {"oPos"}));
}

TEST(Validator, WarnsWhenPositionIsPartlyWritten) {
  Diagnostics d = Validate(Prog({Op(kMov, D(OPos(), "xy"), C(0)), Op(kMov, D(OPos(), "z"), C(0))}));
  EXPECT_TRUE(HasWarning(d, DiagnosticCode::kPositionPartlyWritten, LineOf(1), {"oPos", ".xyz"}));
  EXPECT_FALSE(d.HasErrors());
}

TEST(Validator, AcceptsPositionWrittenInPieces) {
  EXPECT_TRUE(Clean(Validate(Prog({Op(kMov, D(OPos(), "xy"), C(0)), Op(kMov, D(OPos(), "zw"), C(0))}))));
}

// ---------------------------------------------------------------------------------------------
// Declarations and dialects (§1.2, §6.2.8).

TEST(Validator, RejectsUndeclaredInputInDx9) {
  Diagnostics d =
      Validate(Prog({Dcl("position", 0, V(0)), Op(kAdd, D(OPos()), V(0), S(V(0), "x")), Op(kMov, D(OD(0)), V(3))}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kUndeclaredInput, LineOf(2), {"v3"}));
  EXPECT_EQ(d.error_count(), 1);
}

TEST(Validator, RejectsUndeclaredMatrixRowInputInDx9) {
  Diagnostics d = Validate(Prog({Dcl("position", 0, V(0)), Dcl("normal", 0, V(1)),
                                 Op(kM3x2, D(OPos(), "xy"), C(0), V(0)), Op(kMov, D(OPos(), "zw"), C(1))}));
  EXPECT_TRUE(Clean(d));
  Diagnostics d2 = Validate(
      Prog({Dcl("position", 0, V(0)), Op(kM3x2, D(OPos(), "xy"), C(0), V(0)), Op(kMov, D(OPos(), "zw"), C(1))}));
  EXPECT_TRUE(HasError(d2, DiagnosticCode::kUndeclaredInput, LineOf(1), {"v1"}));
}

TEST(Validator, AcceptsUndeclaredInputsInDx8Program) {
  // No dcl at all: the automatic dialect is DX8.
  EXPECT_TRUE(Clean(Validate(Prog({Op(kM4x4, D(OPos()), V(0), C(0)), Op(kMov, D(OD(0)), V(5))}))));
}

TEST(Validator, ForcedDx9RequiresDclEvenWithoutAny) {
  ValidatorOptions options;
  options.dialect = Dialect::kDx9;
  Diagnostics d = Validate(Prog({Op(kMov, D(OPos()), V(0))}), options);
  EXPECT_TRUE(HasError(d, DiagnosticCode::kUndeclaredInput, LineOf(0), {"v0"}));
}

TEST(Validator, ForcedDx8AcceptsDclAndUndeclaredInputs) {
  ValidatorOptions options;
  options.dialect = Dialect::kDx8;
  Program program = Prog({Dcl("position", 0, V(0)), Op(kMov, D(OPos()), V(0)), Op(kMov, D(OD(0)), V(1))});
  EXPECT_TRUE(Clean(Validate(program, options)));
}

TEST(Validator, RejectsRegisterDeclaredTwice) {
  Diagnostics d = Validate(Prog({Dcl("position", 0, V(0)), Dcl("normal", 0, V(0)), Op(kMov, D(OPos()), V(0))}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kDuplicateDeclaration, LineOf(1), {"v0"}));
}

TEST(Validator, RejectsUsageDeclaredTwice) {
  Diagnostics d = Validate(Prog({Dcl("texcoord", 1, V(0)), Dcl("texcoord", 1, V(1)), Op(kMov, D(OPos()), V(0))}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kDuplicateDeclaration, LineOf(1)));
}

TEST(Validator, AcceptsSameUsageWithDifferentIndices) {
  EXPECT_TRUE(Clean(Validate(Prog(
      {Dcl("texcoord", 0, V(0)), Dcl("texcoord", 1, V(1)), Op(kMov, D(OPos()), V(0)), Op(kMov, D(OT(0)), V(1))}))));
}

// ---------------------------------------------------------------------------------------------
// Bytecode programs have no source locations: messages name the instruction instead.

TEST(Validator, NamesInstructionIndexWhenThereIsNoSourceLine) {
  Diagnostics d = Validate(Bytecode({Op(kMov, D(R(1)), C(0)), Op(kAdd, D(OPos()), C(4), C(3))}));
  EXPECT_TRUE(HasError(d, DiagnosticCode::kReadPorts, 0, {"c4", "c3"}));
  ASSERT_EQ(d.all().size(), 1u);
  EXPECT_EQ(d.all().front().loc, SourceLoc{});
}

TEST(Validator, GivesTheWordOffsetOfDecodedInstructions) {
  Program program = Bytecode({Op(kMov, D(R(1)), C(0)), Op(kAdd, D(OPos()), C(4), C(3))});
  program.word_offsets = {1, 4};
  Diagnostics d = Validate(program);
  ASSERT_EQ(d.all().size(), 1u);
  EXPECT_EQ(d.all().front().word_offset, 4);
  EXPECT_EQ(FormatDiagnostic(d.all().front()),
            "word 4: error: instruction 1 (add): reads two different constant registers (c4, c3); vs_1_1 allows one "
            "per instruction — copy one of them into a temporary first [read-ports]");
}

TEST(Validator, UsesTheSourceLineAndColumnOfTheInstruction) {
  Program program = Prog({Op(kAdd, D(OPos()), C(4), C(3))});
  program.source_locs[0] = {"shader.vsh", 17, 5};
  Diagnostics d = Validate(program);
  ASSERT_EQ(d.all().size(), 1u);
  EXPECT_EQ(d.all().front().loc, (SourceLoc{"shader.vsh", 17, 5}));
  EXPECT_EQ(d.all().front().message.rfind("add: ", 0), 0u) << d.all().front().message;
}

}  // namespace
}  // namespace vs11

namespace vs11 {
namespace {

// `count` def lines, register c(i % registers), then a position write.
std::string Definitions(int count, int registers) {
  std::string text = "vs_1_1\ndcl_position v0\n";
  for (int i = 0; i < count; ++i) text += fmt::format("def c{}, {}, 0, 0, 1\n", i % registers, i);
  return text + "mov oPos, v0\n";
}

TEST(ValidatorDefinitions, ARedefinedRegisterIsAWarningAndTheLastValueWins) {
  const Program program = Assemble(Definitions(3, 2));  // c0, c1, then c0 again
  const Diagnostics diagnostics = Validate(program);
  ASSERT_EQ(diagnostics.all().size(), 1u) << diagnostics.ToString();
  const Diagnostic& warning = diagnostics.all().front();
  EXPECT_EQ(warning.severity, Severity::kWarning);
  EXPECT_EQ(warning.code, DiagnosticCode::kDuplicateDefinition);
  EXPECT_EQ(warning.loc.line, 5);
  EXPECT_THAT(warning.message, ::testing::HasSubstr("c0 is defined again"));
  EXPECT_THAT(warning.message, ::testing::HasSubstr("(line 3)"));
  EXPECT_EQ(ApplyDefinitions(program, ConstantBank())[0][0], 2.0f);
}

TEST(ValidatorDefinitions, AsManyDefsAsRegistersAreValid) {
  EXPECT_TRUE(Clean(Validate(Assemble(Definitions(kDefaultConstantCount, kDefaultConstantCount)))));
}

TEST(ValidatorDefinitions, MoreDefsThanRegistersIsOneErrorAtTheFirstOneOver) {
  const Diagnostics diagnostics = Validate(Assemble(Definitions(100000, kDefaultConstantCount)));
  ASSERT_EQ(diagnostics.all().size(), 1u) << diagnostics.all().front().message;
  const Diagnostic& error = diagnostics.all().front();
  EXPECT_EQ(error.code, DiagnosticCode::kTooManyDefinitions);
  EXPECT_EQ(error.loc.line, kDefaultConstantCount + 3);
  EXPECT_EQ(error.loc.column, 1);
  ValidatorOptions device;  // a device with more registers takes more
  device.constant_count = 256;
  EXPECT_EQ(Validate(Assemble(Definitions(200, 200)), device).error_count(), 0);
}

}  // namespace
}  // namespace vs11

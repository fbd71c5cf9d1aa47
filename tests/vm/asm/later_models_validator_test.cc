// The validator's rules for vs_2_0, vs_2_x and vs_3_0 (vm/asm/validator_models.cc), each with a program
// that breaks one rule and the code of the error, and programs that keep them all; and every engine's
// refusal to run a program of a model it does not execute yet.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "vm/asm/assembler.h"
#include "vm/engines/engine_factory.h"
#include "vm/translate/translate.h"

namespace vs11 {
namespace {

std::optional<std::string> NoFiles(const std::filesystem::path&) { return std::nullopt; }

AssembleResult AssembleValidated(const std::string& source) { return AssembleSource(source, "m.vsh", {}, NoFiles); }

std::string Messages(const Diagnostics& diagnostics) {
  std::string text;
  for (const Diagnostic& d : diagnostics.all()) text += FormatDiagnostic(d) + "\n";
  return text;
}

TEST(LaterModelValidator, AcceptsProgramsThatKeepEveryRule) {
  const char* programs[] = {
      "vs_2_0\ndcl_position v0\ndefi i0, 3, 0, 1, 0\ndefb b0, true\nmov r0, c0\nloop aL, i0\n"
      "add r0, r0, c1[aL]\nendloop\nrep i0\nif b0\nmul r0, r0, c2\nelse\nadd r0, r0, c2\nendif\nendrep\n"
      "call l1\nmov oPos, r0\nret\nlabel l1\nmova a0.x, c3\nmov r1, c4[a0.x]\nret\n",
      "vs_2_x\ndcl_position v0\nsetp_gt p0, v0, c0\n(!p0) add r0, v0, c1\n(p0) mov r0, v0\nrep i0\n"
      "break_ne r0.x, c0.x\nbreakp p0.x\nendrep\nif_lt r0.x, c0.y\nmov r0, c1\nendif\nmov oPos, r0\n",
      "vs_3_0\ndcl_position v0\ndcl_position o0\ndcl_texcoord3 o3\ndcl_2d s0\ntexldl r0, v0, s0\n"
      "mov o0, r0_abs\nmov_sat o3, r0\nsincos r1.xy, r0.x\n",
  };
  for (const char* source : programs) {
    const AssembleResult result = AssembleValidated(source);
    EXPECT_TRUE(result.program) << source << Messages(result.diagnostics);
  }
}

struct RuleCase {
  std::string name;
  std::string source;
  int line;
  DiagnosticCode code;
};

void PrintTo(const RuleCase& c, std::ostream* os) { *os << c.name; }

class LaterModelRule : public testing::TestWithParam<RuleCase> {};

TEST_P(LaterModelRule, IsReportedWhereItIsBroken) {
  const RuleCase& c = GetParam();
  const AssembleResult result = AssembleValidated(c.source);
  EXPECT_FALSE(result.program);
  bool found = false;
  for (const Diagnostic& d : result.diagnostics.all()) {
    if (d.code == c.code && d.loc.line == c.line && (c.line == 0 || d.loc.column >= 1)) found = true;
  }
  EXPECT_TRUE(found) << DiagnosticCodeName(c.code) << " at line " << c.line << ":\n" << Messages(result.diagnostics);
}

const std::string kPos = "dcl_position v0\nmov oPos, v0\n";

const RuleCase kRules[] = {
    {"EndloopWithoutLoop", "vs_2_0\n" + kPos + "endloop\n", 4, DiagnosticCode::kUnmatchedFlowControl},
    {"LoopNotClosed", "vs_2_0\n" + kPos + "loop aL, i0\n", 4, DiagnosticCode::kUnmatchedFlowControl},
    {"EndrepClosesIf", "vs_2_0\n" + kPos + "if b0\nendrep\n", 5, DiagnosticCode::kUnmatchedFlowControl},
    {"ElseWithoutIf", "vs_2_0\n" + kPos + "else\n", 4, DiagnosticCode::kUnmatchedFlowControl},
    {"BreakOutsideLoop", "vs_2_x\n" + kPos + "break\n", 4, DiagnosticCode::kUnmatchedFlowControl},
    {"LoopsNestedFiveDeep",
     "vs_2_0\n" + kPos + "rep i0\nrep i0\nrep i0\nrep i0\nrep i0\nendrep\nendrep\nendrep\nendrep\nendrep\n", 8,
     DiagnosticCode::kNestingTooDeep},
    {"StaticIfNestedFiveDeep",
     "vs_2_0\n" + kPos + "if b0\nif b0\nif b0\nif b0\nif b0\nendif\nendif\nendif\nendif\nendif\n", 8,
     DiagnosticCode::kNestingTooDeep},
    {"UndefinedLabel", "vs_2_0\n" + kPos + "call l3\nret\n", 4, DiagnosticCode::kUndefinedLabel},
    {"DuplicateLabel", "vs_2_0\n" + kPos + "ret\nlabel l0\nret\nlabel l0\nret\n", 7, DiagnosticCode::kDuplicateLabel},
    {"RecursiveCall", "vs_2_0\n" + kPos + "call l0\nret\nlabel l0\ncall l0\nret\n", 7, DiagnosticCode::kNestingTooDeep},
    {"CallsFiveDeep",
     "vs_2_0\n" + kPos + "call l1\nret\nlabel l1\ncall l2\nret\nlabel l2\ncall l3\nret\nlabel l3\ncall l4\nret\n"
                         "label l4\ncall l5\nret\nlabel l5\nret\n",
     16, DiagnosticCode::kNestingTooDeep},
    {"RetInsideIf", "vs_2_0\n" + kPos + "if b0\nret\nendif\n", 5, DiagnosticCode::kUnmatchedFlowControl},
    {"LoopRegisterOutsideLoop", "vs_2_0\n" + kPos + "mov r0, c0[aL]\n", 4, DiagnosticCode::kLoopRegisterOutsideLoop},
    {"RepCountNotAnInteger", "vs_2_0\n" + kPos + "rep b0\nendrep\n", 4, DiagnosticCode::kBadOperand},
    {"MovWritesAddress", "vs_2_0\n" + kPos + "mov a0.x, c0.x\n", 4, DiagnosticCode::kReadOnlyDestination},
    {"CrsWritesW", "vs_2_0\n" + kPos + "crs r0, c0, c1\n", 4, DiagnosticCode::kBadOperand},
    {"Vs20Temp12", "vs_2_0\n" + kPos + "mov r12, c0\n", 4, DiagnosticCode::kNoSuchRegister},
    {"Vs2xHasTemp31ButNot32", "vs_2_x\n" + kPos + "mov r32, c0\n", 4, DiagnosticCode::kNoSuchRegister},
    {"UndeclaredInput", "vs_2_0\n" + kPos + "mov r0, v1\n", 4, DiagnosticCode::kUndeclaredInput},
    {"NoPosition", "vs_2_0\nmov r0, c0\n", 0, DiagnosticCode::kPositionNotWritten},
    {"Vs30NoPositionOutput", "vs_3_0\ndcl_texcoord o0\nmov o0, c0\n", 0, DiagnosticCode::kPositionNotWritten},
    {"TooManySlots", "vs_2_0\n" + kPos + [] {
       std::string body;
       for (int i = 0; i < 256; ++i) body += "mov r0, c0\n";
       return body;
     }(),
     259, DiagnosticCode::kTooManySlots},
};

INSTANTIATE_TEST_SUITE_P(Rules, LaterModelRule, testing::ValuesIn(kRules),
                         [](const testing::TestParamInfo<RuleCase>& info) { return info.param.name; });

// The ref engine runs a later model's program, batch and jit one with static flow (this one's is):
// every other engine refuses it, naming the model and itself.
TEST(LaterModelEngines, EveryEngineButRefBatchAndJitRefusesALaterModelsProgram) {
  for (const char* source : {"vs_2_0\ndcl_position v0\nmov oPos, v0\n", "vs_3_0\ndcl_position o0\nmov o0, c0\n"}) {
    const AssembleResult result = AssembleValidated(source);
    ASSERT_TRUE(result.program) << Messages(result.diagnostics);
    const std::string model = result.program->model() == ShaderModel::kVs20 ? "vs_2_0" : "vs_3_0";
    for (const EngineInfo& engine : RegisteredEngines()) {
      const Result<std::unique_ptr<Engine>> made = MakeEngine(engine.name, *result.program, ConstantBank());
      if (engine.name == kLaterModelEngine || std::ranges::find(kStaticFlowEngines, engine.name) != kStaticFlowEngines.end()) {
        EXPECT_TRUE(made.ok()) << made.message();
        continue;
      }
      ASSERT_FALSE(made.ok()) << engine.name;
      EXPECT_EQ(made.error().code, DiagnosticCode::kEngineUnavailable);
      EXPECT_NE(made.message().find(model), std::string::npos) << engine.name << ": " << made.message();
      EXPECT_NE(made.message().find(std::string(engine.name)), std::string::npos) << made.message();
    }
    const Result<translate::Artifact> artifact = translate::Translate(*result.program, {});
    EXPECT_FALSE(artifact.ok());
    EXPECT_NE(artifact.message().find(model), std::string::npos) << artifact.message();
    EXPECT_NE(artifact.message().find("translate"), std::string::npos) << artifact.message();
  }
  const AssembleResult vs11 = AssembleValidated("vs_1_1\ndcl_position v0\nmov oPos, v0\n");
  ASSERT_TRUE(vs11.program);
  EXPECT_EQ(MakeEngine("ref", *vs11.program, ConstantBank()).message(), "");
}

}  // namespace
}  // namespace vs11

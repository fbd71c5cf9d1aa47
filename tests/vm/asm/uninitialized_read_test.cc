// Reads of temporary lanes that nothing wrote (issue 22 §5). Microsoft's DX8 samples do it: the
// SkinnedMesh sample's `m4x3 r4, v0, c[a0.x + 9]` writes .xyz and the next `mul r4, r4, v1.xxxx` reads
// r4.w; the ShaderX samples do the same after m3x3. The D3D8 runtime ran them, so in DX8 syntax this
// is a warning and the lanes read 0; --strict, and DX9 syntax (as Microsoft's D3D9 validator, "read
// of uninitialized components"), make it an error. A temporary never written at all is an error in
// both syntaxes. The programs below are written for these tests in the samples' shapes.
#include <bit>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "vm/asm/assembler.h"
#include "vm/core/diagnostic.h"
#include "vm/core/machine.h"
#include "vm/engines/engine_factory.h"

namespace vs11 {
namespace {

// Blends one bone's 4x3 matrix (c9..c11, picked by a0.x) by the weight in v1.x.
constexpr std::string_view kSkinningBody =
    "mov a0.x, v2.x\n"
    "m4x3 r4, v0, c[a0.x + 9]\n"
    "mul r4, r4, v1.xxxx\n"  // line 5 in both syntaxes: reads r4.w, which the m4x3 did not write
    "mov oPos, r4\n";
constexpr int kSkinningReadLine = 5;

// A normal transformed by m3x3 (.xyz) and written out whole, as in a diffuse-lighting sample.
constexpr std::string_view kNormalBody =
    "mov oPos, v0\n"
    "m3x3 r1, v3, c4\n"
    "mov oD0, r1\n";  // line 5: reads r1.w
constexpr int kNormalReadLine = 5;

constexpr std::string_view kDx8Head = "vs.1.1\n; dx8\n";
constexpr std::string_view kDx9Head = "vs_1_1\ndcl_position v0\ndcl_blendweight v1\ndcl_blendindices v2\ndcl_normal v3\n";

AssembleResult Assemble(std::string_view head, std::string_view body, bool strict = false) {
  AssembleOptions options;
  options.strict = strict;
  return AssembleSource(std::string(head) + std::string(body), "skin.vsh", options);
}

// The DX9 head has five lines before the body, the DX8 head two: shift the body's line numbers.
int Dx9Line(int dx8_line) { return dx8_line + 3; }

int Count(const Diagnostics& diagnostics, Severity severity, DiagnosticCode code) {
  int count = 0;
  for (const Diagnostic& d : diagnostics.all()) count += d.severity == severity && d.code == code;
  return count;
}

const Diagnostic* Find(const Diagnostics& diagnostics, DiagnosticCode code) {
  for (const Diagnostic& d : diagnostics.all()) {
    if (d.code == code) return &d;
  }
  return nullptr;
}

TEST(UninitializedRead, Dx8M4x3ResultReadWholeIsAWarningNamingRegisterLanesAndLine) {
  AssembleResult result = Assemble(kDx8Head, kSkinningBody);
  ASSERT_TRUE(result.program) << result.diagnostics.ToString();
  EXPECT_EQ(result.diagnostics.error_count(), 0);
  ASSERT_EQ(Count(result.diagnostics, Severity::kWarning, DiagnosticCode::kUninitializedLanes), 1)
      << result.diagnostics.ToString();
  const Diagnostic* warning = Find(result.diagnostics, DiagnosticCode::kUninitializedLanes);
  EXPECT_EQ(warning->loc, (SourceLoc{"skin.vsh", kSkinningReadLine, 1}));
  EXPECT_NE(warning->message.find("r4.w"), std::string::npos) << warning->message;
}

TEST(UninitializedRead, Dx8M3x3ResultReadWholeIsAWarning) {
  AssembleResult result = Assemble(kDx8Head, kNormalBody);
  ASSERT_TRUE(result.program) << result.diagnostics.ToString();
  const Diagnostic* warning = Find(result.diagnostics, DiagnosticCode::kUninitializedLanes);
  ASSERT_NE(warning, nullptr) << result.diagnostics.ToString();
  EXPECT_EQ(warning->severity, Severity::kWarning);
  EXPECT_EQ(warning->loc.line, kNormalReadLine);
  EXPECT_NE(warning->message.find("r1.w"), std::string::npos) << warning->message;
}

TEST(UninitializedRead, StrictMakesTheDx8ReadAnError) {
  for (std::string_view body : {kSkinningBody, kNormalBody}) {
    AssembleResult result = Assemble(kDx8Head, body, /*strict=*/true);
    EXPECT_FALSE(result.program);
    EXPECT_EQ(Count(result.diagnostics, Severity::kError, DiagnosticCode::kUninitializedLanes), 1)
        << result.diagnostics.ToString();
  }
}

TEST(UninitializedRead, Dx9SyntaxMakesTheReadAnError) {
  AssembleResult skinning = Assemble(kDx9Head, kSkinningBody);
  EXPECT_FALSE(skinning.program);
  const Diagnostic* error = Find(skinning.diagnostics, DiagnosticCode::kUninitializedLanes);
  ASSERT_NE(error, nullptr) << skinning.diagnostics.ToString();
  EXPECT_EQ(error->severity, Severity::kError);
  EXPECT_EQ(error->loc.line, Dx9Line(kSkinningReadLine));
  EXPECT_NE(error->message.find("r4.w"), std::string::npos) << error->message;

  AssembleResult normal = Assemble(kDx9Head, kNormalBody);
  EXPECT_FALSE(normal.program);
  EXPECT_EQ(Count(normal.diagnostics, Severity::kError, DiagnosticCode::kUninitializedLanes), 1)
      << normal.diagnostics.ToString();
}

TEST(UninitializedRead, NeverWrittenRegisterIsAnErrorInBothSyntaxes) {
  constexpr std::string_view kBody = "mov oPos, v0\nmul oD0, r7, v1.xxxx\n";
  for (std::string_view head : {kDx8Head, kDx9Head}) {
    AssembleResult result = Assemble(head, kBody);
    EXPECT_FALSE(result.program) << head;
    const Diagnostic* error = Find(result.diagnostics, DiagnosticCode::kUninitializedRegister);
    ASSERT_NE(error, nullptr) << result.diagnostics.ToString();
    EXPECT_EQ(error->severity, Severity::kError);
    EXPECT_NE(error->message.find("r7.xyzw"), std::string::npos) << error->message;
    EXPECT_EQ(Count(result.diagnostics, Severity::kWarning, DiagnosticCode::kUninitializedLanes), 0);
  }
}

TEST(UninitializedRead, PartlyAndNeverWrittenInOneInstructionGiveOneOfEach) {
  AssembleResult result = Assemble(kDx8Head, "mov oPos, v0\nmov r1.xy, v0\nmad oD0, r1, r2, v0\n");
  EXPECT_FALSE(result.program);
  EXPECT_EQ(Count(result.diagnostics, Severity::kError, DiagnosticCode::kUninitializedRegister), 1);
  EXPECT_EQ(Count(result.diagnostics, Severity::kWarning, DiagnosticCode::kUninitializedLanes), 1)
      << result.diagnostics.ToString();
}

std::uint32_t Bits(float x) { return std::bit_cast<std::uint32_t>(x); }

// The accepted DX8 program runs, and the lane nothing wrote reads 0 on every engine: oPos.w =
// r4.w * v1.x = 0, while x, y and z are the bone's rows dotted with the position, times the weight.
TEST(UninitializedRead, UnwrittenLaneReadsZeroOnEveryEngine) {
  AssembleResult result = Assemble(kDx8Head, kSkinningBody);
  ASSERT_TRUE(result.program) << result.diagnostics.ToString();
  ConstantBank constants;
  constants[9] = {1, 0, 0, 0.5f};
  constants[10] = {0, 2, 0, 0};
  constants[11] = {0, 0, 3, 0};
  constexpr std::size_t kCount = 16;
  const std::vector<int> registers = {0, 1, 2};
  VertexArrays inputs = MakeInputArrays(kCount, registers);
  const Vec4f position = {1, 2, 3, 1};
  for (int lane = 0; lane < 4; ++lane) {
    inputs.FillUniform(0, lane, position[lane]);
    inputs.FillUniform(1, lane, lane == 0 ? 2.0f : 0.0f);  // weight 2
    inputs.FillUniform(2, lane, 0.0f);                     // bone 0: c9..c11
  }
  const Vec4f expected = {(1 + 0.5f) * 2, 4 * 2, 9 * 2, 0};
  for (std::string kind : {"ref", "batch", "jit"}) {
    std::unique_ptr<Engine> engine = MakeEngine(kind, *result.program, constants).value();
    VertexArrays outputs = MakeOutputArrays(kCount, *result.program);
    ASSERT_EQ(engine->Run(inputs, outputs).message(), "");
    for (int lane = 0; lane < 4; ++lane) {
      const float* values = outputs.lane(static_cast<int>(OutputSlot::kPosition), lane);
      for (std::size_t v = 0; v < kCount; ++v) {
        ASSERT_EQ(Bits(values[v]), Bits(expected[lane])) << kind << " lane " << lane << " vertex " << v;
      }
    }
  }
}

}  // namespace
}  // namespace vs11

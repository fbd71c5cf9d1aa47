// The reference engine on vs_2_0, vs_2_x and vs_3_0 programs (vm/engines/reference_flow.cc): every
// flow-control construct, predicates, relative addressing through aL and a0 at the bank's edges, and
// vs_3_0's declared outputs, each against outputs worked out by hand.
#include <cmath>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "vm/asm/assembler.h"
#include "vm/engines/engine_factory.h"

namespace vs11 {
namespace {

constexpr int kBankSize = 256;
constexpr int kPosition = static_cast<int>(OutputSlot::kPosition);

std::optional<std::string> NoFiles(const std::filesystem::path&) { return std::nullopt; }

// c_k = (k, k, k, k) for k >= 1, c0 = 0: a relative read says which register it reached.
ConstantBank IndexBank() {
  ConstantBank bank(kBankSize);
  for (int k = 1; k < kBankSize; ++k) bank[k] = {float(k), float(k), float(k), float(k)};
  return bank;
}

// Assembles and validates `source`, runs it on the ref engine over one vertex per entry of `v0`, and
// returns output `slot` of each vertex.
std::vector<Vec4f> RunRef(const std::string& source, ConstantBank bank = ConstantBank(kBankSize),
                          std::vector<Vec4f> v0 = {{0, 0, 0, 1}}, int slot = kPosition,
                          FloatRules rules = FloatRules::kD3d9) {
  const AssembleResult assembled = AssembleSource(source, "flow.vsh", {}, NoFiles);
  EXPECT_TRUE(assembled.program) << assembled.diagnostics.ToString();
  if (!assembled.program) return {};
  EngineOptions options;
  options.float_rules = rules;
  Result<std::unique_ptr<Engine>> engine = MakeEngine("ref", *assembled.program, bank, options);
  EXPECT_TRUE(engine.ok()) << engine.message();
  if (!engine.ok()) return {};
  const std::vector<int> registers = {0};
  VertexArrays inputs = MakeInputArrays(v0.size(), registers);
  for (std::size_t i = 0; i < v0.size(); ++i) {
    for (int c = 0; c < 4; ++c) inputs.lane(0, c)[i] = v0[i][c];
  }
  VertexArrays outputs = MakeOutputArrays(v0.size(), *assembled.program);
  EXPECT_EQ((*engine)->Run(inputs, outputs).message(), "");
  std::vector<Vec4f> result(v0.size());
  for (std::size_t i = 0; i < v0.size(); ++i) {
    for (int c = 0; c < 4; ++c) result[i][c] = outputs.lane(slot, c)[i];
  }
  return result;
}

// A bank of kBankSize registers holding `values`, the rest 0.
ConstantBank Bank(std::initializer_list<std::pair<int, Vec4f>> values) {
  ConstantBank bank(kBankSize);
  for (const auto& [index, value] : values) bank[index] = value;
  return bank;
}

Vec4f RunOne(const std::string& source, ConstantBank bank = ConstantBank(kBankSize), int slot = kPosition) {
  const std::vector<Vec4f> result = RunRef(source, std::move(bank), {{0, 0, 0, 1}}, slot);
  return result.empty() ? Vec4f{-999, -999, -999, -999} : result[0];
}

TEST(ReferenceFlow, RepAndLoopThatRunZeroTimesSkipTheirBodies) {
  const Vec4f r = RunOne(
      "vs_2_0\ndefi i0, 0, 0, 0, 0\ndefi i1, 3, 0, 1, 0\ndef c1, 1, 1, 1, 1\ndef c2, 100, 100, 100, 100\n"
      "dcl_position v0\nmov r0, c0\nrep i0\nadd r0, r0, c2\nendrep\nloop aL, i0\nadd r0, r0, c2\nendloop\n"
      "rep i1\nadd r0, r0, c1\nendrep\nmov oPos, r0\n");
  EXPECT_EQ(r, (Vec4f{3, 3, 3, 3}));
}

TEST(ReferenceFlow, LoopCountsOutsideTheRangeAreClamped) {
  ConstantBank bank = Bank({{1, {1, 1, 1, 1}}});
  bank.integer(0) = {300, 0, 1, 0};
  bank.integer(1) = {-5, 0, 1, 0};
  const Vec4f r = RunOne("vs_2_0\ndcl_position v0\nmov r0, c0\nrep i0\nadd r0.x, r0.x, c1.x\nendrep\n"
                         "rep i1\nadd r0.y, r0.y, c1.y\nendrep\nmov oPos, r0\n",
                         bank);
  EXPECT_EQ(r, (Vec4f{255, 0, 0, 0}));
}

TEST(ReferenceFlow, NestedLoopsUseTheInnerAlAndRestoreTheOuter) {
  // Outer aL = 1, 2; inner aL = 10, 12, 14 each time.
  const Vec4f r = RunOne(
      "vs_2_0\ndefi i0, 2, 1, 1, 0\ndefi i1, 3, 10, 2, 0\ndcl_position v0\nmov r0, c0\n"
      "loop aL, i0\nloop aL, i1\nadd r0.x, r0.x, c0[aL]\nendloop\nadd r0.y, r0.y, c0[aL]\nendloop\nmov oPos, r0\n",
      IndexBank());
  EXPECT_EQ(r, (Vec4f{2 * (10 + 12 + 14), 1 + 2, 0, 0}));
}

TEST(ReferenceFlow, BreakLeavesOnlyTheInnermostLoop) {
  // Inner rep of 5 broken after 2 passes, three times over.
  const Vec4f counted = RunOne(
      "vs_2_x\ndefi i0, 3, 0, 1, 0\ndefi i1, 5, 0, 1, 0\ndef c1, 1, 1, 1, 1\ndef c2, 2, 2, 2, 2\n"
      "dcl_position v0\nmov r0, c0\nrep i0\nmov r1.x, c0.x\nrep i1\nadd r1.x, r1.x, c1.x\n"
      "add r0.x, r0.x, c1.x\nbreak_ge r1.x, c2.x\nendrep\nadd r0.y, r0.y, c1.y\nendrep\nmov oPos, r0\n");
  EXPECT_EQ(counted, (Vec4f{6, 3, 0, 0}));
  // break out of an inner loop restores the outer aL (1, then 2).
  const Vec4f al = RunOne(
      "vs_2_x\ndefi i0, 2, 1, 1, 0\ndefi i1, 4, 20, 1, 0\ndcl_position v0\nmov r0, c0\n"
      "loop aL, i0\nloop aL, i1\nadd r0.x, r0.x, c0[aL]\nbreak\nendloop\nadd r0.y, r0.y, c0[aL]\nendloop\nmov oPos, r0\n",
      IndexBank());
  EXPECT_EQ(al, (Vec4f{40, 3, 0, 0}));
}

TEST(ReferenceFlow, BreakpLeavesWhenThePredicateLaneIsTrue) {
  const Vec4f r = RunOne(
      "vs_2_x\ndefi i0, 10, 0, 1, 0\ndef c1, 1, 1, 1, 1\ndef c2, 4, 4, 4, 4\ndcl_position v0\nmov r0, c0\n"
      "rep i0\nadd r0, r0, c1\nsetp_ge p0, r0, c2\nbreakp p0.y\nendrep\nmov oPos, r0\n");
  EXPECT_EQ(r, (Vec4f{4, 4, 4, 4}));
}

TEST(ReferenceFlow, CallFromInsideALoopReturnsIntoIt) {
  ConstantBank bank = Bank({{1, {1, 2, 3, 4}}});
  const Vec4f r = RunOne("vs_2_0\ndefi i0, 3, 0, 0, 0\ndcl_position v0\nmov r0, c0\nrep i0\ncall l0\nendrep\n"
                         "mov oPos, r0\nret\nlabel l0\nadd r0, r0, c1\nret\n",
                         bank);
  EXPECT_EQ(r, (Vec4f{3, 6, 9, 12}));
}

TEST(ReferenceFlow, CallnzOnBooleansFromTheProgramAndTheCaller) {
  ConstantBank bank = Bank({{1, {1, 0, 0, 0}}, {2, {0, 10, 0, 0}}, {3, {0, 0, 100, 0}}});
  bank.SetBoolean(2, true);  // set by the API, as c# is
  const Vec4f r = RunOne("vs_2_0\ndefb b0, true\ndefb b1, false\ndcl_position v0\nmov r0, c0\n"
                         "callnz l0, b0\ncallnz l1, b1\ncallnz l2, b2\nmov oPos, r0\nret\n"
                         "label l0\nadd r0, r0, c1\nret\nlabel l1\nadd r0, r0, c2\nret\nlabel l2\nadd r0, r0, c3\nret\n",
                         bank);
  EXPECT_EQ(r, (Vec4f{1, 0, 100, 0}));
}

TEST(ReferenceFlow, IfOnABooleanTakesEitherBranch) {
  ConstantBank bank = Bank({{1, {1, 0, 0, 0}}, {2, {0, 1, 0, 0}}});
  const Vec4f r = RunOne("vs_2_0\ndefb b0, true\ndefb b1, false\ndcl_position v0\nmov r0, c0\n"
                         "if b0\nadd r0, r0, c1\nelse\nadd r0, r0, c2\nendif\n"
                         "if b1\nadd r0.zw, r0, c1.x\nelse\nadd r0.z, r0.z, c2.y\nendif\nmov oPos, r0\n",
                         bank);
  EXPECT_EQ(r, (Vec4f{1, 0, 1, 0}));
}

TEST(ReferenceFlow, APredicatedWriteChangesOnlyTheTrueLanes) {
  ConstantBank bank = Bank({{1, {5, 5, 5, 5}}, {2, {7, 7, 7, 7}}});
  const std::vector<Vec4f> r = RunRef("vs_2_x\ndcl_position v0\nsetp_gt p0, v0, c0\nmov r0, c1\n(p0) mov r0, v0\n"
                                      "mov r1, c1\n(!p0) mov r1, c2\n(p0.x) add r0.w, r0.w, c2.w\n"
                                      "mov oPos, r0\nmov oD0, r1\n",
                                      bank, {{1, -1, 2, -2}});
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0], (Vec4f{1, 5, 2, 12}));
  const std::vector<Vec4f> d0 = RunRef("vs_2_x\ndcl_position v0\nsetp_gt p0, v0, c0\nmov r1, c1\n(!p0) mov r1, c2\n"
                                       "mov oPos, v0\nmov oD0, r1\n",
                                       bank, {{1, -1, 2, -2}}, static_cast<int>(OutputSlot::kDiffuse));
  ASSERT_EQ(d0.size(), 1u);
  EXPECT_EQ(d0[0], (Vec4f{5, 7, 5, 7}));
}

TEST(ReferenceFlow, IfAndCallnzOnAPredicateLane) {
  ConstantBank bank = Bank({{1, {1, 0, 0, 0}}, {2, {0, 1, 0, 0}}, {3, {0, 0, 1, 0}}, {4, {0, 0, 0, 1}}});
  const std::string source =
      "vs_2_x\ndcl_position v0\nsetp_gt p0, v0, c0\nmov r0, c0\nif p0.x\nadd r0, r0, c1\nendif\n"
      "if !p0.y\nadd r0, r0, c2\nendif\ncallnz l0, p0.z\ncallnz l1, !p0.w\nmov oPos, r0\nret\n"
      "label l0\nadd r0, r0, c3\nret\nlabel l1\nadd r0, r0, c4\nret\n";
  const std::vector<Vec4f> r = RunRef(source, bank, {{1, 1, 1, 1}, {-1, -1, -1, -1}});
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0], (Vec4f{1, 0, 1, 0}));
  EXPECT_EQ(r[1], (Vec4f{0, 1, 0, 1}));
}

TEST(ReferenceFlow, IfCompBranchesPerVertex) {
  ConstantBank bank = Bank({{1, {1, 1, 1, 1}}, {2, {2, 2, 2, 2}}});
  const std::vector<Vec4f> r =
      RunRef("vs_2_x\ndcl_position v0\nif_gt v0.x, c0.x\nmov r0, c1\nelse\nmov r0, c2\nendif\nmov oPos, r0\n", bank,
             {{1, 0, 0, 1}, {-1, 0, 0, 1}, {0, 0, 0, 1}});
  ASSERT_EQ(r.size(), 3u);
  EXPECT_EQ(r[0], (Vec4f{1, 1, 1, 1}));
  EXPECT_EQ(r[1], (Vec4f{2, 2, 2, 2}));
  EXPECT_EQ(r[2], (Vec4f{2, 2, 2, 2}));
}

TEST(ReferenceFlow, RelativeReadsAtTheBanksEdgesReadZeroOutside) {
  ConstantBank bank = IndexBank();
  bank[3] = {-1.4f, 0, 0, 0};
  // aL = 254, 255 (both inside); aL = 255, 256 (the second outside: 0); a0.x = round(-1.4) = -1: c[-1] = 0.
  const Vec4f r = RunOne("vs_2_0\ndefi i0, 2, 254, 1, 0\ndefi i1, 2, 255, 1, 0\ndcl_position v0\nmov r0, c0\n"
                         "loop aL, i0\nadd r0.x, r0.x, c0[aL]\nendloop\nloop aL, i1\nadd r0.y, r0.y, c0[aL]\nendloop\n"
                         "mova a0.x, c3.x\nmov r1.z, c2.z\nadd r0.z, c0[a0.x].z, r1.z\nmov oPos, r0\n",
                         bank);
  EXPECT_EQ(r, (Vec4f{254 + 255, 255, 2, 0}));
}

TEST(ReferenceFlow, MovaRoundsHalvesAwayFromZero) {
  ConstantBank bank = IndexBank();
  bank[200] = {2.5f, -2.5f, 0.5f, -0.5f};
  const Vec4f r = RunOne("vs_2_x\ndcl_position v0\nmova a0, c200\nmov r0.x, c10[a0.x].x\nmov r0.y, c10[a0.y].y\n"
                         "mov r0.z, c10[a0.z].z\nmov r0.w, c10[a0.w].w\nmov oPos, r0\n",
                         bank);
  EXPECT_EQ(r, (Vec4f{13, 7, 11, 9}));
}

TEST(ReferenceFlow, TheNewArithmeticThroughTheEngine) {
  const Vec4f r = RunOne(
      "vs_2_0\ndef c1, 0, 0, 0, 0\ndef c2, 3, 0, 4, 10\ndef c3, -1.5, 0, 2, -0\ndef c4, 1, 2, 3, 0\ndef c5, 4, 5, 6, 0\n"
      "def c6, -1.5500992e-006, -2.1701389e-005, 0.0026041667, 0.00026041668\n"
      "def c7, -0.020833334, -0.12500000, 1.0, 0.50000000\ndef c8, 9, 9, 9, 9\ndef c9, 2, 3, 0, 0\n"
      "dcl_position v0\nmov r0, c8\nsincos r0.xy, c1.x, c6, c7\nnrm r1, c2\nsgn r2, c3, r4, r5\nmov r9, c5\ncrs r3.xyz, c4, r9\n"
      "pow r6, c9.x, c9.y\nadd r7.x, r0.x, r0.y\nadd r7.y, r0.z, r0.w\nadd r7.z, r1.x, r1.z\nadd r7.w, r1.w, r6.x\n"
      "dp4 r8.x, r2, c4\ndp3 r8.y, r3, c4\nmov r8.zw, r7\nadd oPos, r7, r8\n");
  // r0 = (cos 0, sin 0, 9, 9); r1 = (0.6, 0, 0.8, 2); r2 = (-1, 0, 1, 0); r3 = (-3, 6, -3); r6 = 8.
  // r7 = (1, 18, 1.4, 10); r8 = (-1 + 3, -3 + 12 - 9, 1.4, 10).
  EXPECT_FLOAT_EQ(r[0], 1 + 2);
  EXPECT_FLOAT_EQ(r[1], 18 + 0);
  EXPECT_FLOAT_EQ(r[2], 2.8f);
  EXPECT_FLOAT_EQ(r[3], 20);
}

TEST(ReferenceFlow, Vs30OutputsGoToTheSlotsTheirDeclarationsName) {
  ConstantBank bank = Bank({{1, {1, 2, 3, 4}}, {2, {5, 6, 7, 8}}});
  const std::string source =
      "vs_3_0\ndcl_position v0\ndcl_position o0\ndcl_texcoord2 o5\ndcl_color1 o3\n"
      "mov o0, v0\nmov o5, c1\nmov o3, c2\n";
  EXPECT_EQ(RunRef(source, bank, {{9, 8, 7, 6}})[0], (Vec4f{9, 8, 7, 6}));
  EXPECT_EQ(RunRef(source, bank, {{9, 8, 7, 6}}, static_cast<int>(OutputSlot::kTexCoord0) + 2)[0], (Vec4f{1, 2, 3, 4}));
  EXPECT_EQ(RunRef(source, bank, {{9, 8, 7, 6}}, static_cast<int>(OutputSlot::kSpecular))[0], (Vec4f{5, 6, 7, 8}));
}

TEST(ReferenceFlow, Vs30OutputsThroughAlAndSaturatedAbsoluteSources) {
  ConstantBank bank = Bank({{1, {1, 2, 3, 4}}, {2, {5, 6, 7, 8}}, {4, {-0.5f, 2, -3, -0.25f}}});
  const std::string source =
      "vs_3_0\ndefi i0, 2, 0, 1, 0\ndcl_position v0\ndcl_position o0\ndcl_texcoord0 o1\ndcl_texcoord1 o2\n"
      "dcl_color0 o3\nmov o0, v0\nloop aL, i0\nmov o[aL + 1], c1[aL]\nendloop\nmov_sat o3, c4_abs\n";
  const int texcoord0 = static_cast<int>(OutputSlot::kTexCoord0);
  EXPECT_EQ(RunRef(source, bank, {{0, 0, 0, 1}}, texcoord0)[0], (Vec4f{1, 2, 3, 4}));
  EXPECT_EQ(RunRef(source, bank, {{0, 0, 0, 1}}, texcoord0 + 1)[0], (Vec4f{5, 6, 7, 8}));
  EXPECT_EQ(RunRef(source, bank, {{0, 0, 0, 1}}, static_cast<int>(OutputSlot::kDiffuse))[0], (Vec4f{0.5f, 1, 1, 0.25f}));
}

TEST(ReferenceFlow, TheBankHasTheModelsConstantsWhateverTheApiBanksSize) {
  ConstantBank small;  // kDefaultConstantCount, vs_1_1's 96
  small[5] = {5, 5, 5, 5};
  const Vec4f r = RunOne("vs_2_0\ndef c200, 1, 2, 3, 4\ndcl_position v0\nmov r0, c5\nadd oPos, c200, r0\n", small);
  EXPECT_EQ(r, (Vec4f{6, 7, 8, 9}));
}

AssembleResult Assembled(const std::string& source) { return AssembleSource(source, "refused.vsh", {}, NoFiles); }

TEST(ReferenceFlow, EnginesWithoutVertexTexturesRefuseTexldlAndOutputsWithoutASlotByName) {
  const AssembleResult texldl = Assembled("vs_3_0\ndcl_position v0\ndcl_position o0\ndcl_2d s0\ntexldl r0, v0, s0\nmov o0, r0\n");
  ASSERT_TRUE(texldl.program) << texldl.diagnostics.ToString();
  EXPECT_TRUE(MakeEngine("ref", *texldl.program, ConstantBank()).ok());
  const Result<std::unique_ptr<Engine>> refused = MakeEngine("gl", *texldl.program, ConstantBank());
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().code, DiagnosticCode::kEngineUnavailable);
  EXPECT_NE(refused.message().find("texldl"), std::string::npos) << refused.message();
  EXPECT_NE(refused.message().find("line 5"), std::string::npos) << refused.message();

  const AssembleResult normal = Assembled("vs_3_0\ndcl_position v0\ndcl_position o0\ndcl_normal o1\nmov o0, v0\nmov o1, v0\n");
  ASSERT_TRUE(normal.program) << normal.diagnostics.ToString();
  const Result<std::unique_ptr<Engine>> no_slot = MakeEngine("reference", *normal.program, ConstantBank());
  ASSERT_FALSE(no_slot.ok());
  EXPECT_NE(no_slot.message().find("o1 is declared dcl_normal"), std::string::npos) << no_slot.message();
}

TEST(ReferenceFlow, BothFloatRulesRunTheLaterModels) {
  // lrp with a zero weight and an infinite span: NaN under d3d9's products, s2 under legacy's.
  ConstantBank bank = Bank({{1, {INFINITY, INFINITY, INFINITY, INFINITY}}, {2, {1, 1, 1, 1}}});
  const std::string source = "vs_2_0\ndcl_position v0\nmov r1, c1\nmov r2, c2\nlrp r0, c0, r1, r2\nmov oPos, r0\n";
  EXPECT_TRUE(std::isnan(RunRef(source, bank, {{0, 0, 0, 1}}, kPosition, FloatRules::kD3d9)[0][0]));
  EXPECT_EQ(RunRef(source, bank, {{0, 0, 0, 1}}, kPosition, FloatRules::kLegacy)[0], (Vec4f{1, 1, 1, 1}));
}

}  // namespace
}  // namespace vs11

// The batch engine's plan (vm/engines/batch_plan.cc) on hand-written programs: the steps it makes, and
// above all when it joins a dp into the previous dot step (one kernel then loads the shared vector
// once). A joined row is computed before the earlier rows store, so a join that reads what those
// rows write, or that crosses a gather, would compute with stale values: each case below checks the
// plan's shape and then runs the program on the batch engine against the reference engine, bit for
// bit.
#include "vm/engines/batch_plan.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "vm/asm/assembler.h"
#include "vm/engines/batch_engine.h"
#include "vm/engines/reference_engine.h"

namespace vs11::batch {
namespace {

Program Assemble(const std::string& body) {
  AssembleOptions options;
  options.validate = false;  // some cases read registers the same instruction writes, on purpose
  AssembleResult assembled = AssembleSource("vs.1.1\n" + body, "plan.vsh", options);
  EXPECT_TRUE(assembled.program.has_value()) << assembled.diagnostics.ToString();
  return assembled.program.value_or(Program{});
}

// A kernel table whose dot kernels are distinct functions, so that a step's kernel tells which row
// count and operand kinds the plan chose. The other families stay null: the plan only stores them.
template <int kId>
void FakeDotKernel(const Step&, const Frame&) {
  static volatile int calls = 0;
  calls = calls + kId;  // distinct bodies, so that no two are folded into one function
}

template <int... kIds>
KernelTable FakeTable(std::integer_sequence<int, kIds...>) {
  KernelTable table;
  const Kernel kernels[] = {&FakeDotKernel<kIds>...};
  int next = 0;
  for (auto& width : table.dot) {
    for (auto& rows : width) {
      for (Kernel& kernel : rows) kernel = kernels[next++];
    }
  }
  return table;
}

const KernelTable& Table() {
  static const KernelTable table = FakeTable(std::make_integer_sequence<int, 2 * 4 * 9>());
  return table;
}

// Kinds index of a dot step: vector kind + 3 * row kind (OperandKind: array 0, negated 1, broadcast 2).
constexpr int kArrayVectorConstantRows = 0 + 3 * 2;

// The dot steps of `plan` (pointers into it: keep the plan alive).
std::vector<const Step*> DotSteps(const BatchPlan& plan) {
  std::vector<const Step*> dots;
  for (const Step& step : plan.steps) {
    for (const auto& width : Table().dot) {
      for (const auto& rows : width) {
        if (std::find(rows.begin(), rows.end(), step.kernel) != rows.end()) dots.push_back(&step);
      }
    }
  }
  return dots;
}

int RowsOf(const Step& step) {
  return static_cast<int>(std::count_if(step.dest.begin(), step.dest.end(), [](std::uint16_t l) { return l != kNoLane; }));
}

// The rows of each dot step of the program's plan, in order.
std::vector<int> DotRowCounts(const Program& program) {
  const BatchPlan plan = BuildBatchPlan(program, Table());
  std::vector<int> rows;
  for (const Step* step : DotSteps(plan)) rows.push_back(RowsOf(*step));
  return rows;
}

// The program on the batch engine and the reference engine, over inputs that make every row differ.
void ExpectBatchMatchesReference(const Program& program) {
  constexpr std::size_t kCount = 300;  // a full batch and a padded short one
  ConstantBank constants;
  for (int r = 0; r < 16; ++r) constants[r] = {0.5f + r, -1.25f * r, 3.0f - r, 0.125f * (r + 1)};
  const int registers[] = {0, 1};
  VertexArrays inputs = MakeInputArrays(kCount, registers);
  for (int reg : registers) {
    for (int c = 0; c < 4; ++c) {
      for (std::size_t i = 0; i < kCount; ++i) inputs.lane(reg, c)[i] = static_cast<float>((i * 7 + c * 3 + reg) % 11) - 4.5f;
    }
  }
  VertexArrays expected = MakeOutputArrays(kCount, program), actual = MakeOutputArrays(kCount, program);
  ASSERT_EQ(MakeReferenceEngine(program, constants)->Run(inputs, expected).message(), "");
  ASSERT_EQ(MakeBatchEngine(program, constants, {})->Run(inputs, actual).message(), "");
  for (int slot : expected.registers()) {
    for (int c = 0; c < 4; ++c) {
      for (std::size_t i = 0; i < kCount; ++i) {
        ASSERT_EQ(std::bit_cast<std::uint32_t>(actual.lane(slot, c)[i]),
                  std::bit_cast<std::uint32_t>(expected.lane(slot, c)[i]))
            << OutputSlotName(slot) << " lane " << c << " vertex " << i;
      }
    }
  }
}

TEST(BatchPlan, ThreeDotsOfOneVectorBecomeOneStepOfThreeRows) {
  const Program program = Assemble(
      "dcl_position v0\n"
      "dp4 r0.x, v0, c4\n"
      "dp4 r0.y, v0, c5\n"
      "dp4 r0.z, v0, c6\n"
      "mov oPos, r0\n");
  const BatchPlan plan = BuildBatchPlan(program, Table());
  const std::vector<const Step*> dots = DotSteps(plan);
  ASSERT_EQ(dots.size(), 1u);
  const Step& step = *dots[0];
  EXPECT_EQ(RowsOf(step), 3);
  EXPECT_EQ(step.kernel, Table().dot[1][2][kArrayVectorConstantRows]);
  for (int row = 0; row < 3; ++row) {
    for (int c = 0; c < 4; ++c) EXPECT_EQ(step.sources[1 + row][c], (Operand{ConstantIndex(4 + row, c), false}));
  }
  EXPECT_EQ(plan.max_static_constant, 6);
  ExpectBatchMatchesReference(program);
}

TEST(BatchPlan, AJoinStopsAtFourRows) {
  const Program program = Assemble(
      "dcl_position v0\n"
      "dp4 r0.x, v0, c0\n"
      "dp4 r0.y, v0, c1\n"
      "dp4 r0.z, v0, c2\n"
      "dp4 r0.w, v0, c3\n"
      "dp4 r1.x, v0, c4\n"
      "mov oPos, r0\n"
      "mov oD0, r1.x\n");
  EXPECT_EQ(DotRowCounts(program), (std::vector<int>{4, 1}));
  ExpectBatchMatchesReference(program);
}

TEST(BatchPlan, MatrixRowsTakeAFollowingDotOfTheSameVector) {
  const Program program = Assemble(
      "dcl_position v0\n"
      "m4x3 r0.xyz, v0, c0\n"
      "dp4 r0.w, v0, c3\n"
      "mov oPos, r0\n");
  const BatchPlan plan = BuildBatchPlan(program, Table());
  const std::vector<const Step*> dots = DotSteps(plan);
  ASSERT_EQ(dots.size(), 1u);
  EXPECT_EQ(dots[0]->kernel, Table().dot[1][3][kArrayVectorConstantRows]);  // four rows
  ExpectBatchMatchesReference(program);
}

// Each program has two dot steps that share their vector but must stay apart; why is in its name.
struct Hazard {
  const char* name;
  const char* body;
};

class BatchPlanHazard : public ::testing::TestWithParam<Hazard> {};

TEST_P(BatchPlanHazard, KeepsTheDotsApartAndMatchesTheReferenceEngine) {
  const Program program = Assemble(std::string("dcl_position v0\ndcl_normal v1\n") + GetParam().body);
  EXPECT_EQ(DotRowCounts(program), (std::vector<int>{1, 1}));
  ExpectBatchMatchesReference(program);
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BatchPlanHazard,
    ::testing::Values(
        // The second row's matrix source is the lane the first row writes (rows of one kind: arrays).
        Hazard{"RowReadsAnEarlierRowsResult", "dp4 r0.x, v0, v1\ndp4 r0.y, v0, r0.x\nmov oPos, r0\n"},
        // The shared vector is the register the rows write.
        Hazard{"VectorIsTheDestination", "mov r1, v0\ndp4 r1.x, r1, c0\ndp4 r1.y, r1, c1\nmov oPos, r1\n"},
        // -v0 is loaded negated, v0 not.
        Hazard{"DifferentNegation", "dp4 r0.x, v0, c0\ndp4 r0.y, -v0, c1\nmov oPos, r0\n"},
        // dp3 reads three components, dp4 four.
        Hazard{"DifferentWidth", "dp3 r0.x, v0, c0\ndp4 r0.y, v0, c1\nmov oPos, r0\n"},
        // Another instruction comes between them.
        Hazard{"InstructionBetween", "dp4 r0.x, v0, c0\nmov r2, v1\ndp4 r0.y, v0, c1\nadd oPos, r0, r2\n"},
        // The first dp writes two lanes (a copy step follows it).
        Hazard{"ReplicatedFirstDot", "dp4 r0.xy, v0, c0\ndp4 r0.z, v0, c1\nmov oPos, r0\n"},
        // The rows are gathered through a0 after it is written, each in a gather step of its own.
        Hazard{"RelativeRows",
               "mov a0.x, v1.x\ndp4 r0.x, v0, c[a0.x + 2]\ndp4 r0.y, v0, c[a0.x + 3]\nmov oPos, r0\n"}),
    [](const ::testing::TestParamInfo<Hazard>& info) { return std::string(info.param.name); });

TEST(BatchPlan, ListsTheInputLanesReadAndTheOutputLanesStored) {
  const Program program = Assemble(
      "dcl_position v0\n"
      "dcl_normal v3\n"
      "mov oPos, v0\n"
      "mov oD0.xz, v3.y\n");
  const BatchPlan plan = BuildBatchPlan(program, Table());
  const std::vector<std::uint16_t> inputs = {
      static_cast<std::uint16_t>(InputLane(0, 0)), static_cast<std::uint16_t>(InputLane(0, 1)),
      static_cast<std::uint16_t>(InputLane(0, 2)), static_cast<std::uint16_t>(InputLane(0, 3)),
      static_cast<std::uint16_t>(InputLane(3, 1))};
  EXPECT_EQ(plan.input_lanes, inputs);
  const int position = static_cast<int>(OutputSlot::kPosition), diffuse = static_cast<int>(OutputSlot::kDiffuse);
  EXPECT_EQ(plan.stored_lanes[position], 0xF);
  EXPECT_EQ(plan.stored_lanes[diffuse], 0x5);
  EXPECT_EQ(std::count(plan.output_lanes.begin(), plan.output_lanes.end(), OutputLane(diffuse, 1)), 0);
  EXPECT_EQ(std::count(plan.output_lanes.begin(), plan.output_lanes.end(), OutputLane(diffuse, 2)), 1);
  EXPECT_EQ(plan.max_static_constant, -1);
}

}  // namespace
}  // namespace vs11::batch

// The shader debugger on the later models (vm/engines/flow_trace.h): every instruction in the order the
// reference engine runs it, loops once per iteration, branches not taken left out, calls into their
// label, with the aL, a0, p0, b# and i# values read, predicated-off lanes marked; text and JSON.
#include "vm/engines/flow_trace.h"

#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/vm/engines/later_model_comparison.h"
#include "vm/core/machine.h"

namespace vs11 {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// A loop of three iterations over c10[aL] (aL 0, 2, 4: 1, 2, 1) that a vertex leaves early by break_gt, an if
// on b0 (true) around a call, an if on b1 (false) that is skipped, mova and a relative read through
// a0.y, setp and a predicated write.
constexpr const char* kProgram =
    "vs_2_x\n"                   // line 1
    "defi i0, 3, 0, 2, 0\n"
    "defb b0, true\n"
    "defb b1, false\n"
    "def c0, 5, 0, 0, 0\n"       // line 5
    "dcl_position v0\n"
    "mov r0, v0\n"
    "loop aL, i0\n"
    "add r0, r0, c10[aL]\n"
    "break_gt r0.x, c0.x\n"      // line 10
    "endloop\n"
    "if b0\n"
    "call l1\n"
    "endif\n"
    "if b1\n"                    // line 15
    "mov r0, c0\n"
    "endif\n"
    "mova a0.y, c0.y\n"
    "add r0, r0, c20[a0.y]\n"
    "setp_gt p0, r0, c0\n"       // line 20
    "(p0) mov r0.xyz, c0\n"
    "mov oPos, r0\n"
    "ret\n"
    "label l1\n"
    "add r0, r0, c0\n"           // line 25
    "ret\n";

ConstantBank Bank() {
  ConstantBank bank(256);
  bank[10] = {1, 0, 0, 0};
  bank[12] = {2, 0, 0, 0};
  bank[14] = {1, 0, 0, 0};
  bank[20] = {0, 1, 0, 0};
  return bank;
}

VertexArrays Inputs(float x) {
  VertexArrays inputs = MakeInputArrays(1, std::vector<int>{0});
  const Vec4f v = {x, 0, 0, 1};
  for (int c = 0; c < 4; ++c) inputs.lane(0, c)[0] = v[c];
  return inputs;
}

std::vector<int> Lines(const Program& program, const VertexTrace& trace) {
  std::vector<int> lines;
  for (const TraceStep& step : trace.steps) lines.push_back(program.LocOf(step.instruction_index).line);
  return lines;
}

TEST(FlowTrace, StepsFollowTheProgramCounterThroughLoopsBranchesAndCalls) {
  const Program program = later_model::Assemble(kProgram);
  // x = 0: all three iterations (r0.x 1, 3, 4: no break); the call; b1's block skipped.
  const VertexTrace all = TraceVertex(program, Bank(), Inputs(0), 0);
  EXPECT_EQ(Lines(program, all), (std::vector<int>{7, 8, 9, 10, 11, 9, 10, 11, 9, 10, 11, 12, 13, 25, 26, 14, 15, 18,
                                                   19, 20, 21, 22, 23}));
  // x = 3: the second iteration's break (3 + 1 + 2 = 6 > 5) leaves the loop.
  const VertexTrace early = TraceVertex(program, Bank(), Inputs(3), 0);
  EXPECT_EQ(Lines(program, early), (std::vector<int>{7, 8, 9, 10, 11, 9, 10, 12, 13, 25, 26, 14, 15, 18, 19, 20, 21, 22, 23}));
}

TEST(FlowTrace, NotesSayWhatEachFlowInstructionDecided) {
  const Program program = later_model::Assemble(kProgram);
  const VertexTrace trace = TraceVertex(program, Bank(), Inputs(3), 0);
  std::vector<std::string> notes;
  for (const TraceStep& step : trace.steps) {
    if (!step.note.empty()) notes.push_back(step.note);
  }
  EXPECT_EQ(notes, (std::vector<std::string>{"3 iterations, aL = 0, step 2", "false: stays in the loop",
                                             "next iteration, aL = 2", "true: leaves the loop, continues at line 12",
                                             "true: runs the block", "calls l1 at line 25", "returns to line 14",
                                             "false: continues at line 18", "the program ends"}));
}

TEST(FlowTrace, ReadsShowTheAddressAndConditionsAndPredicatedOffLanes) {
  const Program program = later_model::Assemble(kProgram);
  VertexTrace trace = TraceVertex(program, Bank(), Inputs(0), 0);
  CompareOutputs(later_model::RunOn("ref", program, Bank(), Inputs(0), {}), trace);
  SourceLines sources;
  const std::string text = FormatTraceText(program, trace, "ref", sources);
  EXPECT_THAT(text, HasSubstr("read  c10[aL] = (2, 0, 0, 0)   from c12 = (2, 0, 0, 0) (aL = 2)"));
  EXPECT_THAT(text, HasSubstr("read  i0 = (3, 0, 2, 0)"));
  EXPECT_THAT(text, HasSubstr("read  b1 = false"));
  EXPECT_THAT(text, HasSubstr("write a0.y -> a0 = (kept 0, 0, kept 0, kept 0)"));
  EXPECT_THAT(text, HasSubstr("from c20 = (0, 1, 0, 0) (a0.y = 0)"));
  // r0 = (9, 1, 0, 1) > (5, 0, 0, 0) but on z: p0 = (true, true, false, true); z is predicated off.
  EXPECT_THAT(text, HasSubstr("write p0 -> p0 = (true, true, false, true)"));
  EXPECT_THAT(text, HasSubstr("read  (p0) = (true, true, false, true)   from p0 = (true, true, false, true)"));
  EXPECT_THAT(text, HasSubstr("write r0.xyz -> r0 = (5, 0, off 0, kept 1)"));
  EXPECT_THAT(text, HasSubstr("flow  calls l1 at line 25"));
  EXPECT_THAT(text, Not(HasSubstr("mov r0, c0\n")));  // b1's block never ran
  EXPECT_THAT(text, HasSubstr("oPos = (5, 0, 0, 1) | (5, 0, 0, 1)  identical"));

  const nlohmann::json json = nlohmann::json::parse(TraceJson(program, trace, sources));
  const nlohmann::json& steps = json["steps"];
  ASSERT_EQ(steps.size(), trace.steps.size());
  EXPECT_EQ(steps[1]["flow"], "3 iterations, aL = 0, step 2");
  EXPECT_EQ(steps[2]["reads"][1]["address"], "aL = 0");
  EXPECT_EQ(steps[2]["reads"][1]["register"], "c10");
  const nlohmann::json& predicated = steps[20];
  EXPECT_EQ(predicated["instruction"], "(p0) mov r0.xyz, c0");
  EXPECT_EQ(predicated["write"]["lanes"], "xy");
  EXPECT_EQ(predicated["write"]["predicated_off"], "z");
  EXPECT_EQ(predicated["reads"][1]["value"], nlohmann::json({true, true, false, true}));
}

}  // namespace
}  // namespace vs11

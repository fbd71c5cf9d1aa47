// The shader debugger (vm/engines/trace.h) and `vs11 run --trace` end to end.
#include "vm/engines/engine_factory.h"
#include "vm/engines/trace.h"

#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "tests/run_tool.h"
#include "vm/asm/assembler.h"
#include "vm/core/machine.h"

namespace vs11 {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;
using testing::CommandResult;
using testing::RunVs11;

// A masked write of a negated, swizzled read through a macro, a relative constant set up by an
// instruction in an #include'd file, and a matrix. With v0 = (1, 2, 3, 4), c0-c3 the identity and
// c4 = (10, 20, 30, 40): r1 = (4, 3, 2, 1), a0 = 1, r2.xz = -3 + (10, 30), oPos = v0.
constexpr const char* kMainSource =
    "vs_1_1\n"
    "dcl_position v0\n"
    "def c10, 1, 2, 3, 4\n"
    "#define NEG_Y -r1.y\n"
    "mov r1, v0.wzyx\n"
    "#include \"step.inc\"\n"
    "add r2.xz, NEG_Y, c[a0.x + 3]  ; masked\n"
    "m4x4 oPos, v0, c0\n"
    "mov oD0.xz, r2\n";
constexpr const char* kIncludedSource = "mov a0.x, c10.x\n";
constexpr const char* kConstants = "c0 = 1 0 0 0\nc1 = 0 1 0 0\nc2 = 0 0 1 0\nc3 = 0 0 0 1\nc4 = 10 20 30 40\n";

class TraceTest : public vs11::testing::ToolFolderTest {
 protected:
  void SetUp() override {
    ToolFolderTest::SetUp();
    main_ = Write("main.vsh", kMainSource);
    Write("step.inc", kIncludedSource);
    constants_ = Write("k.txt", kConstants);
    inputs_ = Write("v0.csv", "0,0,0,1\n1,2,3,4\n");
  }
  std::string RunArgs() const { return main_ + " --consts " + constants_ + " --input v0=" + inputs_; }

  std::string main_, constants_, inputs_;
};

ConstantBank TestConstants() {
  ConstantBank bank;
  for (int i = 0; i < 4; ++i) bank[i][i] = 1.0f;
  bank[4] = {10.0f, 20.0f, 30.0f, 40.0f};
  return bank;
}

VertexArrays OneVertex(const Vec4f& v0) {
  std::vector<int> registers = {0};
  VertexArrays inputs = MakeInputArrays(1, registers);
  for (int c = 0; c < 4; ++c) inputs.lane(0, c)[0] = v0[c];
  return inputs;
}

TEST_F(TraceTest, RecordsReadsWritesAndSourceLines) {
  AssembleResult assembled = AssembleFile(main_, {});
  ASSERT_TRUE(assembled.program) << assembled.diagnostics.ToString();
  const Program& program = *assembled.program;
  VertexTrace trace = TraceVertex(program, TestConstants(), OneVertex({1, 2, 3, 4}), 0);

  ASSERT_EQ(trace.steps.size(), 5u);  // dcl and def are not executed
  EXPECT_THAT(program.LocOf(trace.steps[1].instruction_index).file, HasSubstr("step.inc"));
  EXPECT_EQ(program.LocOf(trace.steps[1].instruction_index).line, 1);
  EXPECT_EQ(trace.steps[1].write->after[0], 1.0f);  // a0.x

  const TraceStep& add = trace.steps[2];
  EXPECT_EQ(program.LocOf(add.instruction_index).line, 7);
  ASSERT_EQ(add.reads.size(), 2u);
  EXPECT_EQ(add.reads[0].raw, (Vec4f{4, 3, 2, 1}));
  EXPECT_EQ(add.reads[0].value, (Vec4f{-3, -3, -3, -3}));
  EXPECT_EQ(add.reads[1].register_read, (RegisterRef{RegisterFile::kConst, 4, false}));
  EXPECT_EQ(add.reads[1].value, (Vec4f{10, 20, 30, 40}));
  ASSERT_TRUE(add.write);
  EXPECT_EQ(add.write->written.bits(), 0b0101);
  EXPECT_EQ(add.write->before, (Vec4f{0, 0, 0, 0}));
  EXPECT_EQ(add.write->after, (Vec4f{7, 0, 27, 0}));

  const TraceStep& matrix = trace.steps[3];
  ASSERT_EQ(matrix.reads.size(), 5u);  // v0, then c0-c3
  for (int row = 0; row < 4; ++row) EXPECT_EQ(matrix.reads[1 + row].register_read.index, row);
  EXPECT_EQ(trace.end.outputs[static_cast<int>(OutputSlot::kPosition)], (Vec4f{1, 2, 3, 4}));

  SourceLines sources;
  std::string text = FormatTraceText(program, trace, "batch", sources);
  EXPECT_THAT(text, HasSubstr("main.vsh:7  add r2.xz, NEG_Y, c[a0.x + 3]\n        = add r2.xz, -r1.y, c3[a0.x]\n"));
  EXPECT_THAT(text, HasSubstr("read  -r1.y = (-3, -3, -3, -3)   from r1 = (4, 3, 2, 1)\n"));
  EXPECT_THAT(text, HasSubstr("from c4 = (10, 20, 30, 40)"));
  EXPECT_THAT(text, HasSubstr("write r2.xz -> r2 = (7, kept 0, 27, kept 0)\n"));
  EXPECT_THAT(text, HasSubstr("step.inc:1  mov a0.x, c10.x\n"));
}

TEST_F(TraceTest, ComparisonFailsOnAnyDifferentBit) {
  AssembleResult assembled = AssembleFile(main_, {});
  ASSERT_TRUE(assembled.program);
  VertexArrays inputs = OneVertex({1, 2, 3, 4});
  VertexTrace trace = TraceVertex(*assembled.program, TestConstants(), inputs, 0);
  VertexArrays outputs = MakeOutputArrays(1, *assembled.program);
  ASSERT_EQ(MakeEngine("batch", *assembled.program, TestConstants()).value()->Run(inputs, outputs).message(), "");
  CompareOutputs(outputs, trace);
  ASSERT_EQ(trace.outputs.size(), 2u);  // oPos and oD0
  EXPECT_TRUE(trace.identical());
  int diffuse = static_cast<int>(OutputSlot::kDiffuse);
  outputs.lane(diffuse, 2)[0] = std::nextafter(outputs.lane(diffuse, 2)[0], 100.0f);
  CompareOutputs(outputs, trace);
  EXPECT_FALSE(trace.identical());
}

TEST_F(TraceTest, CliPrintsTheTraceAndWritesJson) {
  std::string json_path = (dir_ / "trace.json").string();
  for (const char* engine : {"batch", "jit"}) {
    CommandResult r = RunVs11("run " + RunArgs() + " --trace 1 --trace-json " + json_path + " --engine " + engine);
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_THAT(r.output, HasSubstr("vertex 1\n  input v0 = (1, 2, 3, 4)\n"));
    EXPECT_THAT(r.output, HasSubstr("write r2.xz -> r2 = (7, kept 0, 27, kept 0)"));
    EXPECT_THAT(r.output, HasSubstr("oD0 = (7, 0, 27, 0) | (7, 0, 27, 0)  identical"));
    EXPECT_THAT(r.output, HasSubstr(std::string("reference | ") + engine));
    EXPECT_THAT(r.output, Not(HasSubstr("oPos.x")));  // the CSV is not mixed into the trace
  }
  std::ifstream in(json_path);
  nlohmann::json trace = nlohmann::json::parse(in);
  EXPECT_TRUE(trace["identical"].get<bool>());
  const nlohmann::json& vertex = trace["vertices"][0];
  EXPECT_EQ(vertex["vertex"], 1);
  const nlohmann::json& add = vertex["steps"][2];
  EXPECT_EQ(add["line"], 7);
  EXPECT_EQ(add["source"], "add r2.xz, NEG_Y, c[a0.x + 3]");
  EXPECT_EQ(add["instruction"], "add r2.xz, -r1.y, c3[a0.x]");
  EXPECT_EQ(add["reads"][0]["value"], nlohmann::json({-3.0, -3.0, -3.0, -3.0}));
  EXPECT_EQ(add["reads"][0]["raw"], nlohmann::json({4.0, 3.0, 2.0, 1.0}));
  EXPECT_EQ(add["reads"][1]["register"], "c4");
  EXPECT_EQ(add["write"]["lanes"], "xz");
  EXPECT_EQ(add["write"]["after"], nlohmann::json({7.0, 0.0, 27.0, 0.0}));
  EXPECT_THAT(vertex["steps"][1]["file"].get<std::string>(), HasSubstr("step.inc"));
}

TEST_F(TraceTest, CliTracesBytecodeAsDisassembly) {
  std::string bytecode = (dir_ / "main.vso").string();
  ASSERT_EQ(RunVs11("asm " + main_ + " -o " + bytecode).status, 0);
  CommandResult r =
      RunVs11("run " + bytecode + " --consts " + constants_ + " --input v0=" + inputs_ + " --trace 0,1");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("vertex 0\n"));
  EXPECT_THAT(r.output, HasSubstr("[3] instruction 4  add r2.xz, -r1.y, c3[a0.x]\n"));
  EXPECT_THAT(r.output, Not(HasSubstr("main.vsh")));
}

TEST_F(TraceTest, CliRejectsVerticesOutOfRangeAndJsonWithoutTrace) {
  CommandResult r = RunVs11("run " + RunArgs() + " --trace 2");
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("--trace 2: there are 2 vertices"));
  // A usage error (CLI11's exit code until the tool maps every usage error to 2).
  CommandResult json_alone = RunVs11("run " + RunArgs() + " --trace-json " + (dir_ / "t.json").string());
  EXPECT_NE(json_alone.status, 0);
  EXPECT_THAT(json_alone.output, HasSubstr("--trace"));
  EXPECT_FALSE(fs::exists(dir_ / "t.json"));
}

}  // namespace
}  // namespace vs11

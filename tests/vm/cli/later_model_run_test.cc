// `vs11 run` on a vs_2_0 program end to end: the ref engine runs a skinning loop over bones with
// c#[aL], and batch and jit run it specialised for its i0 with the same numbers; a program with dynamic
// flow control they refuse by name; --const and --consts set i# and b#; --trace follows the flow.
#include <fstream>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/run_tool.h"

namespace {

using ::testing::EndsWith;
using ::testing::HasSubstr;
using vs11::testing::CommandResult;
using vs11::testing::RunVs11;

// Two bones at c10..c13 and c14..c17 (aL = 10, 14), their weights in c40.x and c44.x (c30[aL]):
// bone 0 moves x by 1, bone 1 scales by 2, each weighted 0.5.
const std::string kSkinning =
    "vs_2_0\n"
    "defi i0, 2, 10, 4, 0\n"
    "def c40, 0.5, 0, 0, 0\n"
    "def c44, 0.5, 0, 0, 0\n"
    "dcl_position v0\n"
    "mov r0, c0\n"
    "loop aL, i0\n"
    "dp4 r1.x, v0, c0[aL]\n"
    "dp4 r1.y, v0, c1[aL]\n"
    "dp4 r1.z, v0, c2[aL]\n"
    "dp4 r1.w, v0, c3[aL]\n"
    "mad r0, r1, c30[aL].x, r0\n"
    "endloop\n"
    "mov oPos, r0\n";
const std::string kBones =
    " --const c10=1,0,0,1 --const c11=0,1,0,0 --const c12=0,0,1,0 --const c13=0,0,0,1"
    " --const c14=2,0,0,0 --const c15=0,2,0,0 --const c16=0,0,2,0 --const c17=0,0,0,1";

class LaterModelRun : public vs11::testing::ToolFolderTest {
 protected:
  void SetUp() override {
    ToolFolderTest::SetUp();
    program_ = Write("skin.vsh", kSkinning);
    positions_ = Write("p.csv", "x,y,z,w\n1,2,3,1\n0,0,0,1\n");
  }
  std::string program_, positions_;
};

TEST_F(LaterModelRun, TheRefEngineRunsASkinningLoopOverBones) {
  const CommandResult r = RunVs11("run " + program_ + " --input v0=" + positions_ + kBones + " --engine ref --missing zeros");
  ASSERT_EQ(r.status, 0) << r.output;
  // (1,2,3,1): bone 0 gives (2,2,3,1), bone 1 (2,4,6,1), half of each (2,3,4.5,1); the origin: (0.5,0,0,1).
  EXPECT_THAT(r.output, EndsWith("oPos.x,oPos.y,oPos.z,oPos.w\n2,3,4.5,1\n0.5,0,0,1\n"));
}

TEST_F(LaterModelRun, BatchAndJitRunTheSkinningLoopWithTheRefEnginesNumbers) {
  for (const char* engine : {"batch", "jit"}) {
    const CommandResult r = RunVs11("run " + program_ + " --input v0=" + positions_ + kBones + " --missing zeros --engine " + engine);
    ASSERT_EQ(r.status, 0) << engine << ": " << r.output;
    EXPECT_THAT(r.output, EndsWith("oPos.x,oPos.y,oPos.z,oPos.w\n2,3,4.5,1\n0.5,0,0,1\n")) << engine;
  }
}

TEST_F(LaterModelRun, BatchAndJitRunDynamicFlowWithTheRefEnginesNumbers) {
  // (1,2,3,1) takes the if (x > c0.x = 0.5), the origin does not.
  const std::string dynamic = Write("dynamic.vsh", "vs_2_x\ndef c0, 0.5, 1, 2, 3\ndcl_position v0\nmov r0, v0\n"
                                                   "if_gt r0.x, c0.x\nadd r0, r0, c0\nendif\nmov oPos, r0\n");
  for (const char* engine : {"ref", "batch", "jit"}) {
    const CommandResult r = RunVs11("run " + dynamic + " --input v0=" + positions_ + " --missing zeros --engine " + engine);
    ASSERT_EQ(r.status, 0) << engine << ": " << r.output;
    EXPECT_THAT(r.output, EndsWith("oPos.x,oPos.y,oPos.z,oPos.w\n1.5,3,5,4\n0,0,0,1\n")) << engine;
  }
}

// rep i0 adds c0 i0.x times, loop aL, i1 adds c2[aL] (c6 = y 10, c7 = z 100 at aL 4, 5), if b0 doubles.
const std::string kFlowConstants =
    "vs_2_0\ndef c0, 1, 0, 0, 0\ndef c1, 2, 2, 2, 1\ndef c6, 0, 10, 0, 0\ndef c7, 0, 0, 100, 0\n"
    "dcl_position v0\nmov r0, v0\nrep i0\nadd r0, r0, c0\nendrep\nloop aL, i1\nadd r0, r0, c2[aL]\nendloop\n"
    "if b0\nmul r0, r0, c1\nendif\nmov oPos, r0\n";

TEST_F(LaterModelRun, ConstFlagsSetIntegerAndBooleanConstantsOnEveryEngine) {
  const std::string program = Write("flow.vsh", kFlowConstants);
  for (const char* engine : {"ref", "batch", "jit"}) {
    CommandResult r = RunVs11("run " + program + " --input v0=" + positions_ +
                              " --const i0=3 --const i1=2,4,1 --const b0=false --engine " + engine);
    ASSERT_EQ(r.status, 0) << engine << ": " << r.output;
    EXPECT_THAT(r.output, EndsWith("oPos.x,oPos.y,oPos.z,oPos.w\n4,12,103,1\n3,10,100,1\n")) << engine;
    r = RunVs11("run " + program + " --input v0=" + positions_ + " --const i0=0 --const i1=1,5,1,0 --const b0=true --engine " +
                engine);
    ASSERT_EQ(r.status, 0) << engine << ": " << r.output;
    EXPECT_THAT(r.output, EndsWith("oPos.x,oPos.y,oPos.z,oPos.w\n2,4,206,1\n0,0,200,1\n")) << engine;
  }
}

TEST_F(LaterModelRun, ConstsFilesSetIntegerAndBooleanConstants) {
  const std::string program = Write("flow.vsh", kFlowConstants);
  const std::string constants = Write("k.vsh", "defi i0, 2, 0, 0, 0\ni1 = 0 0 0 0\ndefb b0, true\n");
  const CommandResult r = RunVs11("run " + program + " --input v0=" + positions_ + " --consts " + constants);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, EndsWith("oPos.x,oPos.y,oPos.z,oPos.w\n6,4,6,1\n4,0,0,1\n"));
}

TEST_F(LaterModelRun, IntegerAndBooleanConstantsNobodySetsAreUsageErrors) {
  const std::string program = Write("flow.vsh", kFlowConstants);
  CommandResult r = RunVs11("run " + program + " --input v0=" + positions_ + " --const i0=1");
  EXPECT_EQ(r.status, 2);
  EXPECT_THAT(r.output, HasSubstr("the program reads i1, which neither"));
  EXPECT_THAT(r.output, HasSubstr("the program reads b0, which neither"));
  r = RunVs11("run " + program + " --input v0=" + positions_ + " --const i0=1 --missing zeros");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("warning: the program reads i1, which no defi, --consts or --const sets"));
  EXPECT_THAT(r.output, EndsWith("2,2,3,1\n1,0,0,1\n"));
}

TEST_F(LaterModelRun, IntegerConstantsOutOfRangeAreUsageErrorsNamingTheFlag) {
  const std::string program = Write("flow.vsh", kFlowConstants);
  for (const char* flag : {"i0=256", "i0=1,-1", "i0=1,0,128", "i0=1,0,0,1", "i16=1", "b0=maybe"}) {
    const CommandResult r = RunVs11("run " + program + " --input v0=" + positions_ + " --missing zeros --const " + flag);
    EXPECT_EQ(r.status, 2) << flag;
    EXPECT_THAT(r.output, HasSubstr("--const: ")) << flag;
    EXPECT_THAT(r.output, HasSubstr(std::string("in '") + flag + "'")) << flag;
  }
  const CommandResult r = RunVs11("run " + program + " --input v0=" + positions_ + " --const i0=1 --const i0=2");
  EXPECT_EQ(r.status, 2);
  EXPECT_THAT(r.output, HasSubstr("--const i0 is given twice"));
}

TEST_F(LaterModelRun, TraceFollowsALoopAnIfAndACallBesideTheEnginesOutputs) {
  // The skinning loop's two iterations, then a call under if b0, then a call under if b1 (false).
  const std::string program = Write("traced.vsh", "vs_2_0\ndefb b0, true\ndefb b1, false\ndef c1, 2, 2, 2, 1\n" +
                                                      kSkinning.substr(kSkinning.find("defi")) + "if b0\ncall l0\nendif\n"
                                                      "if b1\ncall l0\nendif\nret\nlabel l0\nmul oPos, r0, c1\nret\n");
  const std::string json_file = (dir_ / "trace.json").string();
  for (const char* engine : {"ref", "batch", "jit"}) {
    const CommandResult r = RunVs11("run " + program + " --input v0=" + positions_ + kBones +
                                    " --missing zeros --trace 0 --trace-json " + json_file + " --engine " + engine);
    ASSERT_EQ(r.status, 0) << engine << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr("flow  2 iterations, aL = 10, step 4")) << engine;
    EXPECT_THAT(r.output, HasSubstr("read  c0[aL] = (1, 0, 0, 1)   from c10 = (1, 0, 0, 1) (aL = 10)")) << engine;
    EXPECT_THAT(r.output, HasSubstr("read  c0[aL] = (2, 0, 0, 0)   from c14 = (2, 0, 0, 0) (aL = 14)")) << engine;
    EXPECT_THAT(r.output, HasSubstr("flow  next iteration, aL = 14")) << engine;
    EXPECT_THAT(r.output, HasSubstr("flow  the loop ends")) << engine;
    EXPECT_THAT(r.output, HasSubstr("read  b1 = false")) << engine;
    EXPECT_THAT(r.output, HasSubstr("flow  calls l0 at line ")) << engine;
    EXPECT_THAT(r.output, HasSubstr("oPos = (4, 6, 9, 1) | (4, 6, 9, 1)  identical")) << engine;
    const std::string call = "mul oPos, r0, c1";  // b1's call never ran: the routine shows once
    EXPECT_EQ(r.output.find(call), r.output.rfind(call)) << engine;
    std::ostringstream json;
    json << std::ifstream(json_file).rdbuf();
    EXPECT_THAT(json.str(), HasSubstr("\"identical\": true")) << engine;
    EXPECT_THAT(json.str(), HasSubstr("\"address\": \"aL = 14\"")) << engine;
  }
}

}  // namespace

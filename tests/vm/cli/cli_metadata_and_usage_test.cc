// vs11 end to end: the program's `; vs11: fragment=` metadata in every subcommand, --fragment and
// --no-fragment, count going on past a bad program, and usage errors (status 2, the culprit named).
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/run_tool.h"

namespace {

namespace fs = std::filesystem;

using ::testing::HasSubstr;
using ::testing::Not;
using vs11::testing::CommandResult;
using vs11::testing::RunVs11;

using Vs11MetadataAndUsage = vs11::testing::ToolFolderTest;

// A piece of a shader: it writes oD0 only.
const std::string kFragmentBody = "vs_1_1\ndcl_normal v0\nadd oD0.xyz, v0, c0\n";
const std::string kOposMissing = "never writes oPos";

TEST_F(Vs11MetadataAndUsage, FragmentMetadataIsHonouredByEverySubcommand) {
  std::string program = Write("frag.vsh", "; vs11: fragment=yes\n" + kFragmentBody);
  std::string vso = (dir_ / "frag.vso").string();
  CommandResult assembled = RunVs11("asm " + program + " -o " + vso);
  ASSERT_EQ(assembled.status, 0) << assembled.output;
  EXPECT_EQ(RunVs11("disasm " + vso).status, 0);
  CommandResult validated = RunVs11("validate " + program);
  EXPECT_EQ(validated.status, 0) << validated.output;
  CommandResult ran = RunVs11("run " + program + " --sphere 2 --const c0=1,2,3,4 --engine ref");
  EXPECT_EQ(ran.status, 0) << ran.output;
  CommandResult counted = RunVs11("count --no-timing " + program);
  EXPECT_EQ(counted.status, 0) << counted.output;
}

TEST_F(Vs11MetadataAndUsage, NoFragmentFlagWinsOverTheMetadata) {
  std::string program = Write("frag.vsh", "; vs11: fragment=yes\n" + kFragmentBody);
  for (const std::string& command : {"validate " + program, "asm " + program + " -o " + (dir_ / "f.vso").string(),
                                     "count --no-timing " + program, "run " + program + " --sphere 2"}) {
    CommandResult r = RunVs11(command + " --no-fragment");
    EXPECT_EQ(r.status, 1) << command;
    EXPECT_THAT(r.output, HasSubstr(kOposMissing)) << command;
  }
  EXPECT_FALSE(fs::exists(dir_ / "f.vso"));
}

TEST_F(Vs11MetadataAndUsage, FragmentFlagWinsOverMetadataSayingNo) {
  std::string program = Write("frag.vsh", "; vs11: fragment=no\n" + kFragmentBody);
  EXPECT_THAT(RunVs11("validate " + program).output, HasSubstr(kOposMissing));
  EXPECT_EQ(RunVs11("validate --fragment " + program).status, 0);
  CommandResult both = RunVs11("validate --fragment --no-fragment " + program);
  EXPECT_EQ(both.status, 2);
  EXPECT_THAT(both.output, HasSubstr("--no-fragment"));
}

TEST_F(Vs11MetadataAndUsage, CountListsEveryProgramThatLoadsAndFailsForTheRest) {
  std::string good = Write("good.vsh", "; vs11: fragment=yes\n" + kFragmentBody);
  std::string bad = Write("bad.vsh", "vs_1_1\nfrobnicate r0\n");
  std::string later = Write("later.vsh", "vs_1_1\ndcl_position v0\nmov oPos, v0\n");
  CommandResult r = RunVs11("count --no-timing " + bad + " " + good + " " + later);
  EXPECT_EQ(r.status, 1);
  EXPECT_THAT(r.output, HasSubstr("bad.vsh:2:1: error"));
  EXPECT_THAT(r.output, HasSubstr("good.vsh"));
  EXPECT_THAT(r.output, HasSubstr("later.vsh"));
}

TEST_F(Vs11MetadataAndUsage, CountShowsTheExecutedPerVertexColumnItsHelpDescribes) {
  std::string program = Write("p.vsh", "vs_1_1\ndcl_position v0\nm4x4 oPos, v0, c0\nmov oD0, v0\n");
  CommandResult r = RunVs11("count --no-timing " + program);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("exec/v"));
  EXPECT_THAT(RunVs11("count --help").output, HasSubstr("exec/v"));
  // m4x4 is one instruction in four slots: executed per vertex counts instructions.
  EXPECT_THAT(r.output, ::testing::ContainsRegex("p.vsh +2 +5 +4 +0 +1 +2 "));
}

TEST_F(Vs11MetadataAndUsage, UsageErrorsExitTwoAndNameTheCulprit) {
  CommandResult unknown = RunVs11("frobnicate");
  EXPECT_EQ(unknown.status, 2);
  EXPECT_THAT(unknown.output, HasSubstr("frobnicate"));
  EXPECT_THAT(unknown.output, Not(HasSubstr("A subcommand is required")));
  CommandResult flag = RunVs11("validate x.vsh --frob");
  EXPECT_EQ(flag.status, 2);
  EXPECT_THAT(flag.output, HasSubstr("--frob"));
  EXPECT_EQ(RunVs11("").status, 2);
  EXPECT_EQ(RunVs11("asm").status, 2);
  EXPECT_EQ(RunVs11("run p.vsh --engine warp").status, 2);
  CommandResult version = RunVs11("--version");
  EXPECT_EQ(version.status, 0);
  EXPECT_THAT(version.output, HasSubstr("vs11 "));
  EXPECT_EQ(RunVs11("--help").status, 0);
  EXPECT_EQ(RunVs11("run --help").status, 0);
}

TEST_F(Vs11MetadataAndUsage, RunRefusesConstantsAndInputsNobodySetsUnlessAskedToReadZeros) {
  std::string program = Write("xform.vsh", "vs_1_1\ndef c4, 1, 1, 1, 1\ndcl_position v0\ndcl_normal v1\n"
                                           "m4x4 oPos, v0, c0\nmul oD0, v1, c4\n");
  std::string positions = Write("pos.csv", "1,2,3\n");
  const std::string command = "run " + program + " --input v0=" + positions + " --const c4=0,0,0,0 --const c1=1,0,0,0";
  CommandResult refused = RunVs11(command + " --const c9=1,1,1,1");
  EXPECT_EQ(refused.status, 2) << refused.output;
  EXPECT_THAT(refused.output, HasSubstr("reads c0, c2, c3, which neither a def, --consts nor --const sets (they set "
                                        "c9, which it never reads)"));
  EXPECT_THAT(refused.output, HasSubstr("reads v1, which no --input, --sphere, --mesh, --npy or --buffer supplies "
                                        "(given: v0); pass --missing zeros"));
  EXPECT_THAT(refused.output, Not(HasSubstr("oPos.x")));
  CommandResult r = RunVs11(command + " --missing zeros");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("reads c0, c2, c3, which no def"));
  EXPECT_THAT(r.output, HasSubstr("def of c4 overrides"));
  EXPECT_THAT(r.output, HasSubstr("reads v1, which no --input"));
  EXPECT_THAT(RunVs11("run --help").output, HasSubstr("def lines in the program win"));
}

TEST_F(Vs11MetadataAndUsage, RunReadsTheCsvItWritesBackByColumnName) {
  std::string program = Write("p.vsh", "vs_1_1\ndcl_position v0\ndcl_normal v1\nmov oPos, v0\nmov oD0.xyz, v1\n");
  std::string first = (dir_ / "first.csv").string();
  ASSERT_EQ(RunVs11("run " + program + " --sphere 3 --missing zeros --out " + first).status, 0);
  std::string second = (dir_ / "second.csv").string();
  CommandResult again = RunVs11("run " + program + " --input v0=" + first + ":oPos --input v1=" + first +
                                ":oD0.x,oD0.y,oD0.z --out " + second);
  ASSERT_EQ(again.status, 0) << again.output;
  std::ifstream a(first), b(second);
  std::string header_a, header_b;
  std::getline(a, header_a);
  std::getline(b, header_b);
  EXPECT_EQ(header_a, "v1.x,v1.y,v1.z,oPos.x,oPos.y,oPos.z,oPos.w,oD0.x,oD0.y,oD0.z");
  for (std::string row_a, row_b; std::getline(a, row_a) && std::getline(b, row_b);) {
    EXPECT_EQ(row_a.substr(row_a.find(',', row_a.find(',', row_a.find(',') + 1) + 1) + 1), row_b);
  }
  CommandResult whole = RunVs11("run " + program + " --input v0=" + first);
  EXPECT_EQ(whole.status, 1);
  EXPECT_THAT(whole.output, HasSubstr("v#=FILE:NAME"));
  EXPECT_THAT(whole.output, HasSubstr("and 2 more bad rows"));
}

}  // namespace

// The vs11 tool end to end: exit codes, messages, files written or not.
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/run_tool.h"

namespace {

namespace fs = std::filesystem;

using vs11::testing::CommandResult;
using vs11::testing::RunVs11;

class Vs11Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) / ("vs11_cli_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Write(const std::string& name, const std::string& text) {
    fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary) << text;
    return path.string();
  }
  fs::path dir_;
};

const std::string kProgram = "vs_1_1\ndcl_position v0\ndcl_normal v1\nmov oPos, v0\nadd oD0.xyz, v1, c4\n";

TEST_F(Vs11Cli, EverySubcommandHasHelp) {
  for (const char* sub : {"asm", "disasm", "validate", "run", "verify", "count"}) {
    CommandResult r = RunVs11(std::string(sub) + " --help");
    EXPECT_EQ(r.status, 0) << sub;
    EXPECT_NE(r.output.find("Example"), std::string::npos) << sub << ": " << r.output;
  }
}

TEST_F(Vs11Cli, AsmWritesBytecodeThatDisassemblesBack) {
  std::string source = Write("p.vsh", kProgram);
  std::string output = (dir_ / "p.vso").string();
  ASSERT_EQ(RunVs11("asm " + source + " -o " + output).status, 0);
  EXPECT_EQ(fs::file_size(output), 4u * (1 + 3 + 3 + 3 + 4 + 1));
  CommandResult text = RunVs11("disasm " + output);
  EXPECT_EQ(text.status, 0);
  EXPECT_EQ(text.output, "vs_1_1\ndcl_position v0\ndcl_normal v1\nmov oPos, v0\nadd oD0.xyz, v1, c4\n");
}

TEST_F(Vs11Cli, AsmErrorsNameFileLineColumnAndLeaveNoFile) {
  std::string source = Write("bad.vsh", "vs_1_1\nmov oPos, c0\nadd r0, c1, c2\nfoo r1, r0\n");
  std::string output = (dir_ / "bad.vso").string();
  CommandResult r = RunVs11("asm " + source + " -o " + output);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("bad.vsh:4:1: error:"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(output));
  for (const auto& entry : fs::directory_iterator(dir_)) EXPECT_EQ(entry.path().extension(), ".vsh");
}

TEST_F(Vs11Cli, AsmAppliesDefinesAndIncludeFolders) {
  fs::create_directories(dir_ / "inc");
  Write("inc/consts.h", "#define LIGHT c[BASE + 1]\n");
  std::string source = Write("p.vsh", "vs.1.1\n#include \"consts.h\"\nmov oPos, LIGHT\n");
  std::string output = (dir_ / "p.vso").string();
  CommandResult r = RunVs11("asm " + source + " -o " + output + " -I " + (dir_ / "inc").string() + " -D BASE=4");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(RunVs11("disasm " + output).output.find("mov oPos, c5"), std::string::npos);
}

TEST_F(Vs11Cli, DisasmRejectsTruncatedStreamWithWordOffset) {
  std::string path = (dir_ / "t.vso").string();
  {
    std::ofstream out(path, std::ios::binary);
    const unsigned char bytes[] = {0x01, 0x01, 0xFE, 0xFF, 0x09, 0, 0, 0, 0x00, 0x00, 0x01, 0x80};
    out.write(reinterpret_cast<const char*>(bytes), sizeof bytes);
  }
  CommandResult r = RunVs11("disasm " + path);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("word 1"), std::string::npos) << r.output;
}

TEST_F(Vs11Cli, ValidateReportsRuleViolations) {
  std::string source = Write("v.vsh", "vs_1_1\ndcl_position v0\nmov oPos, v0\nadd r0, c1, c2\n");
  CommandResult r = RunVs11("validate " + source);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("v.vsh:4:"), std::string::npos) << r.output;
  EXPECT_EQ(RunVs11("validate " + Write("ok.vsh", kProgram)).status, 0);
}

TEST_F(Vs11Cli, RunPrintsCsvFromInputsAndConstants) {
  std::string source = Write("p.vsh", kProgram);
  std::string normals = Write("n.csv", "nx,ny,nz\n1,2,3\n4,5,6\n");
  std::string consts = Write("k.txt", "def c4, 10, 20, 30, 40\n");
  CommandResult r =
      RunVs11("run " + source + " --input v1=" + normals + " --consts " + consts + " --engine ref --missing zeros");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, ::testing::EndsWith(
                            "\noPos.x,oPos.y,oPos.z,oPos.w,oD0.x,oD0.y,oD0.z\n0,0,0,1,11,22,33\n0,0,0,1,14,25,36\n"));
  // v0 is read but not given: allowed by --missing zeros, and said, not silent.
  EXPECT_THAT(r.output, ::testing::HasSubstr("p.vsh: warning: the program reads v0, which no --input"));
  CommandResult batch = RunVs11("run " + source + " --input v1=" + normals + " --consts " + consts +
                                " --const c4=1,1,1,1 --missing zeros");
  EXPECT_NE(batch.output.find("0,0,0,1,2,3,4\n"), std::string::npos) << batch.output;
}

TEST_F(Vs11Cli, RunSphereUsesTheDeclaredNormalAndWritesAtomically) {
  std::string source = Write("p.vsh", kProgram);
  std::string out = (dir_ / "o.csv").string();
  ASSERT_EQ(RunVs11("run " + source + " --sphere 5 --missing zeros --out " + out).status, 0);
  std::ifstream in(out);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "v1.x,v1.y,v1.z,oPos.x,oPos.y,oPos.z,oPos.w,oD0.x,oD0.y,oD0.z");
  int rows = 0;
  for (std::string line; std::getline(in, line);) ++rows;
  EXPECT_EQ(rows, 5);
}

TEST_F(Vs11Cli, RunRejectsMismatchedInputsAndBadConstants) {
  std::string source = Write("p.vsh", kProgram);
  CommandResult r = RunVs11("run " + source + " --input v0=" + Write("a.csv", "1\n2\n") + " --input v1=" +
                            Write("b.csv", "1\n"));
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("has 1 vertices"), std::string::npos) << r.output;
  CommandResult k = RunVs11("run " + source + " --sphere 2 --consts " + Write("k.txt", "c4 = 1 q\n"));
  EXPECT_EQ(k.status, 1);
  EXPECT_NE(k.output.find("k.txt:1:8: error: expected a number"), std::string::npos) << k.output;
  EXPECT_EQ(RunVs11("run " + source).status, 1);
}

TEST_F(Vs11Cli, CountPrintsJson) {
  std::string source = Write("p.vsh", kProgram);
  CommandResult r = RunVs11("count --json --no-timing " + source);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("\"instructions\": 2"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"slots\": 2"), std::string::npos);
  EXPECT_NE(r.output.find("\"ns_per_vertex\""), std::string::npos);
}

// A DX8 program that reads r4.w after m4x3 wrote r4.xyz (issue 22 §5): a warning with its code, the
// program assembles; --strict refuses it and writes nothing.
const std::string kDx8PartlyWritten = "vs.1.1\nm4x3 r4, v0, c9\nmul r4, r4, v1.xxxx\nmov oPos, r4\n";

TEST_F(Vs11Cli, Dx8ReadOfUnwrittenLanesWarnsAndStrictRefuses) {
  std::string source = Write("skin.vsh", kDx8PartlyWritten);
  std::string output = (dir_ / "skin.vso").string();
  CommandResult r = RunVs11("asm " + source + " -o " + output);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, ::testing::HasSubstr("skin.vsh:3:1: warning: mul: reads r4.w"));
  EXPECT_THAT(r.output, ::testing::HasSubstr("[uninitialized-lanes]"));
  EXPECT_TRUE(fs::exists(output));
  fs::remove(output);
  CommandResult strict = RunVs11("asm --strict " + source + " -o " + output);
  EXPECT_EQ(strict.status, 1);
  EXPECT_THAT(strict.output, ::testing::HasSubstr("skin.vsh:3:1: error: mul: reads r4.w"));
  EXPECT_FALSE(fs::exists(output));
  EXPECT_EQ(RunVs11("validate --strict " + source).status, 1);
  EXPECT_EQ(RunVs11("run --strict " + source + " --sphere 2 --sphere-reg v0 --missing zeros").status, 1);
  EXPECT_EQ(RunVs11("run " + source + " --sphere 2 --sphere-reg v0 --missing zeros").status, 0);
}

TEST_F(Vs11Cli, ValidateJsonCarriesDiagnosticCodes) {
  std::string source = Write("skin.vsh", kDx8PartlyWritten);
  CommandResult r = RunVs11("validate --json " + source);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_THAT(r.output, ::testing::HasSubstr("\"valid\": true"));
  EXPECT_THAT(r.output, ::testing::HasSubstr("\"code\": \"uninitialized-lanes\""));
  EXPECT_THAT(r.output, ::testing::HasSubstr("\"severity\": \"warning\""));
  EXPECT_THAT(r.output, ::testing::HasSubstr("\"line\": 3"));
  CommandResult bad = RunVs11("validate --json " + Write("bad.vsh", "vs_1_1\nfrobnicate r0\n"));
  EXPECT_EQ(bad.status, 1);
  EXPECT_THAT(bad.output, ::testing::HasSubstr("\"valid\": false"));
  EXPECT_THAT(bad.output, ::testing::HasSubstr("\"code\": \"unknown-instruction\""));
}

TEST_F(Vs11Cli, MissingFileIsAnError) {
  CommandResult r = RunVs11("validate " + (dir_ / "nope.vsh").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("cannot read"), std::string::npos);
}

}  // namespace

#include "vm/io/vertex_io.h"

#include <cmath>
#include <limits>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "vm/asm/assembler.h"

namespace vs11 {
using ::testing::HasSubstr;
namespace {

TEST(VertexIo, ParsesDefLinesAndAssignments) {
  ConstantBank bank;
  Diagnostics diagnostics;
  ParseConstantsText("; comment\ndef c4, 1, 2.5, -3, 4f\n c7 = 0.5 0.25\nc8 = 1, 2, 3, 4 // trailing\n", "k.txt", bank,
                     diagnostics);
  ASSERT_FALSE(diagnostics.HasErrors()) << diagnostics.ToString();
  EXPECT_EQ(bank[4], (Vec4f{1, 2.5f, -3, 4}));
  EXPECT_EQ(bank[7], (Vec4f{0.5f, 0.25f, 0, 0}));
  EXPECT_EQ(bank[8], (Vec4f{1, 2, 3, 4}));
}

TEST(VertexIo, ReportsBadConstantLinesWithLineAndColumn) {
  ConstantBank bank;
  Diagnostics diagnostics;
  ParseConstantsText("c1 = 1 2\nc2 = 1 x 3\nr3 = 1\nc200 = 1\nc4 1 2\nc5 = 1 2 3 4 5\n", "k.txt", bank, diagnostics);
  ASSERT_EQ(diagnostics.error_count(), 5);
  const auto& all = diagnostics.all();
  EXPECT_EQ(all[0].loc.line, 2);
  EXPECT_EQ(all[0].loc.column, 8);
  EXPECT_EQ(all[0].code, DiagnosticCode::kConstantValue);  // x
  EXPECT_EQ(all[1].loc.line, 3);
  EXPECT_EQ(all[1].code, DiagnosticCode::kConstantLine);  // r3
  EXPECT_EQ(all[2].loc.line, 4);
  EXPECT_EQ(all[2].code, DiagnosticCode::kConstantRegisterRange);
  EXPECT_THAT(all[2].message, HasSubstr("96"));  // the bank's size
  EXPECT_EQ(all[3].loc.line, 5);
  EXPECT_EQ(all[3].code, DiagnosticCode::kConstantLine);  // no '='
  EXPECT_EQ(all[4].loc.line, 6);
  EXPECT_EQ(all[4].code, DiagnosticCode::kConstantValue);  // five values
}

TEST(VertexIo, ConstantAssignmentFlag) {
  ConstantBank bank;
  EXPECT_TRUE(ParseConstantAssignment("c4=1,0,0,1", bank).ok());
  EXPECT_EQ(bank[4], (Vec4f{1, 0, 0, 1}));
  const Status error = ParseConstantAssignment("c4=1,zz", bank);
  ASSERT_FALSE(error.ok());
  EXPECT_NE(error.message().find("c4=1,zz"), std::string::npos);
  EXPECT_EQ(error.error().code, DiagnosticCode::kConstantValue);
  EXPECT_EQ(error.error().loc.file, "--const");
  EXPECT_EQ(error.error().loc.line, 1);
}

TEST(VertexIo, ParsesIntegerAndBooleanConstantsBothWays) {
  ConstantBank bank;
  Diagnostics diagnostics;
  AssignedConstants assigned;
  ParseConstantsText("defi i0, 3, 10, -4, 0\ni15 = 255 255 127\nDEFB b2, true\nb3 = 1\nb2 = FALSE\ndef c1, 1\n", "k.txt",
                     bank, diagnostics, &assigned);
  ASSERT_FALSE(diagnostics.HasErrors()) << diagnostics.ToString();
  EXPECT_EQ(bank.ReadInteger(0), (Vec4i{3, 10, -4, 0}));
  EXPECT_EQ(bank.ReadInteger(15), (Vec4i{255, 255, 127, 0}));
  EXPECT_FALSE(bank.ReadBoolean(2));  // the later line wins
  EXPECT_TRUE(bank.ReadBoolean(3));
  EXPECT_EQ(assigned.integers, (std::vector<int>{0, 15}));
  EXPECT_EQ(assigned.booleans, (std::vector<int>{2, 3, 2}));
  EXPECT_EQ(assigned.floats, (std::vector<int>{1}));
}

TEST(VertexIo, RefusesIntegerConstantsOutsideTheLoopRanges) {
  // x the count 0-255, y aL's start 0-255, z the step -128-127, w reserved 0 (D3D9 loop - vs).
  for (const char* line : {"i0 = 256", "i0 = -1", "i0 = 1 256", "i0 = 1 -1", "i0 = 1 0 128", "i0 = 1 0 -129",
                           "i0 = 1 0 0 1", "defi i0, 1.5", "i0 = 99999999999999999999"}) {
    ConstantBank bank;
    Diagnostics diagnostics;
    ParseConstantsText(line, "k.txt", bank, diagnostics);
    ASSERT_EQ(diagnostics.error_count(), 1) << line;
    EXPECT_EQ(diagnostics.all()[0].code, DiagnosticCode::kConstantValue) << line;
    EXPECT_EQ(bank.ReadInteger(0), Vec4i{}) << line;
  }
  ConstantBank bank;
  Diagnostics diagnostics;
  ParseConstantsText("i0 = 0 0 -128 0\ni1 = 255 255 127 0", "k.txt", bank, diagnostics);
  EXPECT_FALSE(diagnostics.HasErrors()) << diagnostics.ToString();
  EXPECT_EQ(bank.ReadInteger(0), (Vec4i{0, 0, -128, 0}));
}

TEST(VertexIo, RefusesBadIntegerAndBooleanLines) {
  ConstantBank bank;
  Diagnostics diagnostics;
  ParseConstantsText("i16 = 1\nb16 = true\nb0 = yes\nb1 = true false\ndefi c0, 1\ndef i0, 1\ndefb b1 true\n", "k.txt",
                     bank, diagnostics);
  ASSERT_EQ(diagnostics.error_count(), 6) << diagnostics.ToString();
  const auto& all = diagnostics.all();
  EXPECT_EQ(all[0].code, DiagnosticCode::kConstantRegisterRange);
  EXPECT_THAT(all[0].message, HasSubstr("16 integer constant"));
  EXPECT_EQ(all[1].code, DiagnosticCode::kConstantRegisterRange);
  EXPECT_THAT(all[1].message, HasSubstr("16 boolean constant"));
  EXPECT_EQ(all[2].code, DiagnosticCode::kConstantValue);
  EXPECT_THAT(all[2].message, HasSubstr("true or false"));
  EXPECT_EQ(all[3].code, DiagnosticCode::kConstantValue);
  EXPECT_EQ(all[4].code, DiagnosticCode::kConstantLine);
  EXPECT_THAT(all[4].message, HasSubstr("defi sets i# registers, not c0"));
  EXPECT_EQ(all[5].code, DiagnosticCode::kConstantLine);
  EXPECT_TRUE(bank.ReadBoolean(1));  // `defb b1 true` (commas optional)
}

TEST(VertexIo, ConstantAssignmentFlagSetsIntegerAndBooleanConstants) {
  ConstantBank bank;
  EXPECT_TRUE(ParseConstantAssignment("i0=3,0,1,0", bank).ok());
  EXPECT_TRUE(ParseConstantAssignment("b2=true", bank).ok());
  EXPECT_EQ(bank.ReadInteger(0), (Vec4i{3, 0, 1, 0}));
  EXPECT_TRUE(bank.ReadBoolean(2));
  const Status error = ParseConstantAssignment("i0=300", bank);
  ASSERT_FALSE(error.ok());
  EXPECT_THAT(error.message(), HasSubstr("x (the loop or rep count) must be 0 to 255, not 300 in 'i0=300'"));
  EXPECT_EQ(error.error().loc.file, "--const");
}

TEST(VertexIo, CsvRowsFillMissingComponentsFromZeroZeroZeroOne) {
  Diagnostics diagnostics;
  std::vector<Vec4f> rows = ParseVertexCsv("x,y,z\n1,2\r\n3 4 5 6\n\n7\n", "in.csv", diagnostics);
  ASSERT_FALSE(diagnostics.HasErrors()) << diagnostics.ToString();
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0], (Vec4f{1, 2, 0, 1}));
  EXPECT_EQ(rows[1], (Vec4f{3, 4, 5, 6}));
  EXPECT_EQ(rows[2], (Vec4f{7, 0, 0, 1}));
}

TEST(VertexIo, CsvReportsTheFirstBadRowOnceWithTheCountOfTheRest) {
  Diagnostics diagnostics;
  ParseVertexCsv("1,2\n1,abc\n1,2,3,4,5\n7,q\n", "in.csv", diagnostics);
  ASSERT_EQ(diagnostics.error_count(), 1) << diagnostics.ToString();
  EXPECT_EQ(diagnostics.all()[0].loc.line, 2);
  EXPECT_EQ(diagnostics.all()[0].loc.column, 3);
  EXPECT_EQ(diagnostics.all()[0].code, DiagnosticCode::kCsvNumber);
  EXPECT_THAT(diagnostics.all()[0].message, HasSubstr("'abc'"));
  EXPECT_THAT(diagnostics.all()[0].message, HasSubstr("and 2 more bad rows"));
}

TEST(VertexIo, CsvReadsInfinitiesAndNaN) {
  Diagnostics diagnostics;
  std::vector<Vec4f> rows = ParseVertexCsv("inf,-inf,nan,+inf\n-0,1.5f,1e-45,NaN\n", "in.csv", diagnostics);
  ASSERT_FALSE(diagnostics.HasErrors()) << diagnostics.ToString();
  ASSERT_EQ(rows.size(), 2u);  // the numeric first row is data, not a header
  EXPECT_EQ(rows[0][0], std::numeric_limits<float>::infinity());
  EXPECT_EQ(rows[0][1], -std::numeric_limits<float>::infinity());
  EXPECT_TRUE(std::isnan(rows[0][2]));
  EXPECT_EQ(rows[0][3], std::numeric_limits<float>::infinity());
  EXPECT_TRUE(std::signbit(rows[1][0]));
  EXPECT_EQ(rows[1][1], 1.5f);
  EXPECT_EQ(rows[1][2], std::numeric_limits<float>::denorm_min());
  EXPECT_TRUE(std::isnan(rows[1][3]));
}

TEST(VertexIo, CsvNumericFirstRowIsDataAndAMixedOneIsAnError) {
  Diagnostics diagnostics;
  EXPECT_EQ(ParseVertexCsv("1,2,3\n", "in.csv", diagnostics).size(), 1u);
  ParseVertexCsv("x,2,3\n1,2,3\n", "mixed.csv", diagnostics);
  ASSERT_EQ(diagnostics.error_count(), 1);
  EXPECT_EQ(diagnostics.all()[0].loc.line, 1);
  EXPECT_EQ(diagnostics.all()[0].code, DiagnosticCode::kCsvNumber);
}

TEST(VertexIo, CsvDetectsSemicolonsAndRefusesDecimalCommas) {
  Diagnostics diagnostics;
  std::vector<Vec4f> rows = ParseVertexCsv("x;y;z\n1.5; 2;3\n", "in.csv", diagnostics);
  ASSERT_FALSE(diagnostics.HasErrors()) << diagnostics.ToString();
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0], (Vec4f{1.5f, 2, 3, 1}));
  ParseVertexCsv("x;y\n1,5;2\n", "comma.csv", diagnostics);
  ASSERT_EQ(diagnostics.error_count(), 1);
  EXPECT_EQ(diagnostics.all()[0].code, DiagnosticCode::kCsvSeparator);
  Diagnostics mixed;
  ParseVertexCsv("1,2\n3;4\n", "mixed.csv", mixed);
  ASSERT_EQ(mixed.error_count(), 1);
  EXPECT_EQ(mixed.all()[0].loc.line, 2);
  EXPECT_EQ(mixed.all()[0].code, DiagnosticCode::kCsvSeparator);
}

TEST(VertexIo, CsvTabsAndSpacesSeparate) {
  Diagnostics diagnostics;
  std::vector<Vec4f> rows = ParseVertexCsv("x\ty\n1\t2\n3   4\n", "in.csv", diagnostics);
  ASSERT_FALSE(diagnostics.HasErrors()) << diagnostics.ToString();
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1], (Vec4f{3, 4, 0, 1}));
}

TEST(VertexIo, CsvColumnsByPrefixAndByList) {
  const std::string csv = "v0.x,oPos.x,oPos.y,oPos.z,oPos.w,oD0.x,oD0.z\n9,1,2,3,4,5,6\n";
  Diagnostics diagnostics;
  std::vector<Vec4f> position = ParseVertexCsv(csv, "out.csv", diagnostics, "oPos");
  std::vector<Vec4f> colour = ParseVertexCsv(csv, "out.csv", diagnostics, "oD0");  // lanes x and z only
  std::vector<Vec4f> listed = ParseVertexCsv(csv, "out.csv", diagnostics, "oD0.z,v0.x");
  ASSERT_FALSE(diagnostics.HasErrors()) << diagnostics.ToString();
  EXPECT_EQ(position, (std::vector<Vec4f>{{1, 2, 3, 4}}));
  EXPECT_EQ(colour, (std::vector<Vec4f>{{5, 0, 6, 1}}));
  EXPECT_EQ(listed, (std::vector<Vec4f>{{6, 9, 0, 1}}));
  ParseVertexCsv(csv, "out.csv", diagnostics, "oT0");
  ParseVertexCsv("1,2\n", "bare.csv", diagnostics, "x");
  ASSERT_EQ(diagnostics.error_count(), 2);
  EXPECT_EQ(diagnostics.all()[0].code, DiagnosticCode::kCsvColumns);
  EXPECT_THAT(diagnostics.all()[0].message, HasSubstr("oPos.x"));  // the columns there are
  EXPECT_EQ(diagnostics.all()[1].code, DiagnosticCode::kCsvColumns);  // no header to choose from
}

// Each kind of bad row in a vertex CSV file gets its own code, and no loader diagnostic goes without one.
TEST(VertexIo, EveryCsvAndConstantProblemHasItsCode) {
  struct Case {
    const char* text;
    const char* columns;
    DiagnosticCode code;
  };
  const Case cases[] = {
      {"1,2\n1,x\n", "", DiagnosticCode::kCsvNumber},
      {"1,2\n1,1e99\n", "", DiagnosticCode::kCsvNumber},
      {"1,2\n1,2,3,4,5\n", "", DiagnosticCode::kCsvTooManyValues},
      {"a,b,c\n1,2\n", "a,c", DiagnosticCode::kCsvMissingCell},
      {"a,b\n1,2\n", "a,b,a,b,a", DiagnosticCode::kCsvColumns},
      {"a,b\n1,2\n", "q", DiagnosticCode::kCsvColumns},
      {"1;2\n1,5;2\n", "", DiagnosticCode::kCsvSeparator},
  };
  for (const Case& c : cases) {
    Diagnostics diagnostics;
    ParseVertexCsv(c.text, "in.csv", diagnostics, c.columns);
    ASSERT_EQ(diagnostics.error_count(), 1) << c.text;
    EXPECT_EQ(diagnostics.all()[0].code, c.code) << c.text << " -> " << diagnostics.ToString();
  }
  ConstantBank bank;
  Diagnostics constants;
  ParseConstantsText("c = 1\nc1 1\nc2 = 1 2 3 4 5\nc2 = a\nc999 = 1\ndef c\n", "k.txt", bank, constants);
  const std::vector<DiagnosticCode> expected = {DiagnosticCode::kConstantLine, DiagnosticCode::kConstantLine,
                                                DiagnosticCode::kConstantValue, DiagnosticCode::kConstantValue,
                                                DiagnosticCode::kConstantRegisterRange, DiagnosticCode::kConstantLine};
  std::vector<DiagnosticCode> codes;
  for (const Diagnostic& d : constants.all()) codes.push_back(d.code);
  EXPECT_EQ(codes, expected) << constants.ToString();
}

TEST(VertexIo, InputFlagSplitsRegisterFileAndColumns) {
  Result<InputSpec> spec = ParseInputSpec("v3=out.csv:oD0.x,oD0.y");
  ASSERT_TRUE(spec) << spec.message();
  EXPECT_EQ(spec->reg, 3);
  EXPECT_EQ(spec->file, "out.csv");
  EXPECT_EQ(spec->columns, "oD0.x,oD0.y");
  spec = ParseInputSpec("v0=plain.csv");
  ASSERT_TRUE(spec);
  EXPECT_EQ(spec->columns, "");
  EXPECT_EQ(ParseInputSpec("v16=a.csv").error().code, DiagnosticCode::kInputFlag);
  EXPECT_EQ(ParseInputSpec("a.csv").message(), "'a.csv': expected v#=FILE.csv or v#=FILE.csv:COLUMNS");
}

TEST(VertexIo, WarnsAboutRegistersNobodySetsAndDefsThatOverride) {
  AssembleResult assembled = AssembleSource(
      "vs_1_1\ndef c5, 1, 1, 1, 1\ndcl_position v0\ndcl_normal v1\nm4x4 oPos, v0, c0\nmov a0.x, c9.x\n"
      "mul r0, v1, c5\nadd oD0, r0, c[a0.x + 20]\n",
      "t.vsh", {});
  ASSERT_TRUE(assembled.program) << assembled.diagnostics.ToString();
  std::vector<std::string> warnings = UnsetRegisterWarnings(*assembled.program, {1, 5}, {0});
  ASSERT_EQ(warnings.size(), 3u);
  EXPECT_THAT(warnings[0], HasSubstr("c0, c2, c3, c9,"));  // not c1 (given), c5 (def) or c20 (relative)
  EXPECT_THAT(warnings[1], HasSubstr("def of c5 overrides"));
  EXPECT_THAT(warnings[2], HasSubstr("reads v1,"));
  EXPECT_TRUE(UnsetRegisterWarnings(*assembled.program, {0, 1, 2, 3, 9}, {0, 1}).empty());
}

TEST(VertexIo, FindsIntegerAndBooleanConstantsNobodySets) {
  AssembleResult assembled = AssembleSource(
      "vs_2_0\ndefi i0, 1, 0, 0, 0\ndcl_position v0\nmov r0, v0\nrep i0\nadd r0, r0, r0\nendrep\n"
      "rep i1\nadd r0, r0, r0\nendrep\nif b0\nadd r0, r0, r0\nendif\nmov oPos, r0\n",
      "t.vsh", {});
  ASSERT_TRUE(assembled.program) << assembled.diagnostics.ToString();
  const UnsetRegisters unset = FindUnsetRegisters(*assembled.program, AssignedConstants{{}, {0, 3}, {}}, {0});
  EXPECT_EQ(unset.integers, (std::vector<int>{1}));  // i0: a defi; i3 given, unread
  EXPECT_EQ(unset.booleans, (std::vector<int>{0}));
  EXPECT_EQ(unset.integers_overridden, (std::vector<int>{0}));
  const std::vector<std::string> warnings = UnsetRegisterWarnings(unset);
  ASSERT_EQ(warnings.size(), 3u);
  EXPECT_THAT(warnings[0], HasSubstr("reads i1, which no defi"));
  EXPECT_THAT(warnings[1], HasSubstr("reads b0, which no defb"));
  EXPECT_THAT(warnings[2], HasSubstr("defi of i0 overrides"));
  const Status refused = CheckNoUnsetRegisters(unset, {0}, {"a def", "--input", "--missing zeros"});
  EXPECT_THAT(refused.message(), HasSubstr("reads i1, which neither a def sets; the program reads b0"));
  // Callers that cannot set i# or b# (Python's arguments) are not told about them.
  EXPECT_TRUE(FindUnsetRegisters(*assembled.program, std::vector<int>{}, {0}).integers.empty());
}

TEST(VertexIo, OutputCsvNamesWrittenLanes) {
  AssembleResult assembled = AssembleSource("vs.1.1\nmov oPos, v0\nmov oD0.xz, v0\n", "t.vsh", {});
  ASSERT_TRUE(assembled.program) << assembled.diagnostics.ToString();
  VertexArrays outputs = MakeOutputArrays(1, *assembled.program);
  outputs.lane(static_cast<int>(OutputSlot::kDiffuse), 2)[0] = 0.1f;
  std::string csv = FormatOutputCsv(*assembled.program, outputs, {{"n"}, {7.0f}});
  EXPECT_EQ(csv, "n,oPos.x,oPos.y,oPos.z,oPos.w,oD0.x,oD0.z\n7,0,0,0,0,0,0.1\n");
}

TEST(VertexIo, FloatsPrintShortestRoundTrip) {
  EXPECT_EQ(FormatFloat(0.1f), "0.1");
  EXPECT_EQ(FormatFloat(-std::numeric_limits<float>::infinity()), "-inf");
  EXPECT_EQ(FormatFloat(std::numeric_limits<float>::quiet_NaN()), "nan");
}

}  // namespace
}  // namespace vs11

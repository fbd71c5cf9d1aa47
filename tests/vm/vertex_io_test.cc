#include "vm/vertex_io.h"

#include <gtest/gtest.h>

#include "vm/assembler.h"

namespace vs11 {
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
  EXPECT_NE(all[0].message.find("expected a number"), std::string::npos);
  EXPECT_EQ(all[1].loc.line, 3);
  EXPECT_NE(all[1].message.find("constant register"), std::string::npos);
  EXPECT_EQ(all[2].loc.line, 4);
  EXPECT_NE(all[2].message.find("beyond the 96"), std::string::npos);
  EXPECT_EQ(all[3].loc.line, 5);
  EXPECT_NE(all[3].message.find("'='"), std::string::npos);
  EXPECT_EQ(all[4].loc.line, 6);
  EXPECT_NE(all[4].message.find("more than four"), std::string::npos);
}

TEST(VertexIo, ConstantAssignmentFlag) {
  ConstantBank bank;
  EXPECT_FALSE(ParseConstantAssignment("c4=1,0,0,1", bank).has_value());
  EXPECT_EQ(bank[4], (Vec4f{1, 0, 0, 1}));
  std::optional<std::string> error = ParseConstantAssignment("c4=1,zz", bank);
  ASSERT_TRUE(error.has_value());
  EXPECT_NE(error->find("c4=1,zz"), std::string::npos);
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

TEST(VertexIo, CsvRejectsTextAfterTheHeaderAndLongRows) {
  Diagnostics diagnostics;
  ParseVertexCsv("1,2\n1,abc\n1,2,3,4,5\n", "in.csv", diagnostics);
  ASSERT_EQ(diagnostics.error_count(), 2);
  EXPECT_EQ(diagnostics.all()[0].loc.line, 2);
  EXPECT_EQ(diagnostics.all()[0].loc.column, 3);
  EXPECT_EQ(diagnostics.all()[1].loc.line, 3);
}

TEST(VertexIo, OutputCsvNamesWrittenLanes) {
  AssembleResult assembled = AssembleSource("vs.1.1\nmov oPos, v0\nmov oD0.xz, v0\n", "t.vsh", {});
  ASSERT_TRUE(assembled.program) << assembled.diagnostics.ToString();
  VertexArrays outputs = MakeOutputArrays(1, *assembled.program);
  outputs.lane(static_cast<int>(OutputSlot::kDiffuse), 2)[0] = 0.1f;
  std::string csv = FormatOutputCsv(*assembled.program, outputs, {{"n"}, {{7.0f}}});
  EXPECT_EQ(csv, "n,oPos.x,oPos.y,oPos.z,oPos.w,oD0.x,oD0.z\n7,0,0,0,0,0,0.1\n");
}

TEST(VertexIo, FloatsPrintShortestRoundTrip) {
  EXPECT_EQ(FormatFloat(0.1f), "0.1");
  EXPECT_EQ(FormatFloat(-std::numeric_limits<float>::infinity()), "-inf");
  EXPECT_EQ(FormatFloat(std::numeric_limits<float>::quiet_NaN()), "nan");
}

}  // namespace
}  // namespace vs11

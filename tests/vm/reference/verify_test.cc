// Verify, VerifyEngines, the metadata reader, the coefficient JSON reader, the sh9 packings of
// program_references.h, and the `vs11 verify` command end to end.
#include "vm/reference/verify.h"

#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/run_tool.h"
#include "vm/asm/assembler.h"
#include "vm/reference/program_references.h"
#include "vm/reference/sh9.h"
#include "vm/reference/sphere_normals.h"

namespace vs11 {
namespace {

// The paper's program, corrected, as a fragment (no oPos) reading v0 and writing oD0.
constexpr const char* kPaperProgram = R"(vs.1.1
dp4 r1.x, v0, c0
dp4 r1.y, v0, c1
dp4 r1.z, v0, c2
mul r2, v0.xyzz, v0.yzzx
dp4 r3.x, r2, c3
dp4 r3.y, r2, c4
dp4 r3.z, r2, c5
mul r0.xy, v0.xy, v0.xy
add r0.x, r0.x, -r0.y
mad r2.xyz, c6.xyz, r0.x, r3.xyz
add oD0.xyz, r1.xyz, r2.xyz
)";

Program Assemble(const std::string& text) {
  AssembleOptions options;
  options.validate = false;
  AssembleResult result = AssembleSource(text, "test.vsh", options);
  EXPECT_TRUE(result.program) << result.diagnostics.ToString();
  return result.program.value_or(Program{});
}

ProgramMetadata Sh9Metadata() {
  ProgramMetadata m;
  m.reference = "sh9";
  m.packing = "table1";
  m.normal = 0;
  m.output = static_cast<int>(OutputSlot::kDiffuse);
  m.constants = 0;
  return m;
}

// ---- metadata -------------------------------------------------------------------------------------

TEST(VerifyMetadata, ReadsEveryKeyFromCommentLines) {
  MetadataResult r = ParseProgramMetadata(
      "; header\n"
      "; vs11: reference=sh9\n"
      ";vs11:packing = unit_sphere10\n"
      "// vs11: normal=v3\n"
      ";; vs11: position=V1\n"
      "; vs11: output=oT2\n"
      "; vs11: constants=c[12]\n"
      "; vs11: transform=c40\n"
      "; vs11: fragment=yes\n"
      "; vs11: tolerance=2.5e-6\n"
      "vs.1.1\n"
      "mov oD0, v0 ; vs11: not metadata when it follows an instruction\n",
      "p.vsh");
  EXPECT_FALSE(r.diagnostics.HasErrors()) << r.diagnostics.ToString();
  EXPECT_EQ(r.metadata.reference, "sh9");
  EXPECT_EQ(r.metadata.packing, "unit_sphere10");
  EXPECT_EQ(r.metadata.normal, 3);
  EXPECT_EQ(r.metadata.position, 1);
  EXPECT_EQ(r.metadata.output, static_cast<int>(OutputSlot::kTexCoord0) + 2);
  EXPECT_EQ(r.metadata.constants, 12);
  EXPECT_EQ(r.metadata.transform, 40);
  EXPECT_TRUE(r.metadata.fragment);
  EXPECT_EQ(r.metadata.tolerance, 2.5e-6);
}

TEST(VerifyMetadata, ReportsBadLinesWithFileAndLine) {
  MetadataResult r = ParseProgramMetadata(
      "; vs11: reference=nosuch\n"
      "; vs11: colour=red\n"
      "; vs11: normal=r0\n"
      "; vs11: output=oD7\n"
      "; vs11: just words\n"
      "; vs11: fragment=maybe\n",
      "bad.vsh");
  ASSERT_EQ(r.diagnostics.error_count(), 6) << r.diagnostics.ToString();
  const std::vector<DiagnosticCode> expected = {DiagnosticCode::kMetadataValue,      DiagnosticCode::kMetadataUnknownKey,
                                                DiagnosticCode::kMetadataValue,      DiagnosticCode::kMetadataValue,
                                                DiagnosticCode::kMetadataSyntax,     DiagnosticCode::kMetadataValue};
  for (int line = 1; line <= 6; ++line) {
    const Diagnostic& d = r.diagnostics.all()[line - 1];
    EXPECT_EQ(d.loc.file, "bad.vsh");
    EXPECT_EQ(d.loc.line, line);
    EXPECT_EQ(d.code, expected[line - 1]) << d.message;
  }
  // The key or value at fault is named.
  EXPECT_NE(r.diagnostics.all()[0].message.find("'nosuch'"), std::string::npos);
  EXPECT_NE(r.diagnostics.all()[1].message.find("'colour'"), std::string::npos);
}

// An unknown packing is answered with every packing there is (kSh9PackingNames), not a list typed by hand.
TEST(VerifyMetadata, UnknownPackingNamesEveryPacking) {
  MetadataResult r = ParseProgramMetadata("; vs11: packing=nope\n", "p.vsh");
  ASSERT_EQ(r.diagnostics.error_count(), 1);
  EXPECT_EQ(r.diagnostics.all()[0].code, DiagnosticCode::kMetadataValue);
  for (const NamedChoice<Sh9Packing>& packing : kSh9PackingNames) {
    EXPECT_NE(r.diagnostics.all()[0].message.find(packing.name), std::string::npos) << packing.name;
  }
}

TEST(VerifyMetadata, RepeatedKeyWarnsAndTheLastWins) {
  MetadataResult r = ParseProgramMetadata("; vs11: output=oD0\n; vs11: output=oD1\n", "p.vsh");
  EXPECT_FALSE(r.diagnostics.HasErrors());
  ASSERT_EQ(r.diagnostics.all().size(), 1u);
  EXPECT_EQ(r.diagnostics.all()[0].code, DiagnosticCode::kMetadataDuplicateKey);
  EXPECT_EQ(r.diagnostics.all()[0].loc.line, 2);
  EXPECT_EQ(r.metadata.output, static_cast<int>(OutputSlot::kSpecular));
}

// ---- coefficients ---------------------------------------------------------------------------------

TEST(VerifyCoefficients, ParsesNineRgbRowsInShIndexOrder) {
  Result<Sh9Rgb> sh = ParseCoefficientsJson(
      R"({"name": "test", "coefficients": [[1,2,3],[4,5,6],[7,8,9],[10,11,12],[13,14,15],
          [16,17,18],[19,20,21],[22,23,24],[25,26,-27.5]]})");
  ASSERT_TRUE(sh) << sh.message();
  EXPECT_EQ(sh->at(0, 0), glm::dvec3(1, 2, 3));
  EXPECT_EQ(sh->at(1, -1), glm::dvec3(4, 5, 6));
  EXPECT_EQ(sh->at(2, 0), glm::dvec3(19, 20, 21));
  EXPECT_EQ(sh->at(2, 2), glm::dvec3(25, 26, -27.5));
}

TEST(VerifyCoefficients, RejectsMalformedJsonWithAReason) {
  const std::array<std::pair<const char*, const char*>, 7> cases = {{
      {"{\"coefficients\": [", "not valid JSON"},
      {"[1, 2, 3]", "\"coefficients\" member"},
      {"{\"coeffs\": []}", "\"coefficients\" member"},
      {"{\"coefficients\": [[1,2,3]]}", "got 1 rows"},
      {"{\"coefficients\": 5}", "array of 9"},
      {"{\"coefficients\": [[1,2,3],[1,2,3],[1,2,3],[1,2,3],[1,2,3],[1,2,3],[1,2,3],[1,2,3],[1,2]]}", "row 8"},
      {"{\"coefficients\": [[1,2,3],[1,\"x\",3],[1,2,3],[1,2,3],[1,2,3],[1,2,3],[1,2,3],[1,2,3],[1,2,3]]}",
       "row 1, channel 1"},
  }};
  for (const auto& [text, reason] : cases) {
    const Result<Sh9Rgb> parsed = ParseCoefficientsJson(text);
    ASSERT_FALSE(parsed) << text;
    EXPECT_EQ(parsed.error().code, DiagnosticCode::kCannotReadFile) << text;
    EXPECT_NE(parsed.message().find(reason), std::string::npos) << text << " -> " << parsed.message();
  }
}

TEST(VerifyCoefficients, FileErrorsNameTheFile) {
  std::string error = LoadCoefficientsJson("/nonexistent/dir/coeffs.json").message();
  EXPECT_NE(error.find("/nonexistent/dir/coeffs.json"), std::string::npos) << error;
  const std::filesystem::path bad = std::filesystem::temp_directory_path() / "vs11_verify_test_bad.json";
  std::ofstream(bad) << "{\"coefficients\": [[1, 2]]}";
  error = LoadCoefficientsJson(bad).message();
  EXPECT_NE(error.find(bad.string()), std::string::npos) << error;
  std::filesystem::remove(bad);
}

TEST(VerifyCoefficients, RandomCoefficientsAreReproducible) {
  const Sh9Rgb a = RandomCoefficients(42), b = RandomCoefficients(42), c = RandomCoefficients(43);
  EXPECT_EQ(a.coefficients, b.coefficients);
  EXPECT_NE(a.coefficients, c.coefficients);
  for (int ch = 0; ch < 3; ++ch) EXPECT_GE(a.at(0, 0)[ch], 0.5);
}

// ---- packings -------------------------------------------------------------------------------------

TEST(VerifyPackings, MatrixFormIsEq7) {
  const Sh9Rgb sh = RandomCoefficients(5);
  const std::array<glm::vec4, 12> m = PackMatrix(sh);
  for (const glm::dvec3& d : SphereNormals(50)) {
    const glm::dvec3 n = d * 1.3;  // the polynomial identity holds off the sphere too
    const glm::dvec4 v(n, 1.0);
    const glm::dvec3 expected = IrradianceEq7(sh, n);
    for (int ch = 0; ch < 3; ++ch) {
      glm::dvec4 mv;
      for (int row = 0; row < 4; ++row) mv[row] = glm::dot(glm::dvec4(m[4 * ch + row]), v);
      EXPECT_NEAR(glm::dot(mv, v), expected[ch], 1e-5) << ch;
    }
  }
}

TEST(VerifyPackings, MatrixIsSymmetric) {
  const std::array<glm::vec4, 12> m = PackMatrix(RandomCoefficients(6));
  for (int ch = 0; ch < 3; ++ch) {
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) EXPECT_EQ(m[4 * ch + i][j], m[4 * ch + j][i]);
    }
  }
}

TEST(VerifyPackings, BasisWeightsGiveEq6) {
  const Sh9Rgb sh = RandomCoefficients(8);
  const std::array<glm::vec4, 9> k = PackBasis(sh);
  for (const glm::dvec3& n : SphereNormals(50)) {
    const glm::dvec4 b0(k[0].x, k[0].y * n.y, k[0].y * n.z, k[0].y * n.x);
    const glm::dvec4 b1(k[0].z * n.x * n.y, k[0].z * n.y * n.z, k[0].w * (3 * n.z * n.z - 1), k[0].z * n.z * n.x);
    const double y22 = k[1].x * (n.x * n.x - n.y * n.y);
    const glm::dvec3 expected = IrradianceEq6(sh, n);
    for (int ch = 0; ch < 3; ++ch) {
      const double e = glm::dot(b0, glm::dvec4(k[2 + ch])) + glm::dot(b1, glm::dvec4(k[5 + ch])) + y22 * k[8][ch];
      EXPECT_NEAR(e, expected[ch], 1e-5);
    }
  }
}

// ---- Verify ---------------------------------------------------------------------------------------

TEST(Verify, PaperProgramPassesOnBothEngines) {
  const Program program = Assemble(kPaperProgram);
  for (std::string engine : {"ref", "batch"}) {
    VerifyOptions options;
    options.engine = engine;
    VerifyReport report = Verify(program, Sh9Metadata(), options);
    ASSERT_TRUE(report.error.empty()) << report.error;
    EXPECT_TRUE(report.pass) << FormatVerifyReport(report);
    EXPECT_EQ(report.vertices, static_cast<std::size_t>(kDefaultVerifySamples) + 14);
    ASSERT_EQ(report.outputs.size(), 1u);
    EXPECT_EQ(report.outputs[0].Name(), "oD0.xyz");
    EXPECT_LT(report.outputs[0].max_relative, 1e-6);
    EXPECT_GT(report.outputs[0].scale, 0.0);
    ASSERT_EQ(report.outputs[0].worst_inputs.size(), 1u);
    EXPECT_EQ(report.outputs[0].worst_inputs[0].name, "normal");
  }
}

TEST(Verify, UsesGivenCoefficientsAndSampleCount) {
  VerifyOptions options;
  options.samples = 10;
  options.coefficients = Sh9Rgb{};
  options.coefficients->at(0, 0) = glm::dvec3(1.0, 2.0, 3.0);  // constant environment
  VerifyReport report = Verify(Assemble(kPaperProgram), Sh9Metadata(), options);
  ASSERT_TRUE(report.error.empty()) << report.error;
  EXPECT_TRUE(report.pass);
  EXPECT_EQ(report.vertices, 24u);
  // E = c0 L00 = A0 n0 L00 for every normal; the largest is blue's.
  EXPECT_NEAR(report.outputs[0].scale, 3.0 * kShC0, 1e-12);
}

TEST(Verify, DetectsAWrongProgramAndReportsTheWorstNormal) {
  std::string wrong = kPaperProgram;
  wrong.replace(wrong.find("-r0.y"), 5, "r0.y");  // x^2 + y^2 instead of x^2 - y^2
  VerifyReport report = Verify(Assemble(wrong), Sh9Metadata(), VerifyOptions{});
  ASSERT_TRUE(report.error.empty());
  EXPECT_FALSE(report.pass);
  const OutputReport& out = report.outputs[0];
  EXPECT_GT(out.max_relative, 1e-3);
  // The error is 2 c4 L22 y^2: largest where |y| is largest.
  EXPECT_GT(std::abs(out.worst_inputs[0].value[1]), 0.9f);
  EXPECT_NE(FormatVerifyReport(report).find("FAIL"), std::string::npos);
}

TEST(Verify, ToleranceOptionOverridesTheReferences) {
  VerifyOptions options;
  options.tolerance = 0.0;  // float arithmetic cannot be exact everywhere
  VerifyReport report = Verify(Assemble(kPaperProgram), Sh9Metadata(), options);
  EXPECT_FALSE(report.pass);
  EXPECT_EQ(report.outputs[0].tolerance, 0.0);
  options.tolerance = 1.0;
  EXPECT_TRUE(Verify(Assemble(kPaperProgram), Sh9Metadata(), options).pass);
}

TEST(Verify, LanesTheProgramNeverWritesFail) {
  std::string partial = kPaperProgram;
  partial.replace(partial.find("add oD0.xyz"), 11, "add oD0.xy ");
  VerifyReport report = Verify(Assemble(partial), Sh9Metadata(), VerifyOptions{});
  ASSERT_TRUE(report.error.empty());
  EXPECT_FALSE(report.pass);
  EXPECT_EQ(report.outputs[0].missing_lanes.bits(), 0x4);
  EXPECT_NE(FormatVerifyReport(report).find("never writes oD0.z"), std::string::npos);
}

TEST(Verify, OutputOverrideSelectsAnotherRegister) {
  ProgramMetadata metadata = Sh9Metadata();
  metadata.output = static_cast<int>(OutputSlot::kTexCoord0);  // the program writes oD0, not oT0
  VerifyReport report = Verify(Assemble(kPaperProgram), metadata, VerifyOptions{});
  EXPECT_FALSE(report.pass);
  EXPECT_EQ(report.outputs[0].Name(), "oT0.xyz");
  EXPECT_EQ(report.outputs[0].missing_lanes.bits(), 0x7);
}

TEST(Verify, MissingOrUnknownReferenceIsAnError) {
  ProgramMetadata metadata = Sh9Metadata();
  metadata.reference = "";
  EXPECT_NE(Verify(Assemble(kPaperProgram), metadata, {}).error.find("no reference"), std::string::npos);
  metadata.reference = "sh10";
  VerifyReport report = Verify(Assemble(kPaperProgram), metadata, {});
  EXPECT_NE(report.error.find("unknown reference 'sh10'"), std::string::npos);
  EXPECT_FALSE(report.pass);
  EXPECT_NE(VerifyReportJson(report).find("\"error\""), std::string::npos);
}

TEST(Verify, ReferenceRejectsMetadataThatDoesNotFit) {
  ProgramMetadata metadata = Sh9Metadata();
  metadata.constants = 90;  // c90..c96 is beyond 96 registers
  EXPECT_NE(Verify(Assemble(kPaperProgram), metadata, {}).error.find("beyond"), std::string::npos);
  metadata = Sh9Metadata();
  metadata.packing = "table2";
  EXPECT_NE(Verify(Assemble(kPaperProgram), metadata, {}).error.find("packing"), std::string::npos);
  metadata = Sh9Metadata();
  metadata.transform = 7;  // without position=
  EXPECT_NE(Verify(Assemble(kPaperProgram), metadata, {}).error.find("position"), std::string::npos);
}

TEST(Verify, JsonReportCarriesTheNumbers) {
  VerifyReport report = Verify(Assemble(kPaperProgram), Sh9Metadata(), VerifyOptions{});
  const std::string json = VerifyReportJson(report);
  for (const char* key : {"\"max_abs\"", "\"rms_rel\"", "\"tolerance\"", "\"worst_inputs\"", "\"pass\": true"}) {
    EXPECT_NE(json.find(key), std::string::npos) << key << "\n" << json;
  }
}

// ---- engines --------------------------------------------------------------------------------------

TEST(VerifyEngines, ReferenceAndBatchAgreeBitForBit) {
  const Program program = Assemble(kPaperProgram);
  EngineComparison c = VerifyEngines(program, Sh9Metadata(), "ref", "batch", {});
  EXPECT_TRUE(c.identical()) << FormatEngineComparison(c);
  // oD0 is the only output register: every vertex, four lanes.
  EXPECT_EQ(c.lanes_compared, c.vertices * 4);
  EXPECT_FALSE(c.first);
  EXPECT_NE(FormatEngineComparison(c).find("IDENTICAL"), std::string::npos);
}

TEST(VerifyEngines, RandomInputsWithoutAReference) {
  VerifyOptions options;
  options.samples = 33;
  EngineComparison c =
      VerifyEngines(Assemble(kPaperProgram), ProgramMetadata{}, "ref", "batch", options);
  EXPECT_TRUE(c.identical()) << FormatEngineComparison(c);
  EXPECT_EQ(c.vertices, 33u);
  EXPECT_NE(c.inputs.find("random"), std::string::npos);
}

TEST(VerifyEngines, SameEngineTwiceIsIdentical) {
  const Program program = Assemble(kPaperProgram);
  ConstantBank constants;
  for (int i = 0; i < 7; ++i) constants[i] = {0.5f, 0.25f, 0.125f, 1.0f};
  const int v0 = 0;
  VertexArrays inputs = MakeInputArrays(5, std::span<const int>(&v0, 1));
  EngineComparison same = CompareEngines(program, "ref", "ref", constants, inputs);
  EXPECT_TRUE(same.identical());
  EXPECT_EQ(same.lanes_compared, 20u);
  EXPECT_EQ(EngineComparisonJson(same).find("first_difference"), std::string::npos);
}

TEST(VerifyEngines, CountsDifferingBitPatternsAndLocatesTheFirst) {
  const std::array<int, 2> slots = {static_cast<int>(OutputSlot::kPosition), static_cast<int>(OutputSlot::kDiffuse)};
  VertexArrays a(4, slots, kOutputSlotCount), b(4, slots, kOutputSlotCount);
  b.lane(slots[1], 2)[3] = 1e-30f;                                 // vertex 3, oD0.z
  b.lane(slots[0], 1)[1] = -0.0f;                                  // vertex 1, oPos.y: -0 is not +0
  a.lane(slots[0], 3)[2] = b.lane(slots[0], 3)[2] = std::nanf(""); // same NaN bits: equal
  EngineComparison c = CompareOutputArrays(a, b);
  EXPECT_EQ(c.lanes_compared, 32u);
  EXPECT_EQ(c.differing_lanes, 2u);
  ASSERT_TRUE(c.first);
  EXPECT_EQ(c.first->vertex, 1u);
  EXPECT_EQ(c.first->slot, slots[0]);
  EXPECT_EQ(c.first->lane, 1);
  EXPECT_FALSE(c.identical());
  EXPECT_NE(FormatEngineComparison(c).find("vertex 1, oPos.y"), std::string::npos) << FormatEngineComparison(c);
  EXPECT_NE(EngineComparisonJson(c).find("\"b_bits\": 2147483648"), std::string::npos) << EngineComparisonJson(c);
}

TEST(VerifyEngines, UnknownReferenceIsAnError) {
  ProgramMetadata metadata;
  metadata.reference = "nosuch";
  EngineComparison c = VerifyEngines(Assemble(kPaperProgram), metadata, "ref", "batch", {});
  EXPECT_FALSE(c.identical());
  EXPECT_NE(c.error.find("nosuch"), std::string::npos);
}

// ---- loading --------------------------------------------------------------------------------------

TEST(VerifyLoading, FragmentsSkipOnlyThePositionRule) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path();
  const std::filesystem::path ok = dir / "vs11_verify_fragment_ok.vsh";
  const std::filesystem::path bad = dir / "vs11_verify_fragment_bad.vsh";
  std::ofstream(ok) << "; vs11: reference=sh9\n; vs11: fragment=yes\n" << kPaperProgram;
  std::ofstream(bad) << "; vs11: fragment=yes\nvs.1.1\nadd oD0, c0, c1\n";  // two constants: illegal
  ProgramForVerify loaded = LoadProgramForVerify(ok);
  EXPECT_TRUE(loaded.program) << loaded.diagnostics.ToString();
  EXPECT_EQ(loaded.metadata.reference, "sh9");
  ProgramForVerify rejected = LoadProgramForVerify(bad);
  EXPECT_FALSE(rejected.program);
  EXPECT_EQ(rejected.diagnostics.error_count(), 1) << rejected.diagnostics.ToString();
  EXPECT_NE(rejected.diagnostics.ToString().find(bad.string()), std::string::npos);
  std::filesystem::remove(ok);
  std::filesystem::remove(bad);
}

TEST(VerifyLoading, MissingFileIsAnError) {
  ProgramForVerify loaded = LoadProgramForVerify("/nonexistent/p.vsh");
  EXPECT_FALSE(loaded.program);
  ASSERT_EQ(loaded.diagnostics.all().size(), 1u);
  EXPECT_EQ(loaded.diagnostics.all()[0].code, DiagnosticCode::kCannotReadFile);
  EXPECT_EQ(loaded.diagnostics.all()[0].loc.file, "/nonexistent/p.vsh");
}

// ---- the command line -----------------------------------------------------------------------------

using vs11::testing::CommandResult;
using vs11::testing::RunVs11;

class VerifyCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::exists(std::string(VS11_BINARY_DIR) + "/vm/vs11")) GTEST_SKIP() << "vs11 not built";
  }
  static std::string Program(const char* name) { return std::string(VS11_SOURCE_DIR) + "/programs/" + name; }
};

TEST_F(VerifyCommand, PaperProgramPassesOnBothEngines) {
  for (const char* engine : {"ref", "batch"}) {
    CommandResult r = RunVs11("verify " + Program("sh9_irradiance.vsh") + " --engine " + engine);
    EXPECT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("PASS"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("tolerance 1.0e-05"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("worst normal"), std::string::npos) << r.output;
  }
}

TEST_F(VerifyCommand, AsPrintedListingFails) {
  CommandResult r = RunVs11("verify " + Program("sh9_irradiance_as_printed.vsh"));
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("FAIL"), std::string::npos) << r.output;
}

TEST_F(VerifyCommand, AgainstEngineReportsIdentical) {
  CommandResult r = RunVs11("verify " + Program("skinning.vsh") + " --against-engine ref --json");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("\"differing_lanes\": 0"), std::string::npos) << r.output;
}

TEST_F(VerifyCommand, ErrorsNameTheFileAndExitWithOne) {
  const std::filesystem::path bad = std::filesystem::temp_directory_path() / "vs11_verify_command_bad.json";
  std::ofstream(bad) << "{not json";
  CommandResult r = RunVs11("verify " + Program("sh9_irradiance.vsh") + " --coeffs " + bad.string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("error: " + bad.string()), std::string::npos) << r.output;
  std::filesystem::remove(bad);

  r = RunVs11("verify " + Program("sh9_irradiance.vsh") + " --reference nosuch");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("error: unknown reference 'nosuch'"), std::string::npos) << r.output;

  r = RunVs11("verify /nonexistent/p.vsh");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("/nonexistent/p.vsh"), std::string::npos) << r.output;
}

TEST_F(VerifyCommand, HelpDescribesFlagsAndGivesAnExample) {
  CommandResult r = RunVs11("verify --help");
  EXPECT_EQ(r.status, 0) << r.output;
  for (const char* text : {"--reference", "--coeffs", "--against-engine", "--tolerance", "Examples:", "sh9"}) {
    EXPECT_NE(r.output.find(text), std::string::npos) << text;
  }
}

}  // namespace
}  // namespace vs11

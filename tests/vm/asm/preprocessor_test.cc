#include "vm/asm/preprocessor.h"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace vs11 {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using Files = std::map<std::string, std::string>;

// Serves files from memory, keyed by their normalised generic path ("dir/name.h").
FileReader MapReader(Files files) {
  return [files = std::move(files)](const std::filesystem::path& path) -> std::optional<std::string> {
    auto it = files.find(path.lexically_normal().generic_string());
    if (it == files.end()) return std::nullopt;
    return it->second;
  };
}

PreprocessResult PreprocessText(std::string_view text, const PreprocessOptions& options = {}, Files files = {},
                                const std::string& file_name = "main.vsh") {
  return Preprocess(text, file_name, options, MapReader(std::move(files)));
}

std::vector<std::string> Texts(const PreprocessResult& result) {
  std::vector<std::string> texts;
  for (const PreprocessedLine& line : result.lines) texts.push_back(line.text);
  return texts;
}

// The output of a clean run, one string per line; a run with diagnostics fails the test.
std::vector<std::string> CleanTexts(std::string_view text, const PreprocessOptions& options = {}, Files files = {}) {
  PreprocessResult result = PreprocessText(text, options, std::move(files));
  EXPECT_TRUE(result.diagnostics.all().empty()) << result.diagnostics.ToString();
  return Texts(result);
}

// Whether `#if expression` keeps its body, failing the test on any diagnostic.
bool IfKeeps(const std::string& expression, const PreprocessOptions& options = {}) {
  std::vector<std::string> texts = CleanTexts("#if " + expression + "\nkept\n#endif\n", options);
  return texts == std::vector<std::string>{"kept"};
}

const Diagnostic& OnlyError(const PreprocessResult& result) {
  EXPECT_EQ(result.diagnostics.error_count(), 1) << result.diagnostics.ToString();
  static const Diagnostic kNone{};
  return result.diagnostics.all().empty() ? kNone : result.diagnostics.all().front();
}

TEST(Preprocessor, PassesInstructionsThroughWithTheirLineNumbers) {
  PreprocessResult result = PreprocessText("vs.1.1\n\n  mov oPos, v0\n");
  EXPECT_FALSE(result.diagnostics.HasErrors());
  ASSERT_EQ(result.lines.size(), 2u);
  EXPECT_EQ(result.lines[0].text, "vs.1.1");
  EXPECT_EQ(result.lines[0].line, 1);
  EXPECT_EQ(result.lines[0].file, "main.vsh");
  EXPECT_EQ(result.lines[1].text, "mov oPos, v0");
  EXPECT_EQ(result.lines[1].line, 3);
  EXPECT_THAT(result.lines[1].columns, ElementsAre(3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14));
}

TEST(Preprocessor, RemovesSemicolonCommentsEvenWithUnbalancedQuotes) {
  EXPECT_THAT(CleanTexts("dp4 r1.x, v0, c[4] ; don't \"worry\n; it's a comment\nmov r0, v0 ; \"\n"),
              ElementsAre("dp4 r1.x, v0, c[4]", "mov r0, v0"));
}

TEST(Preprocessor, RemovesDoubleSlashCommentsEvenWithUnbalancedQuotes) {
  EXPECT_THAT(CleanTexts("mov r0, v0 // it's\n// \"\nadd r0, r0, r0\n"), ElementsAre("mov r0, v0", "add r0, r0, r0"));
}

TEST(Preprocessor, QuotesInCodeDoNotHideComments) {
  EXPECT_THAT(CleanTexts("mov r0, v0 \" ; comment\n"), ElementsAre("mov r0, v0 \""));
}

TEST(Preprocessor, RemovesBlockCommentsAndKeepsLaterInstructionOnItsOwnLine) {
  PreprocessResult result = PreprocessText("mov r0, /* a ; b */ v0\n/* one\n two */ add r1, r0, r0\nmul r2, r1, r1\n");
  EXPECT_FALSE(result.diagnostics.HasErrors()) << result.diagnostics.ToString();
  ASSERT_EQ(result.lines.size(), 3u);
  EXPECT_EQ(result.lines[0].text, "mov r0,   v0");
  EXPECT_EQ(result.lines[1].text, "add r1, r0, r0");
  EXPECT_EQ(result.lines[1].line, 3);
  EXPECT_EQ(result.lines[1].columns[0], 9);
  EXPECT_EQ(result.lines[2].line, 4);
}

TEST(Preprocessor, BlockCommentSpanningLinesContinuesADirective) {
  EXPECT_THAT(CleanTexts("#define X 1 /* spans\n lines */ + 2\nc[X]\n"), ElementsAre("c[1 + 2]"));
}

TEST(Preprocessor, ReportsUnterminatedBlockCommentAtItsStart) {
  PreprocessResult result = PreprocessText("mov r0, v0\nadd r0, r0, r0 /* never\nclosed\n");
  const Diagnostic& error = OnlyError(result);
  EXPECT_EQ(error.loc, (SourceLoc{"main.vsh", 2, 16}));
  EXPECT_EQ(error.code, DiagnosticCode::kUnterminatedComment) << error.message;
  EXPECT_THAT(Texts(result), ElementsAre("mov r0, v0", "add r0, r0, r0"));
}

TEST(Preprocessor, JoinsLinesEndingInBackslashInTextAndDirectives) {
  PreprocessResult result = PreprocessText("#define ADD(a, b) \\\n  add a, \\\n  b\nADD(r0, \\\n r1)\nmov r2, r3\n");
  EXPECT_FALSE(result.diagnostics.HasErrors()) << result.diagnostics.ToString();
  EXPECT_THAT(Texts(result), ElementsAre("add r0, r1", "mov r2, r3"));
  EXPECT_EQ(result.lines[0].line, 4);
  EXPECT_EQ(result.lines[1].line, 6);
}

TEST(Preprocessor, HandlesCrlfLineEndingsAndSplices) {
  PreprocessResult result = PreprocessText("#define ONE 1\r\nmov r0, \\\r\nc[ONE]\r\nadd r1, r0, r0\r\n");
  EXPECT_FALSE(result.diagnostics.HasErrors()) << result.diagnostics.ToString();
  EXPECT_THAT(Texts(result), ElementsAre("mov r0, c[1]", "add r1, r0, r0"));
  EXPECT_EQ(result.lines[1].line, 4);
  EXPECT_EQ(result.lines[1].columns.back(), 14);
}

TEST(Preprocessor, HandlesLastLineWithoutNewline) {
  PreprocessResult result = PreprocessText("#define N 3\nmov r0, c[N]");
  EXPECT_THAT(Texts(result), ElementsAre("mov r0, c[3]"));
  EXPECT_EQ(result.lines[0].line, 2);
  EXPECT_THAT(CleanTexts("#if 1\nmov r0, v0\n#endif"), ElementsAre("mov r0, v0"));
}

TEST(Preprocessor, LeavesConstantArithmeticAsTextForTheAssembler) {
  EXPECT_THAT(CleanTexts("#define CV_WORLD 4\n#define cAr c[CV_WORLD + 2]\n"
                         "dp4 r1.x, v0, c[2 + CV_WORLD]\ndp4 r1.y, v0, cAr\n"),
              ElementsAre("dp4 r1.x, v0, c[2 + 4]", "dp4 r1.y, v0, c[4 + 2]"));
}

TEST(Preprocessor, ExpandsFunctionLikeMacroWithNestedParens) {
  EXPECT_THAT(CleanTexts("#define PAIR(a, b) a | b\nPAIR(f(1, 2), (3, 4))\nPAIR( x ,y )\n"),
              ElementsAre("f(1, 2) | (3, 4)", "x | y"));
}

TEST(Preprocessor, ExpandsArgumentsFullyBeforeSubstitution) {
  EXPECT_THAT(CleanTexts("#define W 4\n#define REG(i) c[i]\n#define ID(x) x\nmov r0, REG(W)\nID(ID(REG(W)))\n"),
              ElementsAre("mov r0, c[4]", "c[4]"));
}

TEST(Preprocessor, FunctionLikeMacroWithoutArgumentsIsLeftAlone) {
  EXPECT_THAT(CleanTexts("#define f(x) x\nmov f, r0\n#define N() 7\nc[N()]\n"), ElementsAre("mov f, r0", "c[7]"));
}

TEST(Preprocessor, ExpansionEndingInMacroNameTakesFollowingArguments) {
  EXPECT_THAT(CleanTexts("#define g(x) [x]\n#define f g\nf(1)\n"), ElementsAre("[1]"));
}

TEST(Preprocessor, SelfReferentialMacrosTerminate) {
  EXPECT_THAT(CleanTexts("#define A A\n#define B B + 1\n#define f(x) f(x + 1)\nA B f(0)\n"),
              ElementsAre("A B + 1 f(0 + 1)"));
}

TEST(Preprocessor, MutuallyRecursiveMacrosTerminate) {
  EXPECT_THAT(CleanTexts("#define X Y\n#define Y X\nX Y\n"), ElementsAre("X Y"));
}

TEST(Preprocessor, PastesTokensAndRescansTheResult) {
  EXPECT_THAT(CleanTexts("#define REG(n) r##n\n#define CAT(a, b) a ## b\n#define CV_WORLD 4\n#define XY x ## y\n"
                         "mov REG(1), CAT(CV_, WORLD)\nXY CAT(, c2) CAT(c3, )\n"),
              ElementsAre("mov r1, 4", "xy c2 c3"));
}

TEST(Preprocessor, ReportsWrongArgumentCountWithLineAndColumn) {
  PreprocessResult result = PreprocessText("#define ADD(a, b) add a, b\nmov r0, v0\n  ADD(r0)\n");
  const Diagnostic& error = OnlyError(result);
  EXPECT_EQ(error.loc, (SourceLoc{"main.vsh", 3, 3}));
  EXPECT_EQ(error.code, DiagnosticCode::kMacroInvocation) << error.message;
  EXPECT_THAT(error.message, HasSubstr("2"));
}

TEST(Preprocessor, ReportsUnterminatedMacroArgumentList) {
  PreprocessResult result = PreprocessText("#define F(a) a\nF(r0, \n");
  EXPECT_EQ(OnlyError(result).loc.line, 2);
  EXPECT_EQ(OnlyError(result).code, DiagnosticCode::kMacroInvocation) << OnlyError(result).message;
}

TEST(Preprocessor, ReportsBadDefinitions) {
  PreprocessResult result =
      PreprocessText("#define\n#define 5 x\n#define F(a, a) a\n#define G(a b) a\n#define H(a) ## a\n");
  EXPECT_EQ(result.diagnostics.error_count(), 5) << result.diagnostics.ToString();
  for (int i = 0; i < 5; ++i) EXPECT_EQ(result.diagnostics.all()[i].loc.line, i + 1);
}

TEST(Preprocessor, DirectiveMayFollowABlockCommentOrBlanks) {
  EXPECT_THAT(CleanTexts("/* note */ #define X 1\n \t # define Y 2\nX Y\n"), ElementsAre("1 2"));
}

TEST(Preprocessor, DirectivesNeedingANameReportItsAbsence) {
  PreprocessResult result = PreprocessText("#ifdef\n#endif\n#ifndef 3\n#endif\n#undef\n");
  ASSERT_EQ(result.diagnostics.error_count(), 3) << result.diagnostics.ToString();
  EXPECT_EQ(result.diagnostics.all()[0].loc, (SourceLoc{"main.vsh", 1, 1}));
  EXPECT_EQ(result.diagnostics.all()[1].loc, (SourceLoc{"main.vsh", 3, 9}));
  EXPECT_EQ(result.diagnostics.all()[2].loc.line, 5);
}

TEST(Preprocessor, UndefRemovesMacro) {
  EXPECT_THAT(CleanTexts("#define N 1\nc[N]\n#undef N\nc[N]\n"), ElementsAre("c[1]", "c[N]"));
}

TEST(Preprocessor, MacroNamesAreCaseSensitiveAndRegistersPassThrough) {
  EXPECT_THAT(CleanTexts("#define pos 1\nmov oPos, r0.xyzw\nmov r0, c5\nmov a0.x, v0 ; Pos\npos\n"),
              ElementsAre("mov oPos, r0.xyzw", "mov r0, c5", "mov a0.x, v0", "1"));
}

TEST(Preprocessor, DoesNotExpandInsideNumbers) {
  EXPECT_THAT(CleanTexts("#define e 9\n#define f 9\n#define x 9\ndef c0, 1e3, 1.5f, 0x10, 1e-3\n"),
              ElementsAre("def c0, 1e3, 1.5f, 0x10, 1e-3"));
}

TEST(Preprocessor, DefinedRegisterSuffixIsExpandedLikeC) {
  EXPECT_THAT(CleanTexts("#define xyz www\nmov r0.xyz, r1\n"), ElementsAre("mov r0.www, r1"));
}

TEST(Preprocessor, IfdefIfndefElseChooseBranches) {
  EXPECT_THAT(CleanTexts("#define A\n#ifdef A\na\n#else\nnot_a\n#endif\n#ifndef A\nnot_a2\n#else\na2\n#endif\n"
                         "#ifdef B\nb\n#endif\n"),
              ElementsAre("a", "a2"));
}

TEST(Preprocessor, IfElifElseTakesFirstTrueBranchAndNests) {
  std::string text =
      "#define V 2\n"
      "#if V == 1\none\n#elif V == 2\ntwo\n#if 0\nhidden\n#else\nnested\n#endif\n#elif V == 2\nagain\n"
      "#else\nother\n#endif\n";
  EXPECT_THAT(CleanTexts(text), ElementsAre("two", "nested"));
}

TEST(Preprocessor, IfEvaluatesAllOperatorsWithCPrecedence) {
  EXPECT_TRUE(IfKeeps("1 + 2 * 3 == 7"));
  EXPECT_TRUE(IfKeeps("(1 + 2) * 3 == 9"));
  EXPECT_TRUE(IfKeeps("10 / 3 == 3 && 10 % 3 == 1 && -7 / 2 == -3"));
  EXPECT_TRUE(IfKeeps("1 << 4 == 16 && 256 >> 4 == 16"));
  EXPECT_TRUE(IfKeeps("3 < 4 && 4 > 3 && 3 <= 3 && 3 >= 3 && 3 != 4"));
  EXPECT_TRUE(IfKeeps("(6 & 3) == 2 && (6 | 3) == 7 && (6 ^ 3) == 5"));
  EXPECT_TRUE(IfKeeps("!0 && ~0 == -1 && -(-2) == +2"));
  EXPECT_TRUE(IfKeeps("0 || 1"));
  EXPECT_FALSE(IfKeeps("0 && 1"));
  EXPECT_TRUE(IfKeeps("1 ? 2 : 0"));
  EXPECT_FALSE(IfKeeps("0 ? 2 : 0"));
  EXPECT_TRUE(IfKeeps("0x10 == 16 && 010 == 8 && 10u == 10L"));
  EXPECT_TRUE(IfKeeps("1 | 2 ^ 3 & 4 == 3"));  // == binds tighter than & ^ |
}

TEST(Preprocessor, IfTreatsDefinedAndUnknownNames) {
  PreprocessOptions options;
  options.defines = {{"SHADOWS", "1"}, {"ZERO", "0"}};
  EXPECT_TRUE(IfKeeps("defined(SHADOWS) && defined ZERO", options));
  EXPECT_FALSE(IfKeeps("defined(MISSING) || ZERO", options));
  EXPECT_TRUE(IfKeeps("UNKNOWN == 0 && !MISSING", options));
  EXPECT_TRUE(IfKeeps("SHADOWS + 1 == 2", options));
}

TEST(Preprocessor, DivisionByZeroInIfIsAnErrorNotACrash) {
  PreprocessResult result = PreprocessText("mov r0, v0\n#if 1 / (2 - 2)\nx\n#endif\n#if 5 % 0\ny\n#endif\n");
  ASSERT_EQ(result.diagnostics.error_count(), 2) << result.diagnostics.ToString();
  EXPECT_EQ(result.diagnostics.all()[0].loc, (SourceLoc{"main.vsh", 2, 7}));
  EXPECT_EQ(result.diagnostics.all()[1].loc.line, 5);
  EXPECT_EQ(result.diagnostics.all()[0].code, DiagnosticCode::kConditionExpression);
  EXPECT_THAT(result.diagnostics.all()[0].message, HasSubstr("division by zero"));
  EXPECT_THAT(Texts(result), ElementsAre("mov r0, v0"));
  EXPECT_TRUE(IfKeeps("0 && 1 / 0 || 1"));  // not evaluated, as in C
}

TEST(Preprocessor, MalformedIfExpressionsAreErrors) {
  PreprocessResult result = PreprocessText(
      "#if\n#endif\n#if (1\n#endif\n#if 1 +\n#endif\n#if 1.5\n#endif\n#if 1 2\n#endif\n"
      "#if defined(\n#endif\n#if 9223372036854775807 * 2 + (-9223372036854775807 - 1) / -1\n"
      "#endif\n");
  EXPECT_EQ(result.diagnostics.error_count(), 6) << result.diagnostics.ToString();
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(result.diagnostics.all()[i].loc.line, 2 * i + 1);
    EXPECT_EQ(result.diagnostics.all()[i].code, DiagnosticCode::kConditionExpression);
  }
}

TEST(Preprocessor, ReportsUnterminatedIfAtItsLine) {
  PreprocessResult result = PreprocessText("mov r0, v0\n  #ifdef A\n#if 1\n#endif\n");
  EXPECT_EQ(OnlyError(result).loc, (SourceLoc{"main.vsh", 2, 3}));
  EXPECT_EQ(OnlyError(result).code, DiagnosticCode::kUnbalancedConditional) << OnlyError(result).message;
  EXPECT_THAT(OnlyError(result).message, HasSubstr("#if"));
}

TEST(Preprocessor, ReportsUnbalancedConditionalsAndKeepsGoing) {
  PreprocessResult result =
      PreprocessText("#endif\n#else\n#if 1\n#else\n#else\n#elif 1\n#endif\n#elif 1\nmov r0, v0\n");
  ASSERT_EQ(result.diagnostics.error_count(), 5) << result.diagnostics.ToString();
  std::vector<int> lines;
  for (const Diagnostic& d : result.diagnostics.all()) lines.push_back(d.loc.line);
  EXPECT_THAT(lines, ElementsAre(1, 2, 5, 6, 8));
  EXPECT_EQ(result.diagnostics.all()[0].code, DiagnosticCode::kUnbalancedConditional);
  EXPECT_THAT(result.diagnostics.all()[0].message, HasSubstr("#endif"));
  EXPECT_THAT(Texts(result), ElementsAre("mov r0, v0"));
}

TEST(Preprocessor, SkippedBlocksMayHoldAnything) {
  EXPECT_THAT(CleanTexts("#if 0\n#bogus\n#error no\n#include <missing.h>\n#if 1 / 0\n#endif\n#else\nok\n#endif\n"
                         "#if 1\nok2\n#elif 1 / 0\n#else\n#bogus\n#endif\n"),
              ElementsAre("ok", "ok2"));
}

TEST(Preprocessor, IncludesQuotedFileBesideTheIncluderWithItsOwnLines) {
  Files files = {{"shaders/constants.h", "#define CV_WORLD 4\n\nmov r9, c[CV_WORLD]\n"}};
  PreprocessResult result =
      Preprocess("#include \"constants.h\"\ndp4 r1.x, v0, c[CV_WORLD + 2]\n", "shaders/main.vsh", {}, MapReader(files));
  EXPECT_FALSE(result.diagnostics.HasErrors()) << result.diagnostics.ToString();
  ASSERT_EQ(result.lines.size(), 2u);
  EXPECT_EQ(result.lines[0].text, "mov r9, c[4]");
  EXPECT_EQ(result.lines[0].file, "shaders/constants.h");
  EXPECT_EQ(result.lines[0].line, 3);
  EXPECT_EQ(result.lines[1].file, "shaders/main.vsh");
  EXPECT_EQ(result.lines[1].line, 2);
}

TEST(Preprocessor, QuotedIncludeFallsBackToIncludeDirsInOrder) {
  PreprocessOptions options;
  options.include_dirs = {"first", "second"};
  Files files = {{"first/a.h", "from_first"},
                 {"second/a.h", "from_second_a"},
                 {"second/b.h", "from_second_b"},
                 {"c.h", "beside"},
                 {"first/c.h", "first_c"}};
  EXPECT_THAT(CleanTexts("#include \"a.h\"\n#include \"b.h\"\n#include \"c.h\"\n", options, files),
              ElementsAre("from_first", "from_second_b", "beside"));
}

TEST(Preprocessor, AngleIncludeSearchesOnlyIncludeDirs) {
  PreprocessOptions options;
  options.include_dirs = {"inc"};
  Files files = {{"c.h", "beside"}, {"inc/c.h", "from_inc"}, {"only_beside.h", "x"}};
  PreprocessResult result = PreprocessText("#include <c.h>\n#include <only_beside.h>\n", options, files);
  EXPECT_THAT(Texts(result), ElementsAre("from_inc"));
  EXPECT_EQ(OnlyError(result).loc.line, 2);
}

TEST(Preprocessor, NestedIncludeLooksBesideTheNestedFileAndAcceptsBackslashes) {
  Files files = {{"lib/outer.h", "#include \"inner.h\"\nouter"}, {"lib/inner.h", "inner"}};
  EXPECT_THAT(CleanTexts("#include \"lib\\outer.h\"\nmain\n", {}, files), ElementsAre("inner", "outer", "main"));
}

TEST(Preprocessor, IncludeNameInQuotesMayHoldCommentCharacters) {
  Files files = {{"a;b.h", "ok"}};
  EXPECT_THAT(CleanTexts("#include \"a;b.h\" ; comment\n", {}, files), ElementsAre("ok"));
}

TEST(Preprocessor, IncludeNameMayComeFromAMacro) {
  Files files = {{"c.h", "ok"}};
  EXPECT_THAT(CleanTexts("#define HEADER \"c.h\"\n#include HEADER\n", {}, files), ElementsAre("ok"));
}

TEST(Preprocessor, ReportsMissingIncludeAtIncludeLine) {
  Files files = {{"a.h", "one\n\n#include \"missing.h\"\ntwo\n"}};
  PreprocessResult result = PreprocessText("#include \"a.h\"\nthree\n#include\n", {}, files);
  ASSERT_EQ(result.diagnostics.error_count(), 2) << result.diagnostics.ToString();
  EXPECT_EQ(result.diagnostics.all()[0].loc, (SourceLoc{"a.h", 3, 1}));
  EXPECT_EQ(result.diagnostics.all()[0].code, DiagnosticCode::kIncludeNotFound);
  EXPECT_THAT(result.diagnostics.all()[0].message, HasSubstr("missing.h"));
  EXPECT_EQ(result.diagnostics.all()[1].loc.line, 3);
  EXPECT_EQ(result.diagnostics.all()[1].loc.file, "main.vsh");
  EXPECT_THAT(Texts(result), ElementsAre("one", "two", "three"));
}

TEST(Preprocessor, ReportsIncludeCycleWithLine) {
  PreprocessOptions options;
  options.max_include_depth = 8;
  Files files = {{"a.h", "mov r0, v0\n#include \"b.h\"\n"}, {"b.h", "\n\n#include \"a.h\"\n#include \"a.h\"\n"}};
  PreprocessResult result = PreprocessText("#include \"a.h\"\n", options, files);
  const Diagnostic& error = OnlyError(result);
  EXPECT_EQ(error.loc, (SourceLoc{"b.h", 3, 1}));  // b.h is the eighth level
  EXPECT_EQ(error.code, DiagnosticCode::kIncludeTooDeep) << error.message;
}

TEST(Preprocessor, SelfIncludeWithDefaultOptionsEndsWithAnError) {
  Files files = {{"main.vsh", "#include \"main.vsh\"\n#include \"main.vsh\"\n"}};
  PreprocessResult result = PreprocessText("#include \"main.vsh\"\n", {}, files);
  EXPECT_TRUE(result.diagnostics.HasErrors());
  EXPECT_EQ(result.diagnostics.all().front().loc.line, 1);
}

TEST(Preprocessor, ReportsProblemsInIncludedFilesWithTheirNamesAndLines) {
  Files files = {{"inc.h", "\n#ifdef X\nmov r0, v0 /* open\n"}};
  PreprocessResult result = PreprocessText("#include \"inc.h\"\nmov r1, v1\n", {}, files);
  ASSERT_EQ(result.diagnostics.error_count(), 2) << result.diagnostics.ToString();
  EXPECT_EQ(result.diagnostics.all()[0].loc, (SourceLoc{"inc.h", 3, 12}));
  EXPECT_EQ(result.diagnostics.all()[1].loc, (SourceLoc{"inc.h", 2, 1}));
  EXPECT_THAT(Texts(result), ElementsAre("mov r1, v1"));
}

TEST(Preprocessor, ThrowingReaderIsAMissingFileThatSaysWhy) {
  FileReader reader = [](const std::filesystem::path&) -> std::optional<std::string> {
    throw std::runtime_error("permission denied by the test");
  };
  PreprocessResult result = Preprocess("#include \"a.h\"\nmov r0, v0\n", "main.vsh", {}, reader);
  EXPECT_EQ(OnlyError(result).loc.line, 1);
  EXPECT_EQ(OnlyError(result).code, DiagnosticCode::kIncludeNotFound);
  EXPECT_THAT(OnlyError(result).message, HasSubstr("'a.h'"));
  EXPECT_THAT(OnlyError(result).message, HasSubstr("permission denied by the test"));
  EXPECT_THAT(Texts(result), ElementsAre("mov r0, v0"));
}

TEST(Preprocessor, IncludeGuardsAndPragmaOnceIncludeFilesOnce) {
  Files files = {{"guard.h", "#ifndef GUARD_H\n#define GUARD_H\nguarded\n#endif\n"},
                 {"once.h", "#pragma once\nonce\n"}};
  EXPECT_THAT(
      CleanTexts("#include \"guard.h\"\n#include \"guard.h\"\n#include \"once.h\"\n#include \"./once.h\"\n", {}, files),
      ElementsAre("guarded", "once"));
}

TEST(Preprocessor, LineDirectiveChangesReportedLineAndFile) {
  PreprocessResult result = PreprocessText("a\n#line 100\nb\n\nc\n#line 7 \"orig.vsh\"\nd\n#error here\n");
  ASSERT_EQ(result.lines.size(), 4u);
  EXPECT_EQ(result.lines[0].line, 1);
  EXPECT_EQ(result.lines[1].line, 100);
  EXPECT_EQ(result.lines[2].line, 102);
  EXPECT_EQ(result.lines[3].line, 7);
  EXPECT_EQ(result.lines[3].file, "orig.vsh");
  EXPECT_EQ(OnlyError(result).loc, (SourceLoc{"orig.vsh", 8, 1}));
}

TEST(Preprocessor, BadLineDirectivesAreErrors) {
  PreprocessResult result = PreprocessText("#line\n#line x\n#line 0\n#line 5 name\n");
  EXPECT_EQ(result.diagnostics.error_count(), 4) << result.diagnostics.ToString();
}

TEST(Preprocessor, ErrorDirectiveReportsItsMessage) {
  PreprocessResult result =
      PreprocessText("mov r0, v0\n#ifndef NEEDED\n  #error NEEDED must be set ; really\n#endif\nmul\n");
  EXPECT_EQ(OnlyError(result).loc, (SourceLoc{"main.vsh", 3, 3}));
  EXPECT_EQ(OnlyError(result).code, DiagnosticCode::kErrorDirective);
  EXPECT_EQ(OnlyError(result).message, "#error NEEDED must be set");  // the user's own words
  EXPECT_THAT(Texts(result), ElementsAre("mov r0, v0", "mul"));
}

TEST(Preprocessor, PragmaIsIgnoredAndUnknownDirectiveIsAnError) {
  PreprocessResult result = PreprocessText("#pragma warning(disable: 1234)\n#\nmov r0, v0\n  # bogus x\n#33\n");
  ASSERT_EQ(result.diagnostics.error_count(), 2) << result.diagnostics.ToString();
  EXPECT_EQ(result.diagnostics.all()[0].loc, (SourceLoc{"main.vsh", 4, 5}));
  EXPECT_EQ(result.diagnostics.all()[0].code, DiagnosticCode::kUnknownDirective);
  EXPECT_THAT(result.diagnostics.all()[0].message, HasSubstr("bogus"));
  EXPECT_EQ(result.diagnostics.all()[1].loc.line, 5);
  EXPECT_THAT(Texts(result), ElementsAre("mov r0, v0"));
}

TEST(Preprocessor, CommandLineDefinesArePredefined) {
  PreprocessOptions options;
  options.defines = {{"LIGHTS", "1"}, {"BASE", "c[LIGHTS + 3]"}, {"EMPTY", ""}, {"SQ(x)", "x * x"}};
  EXPECT_THAT(CleanTexts("mov r0, BASE\n[EMPTY]\nSQ(2)\n", options), ElementsAre("mov r0, c[1 + 3]", "[]", "2 * 2"));
  options.defines = {{"1BAD", "1"}};
  EXPECT_TRUE(PreprocessText("x\n", options).diagnostics.HasErrors());
}

TEST(Preprocessor, ExpandedCharactersTakeTheColumnOfTheMacroName) {
  PreprocessResult result =
      PreprocessText("#define OUTER INNER\n#define INNER c[4]\n#define F(x) x\nmov r0,  OUTER, F(v1)\n");
  ASSERT_EQ(result.lines.size(), 1u);
  EXPECT_EQ(result.lines[0].text, "mov r0,  c[4], v1");
  EXPECT_THAT(result.lines[0].columns, ElementsAre(1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 10, 10, 10, 15, 16, 17, 17));
}

TEST(Preprocessor, ColumnsAndLinesSurviveIncludesAndMacros) {
  Files files = {{"inc.h", "#define K c[9]\n\n   add r0, K, r1 ; tail\n"}};
  PreprocessResult result = PreprocessText("\n#include \"inc.h\"\n\tmul r0, K, r1\n", {}, files);
  ASSERT_EQ(result.lines.size(), 2u);
  EXPECT_EQ(result.lines[0].file, "inc.h");
  EXPECT_EQ(result.lines[0].line, 3);
  EXPECT_EQ(result.lines[0].text, "add r0, c[9], r1");
  EXPECT_EQ(result.lines[0].columns[0], 4);
  EXPECT_EQ(result.lines[0].columns[8], 12);
  EXPECT_EQ(result.lines[0].columns[11], 12);
  EXPECT_EQ(result.lines[0].columns[12], 13);
  EXPECT_EQ(result.lines[0].columns[15], 16);
  EXPECT_EQ(result.lines[1].file, "main.vsh");
  EXPECT_EQ(result.lines[1].line, 3);
  EXPECT_EQ(result.lines[1].columns[0], 2);
}

TEST(Preprocessor, ReportsErrorWhenOutputExceedsLimit) {
  PreprocessOptions options;
  options.max_output_bytes = 4096;
  std::string text = "#define A0 mov r0, v0\n";
  for (int i = 1; i < 40; ++i) text += fmt::format("#define A{} A{} A{}\n", i, i - 1, i - 1);
  text += "A39\n";
  PreprocessResult result = PreprocessText(text, options);
  EXPECT_TRUE(result.diagnostics.HasErrors());
  EXPECT_EQ(result.diagnostics.all().front().code, DiagnosticCode::kExpansionLimit);
  EXPECT_EQ(result.diagnostics.all().front().loc.line, 41);

  std::string many;
  for (int i = 0; i < 1000; ++i) many += "mov r0, v0\n";
  result = PreprocessText(many, options);
  EXPECT_EQ(OnlyError(result).code, DiagnosticCode::kExpansionLimit);
  EXPECT_THAT(OnlyError(result).message, HasSubstr("4096"));
  EXPECT_LE(result.lines.size(), 4096u / 11);
}

TEST(Preprocessor, ExponentialMacrosThatExpandToNothingStillTerminate) {
  PreprocessOptions options;
  options.max_output_bytes = 1 << 16;
  std::string text = "#define A0\n";
  for (int i = 1; i < 60; ++i) text += fmt::format("#define A{} A{} A{} A{}\n", i, i - 1, i - 1, i - 1);
  text += "A59\n";
  auto start = std::chrono::steady_clock::now();
  PreprocessResult result = PreprocessText(text, options);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
  EXPECT_TRUE(result.diagnostics.HasErrors());
}

TEST(Preprocessor, DeepNestingIsAnErrorNotAStackOverflow) {
  std::string parens(20000, '(');
  PreprocessResult result = PreprocessText("#if " + parens + "1\n#endif\n");
  EXPECT_EQ(OnlyError(result).code, DiagnosticCode::kConditionExpression) << OnlyError(result).message;

  std::string calls = "#define F(x) x\n";
  for (int i = 0; i < 300; ++i) calls += "F(";
  calls += "1" + std::string(300, ')') + "\n";
  result = PreprocessText(calls);
  EXPECT_TRUE(result.diagnostics.HasErrors());

  std::string unary = "#if " + std::string(20000, '-') + "1\n#endif\n";
  EXPECT_TRUE(PreprocessText(unary).diagnostics.HasErrors());
}

TEST(Preprocessor, ReportsSeveralErrorsInOneRun) {
  PreprocessResult result =
      PreprocessText("#foo\nmov r0, v0\n#if 1/0\n#endif\n#include \"nope.h\"\n#error last\n#if 1\n");
  EXPECT_EQ(result.diagnostics.error_count(), 5) << result.diagnostics.ToString();
  EXPECT_THAT(Texts(result), ElementsAre("mov r0, v0"));
}

TEST(Preprocessor, NeverCrashesOrHangsOnRandomInput) {
  std::mt19937 random(1234);
  const std::string pieces[] = {"#define ", "#if ",    "#elif ", "#endif\n",   "#include \"x.h\"\n",
                                "(",        ")",       ",",      "A",          "B(",
                                "/*",       "*/",      "//",     ";",          "\\\n",
                                "\r\n",     "\n",      "\"",     "'",          "##",
                                "#",        "defined", "1",      "0x",         "/",
                                "%",        "?",       ":",      "#undef A\n", "#line 5\n"};
  Files files = {{"x.h", "#include \"x.h\"\nA B(1)\n"}};
  PreprocessOptions options;
  options.max_output_bytes = 1 << 16;
  for (int round = 0; round < 300; ++round) {
    std::string text;
    int length = std::uniform_int_distribution<int>(0, 400)(random);
    for (int i = 0; i < length; ++i) {
      if (round % 2 == 0) {
        text += static_cast<char>(std::uniform_int_distribution<int>(0, 255)(random));
      } else {
        text += pieces[std::uniform_int_distribution<std::size_t>(0, std::size(pieces) - 1)(random)];
      }
    }
    PreprocessResult result = PreprocessText(text, options, files);
    for (const PreprocessedLine& line : result.lines) ASSERT_EQ(line.text.size(), line.columns.size());
  }
}

TEST(Preprocessor, ReadFileFromDiskReadsBytesAndReportsMissingFiles) {
  std::filesystem::path path =
      std::filesystem::temp_directory_path() / fmt::format("vs11_preprocessor_test_{}.vsh", std::random_device{}());
  {
    std::ofstream out(path, std::ios::binary);
    out << "mov r0, v0\r\n";
  }
  EXPECT_EQ(ReadFileFromDisk(path), std::optional<std::string>("mov r0, v0\r\n"));
  std::filesystem::remove(path);
  EXPECT_EQ(ReadFileFromDisk(path), std::nullopt);
  EXPECT_EQ(ReadFileFromDisk(std::filesystem::temp_directory_path()), std::nullopt);
}

}  // namespace
}  // namespace vs11

namespace vs11 {
namespace {

// `count` #defines, each naming the one before, the first `v0`; then a line using the last.
std::string ChainedDefines(int count) {
  std::string text = "#define A0 v0\n";
  for (int i = 1; i < count; ++i) text += fmt::format("#define A{} A{}\n", i, i - 1);
  return text + fmt::format("mov oPos, A{}\n", count - 1);
}

TEST(PreprocessorBounds, AChainOfDefinesWithinTheNestingBoundExpandsFully) {
  EXPECT_THAT(CleanTexts(ChainedDefines(static_cast<int>(kMaxMacroNesting))), ElementsAre("mov oPos, v0"));
}

TEST(PreprocessorBounds, AChainOfDefinesDeeperThanTheBoundIsAnErrorAtItsUse) {
  const int count = 60000;  // under the bound on macros; quadratic in its length before: seconds
  const PreprocessResult result = PreprocessText(ChainedDefines(count));
  const Diagnostic& error = OnlyError(result);
  EXPECT_EQ(error.code, DiagnosticCode::kExpansionLimit);
  EXPECT_EQ(error.loc.line, count + 1);
  EXPECT_EQ(error.loc.column, 11);
  EXPECT_THAT(error.message, HasSubstr(fmt::format("nested more than {} deep", kMaxMacroNesting)));
}

TEST(PreprocessorBounds, MoreMacrosThanTheBoundIsAnErrorAtTheFirstOneOver) {
  PreprocessOptions options;
  options.max_macros = 3;
  options.defines = {{"FROM_THE_COMMAND_LINE", "1"}};
  const PreprocessResult result = PreprocessText("#define A 1\n#define A 2\n#undef A\n#define B 1\n#define C 1\nmov\n", options);
  const Diagnostic& error = OnlyError(result);
  EXPECT_EQ(error.code, DiagnosticCode::kTooManyMacros);
  EXPECT_EQ(error.loc.line, 5);  // a redefinition or an #undef does not make a new macro
  EXPECT_EQ(error.loc.column, 9);
  EXPECT_THAT(Texts(result), ::testing::IsEmpty());  // nothing after the error is taken
}

}  // namespace
}  // namespace vs11

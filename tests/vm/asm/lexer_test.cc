// The lexer on its own (vm/asm/lexer.h): token kinds, texts and columns of one preprocessed line,
// where a '.' starts a number and where it is a component suffix, comments, the two errors it can
// report, and the spelling helpers the assembler and disassembler share.
#include "vm/asm/lexer.h"

#include <numeric>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace vs11 {
namespace {

using enum TokenKind;

// A line as the preprocessor hands it over, its columns those of the text itself (no macros).
PreprocessedLine Line(std::string text) {
  PreprocessedLine line;
  line.file = "lex.vsh";
  line.line = 7;
  line.columns.resize(text.size());
  std::iota(line.columns.begin(), line.columns.end(), 1);
  line.text = std::move(text);
  return line;
}

struct ExpectedToken {
  TokenKind kind;
  std::string text;
  int column;
  friend bool operator==(const ExpectedToken&, const ExpectedToken&) = default;
};

std::ostream& operator<<(std::ostream& os, const ExpectedToken& t) {
  return os << "{" << static_cast<int>(t.kind) << ", '" << t.text << "', col " << t.column << "}";
}

struct LexCase {
  std::string name;
  std::string text;
  std::vector<ExpectedToken> tokens;
};

void PrintTo(const LexCase& c, std::ostream* os) { *os << c.name; }

class LexerTokens : public testing::TestWithParam<LexCase> {};

TEST_P(LexerTokens, SplitsTheLineIntoKindsTextsAndColumns) {
  const LexCase& c = GetParam();
  Diagnostics diagnostics;
  LexedLine lexed = Lex(Line(c.text), diagnostics);
  EXPECT_TRUE(diagnostics.all().empty()) << diagnostics.ToString();
  std::vector<ExpectedToken> got;
  for (const Token& token : lexed.tokens) got.push_back({token.kind, token.text, token.column});
  EXPECT_EQ(got, c.tokens);
  EXPECT_EQ(lexed.loc, (SourceLoc{"lex.vsh", 7, 1}));
}

const LexCase kLexCases[] = {
    {"Empty", "", {}},
    {"BlanksOnly", " \t\r\f\v ", {}},
    {"Instruction",
     "mov r0.xy, -c[a0.x + 12]",
     {{kIdentifier, "mov", 1},
      {kIdentifier, "r0", 5},
      {kDot, ".", 7},
      {kIdentifier, "xy", 8},
      {kComma, ",", 10},
      {kMinus, "-", 12},
      {kIdentifier, "c", 13},
      {kLeftBracket, "[", 14},
      {kIdentifier, "a0", 15},
      {kDot, ".", 17},
      {kIdentifier, "x", 18},
      {kPlus, "+", 20},
      {kInteger, "12", 22},
      {kRightBracket, "]", 24}}},
    {"Dx8Version", "vs.1.1", {{kIdentifier, "vs", 1}, {kDot, ".", 3}, {kFloat, "1.1", 4}}},
    {"Dx9Version", "vs_1_1", {{kIdentifier, "vs_1_1", 1}}},
    {"DotAfterBracketIsASuffix", "c[2].x", {{kIdentifier, "c", 1}, {kLeftBracket, "[", 2}, {kInteger, "2", 3},
                                            {kRightBracket, "]", 4}, {kDot, ".", 5}, {kIdentifier, "x", 6}}},
    {"LeadingDotNumberAfterComma", "def c0, .5, 1., 1e-3, 2.5f",
     {{kIdentifier, "def", 1}, {kIdentifier, "c0", 5}, {kComma, ",", 7}, {kFloat, ".5", 9}, {kComma, ",", 11},
      {kFloat, "1.", 13}, {kComma, ",", 15}, {kFloat, "1e-3", 17}, {kComma, ",", 21}, {kFloat, "2.5f", 23}}},
    {"IntegerAndSuffixedFloats", "7 1f 1E+2 3.25",
     {{kInteger, "7", 1}, {kFloat, "1f", 3}, {kFloat, "1E+2", 6}, {kFloat, "3.25", 11}}},
    {"SemicolonComment", "mov r0, r1 ; the rest, [ignored] @", {{kIdentifier, "mov", 1}, {kIdentifier, "r0", 5},
                                                                  {kComma, ",", 7}, {kIdentifier, "r1", 9}}},
    {"SlashComment", "nop // @@", {{kIdentifier, "nop", 1}}},
    {"RejectedPunctuationIsStillLexed", "(p0) !r1 +mov",
     {{kLeftParen, "(", 1}, {kIdentifier, "p0", 2}, {kRightParen, ")", 4}, {kBang, "!", 6}, {kIdentifier, "r1", 7},
      {kPlus, "+", 10}, {kIdentifier, "mov", 11}}},
    {"UnderscoresInIdentifiers", "dcl_texcoord1 _x r1_abs",
     {{kIdentifier, "dcl_texcoord1", 1}, {kIdentifier, "_x", 15}, {kIdentifier, "r1_abs", 18}}},
};
INSTANTIATE_TEST_SUITE_P(Lexer, LexerTokens, testing::ValuesIn(kLexCases),
                         [](const auto& info) { return info.param.name; });

TEST(Lexer, TokensTakeTheColumnsThePreprocessorRecorded) {
  // As after a macro expansion: every character of "r5" came from column 20.
  PreprocessedLine line = Line("mov r5");
  line.columns = {1, 2, 3, 4, 20, 20};
  Diagnostics diagnostics;
  LexedLine lexed = Lex(line, diagnostics);
  ASSERT_EQ(lexed.tokens.size(), 2u);
  EXPECT_EQ(lexed.tokens[1].column, 20);
  EXPECT_EQ(LocOf(lexed, lexed.tokens[1]), (SourceLoc{"lex.vsh", 7, 20}));
}

struct LexErrorCase {
  std::string name;
  std::string text;
  DiagnosticCode code;
  int column;
  std::size_t tokens_before;  // tokens kept: the line is cut at the error
};

void PrintTo(const LexErrorCase& c, std::ostream* os) { *os << c.name; }

class LexerErrors : public testing::TestWithParam<LexErrorCase> {};

TEST_P(LexerErrors, ReportsTheCodeAndColumnAndCutsTheLine) {
  const LexErrorCase& c = GetParam();
  Diagnostics diagnostics;
  LexedLine lexed = Lex(Line(c.text), diagnostics);
  ASSERT_EQ(diagnostics.error_count(), 1) << diagnostics.ToString();
  const Diagnostic& error = diagnostics.all().front();
  EXPECT_EQ(error.code, c.code) << error.message;
  EXPECT_EQ(error.loc, (SourceLoc{"lex.vsh", 7, c.column}));
  EXPECT_EQ(lexed.tokens.size(), c.tokens_before);
}

const LexErrorCase kLexErrors[] = {
    {"UnexpectedCharacter", "mov r0, r1 @ r2", DiagnosticCode::kUnexpectedCharacter, 12, 4},
    {"Hash", "#define", DiagnosticCode::kUnexpectedCharacter, 1, 0},
    {"LettersAfterDigits", "def c0, 1x, 0", DiagnosticCode::kMalformedNumber, 9, 3},
    {"ThreePartVersion", "vs.1.1.1", DiagnosticCode::kMalformedNumber, 4, 2},
    {"TwoDecimalPoints", "1.2.3", DiagnosticCode::kMalformedNumber, 1, 0},
    {"ExponentWithoutDigits", "mov r0, 2e", DiagnosticCode::kMalformedNumber, 9, 3},
};
INSTANTIATE_TEST_SUITE_P(Lexer, LexerErrors, testing::ValuesIn(kLexErrors),
                         [](const auto& info) { return info.param.name; });

TEST(LexerSpellings, RegisterNamesRoundTripThroughTheSpellingTable) {
  EXPECT_EQ(RegisterName(RegisterFile::kTemp, 11), "r11");
  EXPECT_EQ(RegisterName(RegisterFile::kRasterOut, kRasterOutFog), "oFog");
  EXPECT_EQ(RegisterName(RegisterFile::kTexCoordOut, 7), "oT7");
  EXPECT_EQ(RegisterName(RegisterFile::kRasterOut, 3), "<register type 4 number 3>");
  EXPECT_TRUE(HasRegisterName(RegisterFile::kAttributeOut, 1));
  EXPECT_FALSE(HasRegisterName(RegisterFile::kRasterOut, 3));
}

TEST(LexerSpellings, LaneLettersAcceptXyzwAndRgbaInAnyCase) {
  const std::string letters = "xyzwrgbaXYZWRGBA";
  for (std::size_t i = 0; i < letters.size(); ++i) EXPECT_EQ(LaneFromLetter(letters[i]), static_cast<int>(i % 4));
  EXPECT_EQ(LaneFromLetter('q'), -1);
  EXPECT_EQ(LaneFromLetter('0'), -1);
}

TEST(LexerSpellings, CaseHelpersAreAsciiOnly) {
  EXPECT_TRUE(EqualsIgnoringAsciiCase("DCL_Normal", "dcl_normal"));
  EXPECT_FALSE(EqualsIgnoringAsciiCase("mov", "mo"));
  EXPECT_EQ(ToLowerAscii("VS.1.1 oPos"), "vs.1.1 opos");
  EXPECT_EQ(ToLowerAscii("\xC3\x84"), "\xC3\x84");  // bytes above 0x7F are left alone
}

}  // namespace
}  // namespace vs11

// Diagnostic codes: stable, distinct names, printed after the message, and set by every front-end
// check (lexer, preprocessor, assembler, validator, bytecode decoder).
#include "vm/core/diagnostic.h"

#include <random>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "vm/asm/assembler.h"
#include "vm/asm/bytecode.h"

namespace vs11 {
namespace {

constexpr DiagnosticCode kAllCodes[] = {
#define VS11_TEST_CODE(code, name) DiagnosticCode::code,
    VS11_DIAGNOSTIC_CODES(VS11_TEST_CODE)
#undef VS11_TEST_CODE
};

TEST(DiagnosticCode, NamesAreDistinctLowerCaseWords) {
  std::set<std::string_view> names;
  for (DiagnosticCode code : kAllCodes) {
    std::string_view name = DiagnosticCodeName(code);
    EXPECT_TRUE(names.insert(name).second) << name;
    for (char c : name) {
      EXPECT_TRUE((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_') << name;
    }
  }
}

TEST(DiagnosticCode, IsPrintedAfterTheMessage) {
  Diagnostic d{{"p.vsh", 3, 7}, Severity::kWarning, DiagnosticCode::kUninitializedLanes, "mul: reads r4.w", -1};
  EXPECT_EQ(FormatDiagnostic(d), "p.vsh:3:7: warning: mul: reads r4.w [uninitialized-lanes]");
  d.code = DiagnosticCode::kUnclassified;  // a Diagnostic made field by field: no code printed
  EXPECT_EQ(FormatDiagnostic(d), "p.vsh:3:7: warning: mul: reads r4.w");
}

// Sources with many kinds of mistakes, and random token soup: every diagnostic the front end gives
// must carry a code.
TEST(DiagnosticCode, EveryFrontEndDiagnosticHasACode) {
  std::vector<std::string> sources = {
      "", "ps_1_1\n", "vs_1_1\nfoo r0\n", "vs_1_1\nmov r0, r1 @\n", "vs_1_1\nmov_sat r0, r1\n",
      "vs_1_1\nmov r0.yx, c[a0.y]\n", "#if 1 +\n#endif\n#bogus\n#include <x>\n#define F(a, a) a\nF(1\n",
      "vs.1.1\nmov r0.xy, v0\nmov oD0, r0\nadd r1, c0, c1\nm4x4 r2, r2, c0\nmov a0.x, c0.x\nfrc r3.x, v0\n",
      "vs_1_1\ndcl_position v0\ndcl_position v0\nmov oFog.y, v1\nrcp r0, c0\ndef c2, 1, 2, 3, 4\n"};
  std::mt19937 random(11);
  const std::string pieces[] = {"mov", "r0", ",", "c[", "a0.x", "]", ".xw", "-", "v16", "1e99", "\n",
                                "dcl_texcoord", "m3x3", "oPos", "#define", "/*", "vs_1_1\n", "lit"};
  std::uniform_int_distribution<std::size_t> pick(0, std::size(pieces) - 1);
  for (int i = 0; i < 200; ++i) {
    std::string soup = "vs_1_1\n";
    for (int j = 0; j < 30; ++j) soup += pieces[pick(random)] + " ";
    sources.push_back(soup);
  }
  for (const std::string& source : sources) {
    AssembleResult result = AssembleSource(source, "p.vsh", {}, [](const auto&) { return std::nullopt; });
    for (const Diagnostic& d : result.diagnostics.all()) {
      EXPECT_NE(d.code, DiagnosticCode::kUnclassified) << FormatDiagnostic(d) << "\nfrom:\n" << source;
    }
  }
  std::uniform_int_distribution<std::uint32_t> word;
  for (int i = 0; i < 200; ++i) {
    std::vector<std::uint32_t> words = {kVersionVs11};
    for (int j = 0; j < 8; ++j) words.push_back(word(random));
    const auto decoded = Decode(words);  // the range below must not outlive a temporary
    for (const Diagnostic& d : decoded.diagnostics.all()) {
      EXPECT_NE(d.code, DiagnosticCode::kUnclassified) << FormatDiagnostic(d);
    }
  }
}

}  // namespace
}  // namespace vs11

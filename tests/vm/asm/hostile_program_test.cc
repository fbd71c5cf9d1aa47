// Hostile programs (issue #6): garbage, truncation, unknown opcodes, oversized comments, huge sources,
// include cycles, recursive macros, absurd registers and relative reads past the constant file. Each
// must be refused with a message saying what is wrong (and where), and finish. Time and memory are
// bounded by design, not timed here: the preprocessor's include depth and output limit, the
// Diagnostics cap of kMaxKeptErrors, the decoder's single pass that never reads past its span.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/run_tool.h"
#include "vm/asm/assembler.h"
#include "vm/asm/bytecode.h"
#include "vm/asm/disassembler.h"
#include "vm/asm/preprocessor.h"
#include "vm/asm/program_file.h"
#include "vm/asm/validator.h"
#include "vm/core/isa.h"
#include "vm/core/machine.h"
#include "vm/engines/engine_factory.h"

namespace vs11 {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using vs11::testing::RunVs11;

class HostileProgram : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) /
           ("vs11_hostile_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path Write(const std::string& name, const std::string& bytes) {
    fs::path path = dir_ / name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }
  fs::path dir_;
};

std::string RandomBytes(std::size_t count, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> byte(0, 255);
  std::string bytes(count, '\0');
  for (char& c : bytes) c = static_cast<char>(byte(random));
  return bytes;
}

std::string BytesOf(const std::vector<std::uint32_t>& words) {
  std::vector<std::uint8_t> bytes = BytesFromWords(words);
  return std::string(bytes.begin(), bytes.end());
}

// Every message of `diagnostics`, one per line, for failure output and substring checks.
std::string Messages(const Diagnostics& diagnostics) { return diagnostics.ToString(); }

// The codes of the diagnostics, in order: what the refusals are asserted by (the wording may change).
std::vector<DiagnosticCode> Codes(const Diagnostics& diagnostics) {
  std::vector<DiagnosticCode> codes;
  for (const Diagnostic& d : diagnostics.all()) codes.push_back(d.code);
  return codes;
}
using ::testing::ElementsAre;

// An in-memory file set for the preprocessor.
FileReader Files(std::map<std::string, std::string> files) {
  return [files = std::move(files)](const fs::path& path) -> std::optional<std::string> {
    auto it = files.find(path.lexically_normal().string());
    if (it == files.end()) return std::nullopt;
    return it->second;
  };
}

std::vector<std::uint32_t> AssembledWords(const std::string& source) {
  AssembleResult assembled = AssembleSource(source, "p.vsh", {});
  EXPECT_TRUE(assembled.program) << Messages(assembled.diagnostics);
  return assembled.program ? Encode(*assembled.program) : std::vector<std::uint32_t>{};
}

const std::string kSmallProgram = "vs_1_1\ndcl_position v0\nmov r0, v0\nadd r0, r0, c1\nm4x4 oPos, r0, c4\n";

// ---- random bytes -----------------------------------------------------------------------------------

TEST_F(HostileProgram, RandomBytesAsSourceAreRefusedWithLocatedErrors) {
  std::string bytes = RandomBytes(64 * 1024, 1);
  bytes[1] = 'x';  // not the little-endian version token, so the loader takes it for source
  fs::path path = Write("random.vsh", bytes);
  LoadedProgram loaded = LoadProgram(path);
  EXPECT_FALSE(loaded.program);
  EXPECT_FALSE(loaded.from_bytecode);
  ASSERT_TRUE(loaded.diagnostics.HasErrors());
  EXPECT_LE(loaded.diagnostics.all().size(), 4u * Diagnostics::kMaxKeptErrors);
  for (const Diagnostic& d : loaded.diagnostics.all()) {
    EXPECT_EQ(d.loc.file, path.string());
    EXPECT_GT(d.loc.line, 0) << d.message;
    EXPECT_GT(d.loc.column, 0) << d.message;
    EXPECT_FALSE(d.message.empty());
  }
}

TEST_F(HostileProgram, RandomBytesAsBytecodeAreRefusedWithAWordOffset) {
  for (unsigned seed = 0; seed < 200; ++seed) {
    std::string bytes = RandomBytes(4 * (1 + seed % 64), seed);
    if (seed % 2 == 0) bytes.replace(0, 4, BytesOf({kVersionVs11}));  // get past the version check
    LoadedProgram loaded = LoadProgram(Write("random.vso", bytes));
    EXPECT_FALSE(loaded.program) << "seed " << seed;
    EXPECT_TRUE(loaded.from_bytecode);
    ASSERT_TRUE(loaded.diagnostics.HasErrors()) << "seed " << seed;
    const Diagnostic& first = loaded.diagnostics.all().front();
    EXPECT_GE(first.word_offset, 0) << first.message;
    EXPECT_LE(first.word_offset, static_cast<long>(bytes.size() / 4)) << first.message;
  }
}

TEST_F(HostileProgram, BytecodeOfAnOddByteCountIsRefused) {
  LoadedProgram loaded = LoadProgram(Write("odd.vso", RandomBytes(7, 3)));
  EXPECT_FALSE(loaded.program);
  EXPECT_THAT(Codes(loaded.diagnostics), ElementsAre(DiagnosticCode::kBytecodeTruncated)) << Messages(loaded.diagnostics);
}

TEST_F(HostileProgram, ToolRefusesRandomBytesWithoutCrashing) {
  for (const char* name : {"random.vsh", "random.vso"}) {
    std::string bytes = RandomBytes(4096, 7);
    bytes[1] = 'x';
    vs11::testing::CommandResult r = RunVs11("validate " + Write(name, bytes).string());
    EXPECT_EQ(r.status, 1) << name << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr(name));
    EXPECT_THAT(r.output, HasSubstr("error: "));
  }
}

// Bytecode errors say which word is at fault, in every subcommand that reads a .vso (README).
TEST_F(HostileProgram, ToolNamesTheWordOfBytecodeErrors) {
  // mov oPos, <RASTOUT register 3>: no such register in vs_1_1; the disassembler refuses it too.
  const std::string rastout3 = Write("rastout3.vso", BytesOf({kVersionVs11, 0x1, 0xC00F0000, 0xC0E40003, kEndToken}));
  for (const char* command : {"disasm", "validate"}) {
    vs11::testing::CommandResult r = RunVs11(std::string(command) + " " + rastout3);
    EXPECT_EQ(r.status, 1) << command << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr("rastout3.vso: word 3: error: register type 4 has no register 3 in vs_1_1"));
  }
  // Well formed, but it reads an output register: the validator names instruction 1 at word 4.
  const std::string reads_output = Write(
      "reads_output.vso", BytesOf({kVersionVs11, 0x1, 0x800F0000, 0x90E40000, 0x1, 0xC00F0000, 0xD0E40000, kEndToken}));
  for (const char* command : {"validate", "run --sphere 2"}) {
    vs11::testing::CommandResult r = RunVs11(std::string(command) + " " + reads_output);
    EXPECT_EQ(r.status, 1) << command << ": " << r.output;
    EXPECT_THAT(r.output, HasSubstr("reads_output.vso: word 4: error: instruction 1 (mov): reads oD0, but output "
                                    "registers are write-only"))
        << command;
  }
}

// ---- truncated token streams ------------------------------------------------------------------------

TEST(HostileBytecode, EveryTruncationOfAProgramIsRefused) {
  std::vector<std::uint32_t> words = AssembledWords(kSmallProgram);
  ASSERT_GT(words.size(), 10u);
  for (std::size_t length = 0; length < words.size(); ++length) {
    DecodeResult decoded = Decode(std::span(words.data(), length));
    EXPECT_FALSE(decoded.program) << length << " words";
    ASSERT_TRUE(decoded.diagnostics.HasErrors()) << length << " words";
    const Diagnostic& first = decoded.diagnostics.all().front();
    EXPECT_LE(first.word_offset, static_cast<long>(length)) << first.message;
  }
}

TEST(HostileBytecode, TruncationInsideAnInstructionNamesIt) {
  // version, dcl (3 words), mov r0, v0 (3 words): cut after the mov's opcode token.
  std::vector<std::uint32_t> words = AssembledWords(kSmallProgram);
  DecodeResult decoded = Decode(std::span(words.data(), 5));
  ASSERT_TRUE(decoded.diagnostics.HasErrors());
  EXPECT_EQ(decoded.diagnostics.all().front().word_offset, 4);
  EXPECT_EQ(decoded.diagnostics.all().front().code, DiagnosticCode::kBytecodeTruncated);
  EXPECT_THAT(Messages(decoded.diagnostics), HasSubstr("mov"));

  DecodeResult no_end = Decode(std::span(words.data(), words.size() - 1));
  EXPECT_THAT(Codes(no_end.diagnostics), ElementsAre(DiagnosticCode::kBytecodeTruncated)) << Messages(no_end.diagnostics);
  EXPECT_THAT(Codes(Decode({}).diagnostics), ElementsAre(DiagnosticCode::kBytecodeTruncated));
}

// ---- unknown opcodes --------------------------------------------------------------------------------

TEST(HostileBytecode, EveryUnknownOpcodeIsRefusedWithItsNumberAndOffset) {
  int unknown = 0;
  for (std::uint32_t opcode = 0; opcode <= 0xFFFF; ++opcode) {
    if (opcode == kCommentOpcode || opcode == (kEndToken & 0xFFFF) || OpcodeFromToken(opcode)) continue;
    ++unknown;
    std::vector<std::uint32_t> words = {kVersionVs11, opcode, kEndToken};
    DecodeResult decoded = Decode(words);
    ASSERT_FALSE(decoded.program) << opcode;
    const Diagnostic& first = decoded.diagnostics.all().front();
    EXPECT_EQ(first.word_offset, 1) << first.message;
    ASSERT_EQ(first.code, DiagnosticCode::kBytecodeUnknownOpcode) << first.message;
    ASSERT_THAT(first.message, HasSubstr(fmt::format("opcode {} (0x{:04X})", opcode, opcode)));
  }
  EXPECT_GT(unknown, 60000);
}

TEST(HostileSource, UnknownMnemonicsAreRefusedWithLineAndColumn) {
  AssembleResult result = AssembleSource("vs_1_1\n  frobnicate r0, v0\ntexld r0, t0\n", "p.vsh", {});
  EXPECT_FALSE(result.program);
  EXPECT_THAT(Messages(result.diagnostics), HasSubstr("p.vsh:2:3: error: unknown instruction 'frobnicate'"));
  EXPECT_THAT(Messages(result.diagnostics), HasSubstr("p.vsh:3:1: error: 'texld' is not a vs_1_1 instruction"));
}

// ---- oversized comment tokens -----------------------------------------------------------------------

TEST(HostileBytecode, CommentLongerThanTheStreamIsRefused) {
  const std::uint32_t largest_comment = (kMaxCommentWords << 16) | kCommentOpcode;
  DecodeResult decoded = Decode(std::vector<std::uint32_t>{kVersionVs11, largest_comment, 0, kEndToken});
  EXPECT_FALSE(decoded.program);
  EXPECT_EQ(decoded.diagnostics.all().front().word_offset, 1);
  EXPECT_THAT(Codes(decoded.diagnostics), ElementsAre(DiagnosticCode::kBytecodeTruncated));
  EXPECT_THAT(Messages(decoded.diagnostics), HasSubstr("32767"));
}

TEST(HostileBytecode, CommentWithBit31IsRefused) {
  DecodeResult decoded = Decode(std::vector<std::uint32_t>{kVersionVs11, 0xFFFFFFFEu, kEndToken});
  EXPECT_FALSE(decoded.program);
  EXPECT_THAT(Codes(decoded.diagnostics), ElementsAre(DiagnosticCode::kBytecodeMalformedToken)) << Messages(decoded.diagnostics);
}

TEST(HostileBytecode, LargestCommentThatFitsIsKeptWhole) {
  // The limit's other side: a full 32767-word comment is legal and survives a round trip.
  std::vector<std::uint32_t> words = AssembledWords(kSmallProgram);
  std::vector<std::uint32_t> comment(1 + kMaxCommentWords, 0x41414141u);
  comment[0] = (kMaxCommentWords << 16) | kCommentOpcode;
  words.insert(words.begin() + 1, comment.begin(), comment.end());
  DecodeResult decoded = Decode(words);
  ASSERT_TRUE(decoded.program) << Messages(decoded.diagnostics);
  ASSERT_EQ(decoded.program->comments.size(), 1u);
  EXPECT_EQ(decoded.program->comments[0].words.size(), kMaxCommentWords);
  EXPECT_EQ(Encode(*decoded.program), words);
}

// ---- a 100 000-line source --------------------------------------------------------------------------

constexpr int kHugeLineCount = 100000;

TEST_F(HostileProgram, HundredThousandInstructionsAreRefusedByTheSlotLimit) {
  std::string source = "vs_1_1\ndcl_position v0\nmov r0, v0\n";
  for (int i = 0; i < kHugeLineCount; ++i) source += "add r0, r0, c1\n";
  source += "mov oPos, r0\n";
  AssembleResult result = AssembleSource(source, "huge.vsh", {});
  EXPECT_FALSE(result.program);
  EXPECT_THAT(Messages(result.diagnostics), HasSubstr(fmt::format("over the vs_1_1 limit of {}", kMaxInstructionSlots)));
  EXPECT_THAT(Messages(result.diagnostics), HasSubstr("huge.vsh:"));
  EXPECT_LE(result.diagnostics.all().size(), static_cast<std::size_t>(Diagnostics::kMaxKeptErrors));

  vs11::testing::CommandResult r = RunVs11("validate " + Write("huge.vsh", source).string());
  EXPECT_EQ(r.status, 1);
  EXPECT_LE(std::count(r.output.begin(), r.output.end(), '\n'), Diagnostics::kMaxKeptErrors + 2) << r.output;
}

TEST(HostileSource, HundredThousandBadLinesKeepABoundedErrorList) {
  std::string source = "vs_1_1\n";
  for (int i = 0; i < kHugeLineCount; ++i) source += "mov r0, q0\n";
  AssembleResult result = AssembleSource(source, "bad.vsh", {});
  EXPECT_FALSE(result.program);
  EXPECT_EQ(result.diagnostics.error_count(), kHugeLineCount);
  EXPECT_EQ(result.diagnostics.all().size(), static_cast<std::size_t>(Diagnostics::kMaxKeptErrors));
  // The printed form is a contract: FILE:LINE:COL: error: MESSAGE [code].
  EXPECT_EQ(FormatDiagnostic(result.diagnostics.all().front()),
            "bad.vsh:2:9: error: unknown register 'q0' [unknown-register]");
  EXPECT_THAT(Messages(result.diagnostics),
              HasSubstr(fmt::format("{} more errors not shown", kHugeLineCount - Diagnostics::kMaxKeptErrors)));
}

TEST(HostileBytecode, HundredThousandInstructionStreamDecodesAndIsRefusedByTheValidator) {
  std::vector<std::uint32_t> words = AssembledWords(kSmallProgram);
  std::vector<std::uint32_t> mov(words.begin() + 4, words.begin() + 7);  // mov r0, v0
  words.pop_back();
  for (int i = 0; i < kHugeLineCount; ++i) words.insert(words.end(), mov.begin(), mov.end());
  words.push_back(kEndToken);
  DecodeResult decoded = Decode(words);
  ASSERT_TRUE(decoded.program) << Messages(decoded.diagnostics);
  Diagnostics problems = Validate(*decoded.program);
  EXPECT_TRUE(problems.HasErrors());
  EXPECT_THAT(Messages(problems), HasSubstr(fmt::format("over the vs_1_1 limit of {}", kMaxInstructionSlots)));
  EXPECT_LE(problems.all().size(), static_cast<std::size_t>(4 * Diagnostics::kMaxKeptErrors));
}

// ---- #include cycles ---------------------------------------------------------------------------------

TEST(HostileSource, IncludeCycleIsRefused) {
  FileReader files = Files({{"a.vsh", "#include \"b.vsh\"\n"}, {"b.vsh", "; b\n#include \"a.vsh\"\n"}});
  PreprocessResult result = Preprocess("vs_1_1\n#include \"a.vsh\"\n", "main.vsh", {}, files);
  ASSERT_TRUE(result.diagnostics.HasErrors());
  EXPECT_EQ(result.diagnostics.error_count(), 1);
  EXPECT_THAT(Codes(result.diagnostics), ElementsAre(DiagnosticCode::kIncludeTooDeep));
  EXPECT_THAT(Messages(result.diagnostics), HasSubstr("64"));
  const Diagnostic& error = result.diagnostics.all().front();
  EXPECT_EQ(error.loc.line, 2);
  EXPECT_EQ(error.loc.column, 1);
}

TEST(HostileSource, IncludeDepthIsCappedWhateverTheOptionSays) {
  PreprocessOptions options;
  options.max_include_depth = std::numeric_limits<int>::max();
  PreprocessResult result =
      Preprocess("#include \"self.vsh\"\n", "self.vsh", options, Files({{"self.vsh", "#include \"self.vsh\"\n"}}));
  EXPECT_THAT(Messages(result.diagnostics), HasSubstr("#include nested more than 200 levels deep"));
}

TEST_F(HostileProgram, ToolRefusesAnIncludeCycle) {
  Write("a.vsh", "#include \"b.vsh\"\n");
  Write("b.vsh", "#include \"a.vsh\"\n");
  fs::path main = Write("main.vsh", "vs_1_1\n#include \"a.vsh\"\nmov oPos, v0\n");
  vs11::testing::CommandResult r = RunVs11("asm " + main.string() + " -o " + (dir_ / "out.vso").string());
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("include cycle?"));
  EXPECT_FALSE(fs::exists(dir_ / "out.vso"));
}

// ---- recursive macros -------------------------------------------------------------------------------

TEST(HostileSource, MutuallyRecursiveMacrosStopAsInC) {
  // C's rule: a macro is not expanded again inside its own expansion, so A -> B -> A stops at A,
  // which the assembler then refuses as an instruction.
  AssembleResult result =
      AssembleSource("#define A B\n#define B A\n#define F(x) F(x + 1)\nvs_1_1\nA r0, v0\nmov r0, F(v0)\n", "m.vsh", {});
  EXPECT_FALSE(result.program);
  EXPECT_THAT(Messages(result.diagnostics), HasSubstr("m.vsh:5:1: error: unknown instruction 'A'"));
  EXPECT_THAT(Messages(result.diagnostics), HasSubstr("m.vsh:6:"));
}

TEST(HostileSource, ExponentialMacroGrowthHitsTheOutputLimit) {
  std::string source = "#define X0 mov r0, v0\n";
  for (int i = 1; i <= 40; ++i) source += fmt::format("#define X{} X{} X{}\n", i, i - 1, i - 1);
  source += "vs_1_1\nX40\n";
  PreprocessOptions options;
  options.max_output_bytes = 1 << 20;
  PreprocessResult result = Preprocess(source, "bomb.vsh", options, Files({}));
  ASSERT_TRUE(result.diagnostics.HasErrors());
  EXPECT_EQ(result.diagnostics.all().front().code, DiagnosticCode::kExpansionLimit) << Messages(result.diagnostics);
  EXPECT_THAT(Messages(result.diagnostics), HasSubstr("1048576"));
  EXPECT_EQ(result.diagnostics.all().front().loc.line, 43);
}

// ---- absurd register indices ------------------------------------------------------------------------

TEST(HostileSource, RegisterNumbersBeyondTheTokenFieldAreRefused) {
  AssembleResult result = AssembleSource(
      "vs_1_1\nmov r99999999999999999999999, v0\nmov r0, c[2000 + 2000]\nmov r0, c[-5]\nmov oT4294967296, v0\n",
      "r.vsh", {});
  EXPECT_FALSE(result.program);
  std::string messages = Messages(result.diagnostics);
  EXPECT_THAT(messages, HasSubstr("r.vsh:2:5: error: register number 99999999999999999999999 does not fit the 11-bit register field (0-2047)"));
  EXPECT_THAT(messages, HasSubstr("r.vsh:3:10: error: constant index 4000 does not fit the 11-bit register field (0-2047)"));
  EXPECT_THAT(messages, HasSubstr("r.vsh:4:10: error: constant index -5 is negative"));
  EXPECT_THAT(messages, HasSubstr("r.vsh:5:5: error: register number 4294967296 does not fit"));
}

TEST(HostileSource, RegistersThatDoNotExistAreRefusedByTheValidator) {
  AssembleResult result = AssembleSource(
      "vs_1_1\ndcl_position v0\nmov r2047, v0\nmov r0, c2047\nmov oT2047, v0\nmov oPos, v0\n", "r.vsh", {});
  EXPECT_FALSE(result.program);
  std::string messages = Messages(result.diagnostics);
  EXPECT_THAT(messages, HasSubstr("r.vsh:3:1: error: mov: the destination names r2047, which does not exist; vs_1_1 has r0-r11"));
  EXPECT_THAT(messages, HasSubstr("r.vsh:4:1: "));
  EXPECT_THAT(messages, HasSubstr("c2047, but the device has only c0-c95"));
  EXPECT_THAT(messages, HasSubstr("r.vsh:5:1: "));
}

TEST(HostileBytecode, RegisterIndicesAtTheFieldMaximumAreRefusedByInstructionIndex) {
  std::vector<std::uint32_t> words = AssembledWords(kSmallProgram);
  constexpr std::uint32_t kRegisterNumberBits = 0x7FF;  // bits 0-10 of a parameter token (§4.4)
  words[5] |= kRegisterNumberBits;                      // mov r0 -> mov r2047
  DecodeResult decoded = Decode(words);
  ASSERT_TRUE(decoded.program) << Messages(decoded.diagnostics);
  EXPECT_THAT(Messages(Validate(*decoded.program)),
              HasSubstr("instruction 1 (mov): the destination names r2047, which does not exist"));
}

// ---- relative addressing past the constant file ------------------------------------------------------

TEST(HostileSource, StaticRelativeOffsetPastTheConstantFileIsRefused) {
  AssembleResult result = AssembleSource(
      "vs_1_1\ndcl_position v0\nmov a0.x, v0.x\nmov r0, c[a0.x + 96]\nmov oPos, c[a0.x + 2047]\n", "rel.vsh", {});
  EXPECT_FALSE(result.program);
  std::string messages = Messages(result.diagnostics);
  EXPECT_THAT(messages, HasSubstr("rel.vsh:4:1: "));
  EXPECT_THAT(messages, HasSubstr("uses relative offset 96, outside 0-95 (the device has 96 constants)"));
  EXPECT_THAT(messages, HasSubstr("uses relative offset 2047, outside 0-95"));
}

TEST(HostileEngines, RelativeReadsPastTheConstantFileReadZeroInBothEngines) {
  // a0.x is data: no static check can bound it, so the engines must (machine.h: out of range reads 0).
  AssembleOptions options;
  options.require_position = false;
  AssembleResult assembled =
      AssembleSource("vs_1_1\ndcl_position v0\nmov a0.x, v0.x\nmov oD0, c[a0.x + 3]\n", "rel.vsh", options);
  ASSERT_TRUE(assembled.program) << Messages(assembled.diagnostics);
  ConstantBank constants;
  for (int i = 0; i < constants.size(); ++i) constants[i] = {1.0f + i, 2.0f, 3.0f, 4.0f};
  const std::vector<float> addresses = {92.0f,  93.0f, -3.0f, -4.0f, 1e30f, -1e30f, std::numeric_limits<float>::infinity(),
                                        std::numeric_limits<float>::quiet_NaN(), 2147483648.0f, -2147483648.0f};
  const std::vector<float> expected_x = {96.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
  const int input_registers[] = {0};
  VertexArrays inputs = MakeInputArrays(addresses.size(), input_registers);
  for (std::size_t i = 0; i < addresses.size(); ++i) inputs.lane(0, 0)[i] = addresses[i];
  for (std::string kind : {"ref", "batch"}) {
    VertexArrays outputs = MakeOutputArrays(addresses.size(), *assembled.program);
    ASSERT_EQ(MakeEngine(kind, *assembled.program, constants).value()->Run(inputs, outputs).message(), "");
    const int diffuse = static_cast<int>(OutputSlot::kDiffuse);
    for (std::size_t i = 0; i < addresses.size(); ++i) {
      EXPECT_EQ(outputs.lane(diffuse, 0)[i], expected_x[i]) << kind << " a0.x from " << addresses[i];
    }
  }
}

}  // namespace
}  // namespace vs11

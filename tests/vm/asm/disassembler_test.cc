// Disassembly text (spec §4.13) and the round trip assemble(disassemble(p)) == encode(p): for the
// worked encodings of §5, for programs/*.vsh, for golden files in tests/data/disasm/ and for
// generated programs covering every executable opcode with many masks, swizzles and register files.
#include "vm/asm/disassembler.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <set>
#include <string>
#include <vector>

#include "vm/asm/assembler.h"
#include "vm/asm/bytecode.h"
#include "vm/asm/validator.h"

namespace vs11 {
namespace {

using Words = std::vector<std::uint32_t>;

const std::filesystem::path kSourceDir = VS11_SOURCE_DIR;

AssembleResult AssembleText(const std::string& text, bool validate, const std::string& name = "disasm.vsh") {
  AssembleOptions options;
  options.validate = validate;
  return AssembleSource(text, name, options);
}

Program DecodeOrDie(const Words& words) {
  DecodeResult decoded = Decode(words);
  EXPECT_TRUE(decoded.program) << decoded.diagnostics.ToString();
  return decoded.program.value_or(Program{});
}

std::string ReadText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Disassembles `program`, assembles the text again (syntax only) and expects the same tokens.
void ExpectRoundTrip(const Program& program) {
  Program without_comments = program;
  without_comments.comments.clear();
  const Words expected = Encode(without_comments);
  const std::string text = Disassemble(program);
  AssembleResult again = AssembleText(text, /*validate=*/false);
  ASSERT_TRUE(again.program) << again.diagnostics.ToString() << text;
  Words words = Encode(*again.program);
  ASSERT_EQ(words.size(), expected.size()) << text;
  for (std::size_t i = 0; i < words.size(); ++i) {
    ASSERT_EQ(words[i], expected[i]) << "word " << i << " of\n" << text;
  }
}

// ---- the worked encodings of §5, decoded from their tokens and printed ----------------------------

struct TextCase {
  std::string name;
  Words tokens;  // one instruction (no version or end token)
  std::string text;
};

void PrintTo(const TextCase& c, std::ostream* os) { *os << c.name; }

class DisassemblerText : public testing::TestWithParam<TextCase> {};

TEST_P(DisassemblerText, PrintsTheCanonicalLine) {
  const TextCase& c = GetParam();
  Words words = {kVersionVs11};
  words.insert(words.end(), c.tokens.begin(), c.tokens.end());
  words.push_back(kEndToken);
  Program program = DecodeOrDie(words);
  ASSERT_EQ(program.instructions.size(), 1u);
  EXPECT_EQ(FormatInstruction(program.instructions[0]), c.text);
  // Without a dcl the program came from DX8 source and prints as DX8 text.
  const bool dcl = program.instructions[0].opcode == Opcode::kDcl;
  EXPECT_EQ(Disassemble(program),
            (dcl ? "vs_1_1\n" : "vs.1.1\n") + FormatInstruction(program.instructions[0], SyntaxOf(program)) + "\n");
  ExpectRoundTrip(program);
}

const TextCase kWorkedEncodingTexts[] = {
    {"DclPosition", {0x1F, 0x80000000, 0x900F0000}, "dcl_position v0"},
    {"DclTexcoord1", {0x1F, 0x80010005, 0x900F0007}, "dcl_texcoord1 v7"},
    {"DclNormal12", {0x1F, 0x800C0003, 0x900F000F}, "dcl_normal12 v15"},
    {"Def", {0x51, 0xA00F0000, 0x3F800000, 0x00000000, 0x00000000, 0x3F800000}, "def c0, 1, 0, 0, 1"},
    {"DefNegativeAndLarge", {0x51, 0xA00F000C, 0x0, 0xBF800000, 0xBF000000, 0x44800000}, "def c12, 0, -1, -0.5, 1024"},
    {"DefRoundTripDigits",
     {0x51, 0xA00F0001, 0x3DCCCCCD, 0x3A83126F, 0x7F7FFFFF, 0x00000001},
     "def c1, 0.1, 0.001, 3.4028235e+38, 1e-45"},
    {"DefNonFinite", {0x51, 0xA00F0002, 0x7F800000, 0xFF800000, 0x7FC00000, 0x80000000}, "def c2, inf, -inf, nan, -0"},
    {"MovOPos", {0x1, 0xC00F0000, 0x90E40000}, "mov oPos, v0"},
    {"Dp4Relative", {0x9, 0x80010001, 0x90E40001, 0xA0E42003}, "dp4 r1.x, v1, c3[a0.x]"},
    {"MulSwizzles", {0x5, 0x800F0002, 0x80A40000, 0x80290000}, "mul r2, r0.xyzz, r0.yzzx"},
    {"MovA0", {0x1, 0xB0010000, 0xA0000004}, "mov a0.x, c4.x"},
    {"MovOFog", {0x1, 0xC00F0001, 0x80000000}, "mov oFog, r0.x"},
    {"MovOPts", {0x1, 0xC00F0002, 0xA0000000}, "mov oPts, c0.x"},
    {"MovOD1", {0x1, 0xD00F0001, 0x80E40003}, "mov oD1, r3"},
    {"MovOT7", {0x1, 0xE0030007, 0x90E40002}, "mov oT7.xy, v2"},
    {"AddNegated", {0x2, 0x800F0000, 0x81000000, 0x81E40001}, "add r0, -r0.x, -r1"},
    {"Dp4MaskXw", {0x9, 0x80090000, 0x801B0001, 0x80F00002}, "dp4 r0.xw, r1.wzyx, r2.xxww"},
    {"RcpW", {0x6, 0x80080000, 0x80FF0001}, "rcp r0.w, r1.w"},
    {"Sub", {0x3, 0x800F0000, 0x80E40001, 0xA0E40003}, "sub r0, r1, c3"},
    {"M4x4", {0x14, 0xC00F0000, 0x90E40000, 0xA0E40000}, "m4x4 oPos, v0, c0"},
    {"Lit", {0x10, 0x800F0001, 0x80E40000}, "lit r1, r0"},
    {"Expp", {0x4E, 0x80010001, 0xA0550006}, "expp r1.x, c6.y"},
    {"Logp", {0x4F, 0x800F0000, 0x80FF0000}, "logp r0, r0.w"},
    {"Frc", {0x13, 0x80030000, 0x80E40001}, "frc r0.xy, r1"},
    {"Nop", {0x0}, "nop"},
    {"NegatedRelativeReplicate", {0x1, 0x800F0000, 0xA1002003}, "mov r0, -c3[a0.x].x"},
    {"RelativeZero", {0x1, 0x800F0000, 0xA0E42000}, "mov r0, c0[a0.x]"},
    {"A0FullMask", {0x1, 0xB00F0000, 0xA0000000}, "mov a0, c0.x"},
    // A mask is printed unless it is .xyzw and the opcode's default, so that text assembles back to it.
    {"M3x3DefaultMask", {0x17, 0x80070005, 0x90E40003, 0xA0E40000}, "m3x3 r5.xyz, v3, c0"},
    {"M3x3FullMask", {0x17, 0x800F0005, 0x90E40003, 0xA0E40000}, "m3x3 r5.xyzw, v3, c0"},
    {"M4x3FullMask", {0x15, 0x800F0000, 0x90E40000, 0xA0E42000}, "m4x3 r0.xyzw, v0, c0[a0.x]"},
    {"M3x2DefaultMask", {0x18, 0xE0030000, 0x90E40002, 0xA0E4000C}, "m3x2 oT0.xy, v2, c12"},
    {"M3x2FullMask", {0x18, 0xE00F0000, 0x90E40002, 0xA0E4000C}, "m3x2 oT0.xyzw, v2, c12"},
    {"MovOFogX", {0x1, 0xC0010001, 0x8000000B}, "mov oFog.x, r11.x"},
    {"MovOFogZw", {0x1, 0xC00C0001, 0x80FF0002}, "mov oFog.zw, r2.w"},
    {"MovOPtsY", {0x1, 0xC0020002, 0xA0000000}, "mov oPts.y, c0.x"},
};
INSTANTIATE_TEST_SUITE_P(DisassemblerWorkedEncodings, DisassemblerText, testing::ValuesIn(kWorkedEncodingTexts),
                         [](const auto& info) { return info.param.name; });

TEST(Disassembler, PrintsWholeGoldenProgram) {
  Program program = DecodeOrDie({0xFFFE0101, 0x0000001F, 0x80000000, 0x900F0000, 0x00000051, 0xA00F0000, 0x3F800000,
                                 0x00000000, 0x00000000, 0x3F800000, 0x00000001, 0xC00F0000, 0x90E40000, 0x0000FFFF});
  EXPECT_EQ(Disassemble(program), "vs_1_1\ndcl_position v0\ndef c0, 1, 0, 0, 1\nmov oPos, v0\n");
}

TEST(Disassembler, PrintsVersion10) {
  Program program = DecodeOrDie({kVersionVs10, 0x1, 0xC00F0000, 0x90E40000, kEndToken});
  EXPECT_EQ(Disassemble(program), "vs.1.0\nmov oPos, v0\n");
  ExpectRoundTrip(program);
  program = DecodeOrDie({kVersionVs10, 0x1F, 0x80000000, 0x900F0000, 0x1, 0xC00F0000, 0x90E40000, kEndToken});
  EXPECT_EQ(Disassemble(program), "vs_1_0\ndcl_position v0\nmov oPos, v0\n");
  ExpectRoundTrip(program);
}

// A stream without dcl comes from DX8 source: printed as DX9 text (vs_1_1) it would not validate
// again ("reads v0, which has no dcl"); printed as DX8 text it does.
TEST(Disassembler, PrintsDx8TextForAStreamWithoutDcl) {
  const Words words = {kVersionVs11, 0x1,        0xB0010000, 0x90000001, 0x15,       0x80070000, 0x90E40000,
                       0xA0E42000,   0x1,        0x80080000, 0x90FF0000, 0x14,       0xC00F0000, 0x80E40000,
                       0xA0E42004,   0x1,        0xD00F0000, 0xA1FF2003, 0x1,        0xC0010001, 0x80000000,
                       kEndToken};
  Program program = DecodeOrDie(words);
  EXPECT_EQ(SyntaxOf(program), Syntax::kDx8);
  const std::string text = Disassemble(program);
  EXPECT_EQ(text,
            "vs.1.1\n"
            "mov a0.x, v1.x\n"
            "m4x3 r0.xyz, v0, c[a0.x]\n"
            "mov r0.w, v0.w\n"
            "m4x4 oPos, r0, c[a0.x + 4]\n"
            "mov oD0, -c[a0.x + 3].w\n"
            "mov oFog.x, r0.x\n");
  AssembleResult again = AssembleText(text, /*validate=*/true);
  ASSERT_TRUE(again.program) << again.diagnostics.ToString();
  EXPECT_EQ(Encode(*again.program), words);
}

TEST(Disassembler, Dx8TextIndexesOnlyConstantsInTheDx8Form) {
  // A relative input (the validator refuses it) still prints as the input it is.
  Program program = DecodeOrDie({kVersionVs11, 0x1, 0x800F0000, 0x90E42003, 0x1, 0x800F0001, 0xA0E42000, kEndToken});
  EXPECT_EQ(Disassemble(program), "vs.1.1\nmov r0, v3[a0.x]\nmov r1, c[a0.x]\n");
}

TEST(Disassembler, ValidatedDx8SourceComesBackValid) {
  const std::string source = "vs.1.1\nm4x4 oPos, v0, c0\nm3x3 r5, v3, c4\nmov oD0.xyz, r5\n";
  AssembleResult first = AssembleText(source, /*validate=*/true);
  ASSERT_TRUE(first.program) << first.diagnostics.ToString();
  const std::string text = Disassemble(*first.program);
  EXPECT_EQ(text, "vs.1.1\nm4x4 oPos, v0, c0\nm3x3 r5.xyz, v3, c4\nmov oD0.xyz, r5\n");
  AssembleResult again = AssembleText(text, /*validate=*/true);
  ASSERT_TRUE(again.program) << again.diagnostics.ToString();
  EXPECT_EQ(Encode(*again.program), Encode(*first.program));
}

TEST(Disassembler, PrintsCommentBlocksWhereTheyStand) {
  Program program = DecodeOrDie({kVersionVs11, 0x0002FFFE, 0x454E494C, 0x0000000C, 0x1, 0xC00F0000, 0x90E40000,
                                 0x0000FFFE, 0x0001FFFE, 0xDEADBEEF, kEndToken});
  EXPECT_EQ(Disassemble(program),
            "vs.1.1\n"
            "; comment (2 words): 0x454E494C 0x0000000C\n"
            "mov oPos, v0\n"
            "; comment (0 words)\n"
            "; comment (1 words): 0xDEADBEEF\n");
  ExpectRoundTrip(program);  // comments are dropped, the rest is identical
}

TEST(Disassembler, NotesNanPayloadsItCannotPrint) {
  Instruction def;
  def.opcode = Opcode::kDef;
  def.dest.reg = {RegisterFile::kConst, 4, false};
  def.def_bits = {0x7FC00001, 0x3F800000, 0xFFC00000, 0xFF800001};
  EXPECT_EQ(FormatInstruction(def),
            "def c4, nan, 1, -nan, -nan ; value 0 is NaN 0x7FC00001, value 3 is NaN 0xFF800001");
  // The text still assembles; the payloads become the canonical quiet NaN.
  AssembleResult again = AssembleText("vs_1_1\n" + FormatInstruction(def) + "\n", /*validate=*/false);
  ASSERT_TRUE(again.program) << again.diagnostics.ToString();
  EXPECT_EQ(again.program->instructions[0].def_bits,
            (std::array<std::uint32_t, 4>{0x7FC00000, 0x3F800000, 0xFFC00000, 0xFFC00000}));
}

TEST(Disassembler, FormatsSingleOperands) {
  EXPECT_EQ(FormatDest(DestOperand{{RegisterFile::kTexCoordOut, 3, false}, WriteMask(0x5)}), "oT3.xz");
  EXPECT_EQ(FormatSource(SourceOperand{{RegisterFile::kConst, 7, true}, Swizzle(0x55), true}), "-c7[a0.x].y");
  EXPECT_EQ(FormatSource(SourceOperand{{RegisterFile::kInput, 2, false}, Swizzle(0x1B), false}), "v2.wzyx");
}

// ---- round trips of whole source files ---------------------------------------------------------

void ExpectSourceRoundTrip(const std::string& source, const std::string& name) {
  AssembleResult first = AssembleText(source, /*validate=*/false, name);
  ASSERT_TRUE(first.program) << name << ":\n" << first.diagnostics.ToString();
  SCOPED_TRACE(name);
  ExpectRoundTrip(*first.program);
}

const char* const kBuiltInSources[] = {
    "vs_1_1\ndcl_position v0\ndef c0, 1, 0, 0, 1\nmov oPos, v0\n",
    "vs.1.1\n#define W 4\nm4x4 oPos, v0, c[W]\nmov a0.x, v1.x\nmov oD0, -c[a0.x + 2 + W].zyxw\nmov oFog.x, v0.z\n",
    "vs.1.0\nexpp r0, v0.w\nlogp r1.xw, r0.y\nfrc r2.y, r1\nlit r3, r0\ndst r4, r0, r1\nmov oPos, r4\n",
    "vs_1_1\ndcl_color1 v9\ndef c1, -0.25, 1e20, 7.5e-30, 0\nmad oT2.yz, v9.zw, c1.wzyx, -c1.x\n",
};

TEST(DisassemblerRoundTrip, BuiltInSources) {
  for (const char* source : kBuiltInSources) ExpectSourceRoundTrip(source, "built-in");
}

// asm -> disasm -> asm, validating both times as `vs11 asm` does (fragments by their metadata).
TEST(DisassemblerRoundTrip, EveryProgramInProgramsFolderValidatesAgain) {
  const std::filesystem::path folder = kSourceDir / "programs";
  ASSERT_TRUE(std::filesystem::is_directory(folder)) << folder;
  int dx8 = 0, dx9 = 0;
  std::set<std::string> seen;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() != ".vsh") continue;
    SCOPED_TRACE(entry.path().string());
    seen.insert(entry.path().filename().string());
    const std::string source = ReadText(entry.path());
    AssembleOptions options;
    options.require_position = source.find("; vs11: fragment=yes") == std::string::npos;
    AssembleResult first = AssembleSource(source, entry.path().string(), options);
    ASSERT_TRUE(first.program) << first.diagnostics.ToString();
    (first.dx9_syntax ? dx9 : dx8) += 1;
    const std::string listing = Disassemble(*first.program);
    AssembleResult again = AssembleSource(listing, "listing.vsh", options);
    ASSERT_TRUE(again.program) << again.diagnostics.ToString() << listing;
    EXPECT_EQ(Encode(*again.program), Encode(*first.program)) << listing;
  }
  std::cout << "[          ] round-tripped " << dx8 << " DX8 and " << dx9 << " DX9 programs from " << folder << "\n";
  EXPECT_GT(dx8, 0);
  EXPECT_GT(dx9, 0);
  // An empty or moved folder must not pass.
  for (const char* name : {"sh9_irradiance.vsh", "all_instructions.vsh", "skinning.vsh"}) {
    EXPECT_TRUE(seen.count(name)) << name << " not found in " << folder;
  }
}

// ---- golden disassembly files -------------------------------------------------------------------

TEST(DisassemblerGolden, MatchesExpectedTextFiles) {
  std::filesystem::path folder = kSourceDir / "tests" / "data" / "disasm";
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().extension() != ".vsh") continue;
    ++count;
    SCOPED_TRACE(entry.path().string());
    AssembleResult result = AssembleFile(entry.path(), AssembleOptions{});  // validated
    ASSERT_TRUE(result.program) << result.diagnostics.ToString();
    std::filesystem::path expected_path = entry.path();
    expected_path.replace_extension(".txt");
    EXPECT_EQ(Disassemble(*result.program), ReadText(expected_path));
    ExpectRoundTrip(*result.program);
  }
  EXPECT_GE(count, 2);
}

// ---- generated programs: every executable opcode x masks x swizzles x negation x files -----------

const RegisterRef kSourceRegisters[] = {
    {RegisterFile::kTemp, 3, false},  {RegisterFile::kInput, 15, false}, {RegisterFile::kConst, 95, false},
    {RegisterFile::kConst, 12, true}, {RegisterFile::kConst, 0, true},   {RegisterFile::kTemp, 11, false},
};
const RegisterRef kDestRegisters[] = {
    {RegisterFile::kTemp, 7, false},
    {RegisterFile::kRasterOut, kRasterOutPosition, false},
    {RegisterFile::kAttributeOut, 1, false},
    {RegisterFile::kTexCoordOut, 7, false},
};
const std::uint8_t kMasks[] = {0x1, 0x2, 0x3, 0x5, 0x8, 0xA, 0xE, 0xF};
const std::uint8_t kSwizzles[] = {0xE4, 0x00, 0x55, 0xAA, 0xFF, 0x54, 0xA4, 0x1B, 0x29, 0xF0, 0x4F};

class DisassemblerGenerated : public testing::TestWithParam<Opcode> {};

// One instruction per (first-source register, swizzle, negation); the destination and its mask cycle
// so that every (dest, mask) pair occurs too, and the other sources cycle through registers and
// swizzles so that the operands of a line differ.
std::vector<Instruction> Combinations(const OpcodeInfo& info) {
  Instruction instruction;
  instruction.opcode = info.opcode;
  if (!info.has_dest()) return {instruction};
  std::vector<Instruction> instructions;
  int variant = 0;
  for (std::uint8_t swizzle : kSwizzles) {
    for (bool negate : {false, true}) {
      for (const RegisterRef& source : kSourceRegisters) {
        const RegisterRef& dest = kDestRegisters[variant % std::size(kDestRegisters)];
        std::uint8_t mask = kMasks[(variant / std::size(kDestRegisters)) % std::size(kMasks)];
        instruction.dest = DestOperand{dest, WriteMask(mask)};
        instruction.sources[0] = SourceOperand{source, Swizzle(swizzle), negate};
        for (int s = 1; s < info.source_count(); ++s) {
          const int k = variant + s;
          instruction.sources[s] =
              SourceOperand{kSourceRegisters[(k + s) % std::size(kSourceRegisters)],
                            Swizzle(kSwizzles[(k * 7 + s) % std::size(kSwizzles)]), negate != (s == 1)};
        }
        instructions.push_back(instruction);
        ++variant;
      }
    }
  }
  return instructions;
}

TEST_P(DisassemblerGenerated, RoundTripsEveryOperandCombination) {
  Program program;
  program.instructions = Combinations(Info(GetParam()));
  Words words = Encode(program);
  ASSERT_EQ(DecodeOrDie(words).instructions, program.instructions);
  ExpectRoundTrip(program);
}

std::vector<Opcode> ExecutableOpcodes() {
  std::vector<Opcode> opcodes;
  for (const OpcodeInfo& info : kOpcodeTable) {
    if (info.is_executable() && info.since == ShaderModel::kVs11) opcodes.push_back(info.opcode);
  }
  return opcodes;
}

INSTANTIATE_TEST_SUITE_P(DisassemblerAllOpcodes, DisassemblerGenerated, testing::ValuesIn(ExecutableOpcodes()),
                         [](const auto& info) { return std::string(Info(info.param).mnemonic); });

TEST(DisassemblerGeneratedSpecial, AddressAndScalarOutputDestinations) {
  Program program;
  for (RegisterRef dest :
       {RegisterRef{RegisterFile::kAddress, 0, false}, RegisterRef{RegisterFile::kRasterOut, kRasterOutFog, false},
        RegisterRef{RegisterFile::kRasterOut, kRasterOutPointSize, false}}) {
    for (std::uint8_t mask : kMasks) {
      Instruction mov;
      mov.opcode = Opcode::kMov;
      mov.dest = DestOperand{dest, WriteMask(mask)};
      mov.sources[0] = SourceOperand{{RegisterFile::kConst, 5, true}, Swizzle(0xAA), true};
      program.instructions.push_back(mov);
    }
  }
  ExpectRoundTrip(program);
}

TEST(DisassemblerGeneratedSpecial, EveryDclUsageAndIndex) {
  Program program;
  for (int usage = 0; usage < static_cast<int>(kDeclUsageNames.size()); ++usage) {
    for (int index = 0; index <= kMaxDeclUsageIndex; ++index) {
      Instruction dcl;
      dcl.opcode = Opcode::kDcl;
      dcl.usage = usage;
      dcl.usage_index = index;
      dcl.dest.reg = {RegisterFile::kInput, (usage + index) % kInputRegisterCount, false};
      program.instructions.push_back(dcl);
    }
  }
  ExpectRoundTrip(program);
}

TEST(DisassemblerGeneratedSpecial, DefValuesKeepTheirBits) {
  std::mt19937 random(1234);
  Program program;
  for (int i = 0; i < 500; ++i) {
    Instruction def;
    def.opcode = Opcode::kDef;
    def.dest.reg = {RegisterFile::kConst, i % kDefaultConstantCount, false};
    for (std::uint32_t& bits : def.def_bits) {
      bits = static_cast<std::uint32_t>(random());
      if (i % 3 == 1) bits &= 0x807FFFFFu;                                                    // subnormals and zeros
      if (std::isnan(std::bit_cast<float>(bits))) bits = (bits & 0x80000000u) | 0x7FC00000u;  // text keeps no payload
    }
    program.instructions.push_back(def);
  }
  ExpectRoundTrip(program);
}

// ---- generated valid programs: asm -> disasm -> asm with validation, DX8 (no dcl) and DX9 ---------

// Random programs that pass the validator: four temporaries written whole first, one input and one
// constant register per instruction (absolute, or relative once a0.x is written), masks the opcode
// allows, matrix operands unswizzled and apart from the destination, oPos written last.
class ValidProgramGenerator {
 public:
  explicit ValidProgramGenerator(unsigned seed) : random_(seed) {}

  Program Next(bool declare_inputs) {
    Program program;
    if (declare_inputs) {
      for (int v = 0; v < kInputRegisterCount; ++v) {
        Instruction dcl;
        dcl.opcode = Opcode::kDcl;
        dcl.usage = 5;  // texcoord<v>
        dcl.usage_index = v;
        dcl.dest.reg = {RegisterFile::kInput, v, false};
        program.instructions.push_back(dcl);
      }
    }
    for (int i = Uniform(0, 3); i > 0; --i) {
      Instruction def;
      def.opcode = Opcode::kDef;
      def.dest.reg = {RegisterFile::kConst, Uniform(0, kDefaultConstantCount - 1), false};
      for (std::uint32_t& bits : def.def_bits) bits = static_cast<std::uint32_t>(random_()) & 0xBFFFFFFFu;  // finite
      program.instructions.push_back(def);
    }
    const bool relative = Uniform(0, 1) == 1;
    if (relative) program.instructions.push_back(Mov({RegisterFile::kAddress, 0, false}, 0x1, Input(0x00)));
    for (int t = 0; t < kTemps; ++t) program.instructions.push_back(Mov(Temp(t), 0xF, Input(Swizzle().bits())));
    int slots = kTemps + 2;
    for (int i = Uniform(5, 40); i > 0; --i) {
      Instruction instruction = RandomInstruction(relative);
      slots += instruction.info().slots;
      if (slots > kMaxInstructionSlots) break;
      program.instructions.push_back(instruction);
    }
    const SourceOperand position{Temp(0), Swizzle(), false};
    program.instructions.push_back(Mov({RegisterFile::kRasterOut, kRasterOutPosition, false}, 0xF, position));
    return program;
  }

 private:
  static constexpr int kTemps = 4;

  int Uniform(int low, int high) { return std::uniform_int_distribution<int>(low, high)(random_); }
  RegisterRef Temp(int index) { return {RegisterFile::kTemp, index, false}; }
  SourceOperand Input(std::uint8_t swizzle) {
    return {{RegisterFile::kInput, Uniform(0, kInputRegisterCount - 1), false}, Swizzle(swizzle), false};
  }
  Instruction Mov(RegisterRef dest, std::uint8_t mask, SourceOperand source) {
    Instruction mov;
    mov.opcode = Opcode::kMov;
    mov.dest = {dest, WriteMask(mask)};
    mov.sources[0] = source;
    return mov;
  }

  std::uint8_t MaskFor(MaskRule rule) {
    switch (rule) {
      case MaskRule::kYOrXy: return Uniform(0, 1) ? 0x2 : 0x3;
      case MaskRule::kXy: return 0x3;
      case MaskRule::kXyz: return 0x7;
      case MaskRule::kXyzw:
      case MaskRule::kFull: return 0xF;
      case MaskRule::kAny: break;
    }
    return static_cast<std::uint8_t>(Uniform(1, 15));
  }

  RegisterRef Destination(bool matrix) {
    switch (Uniform(0, matrix ? 3 : 5)) {
      case 0: return {RegisterFile::kAttributeOut, Uniform(0, kColorOutputCount - 1), false};
      case 1: return {RegisterFile::kTexCoordOut, Uniform(0, kTexCoordOutputCount - 1), false};
      case 4: return {RegisterFile::kRasterOut, kRasterOutFog, false};
      case 5: return {RegisterFile::kRasterOut, kRasterOutPointSize, false};
      default: return Temp(Uniform(0, kTemps - 1));
    }
  }

  Instruction RandomInstruction(bool relative) {
    std::vector<const OpcodeInfo*> executable;
    for (const OpcodeInfo& info : kOpcodeTable) {
      if (info.is_executable() && info.has_dest() && info.since == ShaderModel::kVs11) executable.push_back(&info);
    }
    const OpcodeInfo& info = *executable[static_cast<std::size_t>(Uniform(0, static_cast<int>(executable.size()) - 1))];
    const bool matrix = info.kind == ResultKind::kMatrix;
    const int rows = matrix ? info.matrix_rows : 1;
    Instruction instruction;
    instruction.opcode = info.opcode;
    instruction.dest = {Destination(matrix), WriteMask(MaskFor(info.mask_rule))};
    // The one input and the one constant this instruction may read (a matrix reads `rows` of them).
    const RegisterRef input{RegisterFile::kInput, Uniform(0, kInputRegisterCount - rows), false};
    const bool relative_constant = relative && Uniform(0, 1) == 1;
    const RegisterRef constant{RegisterFile::kConst, Uniform(0, kDefaultConstantCount - rows), relative_constant};
    // A matrix's rows come from one file, its first source from another; temporaries only for s0.
    const int matrix_file = Uniform(0, 1);  // 0: constants, 1: inputs
    for (int s = 0; s < info.source_count(); ++s) {
      SourceOperand& source = instruction.sources[s];
      if (matrix && s == 1) {
        source = {matrix_file == 0 ? constant : input, Swizzle(), false};
        continue;
      }
      int file = Uniform(0, 2);  // 0 temp, 1 input, 2 constant
      if (matrix && file == 2 - matrix_file) file = 0;
      source.reg = file == 0 ? Temp(Uniform(0, kTemps - 1)) : file == 1 ? input : constant;
      if (matrix && source.reg == instruction.dest.reg) source.reg = Temp((source.reg.index + 1) % kTemps);
      source.swizzle = Swizzle(static_cast<std::uint8_t>(Uniform(0, 255)));
      source.negate = Uniform(0, 1) == 1;
    }
    return instruction;
  }

  std::mt19937 random_;
};

void ExpectValidRoundTrip(const Program& program, bool dx8) {
  Diagnostics problems = Validate(program);
  ASSERT_FALSE(problems.HasErrors()) << problems.ToString() << Disassemble(program);
  const Words words = Encode(program);
  const std::string listing = Disassemble(program);
  EXPECT_EQ(listing.rfind(dx8 ? "vs.1.1\n" : "vs_1_1\n", 0), 0u) << listing;
  AssembleResult again = AssembleText(listing, /*validate=*/true);
  ASSERT_TRUE(again.program) << again.diagnostics.ToString() << listing;
  ASSERT_EQ(Encode(*again.program), words) << listing;
}

TEST(DisassemblerGeneratedValid, Dx8ProgramsComeBackValidAndIdentical) {
  ValidProgramGenerator generator(20261123);
  for (int i = 0; i < 300; ++i) {
    SCOPED_TRACE(i);
    ExpectValidRoundTrip(generator.Next(/*declare_inputs=*/false), /*dx8=*/true);
  }
}

TEST(DisassemblerGeneratedValid, Dx9ProgramsComeBackValidAndIdentical) {
  ValidProgramGenerator generator(11);
  for (int i = 0; i < 300; ++i) {
    SCOPED_TRACE(i);
    ExpectValidRoundTrip(generator.Next(/*declare_inputs=*/true), /*dx8=*/false);
  }
}

}  // namespace
}  // namespace vs11

// Token streams (spec §4): Decode must reject malformed streams and name the word at fault; Encode and
// Decode are inverses; bytes <-> words is little-endian and whole-word only.
#include "vm/asm/bytecode.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "vm/asm/assembler.h"

namespace vs11 {
namespace {

using Words = std::vector<std::uint32_t>;

struct MalformedCase {
  std::string name;
  Words words;
  long offset;          // word_offset of the first error
  std::string message;  // a distinctive part of its text
};

void PrintTo(const MalformedCase& c, std::ostream* os) { *os << c.name; }

class BytecodeDecode : public testing::TestWithParam<MalformedCase> {};

TEST_P(BytecodeDecode, RejectsMalformedStreamAtTheBadWord) {
  const MalformedCase& c = GetParam();
  DecodeResult result = Decode(c.words);
  EXPECT_FALSE(result.program);
  ASSERT_TRUE(result.diagnostics.HasErrors());
  const Diagnostic& first = result.diagnostics.all().front();
  EXPECT_EQ(first.word_offset, c.offset) << first.message;
  EXPECT_NE(first.message.find(c.message), std::string::npos) << "message: " << first.message;
}

// mov r0, r1 is 0x00000001, 0x800F0000, 0x80E40001 (§5 layout); the cases below break one part of it.
const MalformedCase kMalformed[] = {
    {"EmptyStream", {}, 0, "empty token stream"},
    {"PixelShaderVersion", {0xFFFF0101, 0x0000FFFF}, 0, "is not vs_1_1"},
    {"Version40", {0xFFFE0400, 0x0000FFFF}, 0, "is not vs_1_1"},
    {"NotAVersionAtAll", {0x00000001, 0x800F0000, 0x80E40001, 0x0000FFFF}, 0, "is not vs_1_1"},
    {"LrpOpcode",
     {0xFFFE0101, 0x00000012, 0x800F0000, 0x80E40001, 0x80E40002, 0x80E40003, 0x0000FFFF},
     1,
     "opcode 18 (0x0012) is not a vs_1_1 instruction"},
    {"PowOpcode",
     {0xFFFE0101, 0x00000020, 0x800F0000, 0x80000001, 0x80000002, 0x0000FFFF},
     1,
     "opcode 32 (0x0020) is not a vs_1_1 instruction"},
    {"MovaOpcode", {0xFFFE0101, 0x0000002E, 0xB0010000, 0x80000001, 0x0000FFFF}, 1, "is not a vs_1_1 instruction"},
    {"PixelTexldOpcode", {0xFFFE0101, 0x00000042, 0x0000FFFF}, 1, "is not a vs_1_1 instruction"},
    {"PhaseOpcode", {0xFFFE0101, 0x0000FFFD, 0x0000FFFF}, 1, "is not a vs_1_1 instruction"},
    {"TruncatedInstruction", {0xFFFE0101, 0x00000001, 0x800F0000}, 1, "mov needs 2 parameter tokens"},
    {"TruncatedDef", {0xFFFE0101, 0x00000051, 0xA00F0000, 0x3F800000, 0x0000FFFF}, 1, "def needs 5 parameter tokens"},
    {"MissingEndToken", {0xFFFE0101, 0x00000001, 0x800F0000, 0x80E40001}, 4, "missing end token"},
    {"VersionOnly", {0xFFFE0101}, 1, "missing end token"},
    {"WordsAfterEnd", {0xFFFE0101, 0x0000FFFF, 0x00000000, 0x00000000}, 2, "2 words after the end token"},
    {"OversizedComment", {0xFFFE0101, 0x0005FFFE, 0x1, 0x2, 0x0000FFFF}, 1, "comment of 5 words runs past the end"},
    {"CommentWithBit31", {0xFFFE0101, 0x8001FFFE, 0x1, 0x0000FFFF}, 1, "comment token has bit 31 set"},
    {"InstructionLengthField",
     {0xFFFE0101, 0x02000001, 0x800F0000, 0x80E40001, 0x0000FFFF},
     1,
     "has bits set above the opcode"},
    {"InstructionControls",
     {0xFFFE0101, 0x00010001, 0x800F0000, 0x80E40001, 0x0000FFFF},
     1,
     "has bits set above the opcode"},
    {"InstructionPredicated",
     {0xFFFE0101, 0x10000001, 0x800F0000, 0x80E40001, 0x0000FFFF},
     1,
     "has bits set above the opcode"},
    {"InstructionCoIssue",
     {0xFFFE0101, 0x40000001, 0x800F0000, 0x80E40001, 0x0000FFFF},
     1,
     "has bits set above the opcode"},
    {"DestWithoutBit31", {0xFFFE0101, 0x00000001, 0x000F0000, 0x80E40001, 0x0000FFFF}, 2, "lacks bit 31"},
    {"SourceWithoutBit31", {0xFFFE0101, 0x00000001, 0x800F0000, 0x00E40001, 0x0000FFFF}, 3, "lacks bit 31"},
    {"DestReservedBit14", {0xFFFE0101, 0x00000001, 0x800F4000, 0x80E40001, 0x0000FFFF}, 2, "reserved bits 14-15"},
    {"SourceReservedBit15", {0xFFFE0101, 0x00000001, 0x800F0000, 0x80E48001, 0x0000FFFF}, 3, "reserved bits 14-15"},
    {"SourceConstIntType",
     {0xFFFE0101, 0x00000001, 0x800F0000, 0xF0E40000, 0x0000FFFF},
     3,
     "register type 7 is not used"},
    {"SourceHighTypeBits",
     {0xFFFE0101, 0x00000001, 0x800F0000, 0x80E40800, 0x0000FFFF},
     3,
     "register type 8 is not used"},
    {"SourceBiasModifier", {0xFFFE0101, 0x00000001, 0x800F0000, 0x82E40001, 0x0000FFFF}, 3, "source modifier 2"},
    {"SourceAbsModifier",
     {0xFFFE0101, 0x00000002, 0x800F0000, 0x80E40001, 0x8BE40002, 0x0000FFFF},
     4,
     "source modifier 11"},
    {"RelativeDestination", {0xFFFE0101, 0x00000001, 0x800F2000, 0x80E40001, 0x0000FFFF}, 2, "relative-addressing bit"},
    {"SaturatedDestination", {0xFFFE0101, 0x00000001, 0x801F0000, 0x80E40001, 0x0000FFFF}, 2, "result modifier"},
    {"ShiftedDestination", {0xFFFE0101, 0x00000001, 0x810F0000, 0x80E40001, 0x0000FFFF}, 2, "result modifier"},
    {"DclUsageReservedBits", {0xFFFE0101, 0x0000001F, 0x80000010, 0x900F0000, 0x0000FFFF}, 2, "reserved bits set"},
    {"DclUsageWithoutBit31", {0xFFFE0101, 0x0000001F, 0x00000000, 0x900F0000, 0x0000FFFF}, 2, "reserved bits set"},
    {"DclUnknownUsage",
     {0xFFFE0101, 0x0000001F, 0x8000000E, 0x900F0000, 0x0000FFFF},
     2,
     "dcl usage 14 is not a D3DDECLUSAGE value"},
    {"DclDestReservedBits", {0xFFFE0101, 0x0000001F, 0x80000000, 0x900FC000, 0x0000FFFF}, 3, "reserved bits 14-15"},
    // RASTOUT has oPos, oFog and oPts only: a register with no name could not be disassembled.
    {"RastoutRegister3Dest",
     {0xFFFE0101, 0x00000001, 0xC00F0003, 0x80E40001, 0x0000FFFF},
     2,
     "register type 4 has no register 3 in vs_1_1"},
    {"RastoutRegister2047Source",
     {0xFFFE0101, 0x00000001, 0x800F0000, 0xC0E407FF, 0x0000FFFF},
     3,
     "register type 4 has no register 2047 in vs_1_1"},
};
INSTANTIATE_TEST_SUITE_P(BytecodeMalformed, BytecodeDecode, testing::ValuesIn(kMalformed),
                         [](const auto& info) { return info.param.name; });

TEST(Bytecode, RecordsTheWordOffsetOfEveryInstruction) {
  // version, comment (2 words), dcl (3), def (6), mov (3), end.
  DecodeResult result = Decode(Words{0xFFFE0101, 0x0001FFFE, 0x12345678, 0x0000001F, 0x80000000, 0x900F0000,
                                     0x00000051, 0xA00F0000, 0, 0, 0, 0, 0x00000001, 0xC00F0000, 0x90E40000,
                                     0x0000FFFF});
  ASSERT_TRUE(result.program) << result.diagnostics.ToString();
  EXPECT_EQ(result.program->word_offsets, (std::vector<long>{3, 6, 12}));
  EXPECT_EQ(result.program->WordOffsetOf(2), 12);
  EXPECT_EQ(result.program->WordOffsetOf(3), -1);
}

TEST(Bytecode, DecodesEveryFieldOfAWellFormedStream) {
  // §5: dcl_texcoord1 v7; def c12, 0, -1, -0.5, 1024; dp4 r1.x, v1, c[a0.x + 3]; add r0, -r0.x, -r1;
  // a comment of two words between them; vs.1.0 version.
  Words words = {0xFFFE0100, 0x0000001F, 0x80010005, 0x900F0007, 0x00000051, 0xA00F000C, 0x00000000, 0xBF800000,
                 0xBF000000, 0x44800000, 0x0002FFFE, 0x454E494C, 0x0000000C, 0x00000009, 0x80010001, 0x90E40001,
                 0xA0E42003, 0x00000002, 0x800F0000, 0x81000000, 0x81E40001, 0x0000FFFF};
  DecodeResult result = Decode(words);
  ASSERT_TRUE(result.program) << result.diagnostics.ToString();
  const Program& program = *result.program;
  EXPECT_EQ(program.version, kVersionVs10);
  ASSERT_EQ(program.instructions.size(), 4u);

  const Instruction& dcl = program.instructions[0];
  EXPECT_EQ(dcl.opcode, Opcode::kDcl);
  EXPECT_EQ(dcl.usage, 5);
  EXPECT_EQ(dcl.usage_index, 1);
  EXPECT_EQ(dcl.dest, (DestOperand{{RegisterFile::kInput, 7, false}, WriteMask(0xF)}));

  const Instruction& def = program.instructions[1];
  EXPECT_EQ(def.dest.reg, (RegisterRef{RegisterFile::kConst, 12, false}));
  EXPECT_EQ(def.def_values(), (std::array<float, 4>{0.0f, -1.0f, -0.5f, 1024.0f}));

  const Instruction& dp4 = program.instructions[2];
  EXPECT_EQ(dp4.opcode, Opcode::kDp4);
  EXPECT_EQ(dp4.dest, (DestOperand{{RegisterFile::kTemp, 1, false}, WriteMask(0x1)}));
  EXPECT_EQ(dp4.sources[0], (SourceOperand{{RegisterFile::kInput, 1, false}, Swizzle(), false}));
  EXPECT_EQ(dp4.sources[1], (SourceOperand{{RegisterFile::kConst, 3, true}, Swizzle(), false}));

  const Instruction& add = program.instructions[3];
  EXPECT_EQ(add.sources[0], (SourceOperand{{RegisterFile::kTemp, 0, false}, Swizzle::Replicate(0), true}));
  EXPECT_EQ(add.sources[1], (SourceOperand{{RegisterFile::kTemp, 1, false}, Swizzle(), true}));

  ASSERT_EQ(program.comments.size(), 1u);
  EXPECT_EQ(program.comments[0], (CommentBlock{2, {0x454E494C, 0x0000000C}}));
  EXPECT_EQ(Encode(program), words);
}

TEST(Bytecode, EncodeDecodeRoundTripOfAssembledPrograms) {
  AssembleOptions options;
  options.validate = false;
  const char* const sources[] = {
      "vs_1_1\ndcl_position v0\ndcl_normal v3\ndef c0, 1, 0, 0.5, -2\nm4x4 oPos, v0, c4\nmov a0.x, c0.x\n"
      "dp3 r1.xw, -v3.zyxw, c[a0.x + 20]\nlit oD0, r1\nmov oFog, r1.w\nmov oPts, c0.z\nnop\n",
      "vs.1.1\nexp r0, v0.x\nlog r1.y, r0.w\nexpp r2, r1.y\nlogp r3.z, r2.x\nfrc r4.xy, r3\ndst r5, r4, r3\n"
      "m4x3 r6.xyz, r5, c10\nm3x4 r7, r6, c20\nm3x3 r8.xyz, r7, c30\nm3x2 oT7.xy, r8, c40\nslt r9, r8, c1\n"
      "sge r10, r9, -c1\nmin r11, r10, r9\nmax oD1, r11, r10\nrcp r0.x, r11.y\nrsq r0.y, r0.x\nsub oT0, r0, c2\n",
  };
  for (const char* source : sources) {
    AssembleResult assembled = AssembleSource(source, "round.vsh", options);
    ASSERT_TRUE(assembled.program) << assembled.diagnostics.ToString();
    Words words = Encode(*assembled.program);
    DecodeResult decoded = Decode(words);
    ASSERT_TRUE(decoded.program) << decoded.diagnostics.ToString();
    EXPECT_EQ(decoded.program->instructions, assembled.program->instructions);
    EXPECT_EQ(Encode(*decoded.program), words);
  }
}

TEST(Bytecode, CommentsAfterTheLastInstructionSurvive) {
  Words words = {0xFFFE0101, 0x0001FFFE, 0x11111111, 0x00000000, 0x0000FFFE,
                 0x0002FFFE, 0x7FFFFFFF, 0xFFFFFFFF, 0x0000FFFF};
  DecodeResult result = Decode(words);
  ASSERT_TRUE(result.program) << result.diagnostics.ToString();
  EXPECT_EQ(result.program->comments.size(), 3u);
  EXPECT_EQ(result.program->comments[2].before_instruction, 1);
  EXPECT_EQ(Encode(*result.program), words);
}

TEST(Bytecode, WordsFromBytesRejectsPartialWords) {
  for (std::size_t size : {1u, 2u, 3u, 5u, 7u, 13u}) {
    std::vector<std::uint8_t> bytes(size, 0);
    EXPECT_FALSE(WordsFromBytes(bytes)) << size << " bytes";
  }
  std::optional<Words> empty = WordsFromBytes({});
  ASSERT_TRUE(empty);
  EXPECT_TRUE(empty->empty());
}

TEST(Bytecode, WordsAreLittleEndian) {
  const std::vector<std::uint8_t> bytes = {0x01, 0x01, 0xFE, 0xFF, 0xFF, 0xFF, 0x00, 0x00};
  std::optional<Words> words = WordsFromBytes(bytes);
  ASSERT_TRUE(words);
  EXPECT_EQ(*words, (Words{0xFFFE0101, 0x0000FFFF}));
  EXPECT_EQ(BytesFromWords(*words), bytes);
}

}  // namespace
}  // namespace vs11

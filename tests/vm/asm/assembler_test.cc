// Assembler output checked against full token streams worked out by hand from the bit layout of
// spec §4 (every entry of §5 included). Layout reminders, from §4.4/§4.5:
//   parameter token = 0x80000000 | type bits 28-30 (r 0x0, v 0x1, c 0x2, a0 0x3, RASTOUT 0x4,
//   oD 0x5, oT 0x6) | source modifier bits 24-27 (negate 0x1) | swizzle bits 16-23 (dest: mask
//   bits 16-19) | relative bit 13 (0x2000) | register number bits 0-10.
#include "vm/asm/assembler.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "vm/asm/bytecode.h"

namespace vs11 {
namespace {

using Words = std::vector<std::uint32_t>;

// Files the #include tests can see; everything else is unreadable.
std::optional<std::string> ReadTestFile(const std::filesystem::path& path) {
  static const std::map<std::string, std::string> kFiles = {
      {"constants.h", "#define CV_LIGHT_DIR 7\n#define CV_WORLD 4\n"},
      {"body.vsh", "mov oPos, v0\n"},
  };
  auto it = kFiles.find(path.filename().string());
  if (it == kFiles.end()) return std::nullopt;
  return it->second;
}

AssembleResult AssembleForTest(const std::string& source, bool validate = false) {
  AssembleOptions options;
  options.validate = validate;
  return AssembleSource(source, "test.vsh", options, ReadTestFile);
}

struct EncodingCase {
  std::string name;
  std::string source;
  Words expected;  // the whole stream: version ... end
};

void PrintTo(const EncodingCase& c, std::ostream* os) { *os << c.name; }

class AssemblerEncoding : public testing::TestWithParam<EncodingCase> {};

TEST_P(AssemblerEncoding, ProducesTheExpectedTokenStream) {
  const EncodingCase& c = GetParam();
  AssembleResult result = AssembleForTest(c.source);
  ASSERT_TRUE(result.program) << result.diagnostics.ToString();
  EXPECT_FALSE(result.diagnostics.HasErrors());
  Words words = Encode(*result.program);
  EXPECT_EQ(words.size(), c.expected.size());
  for (std::size_t i = 0; i < std::min(words.size(), c.expected.size()); ++i) {
    EXPECT_EQ(words[i], c.expected[i]) << "word " << i << std::hex << ": got 0x" << words[i] << ", want 0x"
                                       << c.expected[i];
  }
}

// §5 worked encodings, each as a complete program.
const EncodingCase kWorkedEncodings[] = {
    {"VersionDx9", "vs_1_1\n", {0xFFFE0101, 0x0000FFFF}},
    {"VersionDx8", "vs.1.1\n", {0xFFFE0101, 0x0000FFFF}},
    {"VersionDx8_10", "vs.1.0\n", {0xFFFE0100, 0x0000FFFF}},
    {"DclPosition", "vs_1_1\ndcl_position v0\n", {0xFFFE0101, 0x0000001F, 0x80000000, 0x900F0000, 0x0000FFFF}},
    {"DclTexcoord1", "vs_1_1\ndcl_texcoord1 v7\n", {0xFFFE0101, 0x0000001F, 0x80010005, 0x900F0007, 0x0000FFFF}},
    {"DefUnitX",
     "vs_1_1\ndef c0, 1, 0, 0, 1\n",
     {0xFFFE0101, 0x00000051, 0xA00F0000, 0x3F800000, 0x00000000, 0x00000000, 0x3F800000, 0x0000FFFF}},
    {"MovOPos", "vs_1_1\nmov oPos, v0\n", {0xFFFE0101, 0x00000001, 0xC00F0000, 0x90E40000, 0x0000FFFF}},
    {"Dp4Relative",
     "vs_1_1\ndp4 r1.x, v1, c[a0.x + 3]\n",
     {0xFFFE0101, 0x00000009, 0x80010001, 0x90E40001, 0xA0E42003, 0x0000FFFF}},
    {"MulSwizzles",
     "vs_1_1\nmul r2, r0.xyzz, r0.yzzx\n",
     {0xFFFE0101, 0x00000005, 0x800F0002, 0x80A40000, 0x80290000, 0x0000FFFF}},
    {"MovA0", "vs_1_1\nmov a0.x, c4.x\n", {0xFFFE0101, 0x00000001, 0xB0010000, 0xA0000004, 0x0000FFFF}},
    {"MovOFog", "vs_1_1\nmov oFog, r0.x\n", {0xFFFE0101, 0x00000001, 0xC00F0001, 0x80000000, 0x0000FFFF}},
    {"MovOPts", "vs_1_1\nmov oPts, c0.x\n", {0xFFFE0101, 0x00000001, 0xC00F0002, 0xA0000000, 0x0000FFFF}},
    {"MovOD1", "vs_1_1\nmov oD1, r3\n", {0xFFFE0101, 0x00000001, 0xD00F0001, 0x80E40003, 0x0000FFFF}},
    {"MovOT7", "vs_1_1\nmov oT7.xy, v2\n", {0xFFFE0101, 0x00000001, 0xE0030007, 0x90E40002, 0x0000FFFF}},
    {"AddNegated",
     "vs_1_1\nadd r0, -r0.x, -r1\n",
     {0xFFFE0101, 0x00000002, 0x800F0000, 0x81000000, 0x81E40001, 0x0000FFFF}},
    {"Dp4MaskXw",
     "vs_1_1\ndp4 r0.xw, r1.wzyx, r2.xxww\n",
     {0xFFFE0101, 0x00000009, 0x80090000, 0x801B0001, 0x80F00002, 0x0000FFFF}},
    {"RcpW", "vs_1_1\nrcp r0.w, r1.w\n", {0xFFFE0101, 0x00000006, 0x80080000, 0x80FF0001, 0x0000FFFF}},
    {"Sub", "vs_1_1\nsub r0, r1, c3\n", {0xFFFE0101, 0x00000003, 0x800F0000, 0x80E40001, 0xA0E40003, 0x0000FFFF}},
    {"M4x4", "vs_1_1\nm4x4 oPos, v0, c0\n", {0xFFFE0101, 0x00000014, 0xC00F0000, 0x90E40000, 0xA0E40000, 0x0000FFFF}},
    {"Lit", "vs_1_1\nlit r1, r0\n", {0xFFFE0101, 0x00000010, 0x800F0001, 0x80E40000, 0x0000FFFF}},
    {"Expp", "vs_1_1\nexpp r1.x, c6.y\n", {0xFFFE0101, 0x0000004E, 0x80010001, 0xA0550006, 0x0000FFFF}},
    {"Logp", "vs_1_1\nlogp r0, r0.w\n", {0xFFFE0101, 0x0000004F, 0x800F0000, 0x80FF0000, 0x0000FFFF}},
    {"Frc", "vs_1_1\nfrc r0.xy, r1\n", {0xFFFE0101, 0x00000013, 0x80030000, 0x80E40001, 0x0000FFFF}},
    {"GoldenProgram",
     "vs_1_1\ndcl_position v0\ndef c0, 1, 0, 0, 1\nmov oPos, v0\n",
     {0xFFFE0101, 0x0000001F, 0x80000000, 0x900F0000, 0x00000051, 0xA00F0000, 0x3F800000, 0x00000000, 0x00000000,
      0x3F800000, 0x00000001, 0xC00F0000, 0x90E40000, 0x0000FFFF}},
    // Native assembler arrays quoted in §4.9/§4.10/§4.5.
    {"DclNormal12", "vs_1_1\ndcl_normal12 v15\n", {0xFFFE0101, 0x0000001F, 0x800C0003, 0x900F000F, 0x0000FFFF}},
    {"DefNegativeAndLarge",
     "vs_1_1\ndef c12, 0, -1, -0.5, 1024\n",
     {0xFFFE0101, 0x00000051, 0xA00F000C, 0x00000000, 0xBF800000, 0xBF000000, 0x44800000, 0x0000FFFF}},
    {"MovRelativeWithBase",
     "vs_1_1\nmov r0, c1[a0.x + 2]\n",
     {0xFFFE0101, 0x00000001, 0x800F0000, 0xA0E42003, 0x0000FFFF}},
};
INSTANTIATE_TEST_SUITE_P(AssemblerWorkedEncodings, AssemblerEncoding, testing::ValuesIn(kWorkedEncodings),
                         [](const auto& info) { return info.param.name; });

// The opcodes §5 does not show, one each (opcode in the instruction token, §3.2).
const EncodingCase kOpcodes[] = {
    {"Nop", "vs_1_1\nnop\n", {0xFFFE0101, 0x00000000, 0x0000FFFF}},
    {"Mad",
     "vs_1_1\nmad r0, v0, c1, r1\n",
     {0xFFFE0101, 0x00000004, 0x800F0000, 0x90E40000, 0xA0E40001, 0x80E40001, 0x0000FFFF}},
    {"Rsq", "vs_1_1\nrsq r1.w, r0.x\n", {0xFFFE0101, 0x00000007, 0x80080001, 0x80000000, 0x0000FFFF}},
    {"Dp3", "vs_1_1\ndp3 r2.xyz, v3, c10\n", {0xFFFE0101, 0x00000008, 0x80070002, 0x90E40003, 0xA0E4000A, 0x0000FFFF}},
    {"Min", "vs_1_1\nmin r3, r1, c2.y\n", {0xFFFE0101, 0x0000000A, 0x800F0003, 0x80E40001, 0xA0550002, 0x0000FFFF}},
    {"Max",
     "vs_1_1\nmax r4.yw, r1.z, -c2.w\n",
     {0xFFFE0101, 0x0000000B, 0x800A0004, 0x80AA0001, 0xA1FF0002, 0x0000FFFF}},
    {"Slt", "vs_1_1\nslt r5, v0, c0\n", {0xFFFE0101, 0x0000000C, 0x800F0005, 0x90E40000, 0xA0E40000, 0x0000FFFF}},
    {"Sge", "vs_1_1\nsge r6.x, r1, r2\n", {0xFFFE0101, 0x0000000D, 0x80010006, 0x80E40001, 0x80E40002, 0x0000FFFF}},
    {"Exp", "vs_1_1\nexp r7.z, v1.y\n", {0xFFFE0101, 0x0000000E, 0x80040007, 0x90550001, 0x0000FFFF}},
    {"Log", "vs_1_1\nlog r8.yzw, r0.w\n", {0xFFFE0101, 0x0000000F, 0x800E0008, 0x80FF0000, 0x0000FFFF}},
    {"Dst", "vs_1_1\ndst r9, r1, r2\n", {0xFFFE0101, 0x00000011, 0x800F0009, 0x80E40001, 0x80E40002, 0x0000FFFF}},
    {"M4x3",
     "vs_1_1\nm4x3 r10.xyz, v0, c4\n",
     {0xFFFE0101, 0x00000015, 0x8007000A, 0x90E40000, 0xA0E40004, 0x0000FFFF}},
    {"M3x4", "vs_1_1\nm3x4 r11, v1, c8\n", {0xFFFE0101, 0x00000016, 0x800F000B, 0x90E40001, 0xA0E40008, 0x0000FFFF}},
    {"M3x3",
     "vs_1_1\nm3x3 oT0.xyz, v3, c12\n",
     {0xFFFE0101, 0x00000017, 0xE0070000, 0x90E40003, 0xA0E4000C, 0x0000FFFF}},
    {"M3x2Relative",
     "vs_1_1\nm3x2 oT1.xy, v4, c[a0.x + 16]\n",
     {0xFFFE0101, 0x00000018, 0xE0030001, 0x90E40004, 0xA0E42010, 0x0000FFFF}},
};
INSTANTIATE_TEST_SUITE_P(AssemblerOpcodes, AssemblerEncoding, testing::ValuesIn(kOpcodes),
                         [](const auto& info) { return info.param.name; });

// A destination without a mask gets the lanes the macro writes (Microsoft's assembler; MojoShader's
// opcode table records 0x7 for m3x3/m4x3 and 0x3 for m3x2): the DX8 SDK's SkinnedMesh shaders write
// `m4x3 r0, v0, c[a0.x]` and `m3x3 r5, v3, c0`. Every other opcode gets 0xF.
const EncodingCase kDefaultMasks[] = {
    {"M3x3WithoutMask",
     "vs_1_1\nm3x3 r5, v3, c0\n",
     {0xFFFE0101, 0x00000017, 0x80070005, 0x90E40003, 0xA0E40000, 0x0000FFFF}},
    {"M4x3RelativeWithoutMask",
     "vs.1.1\nm4x3 r0, v0, c[a0.x]\n",
     {0xFFFE0101, 0x00000015, 0x80070000, 0x90E40000, 0xA0E42000, 0x0000FFFF}},
    {"M3x2WithoutMask",
     "vs_1_1\nm3x2 oT0, v2, c12\n",
     {0xFFFE0101, 0x00000018, 0xE0030000, 0x90E40002, 0xA0E4000C, 0x0000FFFF}},
    {"M3x3FullMaskWritten",
     "vs_1_1\nm3x3 r5.xyzw, v3, c0\n",
     {0xFFFE0101, 0x00000017, 0x800F0005, 0x90E40003, 0xA0E40000, 0x0000FFFF}},
    {"M4x4AndM3x4WithoutMask",
     "vs_1_1\nm4x4 oPos, v0, c0\nm3x4 r1, v1, c4\n",
     {0xFFFE0101, 0x00000014, 0xC00F0000, 0x90E40000, 0xA0E40000, 0x00000016, 0x800F0001, 0x90E40001, 0xA0E40004,
      0x0000FFFF}},
    {"FrcWithoutMask", "vs_1_1\nfrc r0, v0\n", {0xFFFE0101, 0x00000013, 0x800F0000, 0x90E40000, 0x0000FFFF}},
};
INSTANTIATE_TEST_SUITE_P(AssemblerDefaultMasks, AssemblerEncoding, testing::ValuesIn(kDefaultMasks),
                         [](const auto& info) { return info.param.name; });

TEST(Assembler, MatrixMacrosWithoutMaskValidate) {
  // The SkinnedMesh pattern (DX8 SDK): no masks on m4x3/m3x3, and the result is accepted as written.
  AssembleResult result = AssembleForTest(
      "vs.1.1\nmul r1, v1.x, c2.x\nmov a0.x, r1.x\nm4x3 r0, v0, c[a0.x]\nm3x3 r5, v3, c[a0.x]\n"
      "mov r0.w, c1.x\nm4x4 oPos, r0, c4\nm3x2 oT0, r5, c8\nmov oFog.x, r5.x\n",
      /*validate=*/true);
  ASSERT_TRUE(result.program) << result.diagnostics.ToString();
  EXPECT_EQ(result.diagnostics.ToString(), "");
}

// dcl usages (§4.9: usage token 0x80000000 | index << 16 | usage) and def number spellings (§2.1).
const EncodingCase kDeclarations[] = {
    {"DclEveryUsage",
     "vs_1_1\ndcl_blendweight v1\ndcl_blendindices v2\ndcl_normal v3\ndcl_psize v4\ndcl_texcoord0 v5\n"
     "dcl_tangent v6\ndcl_binormal v7\ndcl_tessfactor v8\ndcl_positiont v9\ndcl_color1 v10\ndcl_fog v11\n"
     "dcl_depth v12\ndcl_sample15 v13\n",
     {0xFFFE0101, 0x1F, 0x80000001, 0x900F0001, 0x1F,      0x80000002, 0x900F0002, 0x1F, 0x80000003,
      0x900F0003, 0x1F, 0x80000004, 0x900F0004, 0x1F,      0x80000005, 0x900F0005, 0x1F, 0x80000006,
      0x900F0006, 0x1F, 0x80000007, 0x900F0007, 0x1F,      0x80000008, 0x900F0008, 0x1F, 0x80000009,
      0x900F0009, 0x1F, 0x8001000A, 0x900F000A, 0x1F,      0x8000000B, 0x900F000B, 0x1F, 0x8000000C,
      0x900F000C, 0x1F, 0x800F000D, 0x900F000D, 0x0000FFFF}},
    {"DclUpperCase", "vs_1_1\nDCL_TEXCOORD3 V2\n", {0xFFFE0101, 0x1F, 0x80030005, 0x900F0002, 0x0000FFFF}},
    {"DefNumberSpellings",
     "vs_1_1\ndef c1, 1., .5, -1.5f, 1e-3\n",
     {0xFFFE0101, 0x51, 0xA00F0001, 0x3F800000, 0x3F000000, 0xBFC00000, 0x3A83126F, 0x0000FFFF}},
    {"DefSignsSuffixAndExponent",
     "vs_1_1\ndef c2, +2, 1.0f, -0, 1E2\n",
     {0xFFFE0101, 0x51, 0xA00F0002, 0x40000000, 0x3F800000, 0x80000000, 0x42C80000, 0x0000FFFF}},
    {"DefNonFinite",
     "vs_1_1\ndef c95, inf, -inf, nan, -NaN\n",
     {0xFFFE0101, 0x51, 0xA00F005F, 0x7F800000, 0xFF800000, 0x7FC00000, 0xFFC00000, 0x0000FFFF}},
    {"DefExtremes",
     "vs_1_1\ndef c3, 3.40282347e+38, -1.17549435e-38, 1.40129846e-45, 127.9961f\n",
     {0xFFFE0101, 0x51, 0xA00F0003, 0x7F7FFFFF, 0x80800000, 0x00000001, 0x42FFFE01, 0x0000FFFF}},
};
INSTANTIATE_TEST_SUITE_P(AssemblerDeclarations, AssemblerEncoding, testing::ValuesIn(kDeclarations),
                         [](const auto& info) { return info.param.name; });

// Register files and every spelling of a constant index (§2.2).
const EncodingCase kRegisters[] = {
    {"TempAndInputHighest", "vs_1_1\nmov r11, v15\n", {0xFFFE0101, 0x1, 0x800F000B, 0x90E4000F, 0x0000FFFF}},
    {"ColourOutput", "vs_1_1\nmov oD0, c95\n", {0xFFFE0101, 0x1, 0xD00F0000, 0xA0E4005F, 0x0000FFFF}},
    {"ConstantInBrackets", "vs_1_1\nmov oT3, c[5]\n", {0xFFFE0101, 0x1, 0xE00F0003, 0xA0E40005, 0x0000FFFF}},
    {"ConstantSum", "vs_1_1\nmov r0, c[2 + 10 + 12]\n", {0xFFFE0101, 0x1, 0x800F0000, 0xA0E40018, 0x0000FFFF}},
    {"ConstantBasePlusIndex", "vs_1_1\nmov r0, c4[2]\n", {0xFFFE0101, 0x1, 0x800F0000, 0xA0E40006, 0x0000FFFF}},
    {"ConstantIndexWithBlanks", "vs_1_1\nmov r0, c [ 3 ]\n", {0xFFFE0101, 0x1, 0x800F0000, 0xA0E40003, 0x0000FFFF}},
    {"RelativeBare", "vs_1_1\nmov r0, c[a0.x]\n", {0xFFFE0101, 0x1, 0x800F0000, 0xA0E42000, 0x0000FFFF}},
    {"RelativeZeroBase", "vs_1_1\nmov r0, c0[a0.x]\n", {0xFFFE0101, 0x1, 0x800F0000, 0xA0E42000, 0x0000FFFF}},
    {"RelativePlusOffset", "vs_1_1\nmov r0, c[a0.x + 12]\n", {0xFFFE0101, 0x1, 0x800F0000, 0xA0E4200C, 0x0000FFFF}},
    {"RelativeOffsetFirst", "vs_1_1\nmov r0, c[12 + a0.x]\n", {0xFFFE0101, 0x1, 0x800F0000, 0xA0E4200C, 0x0000FFFF}},
    {"RelativeBetweenOffsets",
     "vs_1_1\nmov r0, c[2 + a0.x + 12]\n",
     {0xFFFE0101, 0x1, 0x800F0000, 0xA0E4200E, 0x0000FFFF}},
    {"RelativeWithMinus", "vs_1_1\nmov r0, c[a0.x + 5 - 2]\n", {0xFFFE0101, 0x1, 0x800F0000, 0xA0E42003, 0x0000FFFF}},
    {"RelativeNegatedReplicated",
     "vs_1_1\nmov r0, -c[a0.x + 3].x\n",
     {0xFFFE0101, 0x1, 0x800F0000, 0xA1002003, 0x0000FFFF}},
    {"LargestRegisterNumber", "vs_1_1\nmov r0, c2047\n", {0xFFFE0101, 0x1, 0x800F0000, 0xA0E407FF, 0x0000FFFF}},
    {"AddressWithoutMask", "vs_1_1\nmov a0, c0.x\n", {0xFFFE0101, 0x1, 0xB00F0000, 0xA0000000, 0x0000FFFF}},
    // Scalar outputs keep a written mask, as Microsoft's assembler does (shipped DX8 shaders write
    // `mov oFog.x, r11.x`); without one they get 0xF, like any register (Wine: `mov oFog, c0.x` ->
    // 0xC00F0001).
    {"ScalarOutputsKeepTheirMask",
     "vs_1_1\nmov oFog.x, r11.x\nmov oPts.w, r0.x\nmov oFog.xyzw, r0\nmov oFog.zw, r2.w\nmov oPts, c0.x\n",
     {0xFFFE0101, 0x1, 0xC0010001, 0x8000000B, 0x1, 0xC0080002, 0x80000000, 0x1, 0xC00F0001, 0x80E40000,
      0x1, 0xC00C0001, 0x80FF0002, 0x1, 0xC00F0002, 0xA0000000, 0x0000FFFF}},
};
INSTANTIATE_TEST_SUITE_P(AssemblerRegisters, AssemblerEncoding, testing::ValuesIn(kRegisters),
                         [](const auto& info) { return info.param.name; });

// Write masks (bits 16-19: x 1, y 2, z 4, w 8) and swizzles (two bits per lane, x lowest; §2.4
// repeats the last letter).
const EncodingCase kMasksAndSwizzles[] = {
    {"MaskXz", "vs_1_1\nmov r0.xz, r1\n", {0xFFFE0101, 0x1, 0x80050000, 0x80E40001, 0x0000FFFF}},
    {"MaskYzw", "vs_1_1\nmov r0.yzw, r1\n", {0xFFFE0101, 0x1, 0x800E0000, 0x80E40001, 0x0000FFFF}},
    {"MaskFullWritten", "vs_1_1\nmov r0.xyzw, r1\n", {0xFFFE0101, 0x1, 0x800F0000, 0x80E40001, 0x0000FFFF}},
    {"MaskRgbAndA",
     "vs_1_1\nmov r0.rgb, r1\nmov r0.a, r1\n",
     {0xFFFE0101, 0x1, 0x80070000, 0x80E40001, 0x1, 0x80080000, 0x80E40001, 0x0000FFFF}},
    {"SwizzleFullIdentity", "vs_1_1\nmov r0, r1.xyzw\n", {0xFFFE0101, 0x1, 0x800F0000, 0x80E40001, 0x0000FFFF}},
    {"SwizzleReplicated",
     "vs_1_1\nmov r0, r1.x\nmov r0, r1.y\nmov r0, r1.z\nmov r0, r1.w\n",
     {0xFFFE0101, 0x1, 0x800F0000, 0x80000001, 0x1, 0x800F0000, 0x80550001, 0x1, 0x800F0000, 0x80AA0001, 0x1,
      0x800F0000, 0x80FF0001, 0x0000FFFF}},
    {"SwizzleTwoLetters",
     "vs_1_1\nmov r0, r1.xy\nmov r0, r1.zw\n",
     {0xFFFE0101, 0x1, 0x800F0000, 0x80540001, 0x1, 0x800F0000, 0x80FE0001, 0x0000FFFF}},
    {"SwizzleThreeLetters",
     "vs_1_1\nmov r0, r1.xyz\nmov r0, r1.yzx\n",
     {0xFFFE0101, 0x1, 0x800F0000, 0x80A40001, 0x1, 0x800F0000, 0x80090001, 0x0000FFFF}},
    {"SwizzleRgbaLetters",
     "vs_1_1\nmov r0, r1.bgra\nmov r0, r1.rgb\n",
     {0xFFFE0101, 0x1, 0x800F0000, 0x80C60001, 0x1, 0x800F0000, 0x80A40001, 0x0000FFFF}},
    {"SwizzleFourLetters", "vs_1_1\nmov r0, v1.wwxy\n", {0xFFFE0101, 0x1, 0x800F0000, 0x904F0001, 0x0000FFFF}},
    {"NegationOnEveryFile",
     "vs_1_1\nmad r0, -v0, -c1.z, -r1.yx\n",
     {0xFFFE0101, 0x4, 0x800F0000, 0x91E40000, 0xA1AA0001, 0x81010001, 0x0000FFFF}},
};
INSTANTIATE_TEST_SUITE_P(AssemblerMasksAndSwizzles, AssemblerEncoding, testing::ValuesIn(kMasksAndSwizzles),
                         [](const auto& info) { return info.param.name; });

// Case, layout, comments, the preprocessor and DX8 syntax (§2.1).
const EncodingCase kTextForms[] = {
    {"UpperCaseEverything",
     "VS_1_1\nMOV R0.XY, C[A0.X + 1].W\nMOV OPOS, V0\nMOV OPTS, C0.X\nMOV OT2, V1\nMOV OD0, V2\n",
     {0xFFFE0101, 0x1, 0x80030000, 0xA0FF2001, 0x1, 0xC00F0000, 0x90E40000, 0x1, 0xC00F0002, 0xA0000000, 0x1,
      0xE00F0002, 0x90E40001, 0x1, 0xD00F0000, 0x90E40002, 0x0000FFFF}},
    {"UpperCaseDx8Version", "VS.1.1\nMov oPos, v0\n", {0xFFFE0101, 0x1, 0xC00F0000, 0x90E40000, 0x0000FFFF}},
    {"SemicolonComments",
     "; header comment\nvs_1_1 ; version\nmov oPos, v0 ; it's a \"comment\n",
     {0xFFFE0101, 0x1, 0xC00F0000, 0x90E40000, 0x0000FFFF}},
    {"SlashComments",
     "// header\nvs_1_1 // version\nmov oPos, v0 // position\n",
     {0xFFFE0101, 0x1, 0xC00F0000, 0x90E40000, 0x0000FFFF}},
    {"BlockComments",
     "/* a block\n   over lines */ vs_1_1\nmov /* inline */ oPos, v0\n/* mov r0, r1 */\n",
     {0xFFFE0101, 0x1, 0xC00F0000, 0x90E40000, 0x0000FFFF}},
    {"CrLfLineEndings",
     "vs_1_1\r\ndcl_position v0\r\nmov oPos, v0\r\n",
     {0xFFFE0101, 0x1F, 0x80000000, 0x900F0000, 0x1, 0xC00F0000, 0x90E40000, 0x0000FFFF}},
    {"LastLineWithoutNewline", "vs_1_1\nmov oPos, v0", {0xFFFE0101, 0x1, 0xC00F0000, 0x90E40000, 0x0000FFFF}},
    {"BlankLinesTabsAndSpaces",
     "\n\n  vs_1_1\n\n\t mov\toPos ,v0   \n\n",
     {0xFFFE0101, 0x1, 0xC00F0000, 0x90E40000, 0x0000FFFF}},
    {"Dx8DefinedConstantNames",
     "#define CV_WORLD 4\n#define POS v0\nvs.1.1\ndp4 oPos.x, POS, c[CV_WORLD + 0]\n"
     "dp4 oPos.y, POS, c[CV_WORLD+1]\nm4x4 oT0, v1, c[CV_WORLD + 2]\nmov r0, c[a0.x + CV_WORLD]\n",
     {0xFFFE0101, 0x9, 0xC0010000, 0x90E40000, 0xA0E40004, 0x9, 0xC0020000, 0x90E40000, 0xA0E40005, 0x14, 0xE00F0000,
      0x90E40001, 0xA0E40006, 0x1, 0x800F0000, 0xA0E42004, 0x0000FFFF}},
    {"Dx8FunctionLikeMacro",
     "#define ROW(base, n) c[base + n]\nvs.1.1\ndp4 oPos.z, v0, ROW(8, 2)\n",
     {0xFFFE0101, 0x9, 0xC0040000, 0x90E40000, 0xA0E4000A, 0x0000FFFF}},
    {"PreprocessorInclude",
     "#include \"constants.h\"\nvs.1.1\ndp3 r0, v3, -c[CV_LIGHT_DIR]\n#include \"body.vsh\"\n",
     {0xFFFE0101, 0x8, 0x800F0000, 0x90E40003, 0xA1E40007, 0x1, 0xC00F0000, 0x90E40000, 0x0000FFFF}},
    {"PreprocessorConditional",
     "#define USE_FOG 1\nvs_1_1\n#if USE_FOG\nmov oFog, v0.w\n#else\nmov oFog, c0.x\n#endif\n",
     {0xFFFE0101, 0x1, 0xC00F0001, 0x90FF0000, 0x0000FFFF}},
    {"DclAndDefInSourceOrder",
     "vs_1_1\ndef c5, 1, 1, 1, 1\ndcl_normal v3\nmov r0, c5\n",
     {0xFFFE0101, 0x51, 0xA00F0005, 0x3F800000, 0x3F800000, 0x3F800000, 0x3F800000, 0x1F, 0x80000003, 0x900F0003, 0x1,
      0x800F0000, 0xA0E40005, 0x0000FFFF}},
    {"Dx8Version10", "vs.1.0\nmov oPos, v0\n", {0xFFFE0100, 0x1, 0xC00F0000, 0x90E40000, 0x0000FFFF}},
};
INSTANTIATE_TEST_SUITE_P(AssemblerTextForms, AssemblerEncoding, testing::ValuesIn(kTextForms),
                         [](const auto& info) { return info.param.name; });

TEST(Assembler, RecordsSourceLocationOfEveryInstruction) {
  AssembleResult result = AssembleForTest("vs_1_1\n\ndcl_position v0\n  def c0, 1, 0, 0, 1\n\tmov oPos, v0\n");
  ASSERT_TRUE(result.program) << result.diagnostics.ToString();
  ASSERT_EQ(result.program->source_locs.size(), 3u);
  EXPECT_EQ(result.program->source_locs[0], (SourceLoc{"test.vsh", 3, 1}));
  EXPECT_EQ(result.program->source_locs[1], (SourceLoc{"test.vsh", 4, 3}));
  EXPECT_EQ(result.program->source_locs[2].line, 5);
}

TEST(Assembler, ReportsWhichSyntaxTheVersionLineUsed) {
  EXPECT_TRUE(AssembleForTest("vs_1_1\n").dx9_syntax);
  EXPECT_FALSE(AssembleForTest("vs.1.1\n").dx9_syntax);
  EXPECT_FALSE(AssembleForTest("vs.1.0\n").dx9_syntax);
}

TEST(Assembler, ValidatesCompleteDx9Program) {
  AssembleResult result = AssembleForTest(
      "vs_1_1\ndcl_position v0\ndcl_normal v3\ndef c0, 1, 0, 0, 1\nm4x4 oPos, v0, c4\n"
      "dp3 r0.x, v3, c8\nmax r0.x, r0.x, c0.y\nmul oD0, r0.x, c9\nmov oT0.xy, v0\n",
      /*validate=*/true);
  EXPECT_TRUE(result.program) << result.diagnostics.ToString();
}

TEST(Assembler, ValidatesDx8ProgramWithoutDcl) {
  AssembleResult result = AssembleForTest("vs.1.1\nm4x4 oPos, v0, c0\nmov oD0, v5\n", /*validate=*/true);
  EXPECT_TRUE(result.program) << result.diagnostics.ToString();
}

TEST(Assembler, Dx8ProgramWithDclFollowsTheDclRules) {
  // Its tokens are a DX9 program's: loaded as bytecode or disassembled, they get the DX9 rules, so the
  // source gets them too.
  AssembleResult result =
      AssembleForTest("vs.1.1\ndcl_position v0\nmov oPos, v0\nmov oD0, v1\n", /*validate=*/true);
  EXPECT_FALSE(result.program);
  ASSERT_EQ(result.diagnostics.all().size(), 1u) << result.diagnostics.ToString();
  EXPECT_EQ(result.diagnostics.all()[0].code, DiagnosticCode::kUndeclaredInput);
  EXPECT_EQ(result.diagnostics.all()[0].loc, (SourceLoc{"test.vsh", 4, 1}));
}

TEST(Assembler, ValidatorErrorsWithholdTheProgram) {
  // Two constants in one instruction (§1.7): syntactically fine, rejected by the validator.
  const std::string source = "vs_1_1\nmov oPos, c0\nadd r0, c1, c2\n";
  EXPECT_TRUE(AssembleForTest(source, /*validate=*/false).program);
  AssembleResult validated = AssembleForTest(source, /*validate=*/true);
  EXPECT_FALSE(validated.program);
  ASSERT_TRUE(validated.diagnostics.HasErrors());
  for (const Diagnostic& d : validated.diagnostics.all()) {
    if (d.severity == Severity::kError) {
      EXPECT_EQ(d.loc.line, 3) << d.message;
      EXPECT_EQ(d.code, DiagnosticCode::kReadPorts) << d.message;
    }
  }
}

TEST(Assembler, ConstantCountOptionReachesTheValidator) {
  AssembleOptions options;
  options.constant_count = 256;
  const std::string source = "vs_1_1\nmov oPos, c200\n";
  EXPECT_TRUE(AssembleSource(source, "test.vsh", options, ReadTestFile).program);
  options.constant_count = kDefaultConstantCount;
  EXPECT_FALSE(AssembleSource(source, "test.vsh", options, ReadTestFile).program);
}

TEST(Assembler, CommandLineDefinesReachThePreprocessor) {
  AssembleOptions options;
  options.validate = false;
  options.preprocess.defines = {{"CV_BASE", "8"}, {"FLAG", ""}};
  AssembleResult result =
      AssembleSource("vs.1.1\n#ifdef FLAG\nmov r0, c[CV_BASE + a0.x]\n#endif\n", "test.vsh", options, ReadTestFile);
  ASSERT_TRUE(result.program) << result.diagnostics.ToString();
  EXPECT_EQ(Encode(*result.program), (Words{0xFFFE0101, 0x1, 0x800F0000, 0xA0E42008, 0x0000FFFF}));
}

TEST(Assembler, AssemblesFileFromDisk) {
  std::filesystem::path path = std::filesystem::temp_directory_path() / "vs11_assembler_test.vsh";
  std::ofstream(path) << "vs_1_1\ndcl_position v0\nmov oPos, v0\n";
  AssembleResult result = AssembleFile(path, AssembleOptions{});
  std::filesystem::remove(path);
  ASSERT_TRUE(result.program) << result.diagnostics.ToString();
  EXPECT_EQ(Encode(*result.program),
            (Words{0xFFFE0101, 0x1F, 0x80000000, 0x900F0000, 0x1, 0xC00F0000, 0x90E40000, 0x0000FFFF}));
  EXPECT_EQ(result.program->source_locs[0].file, path.string());
}

TEST(Assembler, UnreadableFileIsAnError) {
  AssembleResult result = AssembleFile("/nonexistent/vs11/missing.vsh", AssembleOptions{});
  EXPECT_FALSE(result.program);
  ASSERT_TRUE(result.diagnostics.HasErrors());
  EXPECT_EQ(result.diagnostics.all().front().loc.file, "/nonexistent/vs11/missing.vsh");
  EXPECT_EQ(result.diagnostics.all().front().code, DiagnosticCode::kCannotReadFile);
}

TEST(Assembler, IgnoresUnderflowWithAWarning) {
  AssembleResult result = AssembleForTest("vs_1_1\ndef c0, 1e-50, 0, 0, 0\n");
  ASSERT_TRUE(result.program) << result.diagnostics.ToString();
  EXPECT_EQ(result.program->instructions[0].def_bits[0], 0u);
  ASSERT_EQ(result.diagnostics.all().size(), 1u);
  EXPECT_EQ(result.diagnostics.all()[0].severity, Severity::kWarning);
  EXPECT_EQ(result.diagnostics.all()[0].code, DiagnosticCode::kNumberUnderflow);
}

}  // namespace
}  // namespace vs11

// D3D8 declaration tokens, D3D9 declarations and FVF codes as the C library reads them. The token
// values are written out as d3d8types.h's macros make them.
#include "vm/capi/layouts.h"

#include <bit>
#include <vector>

#include <gtest/gtest.h>

namespace vs11::capi {
namespace {

constexpr std::uint32_t Stream(std::uint32_t n) { return 0x20000000u | n; }                 // D3DVSD_STREAM
constexpr std::uint32_t Reg(std::uint32_t r, std::uint32_t t) { return 0x40000000u | t << 16 | r; }  // D3DVSD_REG
constexpr std::uint32_t Skip(std::uint32_t n) { return 0x50000000u | n << 16; }              // D3DVSD_SKIP
constexpr std::uint32_t Const(std::uint32_t a, std::uint32_t n) { return 0x80000000u | n << 25 | a; }  // D3DVSD_CONST
constexpr std::uint32_t kEnd = 0xFFFFFFFFu;                                                   // D3DVSD_END
constexpr std::uint32_t kFloat3 = 2, kColor = 4, kUbyte4 = 5, kShort2 = 6;                    // D3DVSDT_

void ExpectInput(const InputElement& input, int stream, std::size_t offset, DeclType type, int reg) {
  EXPECT_EQ(input.stream, stream);
  EXPECT_EQ(input.offset, offset);
  EXPECT_EQ(input.type, type);
  EXPECT_EQ(input.reg, reg);
}

TEST(D3d8Declaration, StreamsRegistersSkipsAndConstants) {
  const std::vector<std::uint32_t> tokens = {
      Stream(0), Reg(0, kFloat3), Reg(3, kColor), Skip(2), Reg(7, kShort2), Stream(1), Reg(1, kUbyte4), Const(4, 1),
      std::bit_cast<std::uint32_t>(1.0f), std::bit_cast<std::uint32_t>(2.0f), std::bit_cast<std::uint32_t>(3.0f),
      std::bit_cast<std::uint32_t>(4.0f), 0 /* NOP */, kEnd};
  const auto result = ParseD3d8Declaration(tokens, 96);
  ASSERT_TRUE(std::holds_alternative<D3d8Declaration>(result)) << std::get<LayoutError>(result).message;
  const D3d8Declaration& declaration = std::get<D3d8Declaration>(result);
  ASSERT_EQ(declaration.inputs.size(), 4u);
  ExpectInput(declaration.inputs[0], 0, 0, DeclType::kFloat3, 0);
  ExpectInput(declaration.inputs[1], 0, 12, DeclType::kD3dColor, 3);
  ExpectInput(declaration.inputs[2], 0, 24, DeclType::kShort2, 7);  // 16 + two skipped DWORDs
  ExpectInput(declaration.inputs[3], 1, 0, DeclType::kUbyte4, 1);
  ASSERT_EQ(declaration.constants.size(), 1u);
  EXPECT_EQ(declaration.constants[0].first, 4);
  EXPECT_EQ(declaration.constants[0].second, (Vec4f{1, 2, 3, 4}));
}

struct BadDeclaration {
  const char* name;
  std::vector<std::uint32_t> tokens;
  vs11c_status status;
  long token;
};

class D3d8DeclarationRejects : public ::testing::TestWithParam<BadDeclaration> {};

TEST_P(D3d8DeclarationRejects, NamingTheToken) {
  const auto result = ParseD3d8Declaration(GetParam().tokens, 96);
  ASSERT_TRUE(std::holds_alternative<LayoutError>(result));
  EXPECT_EQ(std::get<LayoutError>(result).status, GetParam().status) << std::get<LayoutError>(result).message;
  EXPECT_EQ(std::get<LayoutError>(result).token, GetParam().token);
}

INSTANTIATE_TEST_SUITE_P(
    Cases, D3d8DeclarationRejects,
    ::testing::Values(BadDeclaration{"RegisterBeforeStream", {Reg(0, kFloat3), kEnd}, VS11C_BAD_DECLARATION, 0},
                      BadDeclaration{"NoEnd", {Stream(0), Reg(0, kFloat3)}, VS11C_BAD_DECLARATION, 2},
                      BadDeclaration{"RegisterSixteen", {Stream(0), Reg(16, kFloat3), kEnd}, VS11C_BAD_DECLARATION, 1},
                      BadDeclaration{"DataTypeEight", {Stream(0), Reg(0, 8), kEnd}, VS11C_BAD_DECLARATION, 1},
                      BadDeclaration{"RegisterTwice", {Stream(0), Reg(2, kFloat3), Reg(2, kColor), kEnd}, VS11C_BAD_DECLARATION, 2},
                      BadDeclaration{"ConstantsBeyondTheBank", {Const(95, 2), 0, 0, 0, 0, 0, 0, 0, 0, kEnd}, VS11C_REGISTER_OUT_OF_RANGE, 0},
                      BadDeclaration{"ConstantDataCut", {Const(0, 1), 0, 0, kEnd}, VS11C_BAD_DECLARATION, 0},
                      BadDeclaration{"Tessellator", {Stream(0), 0x60000000u, kEnd}, VS11C_UNSUPPORTED, 1},
                      BadDeclaration{"TokenTypeSix", {0xC0000000u, kEnd}, VS11C_BAD_DECLARATION, 0}),
    [](const auto& info) { return info.param.name; });

constexpr vs11c_vertex_element kEndElement = VS11C_DECL_END;

TEST(D3d9Declaration, BindsElementsToTheDclOfTheirUsage) {
  Program program;
  Instruction dcl;
  dcl.opcode = Opcode::kDcl;
  dcl.dest.reg = {RegisterFile::kInput, 5, false};
  dcl.usage = static_cast<int>(DeclUsage::kTexCoord);
  dcl.usage_index = 1;
  program.instructions.push_back(dcl);
  const vs11c_vertex_element elements[] = {{0, 0, 2, 0, 0, 0}, {1, 8, 9, 0, 5, 1}, kEndElement};
  const auto read = ReadD3d9Declaration(elements);
  ASSERT_TRUE(std::holds_alternative<std::vector<vs11c_vertex_element>>(read));
  const std::vector<InputElement> inputs = BindD3d9Inputs(program, std::get<std::vector<vs11c_vertex_element>>(read));
  ASSERT_EQ(inputs.size(), 1u);  // POSITION has no dcl: not read
  ExpectInput(inputs[0], 1, 8, DeclType::kShort2n, 5);
}

TEST(D3d9Declaration, RejectsBadTypesMethodsAndRepeatedUsages) {
  const vs11c_vertex_element bad_type[] = {{0, 0, 17, 0, 0, 0}, kEndElement};
  const vs11c_vertex_element method[] = {{0, 0, 2, 1, 0, 0}, kEndElement};
  const vs11c_vertex_element twice[] = {{0, 0, 2, 0, 3, 0}, {0, 12, 2, 0, 3, 0}, kEndElement};
  const vs11c_vertex_element stream[] = {{16, 0, 2, 0, 3, 0}, kEndElement};
  EXPECT_EQ(std::get<LayoutError>(ReadD3d9Declaration(bad_type)).status, VS11C_BAD_DECLARATION);
  EXPECT_EQ(std::get<LayoutError>(ReadD3d9Declaration(method)).status, VS11C_UNSUPPORTED);
  EXPECT_EQ(std::get<LayoutError>(ReadD3d9Declaration(twice)).token, 1);
  EXPECT_EQ(std::get<LayoutError>(ReadD3d9Declaration(stream)).status, VS11C_BAD_DECLARATION);
  std::vector<vs11c_vertex_element> endless(65, vs11c_vertex_element{0, 0, 2, 0, 5, 0});
  for (int i = 0; i < 65; ++i) {  // 65 distinct usages: the limit, not a repeat, is what fails
    endless[static_cast<std::size_t>(i)].usage = static_cast<std::uint8_t>(i / 16);
    endless[static_cast<std::size_t>(i)].usage_index = static_cast<std::uint8_t>(i % 16);
  }
  endless.push_back(kEndElement);
  EXPECT_EQ(std::get<LayoutError>(ReadD3d9Declaration(endless.data())).token, 64);
}

constexpr std::uint32_t kFvfXyzRhw = 0x004, kFvfXyz = 0x002, kFvfDiffuse = 0x040, kFvfSpecular = 0x080, kFvfTex2 = 0x200;
constexpr std::uint32_t kFvfPointSize = 0x020;
constexpr std::uint32_t TexCoordSize3(int n) { return 1u << (n * 2 + 16); }  // D3DFVF_TEXCOORDSIZE3
constexpr std::uint32_t TexCoordSize1(int n) { return 3u << (n * 2 + 16); }  // D3DFVF_TEXCOORDSIZE1

TEST(FvfOutput, ElementsInFvfOrderWithTexCoordSizes) {
  const std::uint32_t fvf = kFvfXyzRhw | kFvfPointSize | kFvfDiffuse | kFvfSpecular | kFvfTex2 | TexCoordSize3(0) | TexCoordSize1(1);
  const auto result = OutputsFromFvf(fvf, 44);
  ASSERT_TRUE(std::holds_alternative<std::vector<OutputElement>>(result)) << std::get<LayoutError>(result).message;
  const auto& outputs = std::get<std::vector<OutputElement>>(result);
  ASSERT_EQ(outputs.size(), 6u);
  const std::size_t offsets[] = {0, 16, 20, 24, 28, 40};
  const DeclType types[] = {DeclType::kFloat4, DeclType::kFloat1, DeclType::kD3dColor, DeclType::kD3dColor,
                            DeclType::kFloat3, DeclType::kFloat1};
  const OutputSlot slots[] = {OutputSlot::kPosition, OutputSlot::kPointSize, OutputSlot::kDiffuse, OutputSlot::kSpecular,
                              OutputSlot::kTexCoord0, static_cast<OutputSlot>(static_cast<int>(OutputSlot::kTexCoord0) + 1)};
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    EXPECT_EQ(outputs[i].offset, offsets[i]) << i;
    EXPECT_EQ(outputs[i].type, types[i]) << i;
    EXPECT_EQ(outputs[i].slot, static_cast<int>(slots[i])) << i;
  }
  EXPECT_TRUE(outputs[0].transformed);
  EXPECT_EQ(std::get<LayoutError>(OutputsFromFvf(fvf, 43)).status, VS11C_BAD_DECLARATION);  // stride too small
}

TEST(FvfOutput, RejectsWhatNoShaderWrites) {
  EXPECT_EQ(std::get<LayoutError>(OutputsFromFvf(0x006 /* XYZB1 */, 64)).status, VS11C_UNSUPPORTED);
  EXPECT_EQ(std::get<LayoutError>(OutputsFromFvf(kFvfXyz | 0x010 /* NORMAL */, 64)).status, VS11C_UNSUPPORTED);
  EXPECT_EQ(std::get<LayoutError>(OutputsFromFvf(kFvfXyz | 0x900 /* TEX9 */, 256)).status, VS11C_BAD_DECLARATION);
  EXPECT_EQ(std::get<LayoutError>(OutputsFromFvf(kFvfXyz | 0x1000, 64)).status, VS11C_BAD_DECLARATION);
}

TEST(DeclarationOutput, UsagesNameOutputRegisters) {
  const vs11c_vertex_element declaration[] = {{0, 0, 3, 0, 9, 0}, {0, 16, 4, 0, 10, 1}, {0, 20, 1, 0, 5, 7}, kEndElement};
  const auto result = OutputsFromDeclaration(declaration, 28);
  ASSERT_TRUE(std::holds_alternative<std::vector<OutputElement>>(result)) << std::get<LayoutError>(result).message;
  const auto& outputs = std::get<std::vector<OutputElement>>(result);
  ASSERT_EQ(outputs.size(), 3u);
  EXPECT_EQ(outputs[0].slot, static_cast<int>(OutputSlot::kPosition));
  EXPECT_TRUE(outputs[0].transformed);  // POSITIONT
  EXPECT_EQ(outputs[1].slot, static_cast<int>(OutputSlot::kSpecular));
  EXPECT_EQ(outputs[2].slot, static_cast<int>(OutputSlot::kTexCoord0) + 7);
  const vs11c_vertex_element normal[] = {{0, 0, 2, 0, 3, 0}, kEndElement};
  EXPECT_EQ(std::get<LayoutError>(OutputsFromDeclaration(normal, 12)).status, VS11C_UNSUPPORTED);
  const vs11c_vertex_element packed[] = {{0, 0, 9, 0, 5, 0}, kEndElement};
  EXPECT_EQ(std::get<LayoutError>(OutputsFromDeclaration(packed, 12)).status, VS11C_UNSUPPORTED);
}

}  // namespace
}  // namespace vs11::capi

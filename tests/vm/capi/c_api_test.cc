// The C library (include/vs11/vs11_c.h) through its C functions: D3D9 and D3D8 shaders over
// interleaved streams, FVF and declaration outputs, validation messages, engines and float rules.
#include <vs11/vs11_c.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "tests/vm/capi/capi_test_support.h"

namespace vs11::capi {
namespace {

using testing::Tokens;

constexpr std::uint32_t kFvfXyz = 0x002, kFvfXyzRhw = 0x004, kFvfXyzW = 0x4002, kFvfDiffuse = 0x040,
                        kFvfSpecular = 0x080, kFvfTex1 = 0x100;
constexpr vs11c_vertex_element kEnd = VS11C_DECL_END;
// Over testing::MakeTwoStreams: stream 1's SHORT4N (NORMAL) is declared, but no dcl_ reads it.
constexpr vs11c_vertex_element kTwoStreams[] = {
    {0, 0, 2, 0, 0, 0}, {0, 12, 4, 0, 10, 0}, {1, 0, 15, 0, 5, 0}, {1, 4, 14, 0, 1, 0}, {1, 8, 10, 0, 3, 0}, kEnd};
constexpr std::size_t kOutputStride = 36;  // XYZW, DIFFUSE, SPECULAR, TEX1 (two floats) and 4 bytes of padding

struct ShaderHandle {
  vs11c_shader* shader = nullptr;
  ~ShaderHandle() { vs11c_shader_destroy(shader); }
};

void SetTwoStreamConstants(vs11c_shader* shader) {
  const float constants[] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 2, 2, 1, 1, 0.25f, 0, 0, 0};
  ASSERT_EQ(vs11c_shader_set_constants(shader, 0, constants, 6), VS11C_OK);
}

std::vector<std::uint8_t> RunTwoStreams(const char* engine, std::size_t count) {
  ShaderHandle handle;
  const std::vector<std::uint32_t> tokens = Tokens(testing::kD3d9Program);
  EXPECT_EQ(vs11c_shader_create_d3d9(tokens.data(), tokens.size(), nullptr, &handle.shader), VS11C_OK);
  if (handle.shader == nullptr) return {};
  SetTwoStreamConstants(handle.shader);
  EXPECT_EQ(vs11c_shader_set_engine(handle.shader, engine, VS11C_FLOAT_RULES_D3D9), VS11C_OK);
  const testing::TwoStreams input = testing::MakeTwoStreams(count);
  const vs11c_stream streams[] = {{input.stream0.data(), input.kStride0}, {input.stream1.data(), input.kStride1}};
  std::vector<std::uint8_t> output(count * kOutputStride, 0xAB);
  const vs11c_output layout{output.data(), kOutputStride, kFvfXyzW | kFvfDiffuse | kFvfSpecular | kFvfTex1, nullptr, nullptr};
  EXPECT_EQ(vs11c_process_vertices(handle.shader, kTwoStreams, streams, 2, count, &layout), VS11C_OK);
  return output;
}

template <class T>
T At(const std::vector<std::uint8_t>& bytes, std::size_t offset) {
  T value;
  std::memcpy(&value, bytes.data() + offset, sizeof value);
  return value;
}

TEST(CApi, D3d9ShaderOverTwoInterleavedStreamsWritesTheFvfVertex) {
  constexpr std::size_t kCount = 9000;  // two whole chunks of the library's loop (arrays reused) and a part
  const std::vector<std::uint8_t> output = RunTwoStreams("ref", kCount);
  ASSERT_EQ(output.size(), kCount * kOutputStride);
  for (std::size_t i : {std::size_t{0}, std::size_t{7}, std::size_t{4097}, std::size_t{8199}, std::size_t{8999}}) {
    const std::size_t at = i * kOutputStride;
    EXPECT_EQ(At<float>(output, at), static_cast<float>(i));  // identity m4x4
    EXPECT_EQ(At<float>(output, at + 4), 0.5f);
    EXPECT_EQ(At<float>(output, at + 8), -2.0f);
    EXPECT_EQ(At<float>(output, at + 12), 1.0f);
    EXPECT_EQ(At<std::uint32_t>(output, at + 16), 0x80FF2000u + (i & 0xFF)) << "D3DCOLOR read and written back";
    // DEC3N (511, -512, i) / 511: x 1, y below -1 clamped to 0, z i / 511; w 1.
    const auto blue = static_cast<std::uint32_t>(std::nearbyint(static_cast<float>(i & 0x3FF) / 511.0f * 255.0f));
    if ((i & 0x3FF) < 512) {
      EXPECT_EQ(At<std::uint32_t>(output, at + 20), 0xFFFF0000u | blue) << i;
    }
    EXPECT_EQ(At<float>(output, at + 24), 2.25f);  // half 1.0 * 2 + 0.25
    EXPECT_EQ(At<float>(output, at + 28), -1.0f);  // half -0.5 * 2
    EXPECT_EQ(At<std::uint32_t>(output, at + 32), 0xABABABABu) << "padding no element names stays";
  }
}

TEST(CApi, EveryEngineWritesTheReferenceBytes) {
  const std::vector<std::uint8_t> reference = RunTwoStreams("reference", 1000);
  for (const char* engine : {"batch", "jit", static_cast<const char*>(nullptr)}) {
    EXPECT_EQ(RunTwoStreams(engine, 1000), reference) << (engine ? engine : "default");
  }
}

TEST(CApi, D3d8ShaderReadsRegistersFromItsDeclarationAndLoadsItsConstants) {
  const std::vector<std::uint32_t> tokens = Tokens("vs.1.1\nmov oPos, v0\nmul oD0, v3, c5\n");
  const std::uint32_t declaration[] = {0x20000000u /* STREAM(0) */, 0x40020000u /* REG(0, FLOAT3) */,
                                       0x40040003u /* REG(3, D3DCOLOR) */, 0x82000005u /* CONST(5, 1) */,
                                       std::bit_cast<std::uint32_t>(0.5f), std::bit_cast<std::uint32_t>(0.5f),
                                       std::bit_cast<std::uint32_t>(0.5f), std::bit_cast<std::uint32_t>(2.0f),
                                       0xFFFFFFFFu};
  ShaderHandle handle;
  ASSERT_EQ(vs11c_shader_create_d3d8(declaration, std::size(declaration), tokens.data(), tokens.size(), nullptr,
                                     &handle.shader),
            VS11C_OK);
  std::vector<std::uint8_t> vertex;
  testing::Put(vertex, 1.0f), testing::Put(vertex, 2.0f), testing::Put(vertex, 3.0f);
  testing::Put(vertex, 0x40FF8000u);  // A 0x40, R 0xFF, G 0x80, B 0
  const vs11c_stream stream{vertex.data(), 16};
  std::vector<std::uint8_t> output(16);
  const vs11c_output layout{output.data(), 16, kFvfXyz | kFvfDiffuse, nullptr, nullptr};
  ASSERT_EQ(vs11c_process_vertices(handle.shader, nullptr, &stream, 1, 1, &layout), VS11C_OK);
  EXPECT_EQ(At<float>(output, 0), 1.0f);
  EXPECT_EQ(At<float>(output, 8), 3.0f);
  // (1, 128/255, 0, 64/255) * (0.5, 0.5, 0.5, 2): R 127.5 rounds to even 128, G 64, A 128.
  EXPECT_EQ(At<std::uint32_t>(output, 12), 0x80804000u);
  EXPECT_EQ(vs11c_process_vertices(handle.shader, kTwoStreams, &stream, 1, 1, &layout), VS11C_INVALID_ARGUMENT)
      << "a D3D8 shader takes no D3D9 declaration";
}

TEST(CApi, ValidationGivesCodeTextAndInstruction) {
  const std::vector<std::uint32_t> tokens = Tokens("vs.1.1\nmov oPos, c0\nmov oD0, v1\n");  // no dcl: D3D8 only
  std::array<vs11c_message, 4> messages{};
  std::size_t count = 0;
  EXPECT_EQ(vs11c_validate_d3d9(tokens.data(), tokens.size(), nullptr, messages.data(), messages.size(), &count),
            VS11C_INVALID_SHADER);
  ASSERT_GE(count, 1u);
  EXPECT_STREQ(messages[0].code, "undeclared-input");
  EXPECT_EQ(messages[0].severity, VS11C_ERROR);
  EXPECT_EQ(messages[0].instruction, 1);
  EXPECT_NE(std::string(messages[0].text).find("v1"), std::string::npos) << messages[0].text;
  std::size_t counted = 0;
  EXPECT_EQ(vs11c_validate_d3d9(tokens.data(), tokens.size(), nullptr, nullptr, 0, &counted), VS11C_INVALID_SHADER);
  EXPECT_EQ(counted, count) << "capacity 0 counts";
  vs11c_shader* shader = nullptr;
  EXPECT_EQ(vs11c_shader_create_d3d9(tokens.data(), tokens.size(), nullptr, &shader), VS11C_INVALID_SHADER);
  EXPECT_EQ(shader, nullptr);

  // Under D3D8 the same tokens are valid; the declaration not loading v1 is a warning.
  const std::uint32_t declaration[] = {0x20000000u, 0x40020000u, 0xFFFFFFFFu};
  EXPECT_EQ(vs11c_validate_d3d8(declaration, 3, tokens.data(), tokens.size(), nullptr, messages.data(), messages.size(),
                                &count),
            VS11C_OK);
  ASSERT_EQ(count, 1u);
  EXPECT_STREQ(messages[0].code, "d3d8-declaration");
  EXPECT_EQ(messages[0].severity, VS11C_WARNING);
  EXPECT_EQ(messages[0].instruction, 1);
  EXPECT_EQ(messages[0].token, 4);  // version 0, mov oPos, c0 at 1-3, mov oD0, v1 at 4
}

TEST(CApi, MalformedTokensAndDeclarationsNameTheirToken) {
  const std::uint32_t truncated[] = {0xFFFE0101u, 0x00000001u};
  vs11c_message message{};
  std::size_t count = 0;
  EXPECT_EQ(vs11c_validate_d3d9(truncated, 2, nullptr, &message, 1, &count), VS11C_MALFORMED_TOKENS);
  ASSERT_GE(count, 1u);
  EXPECT_GE(message.token, 1);
  const std::vector<std::uint32_t> tokens = Tokens("vs.1.1\nmov oPos, v0\n");
  const std::uint32_t no_end[] = {0x20000000u, 0x40020000u};
  EXPECT_EQ(vs11c_validate_d3d8(no_end, 2, tokens.data(), tokens.size(), nullptr, &message, 1, &count),
            VS11C_BAD_DECLARATION);
  EXPECT_STREQ(message.code, "d3d8-declaration");
  EXPECT_EQ(message.token, 2);
  EXPECT_EQ(vs11c_validate_d3d9(nullptr, 3, nullptr, nullptr, 0, nullptr), VS11C_INVALID_ARGUMENT);
}

TEST(CApi, ArgumentsOutOfRangeAreRefused) {
  ShaderHandle handle;
  const std::vector<std::uint32_t> tokens = Tokens(testing::kD3d9Program);
  const vs11c_shader_options options{256};
  ASSERT_EQ(vs11c_shader_create_d3d9(tokens.data(), tokens.size(), &options, &handle.shader), VS11C_OK);
  const float value[4] = {};
  EXPECT_EQ(vs11c_shader_set_constants(handle.shader, 255, value, 1), VS11C_OK);
  EXPECT_EQ(vs11c_shader_set_constants(handle.shader, 256, value, 1), VS11C_REGISTER_OUT_OF_RANGE);
  EXPECT_EQ(vs11c_shader_set_constants(handle.shader, 255, value, 2), VS11C_REGISTER_OUT_OF_RANGE);
  // (Not "gl": the library registers no gl engine, but vs11_tests does, for the gl tests in this process.)
  EXPECT_EQ(vs11c_shader_set_engine(handle.shader, "no-such-engine", VS11C_FLOAT_RULES_D3D9), VS11C_INVALID_ARGUMENT);
  EXPECT_EQ(vs11c_shader_set_engine(handle.shader, "ref", 7), VS11C_INVALID_ARGUMENT);
  std::vector<std::uint8_t> output(64);
  const testing::TwoStreams input = testing::MakeTwoStreams(1);
  const vs11c_stream one_stream[] = {{input.stream0.data(), 16}};
  const vs11c_output layout{output.data(), 64, kFvfXyzW, nullptr, nullptr};
  EXPECT_EQ(vs11c_process_vertices(handle.shader, kTwoStreams, one_stream, 1, 1, &layout), VS11C_INVALID_ARGUMENT)
      << "stream 1 is missing";
  const vs11c_output both{output.data(), 64, kFvfXyzW, kTwoStreams, nullptr};
  const vs11c_stream streams[] = {{input.stream0.data(), 16}, {input.stream1.data(), 16}};
  EXPECT_EQ(vs11c_process_vertices(handle.shader, kTwoStreams, streams, 2, 1, &both), VS11C_INVALID_ARGUMENT);
  EXPECT_EQ(vs11c_process_vertices(handle.shader, nullptr, streams, 2, 1, &layout), VS11C_INVALID_ARGUMENT);
  const vs11c_shader_options too_many{100000};
  vs11c_shader* shader = nullptr;
  EXPECT_EQ(vs11c_shader_create_d3d9(tokens.data(), tokens.size(), &too_many, &shader), VS11C_INVALID_ARGUMENT);
  EXPECT_STREQ(vs11c_status_name(VS11C_BAD_DECLARATION), "bad-declaration");
}

std::array<float, 4> RunPosition(const vs11c_output& layout_template, const float (&position)[4], vs11c_float_rules rules,
                                 const float (&c0)[4]) {
  ShaderHandle handle;
  const std::vector<std::uint32_t> tokens = Tokens("vs_1_1\ndcl_position v0\nmul oPos, v0, c0\n");
  EXPECT_EQ(vs11c_shader_create_d3d9(tokens.data(), tokens.size(), nullptr, &handle.shader), VS11C_OK);
  EXPECT_EQ(vs11c_shader_set_constants(handle.shader, 0, c0, 1), VS11C_OK);
  EXPECT_EQ(vs11c_shader_set_engine(handle.shader, nullptr, rules), VS11C_OK);
  const vs11c_vertex_element declaration[] = {{0, 0, 3, 0, 0, 0}, kEnd};
  const vs11c_stream stream{position, 16};
  std::array<float, 4> out{};
  vs11c_output layout = layout_template;
  layout.data = out.data();
  EXPECT_EQ(vs11c_process_vertices(handle.shader, declaration, &stream, 1, 1, &layout), VS11C_OK);
  return out;
}

TEST(CApi, TransformedPositionsGetTheViewportOfProcessVertices) {
  const float ones[4] = {1, 1, 1, 1};
  const float clip[4] = {2, -1, 0.5f, 2};
  const vs11c_viewport viewport{10, 20, 640, 480, 0, 1};
  const vs11c_output screen{nullptr, 16, kFvfXyzRhw, nullptr, &viewport};
  EXPECT_EQ(RunPosition(screen, clip, VS11C_FLOAT_RULES_D3D9, ones), (std::array<float, 4>{650, 380, 0.25f, 0.5f}));
  const vs11c_output as_is{nullptr, 16, kFvfXyzRhw, nullptr, nullptr};
  EXPECT_EQ(RunPosition(as_is, clip, VS11C_FLOAT_RULES_D3D9, ones), (std::array<float, 4>{2, -1, 0.5f, 2}));
  const vs11c_vertex_element positiont[] = {{0, 0, 3, 0, 9, 0}, kEnd};
  const vs11c_output declared{nullptr, 16, 0, positiont, &viewport};
  EXPECT_EQ(RunPosition(declared, clip, VS11C_FLOAT_RULES_D3D9, ones), (std::array<float, 4>{650, 380, 0.25f, 0.5f}));
}

TEST(CApi, FloatRulesDecideZeroTimesInfinity) {
  const float zero[4] = {0, 1, 1, 1};
  const float infinite[4] = {INFINITY, 1, 1, 1};
  const vs11c_output layout{nullptr, 16, kFvfXyzW, nullptr, nullptr};
  EXPECT_TRUE(std::isnan(RunPosition(layout, infinite, VS11C_FLOAT_RULES_D3D9, zero)[0]));
  EXPECT_EQ(RunPosition(layout, infinite, VS11C_FLOAT_RULES_LEGACY, zero)[0], 0.0f);
}

// A vs_2_0 loop that unrolls past what the batch engine runs (255 * 255 * 2 instructions): the run
// fails with VS11C_ENGINE_FAILED and the engine's message, and the ref engine runs the shader.
TEST(CApi, AnEngineThatCannotRunTheShaderFailsWithItsMessage) {
  ShaderHandle handle;
  const std::vector<std::uint32_t> tokens =
      Tokens("vs_2_0\ndcl_position v0\ndefi i0, 255, 0, 0, 0\nmov r0, v0\nrep i0\nrep i0\nadd r0, r0, c1\n"
             "add r0, r0, c2\nendrep\nendrep\nmov oPos, r0\n");
  ASSERT_EQ(vs11c_shader_create_d3d9(tokens.data(), tokens.size(), nullptr, &handle.shader), VS11C_OK);
  EXPECT_STREQ(vs11c_shader_engine_error(handle.shader), "");
  ASSERT_EQ(vs11c_shader_set_engine(handle.shader, "batch", VS11C_FLOAT_RULES_D3D9), VS11C_OK);
  const vs11c_vertex_element declaration[] = {{0, 0, 3, 0, 0, 0}, kEnd};
  const float position[4] = {1, 2, 3, 1};
  const vs11c_stream stream{position, 16};
  std::array<float, 4> out{};
  const vs11c_output layout{out.data(), 16, kFvfXyzW, nullptr, nullptr};
  EXPECT_EQ(vs11c_process_vertices(handle.shader, declaration, &stream, 1, 1, &layout), VS11C_ENGINE_FAILED);
  const std::string message = vs11c_shader_engine_error(handle.shader);
  EXPECT_NE(message.find("more than 4096 instructions"), std::string::npos) << message;
  ASSERT_EQ(vs11c_shader_set_engine(handle.shader, "ref", VS11C_FLOAT_RULES_D3D9), VS11C_OK);
  EXPECT_EQ(vs11c_process_vertices(handle.shader, declaration, &stream, 1, 1, &layout), VS11C_OK);
  EXPECT_EQ(out, (std::array<float, 4>{1, 2, 3, 1}));  // c1 and c2 are 0
  EXPECT_STREQ(vs11c_shader_engine_error(nullptr), "");
}

}  // namespace
}  // namespace vs11::capi

// vs11c_shader_set_texture: a vs_3_0 shader's texldl through the C library on every engine, the
// unbound sampler's (0, 0, 0, 1), and the arguments it refuses.
#include <array>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include <vs11/vs11_c.h>

#include "tests/vm/capi/capi_test_support.h"

namespace vs11::capi {
namespace {

constexpr std::uint32_t kFvfXyzW = 0x4002;
constexpr vs11c_vertex_element kEnd = VS11C_DECL_END;

struct ShaderHandle {
  vs11c_shader* shader = nullptr;
  ~ShaderHandle() { vs11c_shader_destroy(shader); }
};

// oPos = s0 at the position's xy.
std::array<float, 4> Sample(vs11c_shader* shader, const char* engine, float u, float v) {
  EXPECT_EQ(vs11c_shader_set_engine(shader, engine, VS11C_FLOAT_RULES_D3D9), VS11C_OK);
  const float position[4] = {u, v, 0, 1};
  const vs11c_vertex_element declaration[] = {{0, 0, 3, 0, 0, 0}, kEnd};  // FLOAT4 POSITION
  const vs11c_stream stream{position, 16};
  std::array<float, 4> out{};
  const vs11c_output layout{out.data(), 16, kFvfXyzW, nullptr, nullptr};
  EXPECT_EQ(vs11c_process_vertices(shader, declaration, &stream, 1, 1, &layout), VS11C_OK);
  return out;
}

TEST(CApiTexture, TexldlSamplesTheBoundTextureOnEveryEngine) {
  ShaderHandle handle;
  const std::vector<std::uint32_t> tokens =
      testing::Tokens("vs_3_0\ndcl_position v0\ndcl_position o0\ndcl_2d s0\ntexldl r0, v0, s0\nmov o0, r0\n");
  ASSERT_EQ(vs11c_shader_create_d3d9(tokens.data(), tokens.size(), nullptr, &handle.shader), VS11C_OK);
  const float heights[] = {5, 7, 11, 13, 17, 19};  // 3 x 2 R32F
  ASSERT_EQ(vs11c_shader_set_texture(handle.shader, 0, VS11C_TEXTURE_R32F, 3, 2, heights, VS11C_ADDRESS_CLAMP,
                                     VS11C_ADDRESS_WRAP),
            VS11C_OK);
  for (const char* engine : {"ref", "batch", "jit"}) {
    EXPECT_EQ(Sample(handle.shader, engine, 0.5f, 0.75f), (std::array<float, 4>{17, 1, 1, 1})) << engine;  // (1, 1)
    EXPECT_EQ(Sample(handle.shader, engine, 2.0f, 1.25f), (std::array<float, 4>{11, 1, 1, 1})) << engine;  // (2, 0)
  }
  ASSERT_EQ(vs11c_shader_set_texture(handle.shader, 0, VS11C_TEXTURE_R32F, 0, 0, nullptr, VS11C_ADDRESS_WRAP,
                                     VS11C_ADDRESS_WRAP),
            VS11C_OK);
  EXPECT_EQ(Sample(handle.shader, "batch", 0.5f, 0.5f), (std::array<float, 4>{0, 0, 0, 1}));
}

TEST(CApiTexture, RefusesSamplersFormatsSizesAndAddressModesItDoesNotModel) {
  ShaderHandle handle;
  const std::vector<std::uint32_t> tokens =
      testing::Tokens("vs_3_0\ndcl_position v0\ndcl_position o0\ndcl_2d s0\ntexldl r0, v0, s0\nmov o0, r0\n");
  ASSERT_EQ(vs11c_shader_create_d3d9(tokens.data(), tokens.size(), nullptr, &handle.shader), VS11C_OK);
  const float texel[4] = {1, 2, 3, 4};
  vs11c_shader* shader = handle.shader;
  EXPECT_EQ(vs11c_shader_set_texture(shader, 4, VS11C_TEXTURE_R32F, 1, 1, texel, 1, 1), VS11C_REGISTER_OUT_OF_RANGE);
  EXPECT_EQ(vs11c_shader_set_texture(shader, 0, 7, 1, 1, texel, 1, 1), VS11C_INVALID_ARGUMENT);
  EXPECT_EQ(vs11c_shader_set_texture(shader, 0, VS11C_TEXTURE_R32F, 0, 1, texel, 1, 1), VS11C_INVALID_ARGUMENT);
  EXPECT_EQ(vs11c_shader_set_texture(shader, 0, VS11C_TEXTURE_R32F, 1u << 13, 1u << 12, texel, 1, 1),
            VS11C_INVALID_ARGUMENT);  // 2^25 texels
  EXPECT_EQ(vs11c_shader_set_texture(shader, 0, VS11C_TEXTURE_R32F, 1, 1, texel, 2, 1), VS11C_UNSUPPORTED);  // mirror
  EXPECT_EQ(vs11c_shader_set_texture(shader, 0, VS11C_TEXTURE_R32F, 1, 1, texel, 1, 9), VS11C_INVALID_ARGUMENT);
  EXPECT_EQ(vs11c_shader_set_texture(nullptr, 0, VS11C_TEXTURE_R32F, 1, 1, texel, 1, 1), VS11C_INVALID_ARGUMENT);
  EXPECT_EQ(vs11c_shader_set_texture(shader, 0, VS11C_TEXTURE_A32B32G32R32F, 1, 1, texel, 4, 3), VS11C_OK);
  EXPECT_EQ(Sample(shader, "ref", 0.5f, 0.5f), (std::array<float, 4>{1, 2, 3, 4}));
  EXPECT_EQ(Sample(shader, "ref", 1.5f, 0.5f), (std::array<float, 4>{0, 0, 0, 0}));  // border in u
}

}  // namespace
}  // namespace vs11::capi

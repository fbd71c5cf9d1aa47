// The C library's thread-safety statement (include/vs11/vs11_c.h): distinct shaders run in
// parallel, and validation may run from any thread, with the results of one thread alone. CI's
// ThreadSanitizer stage (.ci/tsan) runs these.
#include <vs11/vs11_c.h>

#include <array>
#include <vector>

#include <gtest/gtest.h>

#include "tests/run_threads.h"
#include "tests/vm/capi/capi_test_support.h"

namespace vs11::capi {
namespace {

constexpr std::uint32_t kFvfXyzW = 0x4002, kFvfDiffuse = 0x040, kFvfSpecular = 0x080, kFvfTex1 = 0x100;
constexpr vs11c_vertex_element kDeclaration[] = {
    {0, 0, 2, 0, 0, 0}, {0, 12, 4, 0, 10, 0}, {1, 0, 15, 0, 5, 0}, {1, 4, 14, 0, 1, 0}, VS11C_DECL_END};
constexpr std::size_t kStride = 32;

// One thread's whole use of a shader: create, set constants (its own scale), run, destroy.
std::vector<std::uint8_t> RunOwnShader(const std::vector<std::uint32_t>& tokens, const testing::TwoStreams& input,
                                       std::size_t count, const char* engine, float scale) {
  vs11c_shader* shader = nullptr;
  EXPECT_EQ(vs11c_shader_create_d3d9(tokens.data(), tokens.size(), nullptr, &shader), VS11C_OK);
  if (shader == nullptr) return {};
  const float constants[] = {scale, 0, 0, 0, 0, scale, 0, 0, 0, 0, scale, 0, 0, 0, 0, 1, 2, 2, 1, 1, 0.25f, 0, 0, 0};
  EXPECT_EQ(vs11c_shader_set_constants(shader, 0, constants, 6), VS11C_OK);
  EXPECT_EQ(vs11c_shader_set_engine(shader, engine, VS11C_FLOAT_RULES_D3D9), VS11C_OK);
  const vs11c_stream streams[] = {{input.stream0.data(), input.kStride0}, {input.stream1.data(), input.kStride1}};
  std::vector<std::uint8_t> output(count * kStride);
  const vs11c_output layout{output.data(), kStride, kFvfXyzW | kFvfDiffuse | kFvfSpecular | kFvfTex1, nullptr, nullptr};
  EXPECT_EQ(vs11c_process_vertices(shader, kDeclaration, streams, 2, count, &layout), VS11C_OK);
  vs11c_shader_destroy(shader);
  return output;
}

TEST(CApiThreads, DistinctShadersRunInParallelOverSharedStreams) {
  constexpr int kThreads = 4;
  constexpr std::size_t kCount = 3000;
  const std::vector<std::uint32_t> tokens = testing::Tokens(testing::kD3d9Program);
  const testing::TwoStreams input = testing::MakeTwoStreams(kCount);  // read by every thread at once
  const std::array<const char*, kThreads> engines = {"ref", "batch", "jit", nullptr};
  std::array<std::vector<std::uint8_t>, kThreads> alone;
  for (int t = 0; t < kThreads; ++t) alone[t] = RunOwnShader(tokens, input, kCount, engines[t], 1.0f + t);
  std::array<std::vector<std::uint8_t>, kThreads> together;
  vs11::testing::RunOnThreads(kThreads, [&](int t) {
    together[t] = RunOwnShader(tokens, input, kCount, engines[t], 1.0f + t);
  });
  for (int t = 0; t < kThreads; ++t) EXPECT_EQ(together[t], alone[t]) << "thread " << t;
}

TEST(CApiThreads, ValidationRunsFromManyThreadsAtOnce) {
  const std::vector<std::uint32_t> tokens = testing::Tokens("vs.1.1\nmov oPos, c0\nmov oD0, v1\n");
  vs11::testing::RunOnThreads(4, [&](int) {
    for (int i = 0; i < 50; ++i) {
      vs11c_message message{};
      std::size_t count = 0;
      EXPECT_EQ(vs11c_validate_d3d9(tokens.data(), tokens.size(), nullptr, &message, 1, &count), VS11C_INVALID_SHADER);
      EXPECT_STREQ(message.code, "undeclared-input");
    }
  });
}

}  // namespace
}  // namespace vs11::capi
